//! A flight made from a plan: a multicopter flying it as an autopilot without splines does
//! (reference §16), and inspection missions that hover at their points, for the mission station's
//! holds (`sweep --mission`, docs/mission.md).

use super::plan::FlightPlan;
use super::Trajectory;
use crate::math::distance;
use crate::rng::Rng;

/// The acceleration and braking of [`fly_plan`], m/s²: ArduPilot's default waypoint
/// acceleration (`WPNAV_ACCEL`, 2.5 m/s²) rounded down.
pub const PLAN_ACCEL: f64 = 2.0;
/// The sample rate of [`fly_plan`]'s flights, Hz: a flight log's GPS and EKF rate.
pub const PLAN_RATE_HZ: f64 = 25.0;
/// The speed of a leg whose plan gives none, m/s ([`fly_plan`]).
pub const PLAN_CRUISE: f64 = 5.0;

/// The flight of a multicopter that flies `plan` from rest: on each leg it speeds up to the leg's
/// planned speed ([`PLAN_CRUISE`] where the plan gives none) and brakes to a stop at the next
/// waypoint, both at [`PLAN_ACCEL`] (a leg too short for the speed peaks lower), then hovers
/// there for the waypoint's hold; sampled at [`PLAN_RATE_HZ`] with its velocities and
/// accelerations. No wind and no corner cutting: the plan flown exactly, a best case for a
/// station that knows it.
///
/// ```
/// use loratrack::{fly_plan, FlightPlan};
/// let plan = FlightPlan::with_holds(vec![[0.0; 3], [100.0, 0.0, 0.0]], vec![Some(10.0)], vec![0.0, 20.0]).unwrap();
/// let flight = fly_plan(&plan, "demo");
/// // 5 s to reach 10 m/s, 5 s at it, 5 s to stop after 100 m, then the 20 s hold.
/// assert!((flight.duration() - 35.0).abs() < 0.05);
/// ```
pub fn fly_plan(plan: &FlightPlan, name: &str) -> Trajectory {
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
        let (from, to) = (w[leg], w[leg + 1]);
        let length = distance(&from, &to);
        let u: [f64; 3] = core::array::from_fn(|k| (to[k] - from[k]) / length);
        let cruise = plan.leg_speed(leg).unwrap_or(PLAN_CRUISE);
        let top = cruise.min((PLAN_ACCEL * length).sqrt());
        let ramp = top / PLAN_ACCEL;
        let total = 2.0 * ramp + (length - top * ramp) / top;
        for j in 0..(total / dt).ceil() as usize {
            let tau = j as f64 * dt;
            let left = total - tau;
            let (s, v, a) = if tau < ramp {
                (PLAN_ACCEL * tau * tau / 2.0, PLAN_ACCEL * tau, PLAN_ACCEL)
            } else if left > ramp {
                (top * (tau - ramp / 2.0), top, 0.0)
            } else {
                (
                    length - PLAN_ACCEL * left * left / 2.0,
                    PLAN_ACCEL * left,
                    -PLAN_ACCEL,
                )
            };
            sample(
                core::array::from_fn(|k| from[k] + u[k] * s),
                u.map(|c| c * v),
                u.map(|c| c * a),
            );
        }
        for _ in 0..(plan.holds()[leg + 1] / dt).round() as usize {
            sample(to, [0.0; 3], [0.0; 3]);
        }
    }
    sample(w[w.len() - 1], [0.0; 3], [0.0; 3]);
    // Finite samples at increasing times from a valid plan: always a flight.
    Trajectory::new(name.to_string(), t, pos, vel, acc).expect("a flown plan is a valid flight")
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
        let f = fly_plan(&plan, "test");
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
    fn an_inspection_is_the_same_for_its_seed_and_another_for_another() {
        assert_eq!(inspection_plan(3), inspection_plan(3));
        assert_ne!(inspection_plan(3), inspection_plan(4));
        let minutes = fly_plan(&inspection_plan(1), "i").duration() / 60.0;
        assert!((30.0..50.0).contains(&minutes), "{minutes}");
    }
}
