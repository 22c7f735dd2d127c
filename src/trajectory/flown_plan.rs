//! A flight made from a plan: a multicopter or a plane flying it as its autopilot does, through
//! the waypoints it need not stop at (reference §16); the path it flies, as a plan, for the
//! mission station on a plane's plan ([`rounded`]); and inspection missions that hover at their
//! points, for the mission station's holds (`sweep --mission`, docs/mission.md).

use super::cornering::{corners, Corner};
use super::plan::{FlightPlan, MAX_WAYPOINTS};
use super::{PlanError, Trajectory, MAX_ROWS};
use crate::math::{distance, sin_cos};
use crate::rng::Rng;

/// The acceleration and braking of [`fly_plan`], m/s²: ArduPilot's default waypoint
/// acceleration (`WPNAV_ACCEL`, 2.5 m/s²) rounded down.
pub const PLAN_ACCEL: f64 = 2.0;
/// The sample rate of [`fly_plan`]'s flights, Hz: a flight log's GPS and EKF rate.
pub const PLAN_RATE_HZ: f64 = 25.0;
/// The speed of a leg whose plan gives none, m/s ([`fly_plan`], and the mission station after a
/// hold before any packet showed the drone moving): QGroundControl's default mission speed for a
/// multi-rotor (`hoverSpeed`) and PX4's `MPC_XY_CRUISE` (ArduPilot's `WPNAV_SPEED` defaults to
/// 10 m/s).
pub const PLAN_CRUISE: f64 = 5.0;

/// The longest flight [`fly_plan`] flies, s: [`MAX_ROWS`] samples at [`PLAN_RATE_HZ`], the
/// longest flight a CSV may give.
pub const MAX_FLOWN_S: f64 = MAX_ROWS as f64 / PLAN_RATE_HZ;

/// A straight as [`fly_plan`] flies it: from one speed to another, at most `top`, changing speed
/// at [`PLAN_ACCEL`].
struct Straight {
    from: [f64; 3],
    /// Unit vector along the leg.
    u: [f64; 3],
    length: f64,
    /// Speeds at its start and end, and the peak between, m/s.
    start: f64,
    end: f64,
    top: f64,
    /// Seconds speeding up, at the peak and slowing down.
    up: f64,
    cruise: f64,
    down: f64,
}

impl Straight {
    /// From `from` to `to` (m), entered at `start` and left at `end` m/s, no faster than
    /// `speed`: the two need be within [`PLAN_ACCEL`]'s reach over the length ([`corners`]).
    fn new(from: [f64; 3], to: [f64; 3], (start, end): (f64, f64), speed: f64) -> Straight {
        let length = distance(&from, &to);
        let a = PLAN_ACCEL;
        let top = speed
            .min((a * length + (start * start + end * end) / 2.0).sqrt())
            .max(start.max(end));
        let ramps = (top * top - start * start) / (2.0 * a) + (top * top - end * end) / (2.0 * a);
        Straight {
            from,
            u: if length > 0.0 {
                core::array::from_fn(|k| (to[k] - from[k]) / length)
            } else {
                [0.0; 3]
            },
            length,
            start,
            end,
            top,
            up: (top - start) / a,
            cruise: if top > 0.0 {
                (length - ramps).max(0.0) / top
            } else {
                0.0
            },
            down: (top - end) / a,
        }
    }

    fn duration(&self) -> f64 {
        self.up + self.cruise + self.down
    }

    /// Position, velocity and acceleration (m, m/s, m/s²) `tau` s into it.
    fn at(&self, tau: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let a = PLAN_ACCEL;
        let (s, v, acc) = if tau < self.up {
            (
                self.start * tau + a * tau * tau / 2.0,
                self.start + a * tau,
                a,
            )
        } else if tau < self.up + self.cruise {
            let ramp = (self.top * self.top - self.start * self.start) / (2.0 * a);
            (ramp + self.top * (tau - self.up), self.top, 0.0)
        } else {
            let left = (self.duration() - tau).max(0.0);
            (
                self.length - self.end * left - a * left * left / 2.0,
                self.end + a * left,
                -a,
            )
        };
        let along = |m: f64| self.u.map(|c| c * m);
        let p = along(s.clamp(0.0, self.length));
        (
            core::array::from_fn(|k| self.from[k] + p[k]),
            along(v),
            along(acc),
        )
    }
}

/// A corner's arc as [`fly_plan`] flies it, at constant speed.
struct Arc {
    /// The arc's centre, m; `inward` the unit vector from its start toward the centre, `u` the
    /// direction it starts in.
    centre: [f64; 3],
    inward: [f64; 3],
    u: [f64; 3],
    radius: f64,
    speed: f64,
    turn: f64,
}

impl Arc {
    /// The arc of `corner` at waypoint `at`, from the leg along `u_in` onto the leg along `u_out`.
    fn new(corner: &Corner, at: [f64; 3], u_in: [f64; 3], u_out: [f64; 3]) -> Arc {
        let along_in: f64 = (0..3).map(|k| u_out[k] * u_in[k]).sum();
        let side: [f64; 3] = core::array::from_fn(|k| u_out[k] - along_in * u_in[k]);
        let norm = side.iter().map(|c| c * c).sum::<f64>().sqrt();
        let inward = side.map(|c| c / norm);
        Arc {
            centre: core::array::from_fn(|k| {
                at[k] - u_in[k] * corner.cut + inward[k] * corner.radius
            }),
            inward,
            u: u_in,
            radius: corner.radius,
            speed: corner.speed,
            turn: corner.turn,
        }
    }

    fn duration(&self) -> f64 {
        self.radius * self.turn / self.speed
    }

    /// The point `angle` rad round the arc from its start, m.
    fn point(&self, angle: f64) -> [f64; 3] {
        let (sin, cos) = sin_cos(angle);
        core::array::from_fn(|k| {
            self.centre[k] - self.radius * cos * self.inward[k] + self.radius * sin * self.u[k]
        })
    }

    /// Position, velocity and acceleration (m, m/s, m/s²) `tau` s into it.
    fn at(&self, tau: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let angle = (self.speed * tau / self.radius).min(self.turn);
        let (sin, cos) = sin_cos(angle);
        let v = self.speed;
        let centripetal = v * v / self.radius;
        (
            self.point(angle),
            core::array::from_fn(|k| v * (cos * self.u[k] + sin * self.inward[k])),
            core::array::from_fn(|k| centripetal * (cos * self.inward[k] - sin * self.u[k])),
        )
    }
}

/// One stretch of a flown plan.
enum Piece {
    Straight(Straight),
    Arc(Arc),
    /// Hovering at a waypoint for so many seconds.
    Hold([f64; 3], f64),
}

impl Piece {
    fn duration(&self) -> f64 {
        match self {
            Piece::Straight(s) => s.duration(),
            Piece::Arc(a) => a.duration(),
            Piece::Hold(_, seconds) => *seconds,
        }
    }

    fn at(&self, tau: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
        match self {
            Piece::Straight(s) => s.at(tau),
            Piece::Arc(a) => a.at(tau),
            Piece::Hold(p, _) => (*p, [0.0; 3], [0.0; 3]),
        }
    }
}

/// A leg of a plan as it is flown: its index, its unit direction, the corners at its ends (none
/// where the vehicle stops) and the arc it turns onto the next leg on (none where it stops there
/// or runs straight on).
struct FlownLeg {
    leg: usize,
    u: [f64; 3],
    from: Option<Corner>,
    to: Option<Corner>,
    arc: Option<Arc>,
}

/// The legs of `plan` as [`fly_plan`] flies them, in order: the one walk that the flight
/// ([`pieces`]) and the path the mission station follows ([`rounded`]) both make.
fn flown_legs(plan: &FlightPlan) -> impl Iterator<Item = FlownLeg> + '_ {
    let w = plan.waypoints();
    let turns = corners(plan);
    (0..w.len() - 1).map(move |leg| {
        let u = leg_direction(w, leg);
        let to = turns[leg + 1];
        FlownLeg {
            leg,
            u,
            from: turns[leg],
            to,
            arc: to
                .filter(|c| c.length() > 0.0)
                .map(|c| Arc::new(&c, w[leg + 1], u, leg_direction(w, leg + 1))),
        }
    })
}

/// The stretches `plan` is flown in: a straight per leg (shortened where a corner cuts it), the
/// arc of each corner, and each hold.
fn pieces(plan: &FlightPlan) -> Vec<Piece> {
    let w = plan.waypoints();
    let mut out = Vec::new();
    for FlownLeg {
        leg,
        u,
        from,
        to,
        arc,
    } in flown_legs(plan)
    {
        let cut = |c: Option<Corner>| c.map_or(0.0, |c| c.cut);
        let start: [f64; 3] = core::array::from_fn(|k| w[leg][k] + u[k] * cut(from));
        let end: [f64; 3] = core::array::from_fn(|k| w[leg + 1][k] - u[k] * cut(to));
        let speeds = (from.map_or(0.0, |c| c.speed), to.map_or(0.0, |c| c.speed));
        out.push(Piece::Straight(Straight::new(
            start,
            end,
            speeds,
            plan.flown_speed(leg, PLAN_CRUISE),
        )));
        match (arc, to) {
            (Some(arc), _) => out.push(Piece::Arc(arc)),
            (None, Some(_)) => {}
            (None, None) => out.push(Piece::Hold(w[leg + 1], plan.holds()[leg + 1])),
        }
    }
    out
}

/// The largest turn between two waypoints of [`rounded`]'s arcs, rad (5°): the polyline then
/// lies within r·(1 − cos 2.5°) of the arc, 7 cm on a plane's 73 m arc.
const ARC_STEP: f64 = core::f64::consts::PI / 36.0;

/// The path `plan` is flown on, as a plan: each corner's arc ([`corners`]) as waypoints every
/// 5° of turn (coarser where so many would pass [`MAX_WAYPOINTS`], as on a loiter of hundreds
/// of turns), each with the speed and climb limits of the leg it leads onto (the
/// autopilot counts a waypoint reached where its turn begins); the straights, stops and holds
/// as planned. For the mission station on a plane's plan, whose arcs pass tens of metres inside
/// its waypoints ([`Cornering::FixedWing`](crate::Cornering::FixedWing)): on the plan's legs a
/// plane in its turn lies farther from them than the station's tolerance.
///
/// ```
/// use loratrack::{rounded, ClimbLimits, Cornering, FlightPlan};
/// let plan = FlightPlan::new(vec![[0.0, 0.0, 80.0], [600.0, 0.0, 80.0], [600.0, 600.0, 80.0]], vec![Some(18.0); 2])
///     .unwrap()
///     .with_climb(Some(ClimbLimits::FIXED_WING))
///     .with_cornering(Cornering::FixedWing);
/// let path = rounded(&plan);
/// // The right angle: its arc's start, 18 points 5° apart, then the last waypoint.
/// assert_eq!(path.waypoints().len(), 1 + 19 + 1);
/// assert!(path.length() < plan.length());
/// ```
pub fn rounded(plan: &FlightPlan) -> FlightPlan {
    let w = plan.waypoints();
    // A plan without climb limits (one traced through a flight) has no corners to round.
    let Some(climbs) = plan.climbs() else {
        return plan.clone();
    };
    let legs: Vec<FlownLeg> = flown_legs(plan).collect();
    // The points fit a plan's MAX_WAYPOINTS: a long loiter's hundreds of turns take coarser
    // steps (each doubling at most halves their count), down to an arc's two ends.
    let count = |step: f64| {
        let arcs = legs.iter().filter_map(|l| l.arc.as_ref());
        w.len() + arcs.map(|a| (a.turn / step).ceil() as usize).sum::<usize>()
    };
    let mut step = ARC_STEP;
    while count(step) > MAX_WAYPOINTS && step < core::f64::consts::PI {
        step *= 2.0;
    }
    let mut path = Rounding {
        points: vec![w[0]],
        speeds: Vec::new(),
        holds: vec![plan.holds()[0]],
        climbs: Vec::new(),
    };
    for FlownLeg { leg, arc, .. } in legs {
        let along_leg = (plan.leg_speed(leg), climbs[leg]);
        match arc {
            Some(arc) => {
                path.push(arc.point(0.0), along_leg, 0.0);
                let onto = (plan.leg_speed(leg + 1), climbs[leg + 1]);
                let n = (arc.turn / step).ceil();
                for k in 1..=n as usize {
                    path.push(arc.point(arc.turn * k as f64 / n), onto, 0.0);
                }
            }
            None => path.push(w[leg + 1], along_leg, plan.holds()[leg + 1]),
        }
    }
    let rounded =
        FlightPlan::with_holds_and_climbs(path.points, path.speeds, path.holds, path.climbs);
    // Every point of the path lies on the plan's legs or between them: as valid as the plan,
    // unless more than MAX_WAYPOINTS / 2 corners leave too many points even so (then its legs).
    rounded.map_or_else(|_| plan.clone(), |p| p.with_cornering(plan.cornering()))
}

/// The waypoints of [`rounded`] so far, with each leg's speed and climb limits.
struct Rounding {
    points: Vec<[f64; 3]>,
    speeds: Vec<Option<f64>>,
    holds: Vec<f64>,
    climbs: Vec<crate::ClimbLimits>,
}

impl Rounding {
    /// Adds waypoint `p` with `hold` s there, reached on a leg with `leg`'s speed and climb
    /// limits; a point within a micrometre of the last (an arc that begins where the one
    /// before ended) only adds its hold, since a leg that short has no direction to turn from.
    fn push(&mut self, p: [f64; 3], leg: (Option<f64>, crate::ClimbLimits), hold: f64) {
        let last = self.points.len() - 1;
        if distance(&self.points[last], &p) < 1e-6 {
            self.holds[last] += hold;
            return;
        }
        self.points.push(p);
        self.speeds.push(leg.0);
        self.holds.push(hold);
        self.climbs.push(leg.1);
    }
}

/// The unit direction of the leg from waypoint `leg` of `w` to the next.
fn leg_direction(w: &[[f64; 3]], leg: usize) -> [f64; 3] {
    let d = distance(&w[leg], &w[leg + 1]);
    core::array::from_fn(|k| (w[leg + 1][k] - w[leg][k]) / d)
}

/// How long [`fly_plan`] takes to fly `plan`, s: its legs, its corners and its holds.
///
/// ```
/// use loratrack::{flown_duration, FlightPlan};
/// let plan = FlightPlan::with_holds(vec![[0.0; 3], [100.0, 0.0, 0.0]], vec![Some(10.0)], vec![0.0, 20.0]).unwrap();
/// assert!((flown_duration(&plan) - 35.0).abs() < 1e-9);
/// ```
pub fn flown_duration(plan: &FlightPlan) -> f64 {
    pieces(plan).iter().map(Piece::duration).sum()
}

/// The flight of a multicopter (or a plane) that flies `plan` from rest: on each leg it speeds up to the leg's
/// planned speed ([`PLAN_CRUISE`] where the plan gives none; slower on a leg too steep for the
/// plan's [`ClimbLimits`](crate::ClimbLimits), [`FlightPlan::flown_speed`]), at [`PLAN_ACCEL`];
/// through a waypoint without a hold it turns onto the next leg on an arc that passes
/// [`CORNER_RADIUS`](crate::CORNER_RADIUS) from it, slowed only as much as the turn asks
/// ([`corners`]: ArduPilot Copter's S-curves and PX4's multicopter missions fly through such
/// waypoints; a plane's plan, [`Cornering::FixedWing`](crate::Cornering::FixedWing), on the wider
/// arc ArduPlane turns on, at its speed); it brakes to a stop where it holds (then hovers for the hold), where the path
/// doubles back and at the last waypoint (a plane's in the air it flies through, and the flight
/// ends there at its speed). Sampled at [`PLAN_RATE_HZ`] with its velocities and
/// accelerations. No wind: the plan flown as planned, a best case for a station that knows it.
/// Refuses a plan that takes longer than [`MAX_FLOWN_S`] to fly ([`PlanError::TooLongToFly`]; an
/// unlimited loiter holds for a day).
///
/// ```
/// use loratrack::{fly_plan, FlightPlan};
/// let plan = FlightPlan::with_holds(vec![[0.0; 3], [100.0, 0.0, 0.0]], vec![Some(10.0)], vec![0.0, 20.0]).unwrap();
/// let flight = fly_plan(&plan, "demo").unwrap();
/// // 5 s to reach 10 m/s, 5 s at it, 5 s to stop after 100 m, then the 20 s hold.
/// assert!((flight.duration() - 35.0).abs() < 0.05);
/// ```
pub fn fly_plan(plan: &FlightPlan, name: &str) -> Result<Trajectory, PlanError> {
    let pieces = pieces(plan);
    let seconds: f64 = pieces.iter().map(Piece::duration).sum();
    if seconds.is_nan() || seconds > MAX_FLOWN_S {
        return Err(PlanError::TooLongToFly { seconds });
    }
    let dt = 1.0 / PLAN_RATE_HZ;
    let samples = (seconds / dt).floor() as usize + 1;
    let (mut t, mut pos, mut vel, mut acc) = (
        Vec::with_capacity(samples + 1),
        Vec::with_capacity(samples + 1),
        Vec::with_capacity(samples + 1),
        Vec::with_capacity(samples + 1),
    );
    let (mut piece, mut began) = (0, 0.0);
    for i in 0..samples {
        let now = i as f64 * dt;
        while piece + 1 < pieces.len() && now >= began + pieces[piece].duration() {
            began += pieces[piece].duration();
            piece += 1;
        }
        let (p, v, a) = pieces[piece].at(now - began);
        t.push(now);
        pos.push(p);
        vel.push(v);
        acc.push(a);
    }
    // A last sample at rest on the last waypoint, where the flight ends between two samples.
    let last = plan.waypoints()[plan.waypoints().len() - 1];
    if pos.last() != Some(&last) {
        t.push(samples as f64 * dt);
        pos.push(last);
        vel.push([0.0; 3]);
        acc.push([0.0; 3]);
    }
    Trajectory::new(name.to_string(), t, pos, vel, acc)
        .map_err(|e| PlanError::Invalid(format!("the flown plan: {e}")))
}

/// Points an [`inspection_plan`] visits.
pub const INSPECTION_POINTS: usize = 24;
/// The holds an [`inspection_plan`] draws from for each point, s (0: flown through).
pub const INSPECTION_HOLDS: [f64; 4] = [0.0, 15.0, 30.0, 60.0];

/// A multicopter inspection mission: take off at 3 m/s to 30 m, fly at 8 m/s to
/// [`INSPECTION_POINTS`] points drawn from `seed` within ±400 m east and north and 25–60 m up,
/// holding at each for one of [`INSPECTION_HOLDS`] (drawn alike), come back above home and land
/// at 2 m/s. About 35 min when flown by [`fly_plan`].
///
/// ```
/// let plan = loratrack::inspection_plan(1);
/// assert_eq!(plan.waypoints().len(), loratrack::INSPECTION_POINTS + 4);
/// assert!(plan.holds().iter().filter(|&&h| h > 0.0).count() > 12);
/// ```
pub fn inspection_plan(seed: u64) -> FlightPlan {
    let mut rng = Rng::new(seed);
    let mut points = vec![[0.0, 0.0, 0.0], [0.0, 0.0, 30.0]];
    let mut speeds = vec![Some(3.0)];
    let mut holds = vec![0.0, 0.0];
    for _ in 0..INSPECTION_POINTS {
        points.push([
            rng.range(-400.0, 400.0),
            rng.range(-400.0, 400.0),
            rng.range(25.0, 60.0),
        ]);
        speeds.push(Some(8.0));
        let pick = (rng.uniform() * INSPECTION_HOLDS.len() as f64) as usize;
        holds.push(INSPECTION_HOLDS[pick.min(INSPECTION_HOLDS.len() - 1)]);
    }
    points.extend([[0.0, 0.0, 30.0], [0.0, 0.0, 0.0]]);
    speeds.extend([Some(8.0), Some(2.0)]);
    holds.extend([0.0, 0.0]);
    FlightPlan::with_holds(points, speeds, holds).expect("an inspection is a valid plan")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flight_stops_where_it_holds_and_hovers_for_the_hold() {
        let plan = FlightPlan::with_holds(
            vec![[0.0; 3], [100.0, 0.0, 0.0], [100.0, 2.0, 0.0]],
            vec![Some(10.0), Some(10.0)],
            vec![0.0, 10.0, 0.0],
        )
        .unwrap();
        let f = fly_plan(&plan, "test").unwrap();
        // The 2 m leg peaks at 2 m/s: 1 s up, 1 s down.
        assert!(
            (f.duration() - (15.0 + 10.0 + 2.0)).abs() < 0.1,
            "{}",
            f.duration()
        );
        let at = |time: f64| f.pos[(time * PLAN_RATE_HZ).round() as usize];
        for time in [15.1, 20.0, 24.9] {
            assert!(distance(&at(time), &[100.0, 0.0, 0.0]) < 1e-6, "{time}");
        }
        assert!(distance(&at(f.duration()), &[100.0, 2.0, 0.0]) < 1e-6);
        let top = f.vel.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
        assert!((top - 10.0).abs() < 1e-9, "{top}");
    }

    #[test]
    fn a_corner_is_flown_through_on_an_arc_near_the_waypoint_within_the_sideways_limit() {
        // East 100 m, then a right angle north, at 8 m/s; no hold.
        let plan = FlightPlan::new(
            vec![[0.0, 0.0, 10.0], [100.0, 0.0, 10.0], [100.0, 100.0, 10.0]],
            vec![Some(8.0), Some(8.0)],
        )
        .unwrap();
        let f = fly_plan(&plan, "corner").unwrap();
        let turn = crate::trajectory::corners(&plan)[1].unwrap();
        // Within 20 m of the waypoint it never stops: its slowest is the arc's speed.
        let slowest = (0..f.len())
            .filter(|&i| distance(&f.pos[i], &[100.0, 0.0, 10.0]) < 20.0)
            .map(|i| f.vel[i][0].hypot(f.vel[i][1]))
            .fold(f64::INFINITY, f64::min);
        assert!((slowest - turn.speed).abs() < 1e-9, "{slowest}");
        // It passes the corner radius from the waypoint, no closer.
        let nearest = f
            .pos
            .iter()
            .map(|p| distance(p, &[100.0, 0.0, 10.0]))
            .fold(f64::INFINITY, f64::min);
        let radius = crate::trajectory::CORNER_RADIUS;
        assert!(
            nearest > radius - 0.05 && nearest < radius + 0.05,
            "{nearest}"
        );
        // Sideways, never more than the cornering limit; along the legs, never more than 2 m/s².
        let most = f.acc.iter().map(|a| a[0].hypot(a[1])).fold(0.0, f64::max);
        assert!(most <= crate::trajectory::CORNER_ACCEL + 1e-9, "{most}");
        // Faster than stopping there: braking to rest and speeding up again cost seconds.
        let stopped = FlightPlan::with_holds(
            plan.waypoints().to_vec(),
            vec![Some(8.0); 2],
            vec![0.0, 1e-9, 0.0],
        )
        .unwrap();
        let lost = flown_duration(&stopped) - f.duration();
        assert!(lost > 2.0, "{lost}");
    }

    #[test]
    fn a_plane_flies_a_corner_at_its_speed_wide_of_the_waypoint() {
        let plan = FlightPlan::new(
            vec![[0.0, 0.0, 80.0], [600.0, 0.0, 80.0], [600.0, 600.0, 80.0]],
            vec![Some(18.0), Some(18.0)],
        )
        .unwrap()
        .with_climb(Some(crate::ClimbLimits::FIXED_WING))
        .with_cornering(crate::Cornering::FixedWing);
        let f = fly_plan(&plan, "plane").unwrap();
        let corner = [600.0, 0.0, 80.0];
        let near: Vec<usize> = (0..f.len())
            .filter(|&i| distance(&f.pos[i], &corner) < 150.0)
            .collect();
        let slowest = near
            .iter()
            .map(|&i| f.vel[i][0].hypot(f.vel[i][1]))
            .fold(f64::INFINITY, f64::min);
        assert!((slowest - 18.0).abs() < 1e-9, "{slowest}");
        // The arc of radius r tangent to both legs passes r (√2 − 1) from the waypoint.
        let r = crate::trajectory::corners(&plan)[1].unwrap().radius;
        let nearest = near
            .iter()
            .map(|&i| distance(&f.pos[i], &corner))
            .fold(f64::INFINITY, f64::min);
        let expected = r * (2f64.sqrt() - 1.0);
        assert!(
            (nearest - expected).abs() < 0.1 && nearest > 25.0,
            "{nearest}"
        );
    }

    #[test]
    fn a_plane_plan_with_a_long_loiter_is_rounded_within_the_waypoint_limit() {
        // A wide right angle, then 300 turns of a 60 m loiter as 12-gons (3600 corners of 30°).
        let mut points = vec![[0.0, 0.0, 80.0], [600.0, 0.0, 80.0], [600.0, 600.0, 80.0]];
        for k in 1..=3600 {
            let a = k as f64 * core::f64::consts::TAU / 12.0;
            points.push([600.0 + 60.0 * a.cos(), 660.0 - 60.0 * a.sin(), 80.0]);
        }
        let legs = points.len() - 1;
        let plan = FlightPlan::new(points, vec![Some(18.0); legs])
            .unwrap()
            .with_climb(Some(crate::ClimbLimits::FIXED_WING))
            .with_cornering(crate::Cornering::FixedWing);
        let path = rounded(&plan);
        assert!(path.waypoints().len() <= MAX_WAYPOINTS);
        assert!(path.waypoints().len() > plan.waypoints().len());
        // The right angle's arc is followed: the path passes near its middle, 21 m from the legs
        // (in 30° steps: within r (1 − cos 15°) = 2.5 m).
        let r = corners(&plan)[1].unwrap().radius;
        let middle = [600.0 - r + r / 2f64.sqrt(), r - r / 2f64.sqrt(), 80.0];
        let off = path.nearest(&middle, 0.0, 1000.0).off;
        assert!(off < 3.0, "{off}");
        assert!(plan.nearest(&middle, 0.0, 1000.0).off > 20.0);
    }

    #[test]
    fn a_steep_leg_is_flown_within_the_climb_limits_and_a_gentle_one_at_its_speed() {
        // Up 40 m at a planned 8 m/s, along 200 m rising 10 m, then down a 45° slope.
        let plan = FlightPlan::new(
            vec![
                [0.0; 3],
                [0.0, 0.0, 40.0],
                [200.0, 0.0, 50.0],
                [250.0, 0.0, 0.0],
            ],
            vec![Some(8.0); 3],
        )
        .unwrap();
        let f = fly_plan(&plan, "steep").unwrap();
        let limits = crate::trajectory::ClimbLimits::MULTICOPTER;
        let (up, down) = f
            .vel
            .iter()
            .fold((0.0f64, 0.0f64), |(u, d), v| (u.max(v[2]), d.min(v[2])));
        assert!((up - limits.up).abs() < 1e-9, "{up}");
        assert!((down + limits.down).abs() < 1e-9, "{down}");
        let top = f
            .vel
            .iter()
            .map(|v| distance(v, &[0.0; 3]))
            .fold(0.0, f64::max);
        assert!((top - 8.0).abs() < 1e-9, "{top}");
        // Without limits (a traced plan's pace) the climb is flown at the planned speed.
        let free = fly_plan(&plan.clone().with_climb(None), "free").unwrap();
        assert!(free.duration() < f.duration() - 20.0);
    }

    #[test]
    fn an_inspection_is_the_same_for_its_seed_and_another_for_another() {
        assert_eq!(inspection_plan(3), inspection_plan(3));
        assert_ne!(inspection_plan(3), inspection_plan(4));
        let minutes = fly_plan(&inspection_plan(1), "i").unwrap().duration() / 60.0;
        assert!((30.0..50.0).contains(&minutes), "{minutes}");
    }

    #[test]
    fn the_duration_is_known_before_the_flight_within_a_sample_a_leg() {
        let plan = inspection_plan(2);
        let flown = fly_plan(&plan, "i").unwrap().duration();
        let legs = (plan.waypoints().len() - 1) as f64;
        let known = flown_duration(&plan);
        assert!(
            (flown - known).abs() <= legs / PLAN_RATE_HZ,
            "{flown} against {known}"
        );
    }

    #[test]
    fn a_plan_too_slow_to_fly_is_refused_without_flying_it() {
        // 30 m at a millimetre a second: 30 000 s at the speed, plus the ramps.
        let plan = FlightPlan::new(vec![[0.0; 3], [0.0, 0.0, 30.0]], vec![Some(1e-3)]).unwrap();
        assert!(fly_plan(&plan, "slow").is_ok());
        let plan = FlightPlan::new(vec![[0.0; 3], [0.0, 0.0, 50.0]], vec![Some(1e-3)]).unwrap();
        match fly_plan(&plan, "slow") {
            Err(PlanError::TooLongToFly { seconds }) => assert!(seconds > MAX_FLOWN_S),
            other => panic!("{:?}", other.map(|f| f.duration())),
        }
    }
}
