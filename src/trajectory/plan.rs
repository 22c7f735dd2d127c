//! A mission plan: the waypoints a drone is told to fly, in order, in the flight's local frame
//! (reference §16). The mission-aware station ([`MissionStation`](crate::sim::MissionStation))
//! predicts along it between packets.

use super::plan_file::PlanError;
use super::{ClimbLimits, Cornering, Trajectory};
use crate::math::distance;

/// At most this many waypoints (a QGroundControl mission rarely has more than a few hundred).
pub const MAX_WAYPOINTS: usize = 10_000;
/// The largest |coordinate| of a waypoint, m: as for a CSV flight.
pub const MAX_PLAN_COORDINATE: f64 = 1.0e6;
/// The largest planned speed, m/s: as for a CSV flight.
pub const MAX_PLAN_SPEED: f64 = 300.0;
/// The longest hold at a waypoint, s: a day.
pub const MAX_HOLD: f64 = 86_400.0;
/// How far the flown path of a synthetic flight may stray from the plan traced through it, m
/// ([`FlightPlan::traced`]): a mission planner's waypoints on a curve, every few metres of sagitta.
pub const TRACE_TOLERANCE: f64 = 2.0;

/// Waypoints joined by straight legs, with an optional planned ground speed per leg and a time
/// the drone holds (hovers) at each waypoint.
///
/// Positions are ENU metres in the flight's frame; `along` is the distance flown along the legs.
/// A plan for an autopilot (as every constructor but [`FlightPlan::traced`] makes one) is flown
/// within its vehicle's [`ClimbLimits`] ([`FlightPlan::flown_speed`]).
///
/// ```
/// use loratrack::FlightPlan;
/// let plan = FlightPlan::new(vec![[0.0, 0.0, 10.0], [100.0, 0.0, 10.0], [100.0, 50.0, 10.0]], vec![None, Some(5.0)]).unwrap();
/// assert_eq!(plan.length(), 150.0);
/// assert_eq!(plan.point_at(120.0), [100.0, 20.0, 10.0]);
/// assert_eq!(plan.speed_at(120.0), Some(5.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct FlightPlan {
    points: Vec<[f64; 3]>,
    /// Distance along the plan at each waypoint, m (0 at the first).
    along: Vec<f64>,
    /// Planned ground speed on leg i (from waypoint i to i + 1), m/s.
    speeds: Vec<Option<f64>>,
    /// Seconds the drone holds at waypoint i before it flies on (MAVLink `NAV_WAYPOINT`'s hold,
    /// `NAV_LOITER_TIME`, `NAV_DELAY`); 0 for most.
    holds: Vec<f64>,
    /// The autopilot's climb and descent limits on each leg; `None` for a plan traced through a
    /// flight, whose leg speeds are the flight's own.
    climbs: Option<Vec<ClimbLimits>>,
    /// How the autopilot turns through the waypoints it flies through.
    cornering: Cornering,
}

/// The nearest point of a plan to a position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OnPlan {
    /// Distance along the plan, m.
    pub along: f64,
    /// Distance from the position to that point, m.
    pub off: f64,
}

impl FlightPlan {
    /// A plan through `points` with `speeds[i]` on the leg from point i to i + 1 (one fewer than
    /// the points; `None` where the plan gives no speed). A waypoint equal to the one before it
    /// is dropped, with its leg. Refuses fewer than two distinct waypoints, more than
    /// [`MAX_WAYPOINTS`], non-finite or absurd values (line numbers count waypoints from 1).
    /// No holds: [`FlightPlan::with_holds`]. Flown within [`ClimbLimits::MULTICOPTER`]
    /// ([`FlightPlan::with_climb`] for another vehicle's).
    pub fn new(points: Vec<[f64; 3]>, speeds: Vec<Option<f64>>) -> Result<Self, PlanError> {
        let holds = vec![0.0; points.len()];
        Self::with_holds(points, speeds, holds)
    }

    /// As [`FlightPlan::new`], with `holds[i]` s held at waypoint i (one per waypoint, each in
    /// 0..=[`MAX_HOLD`]). A dropped repeat's hold is added to the waypoint it repeats, so a
    /// waypoint followed by a timed loiter at the same place holds for both.
    ///
    /// ```
    /// use loratrack::FlightPlan;
    /// let p = FlightPlan::with_holds(vec![[0.0; 3], [50.0, 0.0, 0.0], [50.0, 0.0, 0.0]], vec![None, None], vec![0.0, 10.0, 5.0]).unwrap();
    /// assert_eq!(p.holds(), &[0.0, 15.0]);
    /// ```
    pub fn with_holds(
        points: Vec<[f64; 3]>,
        speeds: Vec<Option<f64>>,
        holds: Vec<f64>,
    ) -> Result<Self, PlanError> {
        let climbs = vec![ClimbLimits::MULTICOPTER; speeds.len()];
        Self::with_holds_and_climbs(points, speeds, holds, climbs)
    }

    /// As [`FlightPlan::with_holds`], with `climbs[i]` the climb limits on the leg from waypoint
    /// i (one per leg, as the speeds; a mission that changes its climb or descent speed on the
    /// way), each in (0, [`MAX_PLAN_SPEED`]] m/s. A dropped repeat's leg takes its limits with it.
    pub fn with_holds_and_climbs(
        points: Vec<[f64; 3]>,
        speeds: Vec<Option<f64>>,
        holds: Vec<f64>,
        climbs: Vec<ClimbLimits>,
    ) -> Result<Self, PlanError> {
        check_climbs(&climbs, speeds.len())?;
        check_holds(&holds, points.len())?;
        check_waypoints(&points, &speeds)?;
        let plan = Self::joined(points, speeds, holds, climbs);
        if plan.points.len() < 2 {
            return Err(PlanError::TooFewWaypoints);
        }
        Ok(plan)
    }

    /// The plan through `points` (checked), a waypoint that repeats the one before (a leg of
    /// zero length) dropped with its leg, its hold added to the one it repeats (at most
    /// [`MAX_HOLD`]).
    fn joined(
        points: Vec<[f64; 3]>,
        speeds: Vec<Option<f64>>,
        holds: Vec<f64>,
        climbs: Vec<ClimbLimits>,
    ) -> Self {
        let mut plan = FlightPlan {
            points: Vec::with_capacity(points.len()),
            along: Vec::with_capacity(points.len()),
            speeds: Vec::with_capacity(speeds.len()),
            holds: Vec::with_capacity(points.len()),
            climbs: None,
            cornering: Cornering::Multicopter,
        };
        let mut kept_climbs = Vec::with_capacity(climbs.len());
        for (i, p) in points.into_iter().enumerate() {
            match plan.points.last() {
                None => plan.along.push(0.0),
                Some(last) => {
                    let leg = distance(last, &p);
                    if leg == 0.0 {
                        let held = plan.holds.len() - 1;
                        plan.holds[held] = (plan.holds[held] + holds[i]).min(MAX_HOLD);
                        continue;
                    }
                    plan.along.push(plan.along[plan.along.len() - 1] + leg);
                    plan.speeds.push(speeds[i - 1]);
                    kept_climbs.push(climbs[i - 1]);
                }
            }
            plan.points.push(p);
            plan.holds.push(holds[i]);
        }
        plan.climbs = Some(kept_climbs);
        plan
    }

    /// The plan a synthetic flight flies: its path simplified (Douglas–Peucker) until no sample
    /// lies more than `tolerance` m from the legs, each leg's speed its length over the time
    /// the flight took for it. The flight then keeps to its plan within `tolerance`, on time on
    /// average over each leg; a real mission strays further (wind, corner cutting).
    pub fn traced(flight: &Trajectory, tolerance: f64) -> Self {
        let keep = simplify(&flight.pos, tolerance);
        let points: Vec<[f64; 3]> = keep.iter().map(|&i| flight.pos[i]).collect();
        let speeds = keep
            .windows(2)
            .map(|w| {
                let leg = distance(&flight.pos[w[0]], &flight.pos[w[1]]);
                Some((leg / (flight.t[w[1]] - flight.t[w[0]])).clamp(1e-3, MAX_PLAN_SPEED))
            })
            .collect();
        let p = points[0];
        // A flight that never moves traces one point; a leg of a millimetre keeps it a plan.
        let plan = FlightPlan::new(points, speeds).unwrap_or_else(|_| FlightPlan {
            points: vec![p, [p[0] + 1e-3, p[1], p[2]]],
            along: vec![0.0, 1e-3],
            speeds: vec![Some(1e-3)],
            holds: vec![0.0; 2],
            climbs: None,
            cornering: Cornering::Multicopter,
        });
        plan.with_climb(None)
    }

    /// The same plan flown within `climb` on every leg (`None`: at its leg speeds however steep
    /// the leg).
    pub fn with_climb(self, climb: Option<ClimbLimits>) -> Self {
        let legs = self.speeds.len();
        FlightPlan {
            climbs: climb.map(|c| vec![c; legs]),
            ..self
        }
    }

    /// The climb and descent limits each leg is flown within, if any.
    pub fn climbs(&self) -> Option<&[ClimbLimits]> {
        self.climbs.as_deref()
    }

    /// The same plan with its waypoints turned through as `cornering` says (a multicopter's
    /// unless set).
    pub fn with_cornering(self, cornering: Cornering) -> Self {
        FlightPlan { cornering, ..self }
    }

    /// The same plan flown as `vehicle` flies a plan that does not say which vehicle it is for
    /// (a CSV, [`parse_plan_as`](super::parse_plan_as)): within its climb limits (a plan traced
    /// through a flight keeps its own leg speeds), turning as it turns, and for a plane through
    /// every hold, as ArduPlane flies through a waypoint's hold time (MAVLink `NAV_WAYPOINT`).
    pub fn flown_as(self, vehicle: Cornering) -> Self {
        let climb = self.climbs.is_some().then(|| ClimbLimits::of(vehicle));
        let plan = match vehicle {
            Cornering::Multicopter => self,
            Cornering::FixedWing => self.without_holds(),
        };
        plan.with_climb(climb).with_cornering(vehicle)
    }

    /// How the autopilot turns through the waypoints it flies through
    /// ([`corners`](super::corners)).
    pub fn cornering(&self) -> Cornering {
        self.cornering
    }

    /// The same waypoints without planned speeds.
    pub fn without_speeds(&self) -> Self {
        FlightPlan {
            speeds: vec![None; self.speeds.len()],
            ..self.clone()
        }
    }

    /// The same waypoints and speeds without holds.
    pub fn without_holds(&self) -> Self {
        FlightPlan {
            holds: vec![0.0; self.holds.len()],
            ..self.clone()
        }
    }

    /// The plan as CSV text that [`parse_plan`](super::parse_plan) reads back to the same plan:
    /// `x,y,z,speed`, and `hold` where any waypoint has one, every number in its shortest
    /// round-trip form; a plan traced through a flight begins with
    /// [`TRACED_MARK`](super::TRACED_MARK), so that it is read back as one, and a plane's plan
    /// with [`VEHICLE_MARK`](super::VEHICLE_MARK) `fixed-wing`, so that it is read back as a
    /// plane's (its climb limits, its turns, no holds: [`FlightPlan::flown_as`]). Climb limits
    /// other than the vehicle's own (a `.plan`'s `DO_CHANGE_SPEED` of a climb or descent speed)
    /// are not written: a CSV plan has no column for them.
    pub fn to_csv(&self) -> String {
        let with_holds = self.holds.iter().any(|&h| h > 0.0);
        let mut out = match self.climbs {
            None => format!("{}\n", super::TRACED_MARK),
            Some(_) => String::new(),
        };
        if self.cornering == Cornering::FixedWing {
            out += &format!("{} {}\n", super::VEHICLE_MARK, self.cornering.name());
        }
        out += if with_holds {
            "x,y,z,speed,hold\n"
        } else {
            "x,y,z,speed\n"
        };
        for (i, p) in self.points.iter().enumerate() {
            let speed = match i.checked_sub(1).and_then(|leg| self.speeds[leg]) {
                Some(v) => format!(",{v}"),
                None if with_holds => ",".into(),
                None => String::new(),
            };
            let hold = if with_holds {
                format!(",{}", self.holds[i])
            } else {
                String::new()
            };
            out += &format!("{},{},{}{speed}{hold}\n", p[0], p[1], p[2]);
        }
        out
    }

    /// Seconds held at each waypoint.
    pub fn holds(&self) -> &[f64] {
        &self.holds
    }

    /// The index of the first waypoint at or past `along` m (the waypoint count past the end).
    pub fn waypoint_at_or_after(&self, along: f64) -> usize {
        self.along.partition_point(|&a| a < along)
    }

    /// The first waypoint from index `from` on that has a hold, with the distance along the plan
    /// at which it stands, m.
    pub fn next_hold(&self, from: usize) -> Option<(usize, f64)> {
        (from..self.points.len())
            .find(|&i| self.holds[i] > 0.0)
            .map(|i| (i, self.along[i]))
    }

    /// The distance along the plan at which waypoint `k` stands, m.
    pub fn along_at(&self, k: usize) -> f64 {
        self.along[k]
    }

    /// The waypoints, m.
    pub fn waypoints(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// Total length along the legs, m.
    pub fn length(&self) -> f64 {
        self.along[self.along.len() - 1]
    }

    /// The leg that contains distance `along` (the last leg past the end).
    fn leg(&self, along: f64) -> usize {
        self.along
            .partition_point(|&a| a <= along)
            .saturating_sub(1)
            .min(self.points.len() - 2)
    }

    /// The point `along` m along the plan, clamped to its ends.
    pub fn point_at(&self, along: f64) -> [f64; 3] {
        let i = self.leg(along);
        let (a, b) = (self.points[i], self.points[i + 1]);
        let w = ((along - self.along[i]) / (self.along[i + 1] - self.along[i])).clamp(0.0, 1.0);
        core::array::from_fn(|k| a[k] + w * (b[k] - a[k]))
    }

    /// The unit direction of the leg at `along`.
    pub fn direction_at(&self, along: f64) -> [f64; 3] {
        let i = self.leg(along);
        let (a, b) = (self.points[i], self.points[i + 1]);
        let len = self.along[i + 1] - self.along[i];
        core::array::from_fn(|k| (b[k] - a[k]) / len)
    }

    /// The planned speed of leg `leg` (from waypoint `leg` to `leg + 1`), m/s, if the plan gives
    /// one.
    pub fn leg_speed(&self, leg: usize) -> Option<f64> {
        self.speeds.get(leg).copied().flatten()
    }

    /// The planned speed of the leg at `along`, m/s, if the plan gives one.
    pub fn speed_at(&self, along: f64) -> Option<f64> {
        self.speeds[self.leg(along)]
    }

    /// The speed along leg `leg` at which the vehicle flies it, m/s: its planned speed
    /// (`otherwise` where the plan gives none), slowed on a steep leg to keep within the plan's
    /// [`ClimbLimits`].
    ///
    /// ```
    /// use loratrack::FlightPlan;
    /// // A take-off to 30 m planned at 5 m/s, then 100 m east with no speed.
    /// let plan = FlightPlan::new(vec![[0.0; 3], [0.0, 0.0, 30.0], [100.0, 0.0, 30.0]], vec![Some(5.0), None]).unwrap();
    /// assert_eq!(plan.flown_speed(0, 8.0), 2.5);
    /// assert_eq!(plan.flown_speed(1, 8.0), 8.0);
    /// ```
    pub fn flown_speed(&self, leg: usize, otherwise: f64) -> f64 {
        self.within_climb(leg, self.speeds[leg].unwrap_or(otherwise))
    }

    /// `speed` (m/s) slowed, on the leg at `along`, to keep within the plan's [`ClimbLimits`].
    pub fn within_climb_at(&self, along: f64, speed: f64) -> f64 {
        self.within_climb(self.leg(along), speed)
    }

    fn within_climb(&self, leg: usize, speed: f64) -> f64 {
        let Some(climb) = self.climbs.as_ref().map(|c| c[leg]) else {
            return speed;
        };
        let rise = (self.points[leg + 1][2] - self.points[leg][2])
            / (self.along[leg + 1] - self.along[leg]);
        climb.speed_along(rise, speed)
    }

    /// The point of the plan nearest to `p` among those between `from` and `to` m along it.
    pub fn nearest(&self, p: &[f64; 3], from: f64, to: f64) -> OnPlan {
        // Every window holds at least the leg it starts on, so the fallback is never taken.
        self.projections(p, from, to)
            .map(|(_, on)| on)
            .min_by(|a, b| a.off.total_cmp(&b.off))
            .unwrap_or_else(|| OnPlan {
                along: from,
                off: distance(p, &self.point_at(from)),
            })
    }

    /// The point of each leg between `from` and `to` m along the plan nearest to `p`, with the
    /// leg's unit direction: a position near a path that passes it more than once has one
    /// near point on each pass.
    pub fn projections(
        &self,
        p: &[f64; 3],
        from: f64,
        to: f64,
    ) -> impl Iterator<Item = ([f64; 3], OnPlan)> + '_ {
        let (from, to) = (from.max(0.0), to.min(self.length()));
        let p = *p;
        (self.leg(from)..self.points.len() - 1)
            .take_while(move |&i| self.along[i] <= to)
            .map(move |i| {
                let (a, b) = (self.points[i], self.points[i + 1]);
                let len = self.along[i + 1] - self.along[i];
                let w: f64 =
                    (0..3).map(|k| (p[k] - a[k]) * (b[k] - a[k])).sum::<f64>() / (len * len);
                let along = (self.along[i] + w.clamp(0.0, 1.0) * len).clamp(from, to);
                let direction = core::array::from_fn(|k| (b[k] - a[k]) / len);
                let off = distance(&p, &self.point_at(along));
                (direction, OnPlan { along, off })
            })
    }
}

/// Indices of the samples Douglas–Peucker keeps so that every sample lies within `tolerance` m
/// of the polyline through them (3D; first and last always kept). Iterative, so a long flight
/// cannot overflow the stack.
fn simplify(points: &[[f64; 3]], tolerance: f64) -> Vec<usize> {
    let n = points.len();
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0, n - 1)];
    while let Some((a, b)) = stack.pop() {
        let (mut worst, mut at) = (0.0, a);
        for (i, p) in points.iter().enumerate().take(b).skip(a + 1) {
            let d = segment_distance(p, &points[a], &points[b]);
            if d > worst {
                (worst, at) = (d, i);
            }
        }
        if worst > tolerance {
            keep[at] = true;
            stack.push((a, at));
            stack.push((at, b));
        }
    }
    (0..n).filter(|&i| keep[i]).collect()
}

/// Distance from `p` to the segment from `a` to `b`, m.
fn segment_distance(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: [f64; 3] = core::array::from_fn(|k| b[k] - a[k]);
    let len2: f64 = ab.iter().map(|c| c * c).sum();
    let w = if len2 == 0.0 {
        0.0
    } else {
        ((0..3).map(|k| (p[k] - a[k]) * ab[k]).sum::<f64>() / len2).clamp(0.0, 1.0)
    };
    distance(p, &core::array::from_fn(|k| a[k] + w * ab[k]))
}

/// Whether `v` may be a plan's speed, m/s: in (0, [`MAX_PLAN_SPEED`]], as a leg's speed and its
/// climb and descent speeds must be.
fn is_plan_speed(v: f64) -> bool {
    v.is_finite() && v > 0.0 && v <= MAX_PLAN_SPEED
}

/// One climb limit per leg of `legs`, each speed in (0, [`MAX_PLAN_SPEED`]] m/s.
fn check_climbs(climbs: &[ClimbLimits], legs: usize) -> Result<(), PlanError> {
    if climbs.len() != legs {
        return Err(PlanError::Invalid(format!(
            "a plan has one climb limit per leg (leg speeds: {legs}, limits: {})",
            climbs.len()
        )));
    }
    if let Some(i) = climbs
        .iter()
        .position(|c| ![c.up, c.down].iter().all(|v| is_plan_speed(*v)))
    {
        return Err(PlanError::Invalid(format!(
            "waypoint {}: climb and descent speeds must be in (0, {MAX_PLAN_SPEED}] m/s",
            i + 2
        )));
    }
    Ok(())
}

/// One hold per waypoint of `waypoints`, each in 0..=[`MAX_HOLD`] s.
fn check_holds(holds: &[f64], waypoints: usize) -> Result<(), PlanError> {
    if holds.len() != waypoints {
        return Err(PlanError::Invalid(format!(
            "a plan has one hold per waypoint (waypoints: {waypoints}, holds: {})",
            holds.len()
        )));
    }
    if let Some(i) = holds
        .iter()
        .position(|h| !(h.is_finite() && (0.0..=MAX_HOLD).contains(h)))
    {
        return Err(PlanError::Invalid(format!(
            "waypoint {}: a hold must be in 0..={MAX_HOLD} s, got {}",
            i + 1,
            holds[i]
        )));
    }
    Ok(())
}

/// At most [`MAX_WAYPOINTS`] waypoints, each coordinate finite and within
/// [`MAX_PLAN_COORDINATE`]; one leg speed fewer, each (where given) in (0,
/// [`MAX_PLAN_SPEED`]] m/s.
fn check_waypoints(points: &[[f64; 3]], speeds: &[Option<f64>]) -> Result<(), PlanError> {
    if points.len() > MAX_WAYPOINTS {
        return Err(PlanError::TooManyWaypoints { max: MAX_WAYPOINTS });
    }
    if speeds.len() + 1 != points.len() && !points.is_empty() {
        return Err(PlanError::Invalid(format!(
            "a plan has one leg speed fewer than its waypoints (waypoints: {}, leg speeds: {})",
            points.len(),
            speeds.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| {
        p.iter()
            .any(|c| !c.is_finite() || c.abs() > MAX_PLAN_COORDINATE)
    }) {
        return Err(PlanError::Invalid(format!(
            "waypoint {}: every coordinate must be finite and within 1000 km",
            i + 1
        )));
    }
    for (i, v) in speeds.iter().enumerate() {
        if let Some(v) = v.filter(|v| !is_plan_speed(*v)) {
            return Err(PlanError::Invalid(format!(
                "waypoint {}: speed must be in (0, {MAX_PLAN_SPEED}] m/s, got {v}",
                i + 2
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trajectory::synthetic_flight;

    fn square() -> FlightPlan {
        let pts = vec![
            [0.0, 0.0, 10.0],
            [100.0, 0.0, 10.0],
            [100.0, 100.0, 10.0],
            [0.0, 100.0, 10.0],
        ];
        FlightPlan::new(pts, vec![Some(10.0), None, Some(5.0)]).unwrap()
    }

    #[test]
    fn points_along_the_legs_and_their_speeds() {
        let p = square();
        assert_eq!(p.length(), 300.0);
        assert_eq!(p.point_at(150.0), [100.0, 50.0, 10.0]);
        assert_eq!(p.point_at(-5.0), [0.0, 0.0, 10.0]);
        assert_eq!(p.point_at(400.0), [0.0, 100.0, 10.0]);
        assert_eq!(p.speed_at(50.0), Some(10.0));
        assert_eq!(p.speed_at(150.0), None);
        assert_eq!(p.direction_at(250.0), [-1.0, 0.0, 0.0]);
    }

    #[test]
    fn holds_add_up_where_a_waypoint_repeats_and_are_found_ahead() {
        let p = FlightPlan::with_holds(
            vec![
                [0.0; 3],
                [10.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [20.0, 0.0, 0.0],
            ],
            vec![None; 3],
            vec![0.0, 4.0, 6.0, 0.0],
        )
        .unwrap();
        assert_eq!(p.holds(), &[0.0, 10.0, 0.0]);
        assert_eq!(p.next_hold(p.waypoint_at_or_after(3.0)), Some((1, 10.0)));
        assert_eq!(p.next_hold(p.waypoint_at_or_after(10.0)), Some((1, 10.0)));
        assert_eq!(p.next_hold(p.waypoint_at_or_after(10.5)), None);
        assert_eq!(p.without_holds().holds(), &[0.0; 3]);
        assert!(FlightPlan::with_holds(vec![[0.0; 3], [1.0; 3]], vec![None], vec![0.0]).is_err());
        assert!(
            FlightPlan::with_holds(vec![[0.0; 3], [1.0; 3]], vec![None], vec![0.0, f64::NAN])
                .is_err()
        );
    }

    #[test]
    fn a_dropped_repeat_takes_its_legs_climb_limits_with_it() {
        let slow = ClimbLimits { up: 1.0, down: 0.5 };
        let points = vec![
            [0.0; 3],
            [0.0, 0.0, 30.0],
            [0.0, 0.0, 30.0],
            [0.0, 0.0, 60.0],
        ];
        let climbs = vec![ClimbLimits::MULTICOPTER, ClimbLimits::FIXED_WING, slow];
        let p =
            FlightPlan::with_holds_and_climbs(points.clone(), vec![None; 3], vec![0.0; 4], climbs)
                .unwrap();
        assert_eq!(p.climbs(), Some(&[ClimbLimits::MULTICOPTER, slow][..]));
        assert_eq!(p.flown_speed(1, 5.0), 1.0);
        let refused = |climbs| {
            FlightPlan::with_holds_and_climbs(points.clone(), vec![None; 3], vec![0.0; 4], climbs)
                .is_err()
        };
        assert!(refused(vec![slow; 2]));
        assert!(refused(vec![ClimbLimits { up: 0.0, down: 1.0 }; 3]));
        assert!(refused(vec![
            ClimbLimits {
                up: 1.0,
                down: f64::NAN
            };
            3
        ]));
    }

    #[test]
    fn csv_text_reads_back_to_the_same_plan() {
        let p = square();
        assert_eq!(crate::trajectory::parse_plan(&p.to_csv()).unwrap(), p);
        // A plan read from a file is one for an autopilot, within its climb limits; a traced
        // plan is the flight's own pace, and its CSV says so.
        let traced = FlightPlan::traced(&synthetic_flight(9).unwrap(), TRACE_TOLERANCE);
        assert_eq!(traced.climbs(), None);
        let text = traced.to_csv();
        assert!(text.starts_with(crate::trajectory::TRACED_MARK));
        assert_eq!(crate::trajectory::parse_plan(&text).unwrap(), traced);
        let unmarked: String = text.lines().skip(1).map(|l| format!("{l}\n")).collect();
        assert_eq!(
            crate::trajectory::parse_plan(&unmarked).unwrap(),
            traced.with_climb(Some(ClimbLimits::MULTICOPTER))
        );
    }

    #[test]
    fn the_nearest_point_respects_the_window() {
        let p = square();
        let near = p.nearest(&[50.0, 3.0, 10.0], 0.0, 300.0);
        assert_eq!(near.along, 50.0);
        assert!((near.off - 3.0).abs() < 1e-12);
        // The same position, searched only on the third leg, projects onto its start.
        let far = p.nearest(&[50.0, 3.0, 10.0], 200.0, 300.0);
        assert_eq!(far.along, 250.0);
        assert!((far.off - 97.0).abs() < 1e-12);
    }

    #[test]
    fn repeated_waypoints_are_dropped_and_too_few_refused() {
        let p = FlightPlan::new(
            vec![[0.0; 3], [0.0; 3], [3.0, 4.0, 0.0]],
            vec![Some(1.0), Some(2.0)],
        )
        .unwrap();
        assert_eq!(p.waypoints().len(), 2);
        assert_eq!(p.speed_at(1.0), Some(2.0));
        assert_eq!(
            FlightPlan::new(vec![[1.0; 3], [1.0; 3]], vec![None]),
            Err(PlanError::TooFewWaypoints)
        );
        assert!(FlightPlan::new(vec![[0.0; 3], [f64::NAN, 0.0, 0.0]], vec![None]).is_err());
        assert!(FlightPlan::new(vec![[0.0; 3], [1.0, 0.0, 0.0]], vec![Some(0.0)]).is_err());
        // A leg speed for each leg, whatever the counts (no "1 waypoints need 0 leg speeds").
        let Err(PlanError::Invalid(why)) = FlightPlan::new(vec![[0.0; 3]], vec![None]) else {
            panic!("one waypoint with a leg speed was accepted");
        };
        assert!(why.contains("waypoints: 1, leg speeds: 1"), "{why}");
        assert!(!why.contains("1 waypoints"), "{why}");
    }

    #[test]
    fn a_position_has_a_nearest_point_on_each_pass_of_the_plan() {
        // Out along x and back: every point of the line is on both legs.
        let p = FlightPlan::new(
            vec![[0.0; 3], [100.0, 0.0, 0.0], [0.0; 3]],
            vec![None, None],
        )
        .unwrap();
        let q = [30.0, 2.0, 0.0];
        let passes: Vec<_> = p.projections(&q, 0.0, 200.0).collect();
        let out = OnPlan {
            along: 30.0,
            off: 2.0,
        };
        let back = OnPlan {
            along: 170.0,
            off: 2.0,
        };
        assert_eq!(passes, [([1.0, 0.0, 0.0], out), ([-1.0, 0.0, 0.0], back)]);
        // The first of equally near points; within a window, only its own.
        assert_eq!(p.nearest(&q, 0.0, 200.0), out);
        assert_eq!(p.nearest(&q, 90.0, 200.0), back);
    }

    #[test]
    fn a_traced_plan_stays_within_its_tolerance_and_keeps_time() {
        let flight = synthetic_flight(4).unwrap();
        let plan = FlightPlan::traced(&flight, TRACE_TOLERANCE);
        assert!(plan.waypoints().len() < flight.pos.len() / 10);
        let mut from = 0.0;
        for p in &flight.pos {
            let near = plan.nearest(p, 0.0, plan.length());
            assert!(near.off <= TRACE_TOLERANCE + 1e-9, "{}", near.off);
            from = near.along.max(from);
        }
        assert!(from > 0.99 * plan.length());
        // Flying every leg at its planned speed takes the flight's time.
        let time: f64 = (0..plan.waypoints().len() - 1)
            .map(|i| (plan.along[i + 1] - plan.along[i]) / plan.speeds[i].unwrap())
            .sum();
        assert!(
            (time - flight.duration()).abs() < 1e-6 * flight.duration(),
            "{time}"
        );
    }
}
