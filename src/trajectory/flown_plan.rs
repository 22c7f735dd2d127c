//! A flight made from a plan: a multicopter flying it as an autopilot without splines does
//! (reference §16), and inspection missions that hover at their points, for the mission station's
//! holds (`sweep --mission`, docs/mission.md).

use super::plan::FlightPlan;
use super::{PlanError, Trajectory, MAX_ROWS};
use crate::math::distance;
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

/// One leg as [`fly_plan`] flies it: a trapezoid of speed from rest to rest.
struct Leg {
    from: [f64; 3],
    /// Unit vector along the leg.
    u: [f64; 3],
    length: f64,
    /// The peak speed, m/s, and the time to reach it, s.
    top: f64,
    ramp: f64,
    /// Seconds from the leg's start to rest at its end.
    total: f64,
}

impl Leg {
    fn of(plan: &FlightPlan, leg: usize) -> Leg {
        let w = plan.waypoints();
        let (from, to) = (w[leg], w[leg + 1]);
        let length = distance(&from, &to);
        let cruise = plan.flown_speed(leg, PLAN_CRUISE);
        let top = cruise.min((PLAN_ACCEL * length).sqrt());
        let ramp = top / PLAN_ACCEL;
        Leg {
            from,
            u: core::array::from_fn(|k| (to[k] - from[k]) / length),
            length,
            top,
            ramp,
            total: 2.0 * ramp + (length - top * ramp) / top,
        }
    }

    /// Position along the leg, speed and acceleration (m, m/s, m/s²) `tau` s into it.
    fn at(&self, tau: f64) -> (f64, f64, f64) {
        let left = self.total - tau;
        if tau < self.ramp {
            (PLAN_ACCEL * tau * tau / 2.0, PLAN_ACCEL * tau, PLAN_ACCEL)
        } else if left > self.ramp {
            (self.top * (tau - self.ramp / 2.0), self.top, 0.0)
        } else {
            (
                self.length - PLAN_ACCEL * left * left / 2.0,
                PLAN_ACCEL * left,
                -PLAN_ACCEL,
            )
        }
    }
}

/// How long [`fly_plan`] takes to fly `plan`, s: its legs and its holds.
///
/// ```
/// use loratrack::{flown_duration, FlightPlan};
/// let plan = FlightPlan::with_holds(vec![[0.0; 3], [100.0, 0.0, 0.0]], vec![Some(10.0)], vec![0.0, 20.0]).unwrap();
/// assert!((flown_duration(&plan) - 35.0).abs() < 1e-9);
/// ```
pub fn flown_duration(plan: &FlightPlan) -> f64 {
    let legs: f64 = (0..plan.waypoints().len() - 1)
        .map(|leg| Leg::of(plan, leg).total)
        .sum();
    legs + plan.holds().iter().sum::<f64>()
}

/// The flight of a multicopter that flies `plan` from rest: on each leg it speeds up to the leg's
/// planned speed ([`PLAN_CRUISE`] where the plan gives none; slower on a leg too steep for the
/// plan's [`ClimbLimits`](crate::ClimbLimits), [`FlightPlan::flown_speed`]) and brakes to a stop
/// at the next waypoint, both at [`PLAN_ACCEL`] (a leg too short for the speed peaks lower), then hovers
/// there for the waypoint's hold; sampled at [`PLAN_RATE_HZ`] with its velocities and
/// accelerations. No wind and no corner cutting: the plan flown exactly, a best case for a
/// station that knows it. Refuses a plan that takes longer than [`MAX_FLOWN_S`] to fly
/// ([`PlanError::TooLongToFly`]; an unlimited loiter holds for a day).
///
/// ```
/// use loratrack::{fly_plan, FlightPlan};
/// let plan = FlightPlan::with_holds(vec![[0.0; 3], [100.0, 0.0, 0.0]], vec![Some(10.0)], vec![0.0, 20.0]).unwrap();
/// let flight = fly_plan(&plan, "demo").unwrap();
/// // 5 s to reach 10 m/s, 5 s at it, 5 s to stop after 100 m, then the 20 s hold.
/// assert!((flight.duration() - 35.0).abs() < 0.05);
/// ```
pub fn fly_plan(plan: &FlightPlan, name: &str) -> Result<Trajectory, PlanError> {
    let seconds = flown_duration(plan);
    if seconds.is_nan() || seconds > MAX_FLOWN_S {
        return Err(PlanError::TooLongToFly { seconds });
    }
    let dt = 1.0 / PLAN_RATE_HZ;
    let (mut t, mut pos, mut vel, mut acc) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut sample = |p: [f64; 3], v: [f64; 3], a: [f64; 3]| {
        t.push(t.len() as f64 * dt);
        pos.push(p);
        vel.push(v);
        acc.push(a);
    };
    let w = plan.waypoints();
    for leg in 0..w.len() - 1 {
        let l = Leg::of(plan, leg);
        for j in 0..(l.total / dt).ceil() as usize {
            let (s, v, a) = l.at(j as f64 * dt);
            sample(
                core::array::from_fn(|k| l.from[k] + l.u[k] * s),
                l.u.map(|c| c * v),
                l.u.map(|c| c * a),
            );
        }
        for _ in 0..(plan.holds()[leg + 1] / dt).round() as usize {
            sample(w[leg + 1], [0.0; 3], [0.0; 3]);
        }
    }
    sample(w[w.len() - 1], [0.0; 3], [0.0; 3]);
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
    fn the_flight_stops_at_every_waypoint_and_hovers_for_its_hold() {
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
