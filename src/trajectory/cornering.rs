//! How an autopilot flies through a waypoint it need not stop at (reference §16): it turns onto
//! the next leg on an arc, a multicopter's passing close to the waypoint and slowed only as much
//! as the turn asks, a plane's begun early and flown at its speed, for the flown plan
//! ([`crate::fly_plan`]) and the mission station's pace alike.

use super::plan::FlightPlan;
use crate::math::{acos, cos, distance, tan};
use core::f64::consts::{FRAC_PI_2, PI};

/// How close to a waypoint flown through the path passes, m: ArduPilot Copter's waypoint radius
/// (`WPNAV_RADIUS`, 2 m by default), within which its S-curves cut a corner.
pub const CORNER_RADIUS: f64 = 2.0;
/// The sideways acceleration in a corner, m/s²: twice the along-track one, as ArduPilot's
/// cornering acceleration (`WPNAV_ACCEL_C`) is twice `WPNAV_ACCEL` by default (Copter 4.5).
pub const CORNER_ACCEL: f64 = 2.0 * super::PLAN_ACCEL;

/// How far before a waypoint a fixed-wing aircraft may begin its turn onto the next leg, m:
/// ArduPlane's waypoint radius (`WP_RADIUS`, 90 m by default).
pub const PLANE_WP_RADIUS: f64 = 90.0;
/// ArduPlane's L1 navigation period (`NAVL1_PERIOD`, 17 s) and damping (`NAVL1_DAMPING`, 0.75):
/// the L1 distance, which bounds how early a turn begins, is period × damping / π × speed (73 m
/// at 18 m/s; `AP_L1_Control`).
const L1_PERIOD: f64 = 17.0;
const L1_DAMPING: f64 = 0.75;

/// How an autopilot turns through a waypoint it flies through: the vehicle a plan is flown as
/// and a bounded station holds the drone to (as [`VehicleChoice`] sets it or the plan file says;
/// JSON `config.planCornering`, `multicopter` or `fixed-wing`, so a page can say which).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum Cornering {
    /// A multicopter's (ArduPilot Copter's S-curves): an arc passing [`CORNER_RADIUS`] from the
    /// waypoint, slowed to within [`CORNER_ACCEL`] sideways.
    #[default]
    Multicopter,
    /// A fixed-wing aircraft's (ArduPlane's L1 navigation): the turn begins where ArduPlane
    /// counts the waypoint reached (`AP_L1_Control::turn_distance`: the L1 distance, at most
    /// [`PLANE_WP_RADIUS`], scaled down for turns under 90°), on the arc tangent to both legs from
    /// there, at the legs' speed: a plane holds its airspeed through a turn (ArduPlane's TECS)
    /// and banks instead. The 90° corner a multicopter takes at 4.4 m/s on a 4.8 m arc, a plane
    /// at 18 m/s takes on a 73 m arc (a 24° bank). Where the legs are too short for the arc, it
    /// is tightened to fit them, as for a multicopter, though a real plane turning it would bank
    /// past its 45° limit (ArduPlane's `ROLL_LIMIT_DEG`) and swing wide instead.
    FixedWing,
}

/// Which vehicle the drone is (`--vehicle`, JS `vehicle`; reference §16): as its plan file says,
/// or set. It decides how a plan is flown and followed (a plane turns wide at its speed, flies
/// through a waypoint's hold and climbs faster: [`Cornering`], [`ClimbLimits`]) and the top speed
/// a bounded or mission station holds the drone to ([`Bounds::for_vehicle`]). Set it for a plane's
/// CSV log, waypoint list or CSV plan without a [`VEHICLE_MARK`](crate::VEHICLE_MARK) line, which
/// do not say which vehicle flew them.
///
/// [`ClimbLimits`]: crate::ClimbLimits
/// [`Bounds::for_vehicle`]: crate::Bounds::for_vehicle
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum VehicleChoice {
    /// A QGroundControl `.plan`'s `vehicleType` or a CSV plan's `# vehicle:` line; a multicopter
    /// for every other plan and flight (the paper's drone, the synthetic set and the Canberra
    /// flight are multicopters).
    #[default]
    Auto,
    /// A multicopter, whatever the plan file says.
    Multicopter,
    /// A fixed-wing aircraft (ArduPlane), whatever the plan file says.
    FixedWing,
}

impl Cornering {
    /// Both vehicles, the multicopter first.
    pub const ALL: [Cornering; 2] = [Cornering::Multicopter, Cornering::FixedWing];

    /// Its name in JSON (`config.planCornering`), in `--vehicle` and in a CSV plan's
    /// [`VEHICLE_MARK`](super::VEHICLE_MARK) line: `multicopter` or `fixed-wing`.
    pub fn name(self) -> &'static str {
        match self {
            Cornering::Multicopter => "multicopter",
            Cornering::FixedWing => "fixed-wing",
        }
    }
}

impl VehicleChoice {
    /// The vehicle set, or `None` to take the plan file's.
    pub fn given(self) -> Option<Cornering> {
        match self {
            VehicleChoice::Auto => None,
            VehicleChoice::Multicopter => Some(Cornering::Multicopter),
            VehicleChoice::FixedWing => Some(Cornering::FixedWing),
        }
    }
}

/// The smallest arc radius a waypoint is turned on, m; a sharper turn (the path doubling back)
/// is flown by stopping there.
const MIN_ARC: f64 = 0.01;

/// A turn through a waypoint: the arc tangent to both legs that passes [`CORNER_RADIUS`] from the
/// waypoint (a multicopter's; a plane's begins earlier, [`Cornering::FixedWing`]), tighter where a
/// leg is too short for it, flown at one speed.
///
/// ```
/// use loratrack::{corners, FlightPlan};
/// let plan = FlightPlan::new(vec![[0.0, 0.0, 10.0], [100.0, 0.0, 10.0], [100.0, 100.0, 10.0]], vec![Some(8.0), Some(8.0)]).unwrap();
/// let turn = corners(&plan)[1].unwrap();
/// // A right angle: an arc of 4.8 m radius, entered 4.8 m before the waypoint, flown at 4.4 m/s
/// // (4 m/s² sideways).
/// assert!((turn.radius - 4.83).abs() < 0.01 && (turn.cut - turn.radius).abs() < 1e-9);
/// assert!((turn.speed - (4.0 * turn.radius).sqrt()).abs() < 1e-9);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// How far before and after the waypoint the arc meets the legs, m.
    pub cut: f64,
    /// The arc's radius, m (infinite where the legs run straight on).
    pub radius: f64,
    /// The change of direction, rad (0 to π).
    pub turn: f64,
    /// The speed through the arc, m/s: within the sideways acceleration ([`CORNER_ACCEL`]; a
    /// plane's is not limited, [`Cornering::FixedWing`]), the two legs' speeds, and what the legs
    /// on either side let the vehicle reach or brake from.
    pub speed: f64,
}

impl Corner {
    /// The arc's length, m.
    pub fn length(&self) -> f64 {
        if self.turn == 0.0 {
            0.0
        } else {
            self.radius * self.turn
        }
    }
}

/// How `plan` is flown at each waypoint: `None` where the vehicle stops (the first and the last,
/// a waypoint with a hold, one where the path doubles back), and the [`Corner`] it turns on
/// elsewhere (a plane's last waypoint in the air: a corner of no turn, flown through at its
/// speed). Only a plan for an autopilot (one with [`ClimbLimits`]) has corners: a plan traced
/// through a flight has none, its leg speeds being the flight's own, so [`crate::fly_plan`] flies
/// it from rest to rest on every leg and [`CornerSpeeds`] leaves the mission station's pace on it
/// unlimited.
///
/// The speeds respect the along-track acceleration [`PLAN_ACCEL`](super::PLAN_ACCEL): a corner
/// is flown no faster than the straight before it lets the vehicle reach, nor than the straight
/// after it lets it brake from (one pass forward, one back, as a trajectory planner's).
///
/// [`ClimbLimits`]: crate::ClimbLimits
pub fn corners(plan: &FlightPlan) -> Vec<Option<Corner>> {
    passed(plan, super::PLAN_CRUISE)
}

/// [`corners`], each corner's speed held within its legs' flown speeds, `unplanned` m/s on a leg
/// the plan gives none (within the climb limits all the same).
fn passed(plan: &FlightPlan, unplanned: f64) -> Vec<Option<Corner>> {
    let w = plan.waypoints();
    let n = w.len();
    let mut out: Vec<Option<Corner>> = (0..n).map(|k| turn_at(plan, k, unplanned)).collect();
    // The straight of a leg between the corners at its ends, m.
    let straight = |out: &[Option<Corner>], leg: usize| {
        distance(&w[leg], &w[leg + 1])
            - out[leg].map_or(0.0, |c| c.cut)
            - out[leg + 1].map_or(0.0, |c| c.cut)
    };
    let reach = |from: f64, length: f64| (from * from + 2.0 * super::PLAN_ACCEL * length).sqrt();
    for k in 1..n {
        let before = out[k - 1].map_or(0.0, |c| c.speed);
        let length = straight(&out, k - 1);
        if let Some(c) = &mut out[k] {
            c.speed = c.speed.min(reach(before, length));
        }
    }
    for k in (0..n - 1).rev() {
        let after = out[k + 1].map_or(0.0, |c| c.speed);
        let length = straight(&out, k);
        if let Some(c) = &mut out[k] {
            c.speed = c.speed.min(reach(after, length));
        }
    }
    out
}

/// The fastest a vehicle flying a plan may be anywhere along it, given how it passes each
/// waypoint ([`corners`]): braking at [`PLAN_ACCEL`](super::PLAN_ACCEL) into each corner and each
/// stop, and speeding up at it out of them. The mission station paces the drone within it.
///
/// ```
/// use loratrack::{CornerSpeeds, FlightPlan};
/// let plan = FlightPlan::new(vec![[0.0, 0.0, 10.0], [100.0, 0.0, 10.0], [100.0, 100.0, 10.0]], vec![Some(8.0), Some(8.0)]).unwrap();
/// let caps = CornerSpeeds::of(&plan);
/// // From rest at the start, 2 m/s² for 4 m: 4 m/s.
/// assert!((caps.cap(4.0) - 4.0).abs() < 1e-9);
/// // Far from every corner, nothing.
/// assert!(caps.cap(50.0) > 8.0);
/// // Entering the right angle's arc, 4.8 m before it, its speed through it (4.4 m/s).
/// assert!((caps.cap(100.0 - 4.83) - 4.4).abs() < 0.01);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CornerSpeeds {
    at: Vec<Pass>,
}

/// How a waypoint is passed, along the plan's straight legs.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pass {
    /// The waypoint's distance along the plan, m, and the corner's cut on either side of it.
    along: f64,
    cut: f64,
    /// The speed through it, m/s: 0 at a stop, infinite where no limit applies.
    speed: f64,
    /// The legs' length within the cut over the arc's, so that the plan's straight legs are
    /// covered within the cut in the time the arc takes.
    stretch: f64,
}

impl CornerSpeeds {
    /// The limits of `plan`: none for a plan traced through a flight (whose leg speeds are the
    /// flight's own) and none at a waypoint with a hold (the mission station brakes into a hold
    /// and leaves it by its own rules).
    pub fn of(plan: &FlightPlan) -> Self {
        let autopilot = plan.climbs().is_some();
        // A leg without a planned speed (every leg with `--plan-pace packet`) sets no limit: the
        // station follows the packet's speed there, which need not be the flown plan's cruise.
        let at = passed(plan, f64::INFINITY)
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let along = plan.along_at(k);
                let free = Pass {
                    along,
                    cut: 0.0,
                    speed: f64::INFINITY,
                    stretch: 1.0,
                };
                match c {
                    _ if !autopilot || plan.holds()[k] > 0.0 => free,
                    Some(c) => Pass {
                        cut: c.cut,
                        speed: c.speed,
                        stretch: if c.length() > 0.0 {
                            2.0 * c.cut / c.length()
                        } else {
                            1.0
                        },
                        ..free
                    },
                    None => Pass { speed: 0.0, ..free },
                }
            })
            .collect();
        CornerSpeeds { at }
    }

    /// The fastest the vehicle may move along the plan's legs `along` m along it, m/s: within
    /// reach of the corners and stops on either side, and within a corner's cut its speed
    /// through the arc, scaled to the legs' longer way round.
    pub fn cap(&self, along: f64) -> f64 {
        let next = self.at.partition_point(|p| p.along < along);
        let near = [next.checked_sub(1), Some(next)];
        near.into_iter()
            .flatten()
            .filter_map(|k| self.at.get(k))
            .map(|p| {
                let gap = (along - p.along).abs() - p.cut;
                if gap <= 0.0 {
                    p.speed * p.stretch
                } else {
                    (p.speed * p.speed + 2.0 * super::PLAN_ACCEL * gap).sqrt()
                }
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// The turn at waypoint `k` before the speed passes, or `None` where the vehicle stops there.
fn turn_at(plan: &FlightPlan, k: usize, unplanned: f64) -> Option<Corner> {
    let w = plan.waypoints();
    if plan.climbs().is_none() || k == 0 || plan.holds()[k] > 0.0 {
        return None;
    }
    if k + 1 == w.len() {
        // A plane cannot stop in the air: it flies on through its last waypoint (ArduPlane then
        // loiters there) unless it lands on it.
        let airborne = plan.cornering() == Cornering::FixedWing && w[k][2] > 0.0;
        return airborne.then(|| Corner {
            cut: 0.0,
            radius: f64::INFINITY,
            turn: 0.0,
            speed: plan.flown_speed(k - 1, unplanned),
        });
    }
    let (len_in, len_out) = (distance(&w[k - 1], &w[k]), distance(&w[k], &w[k + 1]));
    let cos_turn = (0..3)
        .map(|i| (w[k][i] - w[k - 1][i]) * (w[k + 1][i] - w[k][i]))
        .sum::<f64>()
        / (len_in * len_out);
    let turn = acos(cos_turn.clamp(-1.0, 1.0));
    let legs = plan
        .flown_speed(k - 1, unplanned)
        .min(plan.flown_speed(k, unplanned));
    if turn == 0.0 {
        return Some(Corner {
            cut: 0.0,
            radius: f64::INFINITY,
            turn,
            speed: legs,
        });
    }
    let half = turn / 2.0;
    let (wanted, sideways) = match plan.cornering() {
        // The arc whose midpoint lies CORNER_RADIUS from the waypoint: r (1 / cos(θ/2) − 1) = R.
        Cornering::Multicopter => (CORNER_RADIUS * cos(half) / (1.0 - cos(half)), CORNER_ACCEL),
        // The arc that meets the leg in where the turn begins: r tan(θ/2) = the turn distance.
        Cornering::FixedWing => {
            let l1 = (L1_DAMPING * L1_PERIOD / PI * legs).min(PLANE_WP_RADIUS);
            let begins = l1 * (turn / FRAC_PI_2).min(1.0);
            (begins / tan(half), f64::INFINITY)
        }
    };
    // Each arc may take at most half of either leg, so that two corners never overlap.
    let by_legs = 0.5 * len_in.min(len_out) / tan(half);
    let radius = wanted.min(by_legs);
    if radius.is_nan() || radius < MIN_ARC {
        return None;
    }
    Some(Corner {
        cut: radius * tan(half),
        radius,
        turn,
        speed: legs.min((sideways * radius).sqrt()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ClimbLimits;

    fn plan(points: Vec<[f64; 3]>, speed: f64) -> FlightPlan {
        let legs = points.len() - 1;
        FlightPlan::new(points, vec![Some(speed); legs]).unwrap()
    }

    /// The names a CSV plan's vehicle line and `--vehicle` use are the JSON ones.
    #[test]
    fn a_vehicles_name_is_its_json_and_setting_name() {
        for v in Cornering::ALL {
            assert_eq!(
                serde_json::to_string(&v).unwrap(),
                format!("\"{}\"", v.name())
            );
            let choice: VehicleChoice = serde_json::from_value(v.name().into()).unwrap();
            assert_eq!(choice.given(), Some(v));
        }
    }

    #[test]
    fn a_gentle_turn_keeps_the_legs_speed_and_a_sharp_one_slows() {
        let gentle = plan(vec![[0.0; 3], [100.0, 0.0, 0.0], [200.0, 20.0, 0.0]], 8.0);
        let c = corners(&gentle)[1].unwrap();
        assert_eq!(c.speed, 8.0);
        assert!(c.radius > 50.0, "{}", c.radius);
        let sharp = plan(vec![[0.0; 3], [100.0, 0.0, 0.0], [0.0, 10.0, 0.0]], 8.0);
        let c = corners(&sharp)[1].unwrap();
        assert!(c.speed < 1.5, "{}", c.speed);
        // The arc's midpoint lies the corner radius from the waypoint.
        let mid = c.radius / (c.turn / 2.0).cos() - c.radius;
        assert!((mid - CORNER_RADIUS).abs() < 1e-9, "{mid}");
    }

    fn plane(points: Vec<[f64; 3]>, speed: f64) -> FlightPlan {
        plan(points, speed)
            .with_climb(Some(ClimbLimits::FIXED_WING))
            .with_cornering(Cornering::FixedWing)
    }

    #[test]
    fn a_plane_turns_a_right_angle_at_its_speed_on_an_arc_begun_an_l1_distance_early() {
        let points = vec![[0.0, 0.0, 80.0], [400.0, 0.0, 80.0], [400.0, 400.0, 80.0]];
        let c = corners(&plane(points.clone(), 18.0))[1].unwrap();
        // ArduPlane's L1 distance at 18 m/s: 0.75 × 17 / π × 18 = 73 m, under WP_RADIUS (90 m).
        let l1 = 0.75 * 17.0 / PI * 18.0;
        assert!(
            (c.cut - l1).abs() < 1e-9 && (c.radius - l1).abs() < 1e-9,
            "{c:?}"
        );
        assert_eq!(c.speed, 18.0);
        // A multicopter on the same legs passes 2 m from the waypoint, slowed to 4.4 m/s.
        let copter = corners(&plan(points.clone(), 18.0))[1].unwrap();
        assert!(copter.radius < 5.0 && copter.speed < 4.5, "{copter:?}");
        // Faster, the turn begins no earlier than the waypoint radius.
        let fast = corners(&plane(points, 30.0))[1].unwrap();
        assert!((fast.cut - PLANE_WP_RADIUS).abs() < 1e-9, "{fast:?}");
    }

    #[test]
    fn a_plane_begins_a_gentle_turn_later_and_never_slows_for_a_tight_one() {
        // 30°: the turn distance scaled by 30 / 90.
        let gentle = plane(
            vec![[0.0; 3], [400.0, 0.0, 0.0], [400.0 + 346.4, 200.0, 0.0]],
            18.0,
        );
        let c = corners(&gentle)[1].unwrap();
        let l1 = 0.75 * 17.0 / PI * 18.0;
        assert!((c.turn - PI / 6.0).abs() < 1e-4, "{}", c.turn);
        assert!((c.cut - l1 * c.turn / FRAC_PI_2).abs() < 1e-9, "{c:?}");
        assert_eq!(c.speed, 18.0);
        // Two right angles 40 m apart: each arc takes half of the 40 m leg, a 20 m radius, flown
        // at 18 m/s all the same (a multicopter slows to 8.9 m/s).
        let tight = plane(
            vec![
                [0.0; 3],
                [400.0, 0.0, 0.0],
                [400.0, 40.0, 0.0],
                [800.0, 40.0, 0.0],
            ],
            18.0,
        );
        let c = corners(&tight)[1].unwrap();
        assert!((c.radius - 20.0).abs() < 1e-9, "{c:?}");
        assert_eq!(c.speed, 18.0);
        let copter = corners(&plan(tight.waypoints().to_vec(), 18.0))[1].unwrap();
        assert!(copter.speed < 9.0, "{copter:?}");
    }

    #[test]
    fn a_plane_flies_through_its_last_waypoint_in_the_air_and_stops_where_it_lands() {
        let up = plane(vec![[0.0; 3], [400.0, 0.0, 80.0], [800.0, 0.0, 80.0]], 18.0);
        let last = corners(&up)[2].unwrap();
        assert_eq!((last.turn, last.cut, last.speed), (0.0, 0.0, 18.0));
        let landing = plane(vec![[0.0; 3], [400.0, 0.0, 80.0], [800.0, 0.0, 0.0]], 18.0);
        assert!(corners(&landing)[2].is_none());
        // A multicopter stops at its last waypoint, in the air or not.
        assert!(corners(&plan(up.waypoints().to_vec(), 18.0))[2].is_none());
    }

    #[test]
    fn the_vehicle_stops_at_ends_holds_reversals_and_on_traced_plans() {
        let points = vec![
            [0.0; 3],
            [100.0, 0.0, 0.0],
            [100.0, 50.0, 0.0],
            [0.0, 50.0, 0.0],
        ];
        let held = FlightPlan::with_holds(
            points.clone(),
            vec![Some(5.0); 3],
            vec![0.0, 0.0, 10.0, 0.0],
        )
        .unwrap();
        let c = corners(&held);
        assert!(c[0].is_none() && c[1].is_some() && c[2].is_none() && c[3].is_none());
        let back = plan(vec![[0.0; 3], [100.0, 0.0, 0.0], [0.0, 0.0, 0.0]], 5.0);
        assert!(corners(&back)[1].is_none());
        let traced = plan(points, 5.0).with_climb(None);
        assert!(corners(&traced).iter().all(Option::is_none));
    }

    #[test]
    fn corner_speeds_are_within_reach_of_the_straights_beside_them() {
        // Short legs between right angles: each corner is within what 2 m/s² reaches from rest.
        let zigzag = plan(
            vec![
                [0.0; 3],
                [3.0, 0.0, 0.0],
                [3.0, 30.0, 0.0],
                [60.0, 30.0, 0.0],
            ],
            10.0,
        );
        let c = corners(&zigzag);
        let first = c[1].unwrap();
        let straight = 3.0 - first.cut;
        assert!(first.speed <= (2.0 * super::super::PLAN_ACCEL * straight).sqrt() + 1e-9);
        // Within half of the 3 m leg.
        assert!(first.cut <= 1.5 + 1e-9, "{}", first.cut);
        assert!(c[2].unwrap().speed > 0.0);
    }

    #[test]
    fn on_legs_without_speeds_the_paces_limits_come_from_the_turn_alone() {
        // A 30° turn on legs without speeds: flown at the cruise speed, but a drone flying them
        // faster (the packet's pace) need not slow there.
        let points = vec![[0.0; 3], [200.0, 0.0, 0.0], [373.2, 100.0, 0.0]];
        let plan = FlightPlan::new(points, vec![None, None]).unwrap();
        assert_eq!(corners(&plan)[1].unwrap().speed, super::super::PLAN_CRUISE);
        let turn = (CORNER_ACCEL * corners(&plan)[1].unwrap().radius).sqrt();
        assert!(turn > 10.0, "{turn}");
        assert!(CornerSpeeds::of(&plan).cap(200.0) >= turn);
    }

    #[test]
    fn a_climb_limited_leg_caps_the_corner() {
        let climb = plan(
            vec![[0.0, 0.0, 10.0], [50.0, 0.0, 10.0], [60.0, 0.0, 40.0]],
            8.0,
        );
        let up = climb.flown_speed(1, 8.0);
        assert!(up < 8.0);
        assert!(corners(&climb)[1].unwrap().speed <= up);
        assert_eq!(
            ClimbLimits::MULTICOPTER.speed_along(30.0 / climb_leg(), 8.0),
            up
        );
    }

    fn climb_leg() -> f64 {
        (10.0f64 * 10.0 + 30.0 * 30.0).sqrt()
    }
}
