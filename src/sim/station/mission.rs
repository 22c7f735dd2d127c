//! The mission-aware station (`--model mission`): between packets it flies the drone's plan
//! instead of extrapolating a manoeuvre (reference §16; the paper's future work, §V, names a
//! movement model that uses mission-level information).

use super::{Prediction, StationPredictor, StationSetup, Tracker};
use crate::math::{distance, exp, sin_cos};
use crate::models::Ctra3d;
use crate::trajectory::{
    rounded, CornerSpeeds, Cornering, FlightPlan, OnPlan, Trajectory, PLAN_ACCEL, PLAN_CRUISE,
};
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// How the mission station paces the drone along its plan (`--plan-pace`; the pace's time
/// constant: [`PACE_TIME`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum PlanPace {
    /// The packet's speed, giving way to each leg's planned speed over 2 s where the plan gives
    /// one: for a drone that keeps its plan's timing.
    #[default]
    Plan,
    /// The packet's speed throughout, ignoring the plan's speeds: for a plan whose timing the
    /// drone does not keep (wind, a different airframe), or one without speeds.
    Packet,
}

/// A plan and how far from it a packet may place the drone before the station stops trusting it.
#[derive(Clone, Debug, PartialEq)]
pub struct MissionPlan {
    /// The waypoints the drone flies.
    pub plan: FlightPlan,
    /// The largest distance from the plan, m, at which a packet still counts as on the plan
    /// (`--plan-tolerance`).
    pub tolerance: f64,
    /// When the drone set out on the plan, s ([`MissionPlan::start_on`]): the station reads a
    /// first packet on a path flown more than once by the plan's timetable from then.
    pub start: f64,
}

impl MissionPlan {
    /// When `flight` sets out on `plan`, s. A plan with an autopilot's timing (read from a file,
    /// with climb limits) starts the last moment the flight was at rest (under [`HOLD_SPEED`])
    /// before it first moved faster, its first time if it moves from the start: a log begins
    /// when the autopilot does, often minutes before it takes off, and a timetable from the
    /// log's first time would put a first packet on a plan flown in laps a lap or more ahead. A
    /// drone seen moving by noise alone (a position-only log's jittery speeds) sets out at its
    /// first time. A plan traced through the flight ([`FlightPlan::traced`]) starts at the
    /// flight's first time: its first leg's speed already counts any wait before it.
    pub fn start_on(plan: &FlightPlan, flight: &Trajectory) -> f64 {
        if plan.climbs().is_none() {
            return flight.t[0];
        }
        let moving = flight
            .vel
            .iter()
            .position(|v| v.iter().map(|c| c * c).sum::<f64>() >= HOLD_SPEED * HOLD_SPEED);
        match moving {
            Some(k) if k > 0 => flight.t[k - 1],
            _ => flight.t[0],
        }
    }

    /// `plan` as the station follows it: a plane's with its corners' arcs ([`rounded`]), which
    /// pass tens of metres inside its waypoints, so that a plane in a turn is on the plan; a
    /// multicopter's as planned, its arcs passing within 2 m of the waypoints
    /// ([`CORNER_RADIUS`](crate::CORNER_RADIUS)), well within the tolerance. Before its speeds
    /// are dropped (`--plan-pace packet`): a plane's arcs are as wide as its speed makes them.
    pub fn followed(plan: FlightPlan) -> FlightPlan {
        match plan.cornering() {
            Cornering::FixedWing => rounded(&plan),
            Cornering::Multicopter => plan,
        }
    }

    /// The wait at the plan's first waypoint before the drone sets out: that waypoint and when
    /// the drone got there, s, so that its hold there (if any) ends at [`MissionPlan::start`], as
    /// the flown plan leaves it at once and a log's drone leaves it when it sets out.
    fn waiting(&self) -> (usize, f64) {
        (0, self.start - self.plan.holds()[0])
    }
}

/// Seconds over which the speed the packet reported gives way to the leg's planned speed: the
/// autopilot's speed loop (the synthetic flights' velocity loop settles in about 2 s). Measured
/// on the synthetic set at SF7/250 … SF12/125, 1 km: 5 s and 10 s lower p75 where packets come
/// every 2–6 s (SF7/250: 1.55 → 1.37 → 1.28 m) and raise it where they are scarce (SF12: 16.8
/// → 21.0 → 25.8 m); the station is for scarce packets. `--plan-pace packet` keeps the
/// packet's speed throughout (docs/mission.md).
pub const PACE_TIME: f64 = 2.0;
/// Seconds over which the packet's offset from the plan closes: the autopilot steers back to
/// the leg (ArduPilot's waypoint navigation corrects cross-track error over a few seconds).
pub const OFFSET_TIME: f64 = 5.0;
/// How fast the station's position uncertainty grows on the plan, m per second since the
/// packet, in every direction: the speed it does not know (planned against flown) moves the
/// drone along the leg, and near a waypoint along the next one. 1 m/s puts coverage95 at
/// 0.93–0.99 on the synthetic set at SF7–SF12 (docs/mission.md; with 0.5 m/s 0.81–0.89, with
/// 2 m/s 0.99–1.00); a growth only along the leg was far too narrow at the corners (NEES about
/// 25 at SF9–12).
pub const PACE_SIGMA: f64 = 1.0;
/// The smallest half-width of the stretch of plan searched for a packet near where the station
/// expected the drone, m; it widens by [`SEARCH_SPEED`] for every second since the last packet.
const SEARCH_MARGIN: f64 = 20.0;
/// m/s: see [`SEARCH_MARGIN`].
const SEARCH_SPEED: f64 = 5.0;
/// Passes of the plan within this distance of each other from a packet, m, are equally near it:
/// the station then takes the one nearest where it expected the drone. A path flown round
/// again (a loiter's turns, laps) is as near on every pass; distinct legs almost never are
/// within a centimetre (choosing by the expectation among all passes within the tolerance cost
/// the real Canberra flight: docs/beyond-the-paper.md, "Laps").
const TIE: f64 = 0.01;
/// A packet shows the drone holding at a waypoint with a hold when it reports less than this
/// speed, m/s, within [`HOLD_RADIUS`] of it: a hovering multicopter's estimated speed is a few
/// tenths of a metre per second.
pub const HOLD_SPEED: f64 = 1.0;
/// m: see [`HOLD_SPEED`]; a hovering drone's filtered position stays within a few metres of the
/// waypoint.
pub const HOLD_RADIUS: f64 = 5.0;

/// Where along the plan the station believes the drone is, from the newest packet on the plan.
#[derive(Clone, Copy, Debug)]
struct Following {
    /// The packet's send time, s.
    sent: f64,
    /// The packet's position less its point on the plan, m.
    offset: [f64; 3],
    /// The packet's speed, m/s.
    speed: f64,
    /// The packet's position covariance, m².
    covariance: Matrix3<f64>,
    /// The time and distance along the plan the station has flown to, s and m.
    t: f64,
    along: f64,
    /// The newest hold since the packet: its waypoint, and when the station believes the drone
    /// got there, s. The station holds there until the hold is over, then speeds up from rest.
    last_hold: Option<(usize, f64)>,
    /// The next waypoint with a hold after the last one, and its distance along the plan, m.
    next_hold: Option<(usize, f64)>,
    /// The speed to fly on at after a hold where the plan gives none, m/s: the newest packet's
    /// that showed the drone moving, [`PLAN_CRUISE`] before any did (a drone that hovers at every
    /// packet would otherwise be kept at its first hold until one showed it moving).
    cruise: f64,
}

/// The mission-aware station: each packet that places the drone within the tolerance of its plan
/// is projected onto the plan, and the station then flies the plan from there — at the packet's
/// speed, giving way to each leg's planned speed over [`PACE_TIME`], with the packet's offset
/// from the plan closing over [`OFFSET_TIME`]. A packet off the plan (or no plan) hands the
/// estimate to a bounded 3D-CTRA station, which runs beside it on every packet, until a packet
/// is back on the plan. The drone sends the 12-byte 3D-CTRA payload.
///
/// A waypoint with a hold (reference §16) stops the station there for the hold; a packet that
/// shows the drone hovering within [`HOLD_RADIUS`] of one (under [`HOLD_SPEED`]) places the
/// drone's arrival halfway between the packet before and this one (but at most a hold before
/// this one; half a hold before a first packet), unless the station has held there since the
/// packet before and the hold is not over (then it keeps its arrival);
/// after a hold the station speeds up from rest at [`PLAN_ACCEL`], as the flown plan does, to
/// the leg's planned speed or, on a leg without one, the speed of the newest packet that showed
/// the drone moving ([`PLAN_CRUISE`] before any did).
///
/// Its covariance on the plan: the packet's (the drone filter's settled covariance, as the
/// bounded station's), plus ([`PACE_SIGMA`]·τ)² in every direction, τ s after the packet.
pub struct MissionStation {
    plan: Option<MissionPlan>,
    /// How fast the plan lets the drone pass each waypoint, from its corners (none for a plan
    /// traced through a flight).
    corners: Option<CornerSpeeds>,
    fallback: StationPredictor<9, Ctra3d>,
    step: f64,
    /// The bounded station's top speed, m/s: a packet's speed is held within it on the plan too.
    speed_limit: f64,
    following: Option<Following>,
    /// The station's own flight of the plan from its start, as far as it has been needed: the
    /// plan's timetable (see [`MissionStation::place`]); none for a plan without speeds.
    timetable: Option<Following>,
}

impl MissionStation {
    /// A station for `plan` (none: always the fallback) whose fallback has `setup` with a
    /// bounded prediction.
    pub fn new(plan: Option<MissionPlan>, setup: StationSetup) -> Self {
        let bounded = StationSetup {
            prediction: Prediction::Bounded,
            ..setup
        };
        MissionStation {
            corners: plan.as_ref().map(|mp| CornerSpeeds::of(&mp.plan)),
            timetable: plan.as_ref().and_then(Self::set_out),
            plan,
            fallback: StationPredictor::new(Ctra3d, bounded),
            step: setup.step,
            speed_limit: setup.bounds.v_max,
            following: None,
        }
    }

    /// Whether the estimate now comes from the plan (rather than the fallback).
    pub fn on_plan(&self) -> bool {
        self.following.is_some()
    }

    /// The speed along the plan over a step of `dt` s from `f`: [`Self::free_pace`] at the
    /// step's midpoint in time, and near a waypoint the drone turns or stops at, no faster than
    /// it can pass there ([`CornerSpeeds`]) at the midpoint of the distance it covers (from rest,
    /// a quarter of what `PLAN_ACCEL` covers in the step: second order where the drone speeds up
    /// out of a stop).
    fn pace(plan: &FlightPlan, corners: &CornerSpeeds, f: &Following, dt: f64) -> f64 {
        let free = Self::free_pace(plan, f, f.t + dt / 2.0, f.along);
        let start = free.min(corners.cap(f.along));
        let half = (start * dt / 2.0).max(PLAN_ACCEL * dt * dt / 8.0);
        free.min(corners.cap(f.along + half))
    }

    /// The speed along the plan at time `t`, at `along` m: after a hold, from rest up to the
    /// leg's planned speed (or the cruise speed) at [`PLAN_ACCEL`]; else from the packet's speed
    /// toward it. On a leg too steep for the plan's climb limits, what the autopilot slows it to.
    fn free_pace(plan: &FlightPlan, f: &Following, t: f64, along: f64) -> f64 {
        let planned = plan.speed_at(along);
        let flown = |v| plan.within_climb_at(along, v);
        let resumed = f.last_hold.map(|(k, reached)| reached + plan.holds()[k]);
        match resumed {
            Some(end) => flown(planned.unwrap_or(f.cruise)).min(PLAN_ACCEL * (t - end).max(0.0)),
            None => match planned {
                Some(v) => flown(v) + (f.speed - flown(v)) * exp(-(t - f.sent) / PACE_TIME),
                None => flown(f.speed),
            },
        }
    }

    /// Where on the plan a packet at `p` (m), sent at `sent` s, places the drone, if within the
    /// tolerance: near where the station expected the drone, so that a path that crosses itself
    /// is followed on the right pass; else, on the pass of the plan nearest to where its
    /// timetable puts the drone then (`scheduled`, m: [`Self::scheduled`]), so that a first
    /// packet on a plan flown in laps is placed on the right lap (without a timetable, the
    /// nearest pass). In each, first onto a leg flown the way the packet's `heading` (a unit
    /// vector; none for a drone too slow to show one) points, where one is near enough, so that
    /// a path that doubles back along itself is followed the right way (an out-and-back
    /// inspection, a survey's return pass).
    fn place(
        &self,
        mp: &MissionPlan,
        p: &[f64; 3],
        heading: Option<[f64; 3]>,
        (sent, scheduled): (f64, Option<f64>),
    ) -> Option<OnPlan> {
        let plan = &mp.plan;
        // The passes between `from` and `to` m along the plan within the tolerance (and, where
        // `heeded`, flown the way the packet heads).
        let passes = move |from: f64, to: f64, heeded: bool| {
            let ahead = move |d: &[f64; 3]| {
                heading.is_none_or(|h| (0..3).map(|k| h[k] * d[k]).sum::<f64>() > 0.0)
            };
            plan.projections(p, from, to)
                .filter(move |(d, n)| (!heeded || ahead(d)) && n.off <= mp.tolerance)
                .map(|(_, n)| n)
        };
        // Of the passes within `margin` m of `centre` that are as near the packet as the nearest
        // (within `TIE`), the one nearest `centre`: a path flown round more than once (a loiter's
        // turns) is as near on every turn.
        let near = |(centre, margin): (f64, f64), heeded: bool| {
            let found: Vec<OnPlan> = passes(centre - margin, centre + margin, heeded).collect();
            let nearest = found.iter().map(|n| n.off).min_by(f64::total_cmp)?;
            nearest_along(found.into_iter().filter(|n| n.off <= nearest + TIE), centre)
        };
        let expected = self.following.map(|f| {
            let margin = SEARCH_MARGIN + SEARCH_SPEED * (sent - f.sent).max(0.0);
            (f.along, margin)
        });
        let on_time = |heeded: bool| {
            let found = passes(0.0, plan.length(), heeded);
            let pass = match scheduled {
                Some(s) => nearest_along(found, s),
                None => found.min_by(|a, b| a.off.total_cmp(&b.off)),
            }?;
            near((pass.along, SEARCH_MARGIN), heeded)
        };
        [true, false].into_iter().find_map(|heeded| {
            expected
                .and_then(|e| near(e, heeded))
                .or_else(|| on_time(heeded))
        })
    }

    /// Flies `f` along `plan` to `t` s, in steps of at most `step` s: the pace
    /// ([`Self::pace`]), each hold waited out, braking into it at [`PLAN_ACCEL`].
    fn fly(plan: &FlightPlan, corners: &CornerSpeeds, step: f64, f: &mut Following, t: f64) {
        while f.t < t {
            if let Some((k, reached)) = f.last_hold {
                let end = reached + plan.holds()[k];
                if f.t < end {
                    f.t = end.min(t);
                    continue;
                }
            }
            let dt = step.min(t - f.t);
            let v = Self::pace(plan, corners, f, dt);
            // Where a hold is ahead and the pace would overshoot it at `PLAN_ACCEL` (a drone that
            // is to hover there has to stop there, braking as the flown plan brakes), the station
            // brakes: exactly, at constant deceleration, to a stop at the hold's waypoint.
            let braking = f.next_hold.and_then(|(_, at)| {
                let brake = (2.0 * PLAN_ACCEL * (at - f.along).max(0.0)).sqrt();
                (brake <= v).then_some(brake)
            });
            let (advance, to_stop) = match braking {
                Some(b) => (b * dt - PLAN_ACCEL * dt * dt / 2.0, b / PLAN_ACCEL),
                None => (v * dt, f64::INFINITY),
            };
            let along = (f.along + advance).min(plan.length());
            match f.next_hold {
                // The hold's waypoint is reached within the step: the station stops there.
                Some((k, at)) if along >= at || to_stop <= dt => {
                    f.t += if to_stop <= dt {
                        to_stop
                    } else if v > 0.0 {
                        ((at - f.along) / v).clamp(0.0, dt)
                    } else {
                        0.0
                    };
                    f.along = at;
                    f.last_hold = Some((k, f.t));
                    f.next_hold = plan.next_hold(k + 1);
                }
                _ => {
                    f.along = along;
                    f.t += dt;
                }
            }
        }
    }

    /// The station's own flight of `mp` as it sets out: from rest at the first waypoint when the
    /// drone set out ([`MissionPlan::start`], by which a hold there is over), at [`PLAN_CRUISE`]
    /// on a leg without a planned speed (as the flown plan). None for a plan without any planned speed, which has no
    /// timetable (every plan with `--plan-pace packet`).
    fn set_out(mp: &MissionPlan) -> Option<Following> {
        let plan = &mp.plan;
        let legs = plan.waypoints().len() - 1;
        (0..legs)
            .any(|leg| plan.leg_speed(leg).is_some())
            .then(|| Following {
                sent: mp.start,
                offset: [0.0; 3],
                speed: 0.0,
                covariance: Matrix3::zeros(),
                t: mp.start,
                along: 0.0,
                last_hold: Some(mp.waiting()),
                next_hold: plan.next_hold(1),
                cruise: PLAN_CRUISE,
            })
    }

    /// Where along the plan, m, its timetable puts the drone at `sent` s: the station's own
    /// flight of the plan ([`Self::fly`]) from [`Self::set_out`]. Kept between packets: a
    /// flight's packets come in the order they were sent, so the flight is flown once.
    fn scheduled(&mut self, sent: f64) -> Option<f64> {
        let Self {
            plan,
            corners,
            timetable,
            step,
            ..
        } = self;
        let (mp, corners, f) = (plan.as_ref()?, corners.as_ref()?, timetable.as_mut()?);
        if f.t > sent {
            *f = Self::set_out(mp)?;
        }
        Self::fly(&mp.plan, corners, *step, f, sent);
        Some(f.along)
    }

    /// The hold a packet at `p` (m; `along` m along the plan), moving at `speed` (m/s), shows
    /// the drone in: the waypoint, its distance along the plan (m), and when the drone got there
    /// (s). A packet sent before the drone set out ([`MissionPlan::start`]) at the plan's first
    /// waypoint shows it waiting there until then, as the timetable has it: a drone seen on the
    /// ground before its mission stays there, not off along the plan.
    fn hold_shown(
        &self,
        plan: &FlightPlan,
        (p, along): (&[f64; 3], f64),
        speed: f64,
        sent: f64,
    ) -> Option<(usize, f64, f64)> {
        if speed >= HOLD_SPEED {
            return None;
        }
        if let Some(mp) = self.plan.as_ref().filter(|mp| sent < mp.start) {
            if distance(p, &plan.waypoints()[0]) <= HOLD_RADIUS {
                let (k, reached) = mp.waiting();
                return Some((k, 0.0, reached));
            }
        }
        let (k, at) = plan
            .next_hold(plan.waypoint_at_or_after(along - HOLD_RADIUS))
            .filter(|&(k, _)| distance(p, &plan.waypoints()[k]) <= HOLD_RADIUS)?;
        let hold = plan.holds()[k];
        let reached = match self.following {
            // Held there already, and the hold not over: the same arrival. A drone that outstays
            // the plan's hold is placed as one that has just come (below): a hold too short in
            // the plan is likelier than a drone about to leave.
            Some(Following {
                last_hold: Some((at, reached)),
                ..
            }) if at == k && reached + hold > sent => reached,
            Some(f) => sent - hold.min((sent - f.sent).max(0.0) / 2.0),
            None => sent - hold / 2.0,
        };
        Some((k, at, reached))
    }
}

impl Tracker for MissionStation {
    fn reset(&mut self, state: &[f64; 9], sent: f64) {
        self.fallback.reset(state, sent);
        let scheduled = self.scheduled(sent);
        let Some(mp) = &self.plan else {
            return;
        };
        let p = [state[0], state[1], state[2]];
        let plan = &mp.plan;
        let speed = state[5].clamp(0.0, self.speed_limit);
        let Some(found) = self.place(mp, &p, heading(state, speed), (sent, scheduled)) else {
            self.following = None;
            return;
        };
        let holding = self.hold_shown(plan, (&p, found.along), speed, sent);
        let along = holding.map_or(found.along, |(_, at, _)| at);
        let on = plan.point_at(along);
        let cruise = match self.following {
            Some(f) if speed < HOLD_SPEED => f.cruise,
            None if speed < HOLD_SPEED => PLAN_CRUISE,
            _ => speed,
        };
        self.following = Some(Following {
            sent,
            offset: core::array::from_fn(|k| p[k] - on[k]),
            speed,
            covariance: self.fallback.position_covariance(),
            t: sent,
            along,
            last_hold: holding.map(|(k, _, reached)| (k, reached)),
            next_hold: match holding {
                Some((k, _, _)) => plan.next_hold(k + 1),
                None => plan.next_hold(plan.waypoint_at_or_after(found.along)),
            },
            cruise,
        });
    }

    fn predict_to(&mut self, t: f64) {
        self.fallback.predict_to(t);
        let (Some(mp), Some(corners), Some(f)) = (&self.plan, &self.corners, &mut self.following)
        else {
            return;
        };
        Self::fly(&mp.plan, corners, self.step, f, t);
    }

    fn position(&self) -> [f64; 3] {
        match (&self.plan, &self.following) {
            (Some(mp), Some(f)) => {
                let on = mp.plan.point_at(f.along);
                let fade = exp(-(f.t - f.sent) / OFFSET_TIME);
                core::array::from_fn(|k| on[k] + f.offset[k] * fade)
            }
            _ => self.fallback.position(),
        }
    }

    fn position_covariance(&self) -> Matrix3<f64> {
        match &self.following {
            Some(f) if self.plan.is_some() => {
                f.covariance + Matrix3::identity() * (PACE_SIGMA * (f.t - f.sent)).powi(2)
            }
            _ => self.fallback.position_covariance(),
        }
    }

    fn set_interval(&mut self, interval: f64) {
        self.fallback.set_interval(interval);
    }

    fn trust_silence(&mut self, trusted: bool) {
        self.fallback.trust_silence(trusted);
    }

    /// The plan's covariance starts from the fallback's just after a packet, which the packet
    /// itself sets, so only the fallback's propagation can be skipped.
    fn ignore_uncertainty(&mut self) {
        self.fallback.ignore_uncertainty();
    }
}

/// Of `passes`, the one nearest `along` m along the plan (the first of equally near ones).
fn nearest_along(passes: impl Iterator<Item = OnPlan>, along: f64) -> Option<OnPlan> {
    passes.min_by(|a, b| (a.along - along).abs().total_cmp(&(b.along - along).abs()))
}

/// The unit direction a 3D-CTRA `state` (`[x, y, z, θ, φ, v, …]`) moves in at `speed` m/s; none
/// below [`HOLD_SPEED`], where a hovering drone's estimated heading is noise.
fn heading(state: &[f64; 9], speed: f64) -> Option<[f64; 3]> {
    let ((st, ct), (sp, cp)) = (sin_cos(state[3]), sin_cos(state[4]));
    (speed >= HOLD_SPEED).then_some([ct * cp, st * cp, sp])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--plan-pace plan`'s help is the variant's doc, written with the pace's time.
    #[cfg(cli)]
    #[test]
    fn the_cli_help_states_the_pace_time() {
        let value = clap::ValueEnum::to_possible_value(&PlanPace::Plan).unwrap();
        let help = value.get_help().unwrap().to_string();
        assert!(help.contains(&format!("over {PACE_TIME} s")), "{help}");
    }

    fn setup() -> StationSetup {
        StationSetup {
            prediction: Prediction::Bounded,
            ..crate::sim::station::tests::paper_setup()
        }
    }

    /// A plan through `points` at `speeds`, a packet on it within 10 m, set out on at 0 s.
    fn mission(points: Vec<[f64; 3]>, speeds: Vec<Option<f64>>) -> MissionPlan {
        MissionPlan {
            plan: FlightPlan::new(points, speeds).unwrap(),
            tolerance: 10.0,
            start: 0.0,
        }
    }

    /// `laps` laps of a square of `side` m, anticlockwise from the origin, 20 m up, at 10 m/s,
    /// traced (no corner slows it).
    fn square_laps(side: f64, laps: usize) -> MissionPlan {
        let corners = [[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]];
        let points = (0..=4 * laps).map(|i| [corners[i % 4][0], corners[i % 4][1], 20.0]);
        let plan = mission(points.collect(), vec![Some(10.0); 4 * laps]);
        MissionPlan {
            plan: plan.plan.with_climb(None),
            ..plan
        }
    }

    /// East 100 m at 10 m/s, then north 100 m at 5 m/s, 20 m up.
    fn corner() -> MissionPlan {
        mission(
            vec![[0.0, 0.0, 20.0], [100.0, 0.0, 20.0], [100.0, 100.0, 20.0]],
            vec![Some(10.0), Some(5.0)],
        )
    }

    /// The distance, m, covered `tau` s after a stop by a drone speeding up at [`PLAN_ACCEL`] to
    /// `v` m/s and holding it.
    fn from_rest(v: f64, tau: f64) -> f64 {
        let speeding_up = (v / PLAN_ACCEL).min(tau);
        PLAN_ACCEL * speeding_up * speeding_up / 2.0 + v * (tau - speeding_up)
    }

    /// A 3D-CTRA state at (x, y, 20) heading east at `v` m/s.
    fn packet(x: f64, y: f64, v: f64) -> [f64; 9] {
        [x, y, 20.0, 0.0, 0.0, v, 0.0, 0.0, 0.0]
    }

    /// The station's largest distance from `flown` over `steps` steps of 0.2 s (five samples)
    /// after sample `k`, predicting to each, m.
    fn worst_error(st: &mut MissionStation, flown: &Trajectory, k: usize, steps: usize) -> f64 {
        (1..=steps).fold(0.0, |worst, step| {
            let i = k + step * 5;
            st.predict_to(flown.t[i]);
            worst.max(distance(&st.position(), &flown.pos[i]))
        })
    }

    #[test]
    fn follows_the_plan_round_a_corner_at_the_planned_speeds() {
        // Traced through a flight, the plan's speeds are the flight's own: no corner slows it.
        let traced = MissionPlan {
            plan: corner().plan.with_climb(None),
            ..corner()
        };
        let mut st = MissionStation::new(Some(traced), setup());
        st.reset(&packet(50.0, 0.0, 10.0), 0.0);
        assert!(st.on_plan());
        // 5 s at 10 m/s reach the corner; then 4 s at 5 m/s plus what is left of the packet's
        // 10 m/s: 20 m + ∫ 5 e^(-τ/2) dτ from 5 to 9 s north.
        st.predict_to(9.0);
        let p = st.position();
        let north = 20.0 + 5.0 * PACE_TIME * (exp(-5.0 / PACE_TIME) - exp(-9.0 / PACE_TIME));
        assert!((p[0] - 100.0).abs() < 1e-9, "{p:?}");
        assert!((p[1] - north).abs() < 1e-3, "{p:?} against {north}");
        // A bounded 3D-CTRA station would have flown on east.
        let mut plain = StationPredictor::new(Ctra3d, setup());
        plain.reset(&packet(50.0, 0.0, 10.0), 0.0);
        plain.predict_to(9.0);
        assert!(plain.position()[0] > 130.0);
    }

    #[test]
    fn paces_through_a_corner_as_the_flown_plan_flies_it() {
        let plan = corner().plan;
        let flown = crate::fly_plan(&plan, "corner").unwrap();
        // A packet 8 s in, cruising east at 10 m/s.
        let k = (8.0 * crate::PLAN_RATE_HZ) as usize;
        let (p, v) = (flown.pos[k], flown.vel[k]);
        assert!((v[0] - 10.0).abs() < 1e-9 && p[0] < 70.0, "{p:?} {v:?}");
        let mut st = MissionStation::new(Some(corner()), setup());
        st.reset(&packet(p[0], p[1], v[0]), flown.t[k]);
        // Through the braking, the right angle (4.4 m/s) and the speeding up to 5 m/s north.
        let worst = worst_error(&mut st, &flown, k, 60);
        // Within the corner radius: the station paces along the legs, the drone cuts the corner.
        assert!(worst < crate::CORNER_RADIUS, "{worst}");
        // Without the corner the station would have rounded it at 5 m/s or more: metres ahead.
        let traced = MissionPlan {
            plan: corner().plan.with_climb(None),
            ..corner()
        };
        let mut fast = MissionStation::new(Some(traced), setup());
        fast.reset(&packet(p[0], p[1], v[0]), flown.t[k]);
        fast.predict_to(flown.t[k + 300]);
        assert!(distance(&fast.position(), &flown.pos[k + 300]) > worst + 2.0);
    }

    #[test]
    fn follows_a_plane_round_its_wide_corner() {
        // East 600 m, north 600 m, at 18 m/s: the plane turns on a 73 m arc, 30 m inside the
        // corner at its middle.
        let plan = FlightPlan::new(
            vec![[0.0, 0.0, 20.0], [600.0, 0.0, 20.0], [600.0, 600.0, 20.0]],
            vec![Some(18.0); 2],
        )
        .unwrap()
        .with_climb(Some(crate::ClimbLimits::FIXED_WING))
        .with_cornering(Cornering::FixedWing);
        let flown = crate::fly_plan(&plan, "plane").unwrap();
        let mp = MissionPlan {
            plan: MissionPlan::followed(plan),
            tolerance: 10.0,
            start: 0.0,
        };
        // A packet 30 s in, 70 m before the turn begins, then 15 s through it.
        let k = (30.0 * crate::PLAN_RATE_HZ) as usize;
        let (p, v) = (flown.pos[k], flown.vel[k]);
        let mut st = MissionStation::new(Some(mp.clone()), setup());
        st.reset(&packet(p[0], p[1], v[0]), flown.t[k]);
        let worst = worst_error(&mut st, &flown, k, 75);
        assert!(worst < 0.5, "{worst}");
        assert!(flown.pos[k + 375][1] > 100.0, "{:?}", flown.pos[k + 375]);
        // A packet in the middle of the turn is on the plan the station follows.
        let mid = flown
            .pos
            .iter()
            .enumerate()
            .min_by(|a, b| {
                let d = |p: &[f64; 3]| distance(p, &[600.0, 0.0, 20.0]);
                d(a.1).total_cmp(&d(b.1))
            })
            .map_or(0, |(i, _)| i);
        let mut st = MissionStation::new(Some(mp), setup());
        let (p, v) = (flown.pos[mid], flown.vel[mid]);
        let state = [p[0], p[1], 20.0, 0.0, 0.0, v[0].hypot(v[1]), 0.0, 0.0, 0.0];
        st.reset(&state, flown.t[mid]);
        assert!(st.on_plan());
    }

    /// [`corner`] with a hold of 10 s at the corner.
    fn corner_with_a_hold() -> MissionPlan {
        let c = corner().plan;
        MissionPlan {
            plan: FlightPlan::with_holds(
                c.waypoints().to_vec(),
                vec![Some(10.0), Some(5.0)],
                vec![0.0, 10.0, 0.0],
            )
            .unwrap(),
            tolerance: 10.0,
            start: 0.0,
        }
    }

    #[test]
    fn a_hold_stops_the_station_at_its_waypoint_then_it_speeds_up_from_rest() {
        let mut st = MissionStation::new(Some(corner_with_a_hold()), setup());
        st.reset(&packet(50.0, 0.0, 10.0), 0.0);
        // At 10 m/s until the braking at PLAN_ACCEL (2 m/s²: 25 m, 5 s) stops it at the corner,
        // 7.5 s in; held there for 10 s.
        let (brake_time, brake_distance) = (10.0 / PLAN_ACCEL, 50.0 / PLAN_ACCEL);
        let arrival = (50.0 - brake_distance) / 10.0 + brake_time;
        st.predict_to(arrival - 1.0);
        let braking = 100.0 - PLAN_ACCEL / 2.0;
        assert!(
            (st.position()[0] - braking).abs() < 0.3,
            "{:?}",
            st.position()
        );
        for t in [arrival + 0.2, arrival + 5.0, arrival + 9.9] {
            st.predict_to(t);
            assert!(
                (st.position()[0] - 100.0).abs() < 1e-9,
                "{t}: {:?}",
                st.position()
            );
            assert!(st.position()[1].abs() < 1e-9, "{t}: {:?}", st.position());
        }
        // Then from rest up to the leg's 5 m/s at PLAN_ACCEL, as the flown plan speeds up:
        // 5 τ − 5² / (2 · 2) north after τ s (once at speed, from 2.5 s), τ about 4 s.
        st.predict_to(arrival + 14.0);
        let north = |tau: f64| from_rest(5.0, tau);
        let y = st.position()[1];
        assert!(
            north(3.8) < y && y < north(4.2),
            "{y} against {}",
            north(4.0)
        );
        // Without the hold the station would be about 70 m further on.
        let mut plain = MissionStation::new(Some(corner()), setup());
        plain.reset(&packet(50.0, 0.0, 10.0), 0.0);
        plain.predict_to(21.0);
        assert!(plain.position()[1] > 70.0, "{:?}", plain.position());
    }

    #[test]
    fn a_packet_hovering_at_a_hold_keeps_or_places_the_arrival() {
        let mut st = MissionStation::new(Some(corner_with_a_hold()), setup());
        st.reset(&packet(50.0, 0.0, 10.0), 0.0);
        st.predict_to(8.0);
        // Hovering at the corner: the station was holding there since about 7 s, and keeps that.
        st.reset(&packet(101.0, 1.0, 0.3), 8.0);
        st.predict_to(16.9);
        assert!((st.position()[1] - 1.0 * exp(-8.9 / OFFSET_TIME)).abs() < 1e-9);
        st.predict_to(18.5);
        assert!(st.position()[1] > 1.0 * exp(-10.5 / OFFSET_TIME) + 0.5);
        // Still hovering 3 s after the hold it planned: placed as if it came halfway since the
        // packet before, so held until 20 + 10 − 6 = 24 s.
        st.reset(&packet(100.0, 0.0, 0.2), 20.0);
        st.predict_to(23.9);
        assert_eq!(st.position(), [100.0, 0.0, 20.0]);
        st.predict_to(25.0);
        assert!(st.position()[1] > 0.2, "{:?}", st.position());
        // A first packet hovering there: the drone got there half a hold before it.
        let mut first = MissionStation::new(Some(corner_with_a_hold()), setup());
        first.reset(&packet(100.0, 0.0, 0.0), 20.0);
        first.predict_to(24.9);
        assert_eq!(first.position(), [100.0, 0.0, 20.0]);
        first.predict_to(26.0);
        assert!(first.position()[1] > 0.5, "{:?}", first.position());
        // A packet passing the corner at speed, north, is not holding.
        let mut passing = MissionStation::new(Some(corner_with_a_hold()), setup());
        let mut north = packet(100.0, 2.0, 5.0);
        north[3] = core::f64::consts::FRAC_PI_2;
        passing.reset(&north, 0.0);
        passing.predict_to(2.0);
        assert!(passing.position()[1] > 8.0, "{:?}", passing.position());
    }

    #[test]
    fn after_a_hold_on_a_leg_without_a_speed_it_flies_on_at_the_cruise_speed_if_no_packet_showed_one(
    ) {
        let c = corner_with_a_hold().plan;
        let plan = MissionPlan {
            plan: FlightPlan::with_holds(
                c.waypoints().to_vec(),
                vec![None, None],
                c.holds().to_vec(),
            )
            .unwrap(),
            tolerance: 10.0,
            start: 0.0,
        };
        // A first packet hovering at the corner: held until 25 s, then from rest up to 5 m/s.
        let mut st = MissionStation::new(Some(plan.clone()), setup());
        st.reset(&packet(100.0, 0.0, 0.0), 20.0);
        st.predict_to(29.0);
        let north = from_rest;
        assert!(
            (st.position()[1] - north(PLAN_CRUISE, 4.0)).abs() < 0.1,
            "{:?}",
            st.position()
        );
        // A packet that showed the drone moving sets the speed instead (the arrival placed
        // halfway since it, so held from 10 s to 20 s).
        let mut seen = MissionStation::new(Some(plan), setup());
        seen.reset(&packet(50.0, 0.0, 8.0), 0.0);
        seen.reset(&packet(100.0, 0.0, 0.0), 20.0);
        seen.predict_to(29.0);
        assert!(
            (seen.position()[1] - north(8.0, 9.0)).abs() < 0.1,
            "{:?}",
            seen.position()
        );
    }

    #[test]
    fn the_offset_from_the_plan_closes_and_the_speed_gives_way() {
        let mut st = MissionStation::new(Some(corner()), setup());
        st.reset(&packet(10.0, 4.0, 2.0), 0.0);
        st.predict_to(0.0);
        assert!((st.position()[1] - 4.0).abs() < 1e-12);
        st.predict_to(30.0);
        let p = st.position();
        assert!(p[0] == 100.0 && p[1] > 60.0, "{p:?}");
        assert!((p[0] - 100.0).abs() < 0.01);
    }

    #[test]
    fn a_packet_off_the_plan_hands_over_to_the_bounded_model() {
        let mut st = MissionStation::new(Some(corner()), setup());
        st.reset(&packet(50.0, 30.0, 10.0), 0.0);
        assert!(!st.on_plan());
        st.predict_to(2.0);
        let mut plain = StationPredictor::new(
            Ctra3d,
            StationSetup {
                prediction: Prediction::Bounded,
                ..setup()
            },
        );
        plain.reset(&packet(50.0, 30.0, 10.0), 0.0);
        plain.predict_to(2.0);
        assert_eq!(st.position(), plain.position());
        // Back on the plan with the next packet.
        st.reset(&packet(100.0, 5.0, 5.0), 3.0);
        assert!(st.on_plan());
    }

    #[test]
    fn a_plan_flown_out_and_back_is_followed_the_way_the_packet_moves() {
        // 200 m east and back along the same line at 10 m/s.
        let there_and_back = mission(
            vec![[0.0, 0.0, 20.0], [200.0, 0.0, 20.0], [0.0, 0.0, 20.0]],
            vec![Some(10.0), Some(10.0)],
        );
        let mut st = MissionStation::new(Some(there_and_back.clone()), setup());
        st.reset(&packet(50.0, 0.0, 10.0), 0.0);
        // The next packet, 20 s on, finds the drone at 150 m heading west: on the way back,
        // though the station expected it at 250 m along, and the way out passes 150 m too.
        let mut west = packet(150.0, 0.0, 10.0);
        west[3] = core::f64::consts::PI;
        st.reset(&west, 20.0);
        st.predict_to(25.0);
        let p = st.position();
        assert!((p[0] - 100.0).abs() < 1e-6, "{p:?}");
        // Read by position alone, the packet is on the way out, and the station flies east.
        let mut blind = MissionStation::new(Some(there_and_back), setup());
        blind.reset(&packet(50.0, 0.0, 10.0), 0.0);
        blind.reset(&packet(150.0, 0.0, 0.5), 20.0);
        blind.predict_to(25.0);
        assert!(blind.position()[0] > 150.0, "{:?}", blind.position());
    }

    #[test]
    fn a_first_packet_on_a_plan_flown_in_laps_is_placed_on_the_lap_its_time_shows() {
        // Three laps of a 400 m square, 40 s a lap, set out on at 100 s.
        let laps = MissionPlan {
            start: 100.0,
            ..square_laps(100.0, 3)
        };
        // 45 s out, halfway along the first side: on the second lap, 450 m along.
        let mut st = MissionStation::new(Some(laps.clone()), setup());
        st.reset(&packet(50.0, 0.0, 10.0), 145.0);
        st.predict_to(175.0);
        let p = st.position();
        assert!(distance(&p, &[0.0, 50.0, 20.0]) < 1e-6, "{p:?}");
        // At the end of the plan (from 220 s) when the drone is.
        st.predict_to(230.0);
        assert!(distance(&st.position(), &[0.0, 0.0, 20.0]) < 1e-6);
        // Had the drone set out 40 s later, the same packet would be on the first lap: the
        // station then flies a third lap.
        let mut later = MissionStation::new(
            Some(MissionPlan {
                start: 140.0,
                ..laps
            }),
            setup(),
        );
        later.reset(&packet(50.0, 0.0, 10.0), 145.0);
        later.predict_to(230.0);
        let p = later.position();
        assert!(distance(&p, &[100.0, 0.0, 20.0]) < 1e-6, "{p:?}");
    }

    #[test]
    fn of_laps_equally_near_a_packet_it_takes_the_one_it_expected() {
        // Six laps of a 200 m square, 20 s a lap.
        let laps = square_laps(50.0, 6);
        let mut st = MissionStation::new(Some(laps), setup());
        st.reset(&packet(25.0, 0.0, 10.0), 2.5);
        // A minute on, the drone is back there three laps later; the search near the station's
        // expectation (625 m along, ±320 m) spans three laps.
        st.predict_to(62.5);
        st.reset(&packet(25.0, 0.0, 10.0), 62.5);
        // Placed on the lap it expected, the station ends the plan with the drone; placed on
        // the first lap searched, it would still fly, at (50, 0), 2.5 s later.
        st.predict_to(125.0);
        let p = st.position();
        assert!(distance(&p, &[0.0, 0.0, 20.0]) < 1e-6, "{p:?}");
    }

    #[test]
    fn a_plan_is_timed_from_when_the_flight_sets_out_and_a_traced_one_from_its_first_time() {
        // At rest for 5 s (a second at 0.3 m/s of noise among them), then east at 5 m/s.
        let t: Vec<f64> = (0..20).map(f64::from).collect();
        let speed = |k: usize| match k {
            0..=5 => [if k == 3 { 0.3 } else { 0.0 }, 0.0, 0.0],
            _ => [5.0, 0.0, 0.0],
        };
        let vel: Vec<[f64; 3]> = (0..20).map(speed).collect();
        let pos = (0..20)
            .map(|k| [5.0 * (k.max(5) - 5) as f64, 0.0, 20.0])
            .collect();
        let flight = Trajectory::new("log".into(), t, pos, vel, vec![[0.0; 3]; 20]).unwrap();
        assert_eq!(MissionPlan::start_on(&corner().plan, &flight), 5.0);
        let traced = FlightPlan::traced(&flight, 2.0);
        assert_eq!(MissionPlan::start_on(&traced, &flight), 0.0);
    }

    #[test]
    fn a_packet_on_the_ground_before_the_drone_set_out_keeps_it_there_until_then() {
        let plan = MissionPlan {
            start: 30.0,
            ..corner()
        };
        let mut st = MissionStation::new(Some(plan), setup());
        st.reset(&packet(0.5, 0.0, 0.0), 10.0);
        st.predict_to(29.9);
        assert!(st.position()[0] < 0.5, "{:?}", st.position());
        // Then from rest at PLAN_ACCEL toward the leg's 10 m/s.
        st.predict_to(33.0);
        assert!(
            (st.position()[0] - from_rest(10.0, 3.0)).abs() < 0.1,
            "{:?}",
            st.position()
        );
        // Once the drone has set out, a packet at rest there is not waiting for it.
        let mut late = MissionStation::new(Some(corner()), setup());
        late.reset(&packet(0.5, 0.0, 0.0), 10.0);
        late.predict_to(13.0);
        assert!(late.position()[0] > 1.0, "{:?}", late.position());
    }

    #[test]
    fn the_timetable_leaves_the_first_waypoint_when_the_drone_set_out_whatever_its_hold() {
        // A plan that holds 20 s at its first waypoint (a delay before the first leg), flown
        // from 30 s: the drone leaves that waypoint then, as a packet before then says.
        let c = corner().plan;
        let held = FlightPlan::with_holds(
            c.waypoints().to_vec(),
            vec![Some(10.0), Some(5.0)],
            vec![20.0, 0.0, 0.0],
        )
        .unwrap();
        let mp = MissionPlan {
            plan: held,
            start: 30.0,
            ..corner()
        };
        let mut st = MissionStation::new(Some(mp.clone()), setup());
        assert_eq!(st.scheduled(30.0), Some(0.0));
        let along = st.scheduled(33.0).unwrap();
        assert!((along - from_rest(10.0, 3.0)).abs() < 0.1, "{along}");
        // A packet on the ground before then holds the station there until the same moment.
        let mut ground = MissionStation::new(Some(mp), setup());
        ground.reset(&packet(0.0, 0.0, 0.0), 10.0);
        ground.predict_to(33.0);
        assert!(
            (ground.position()[0] - along).abs() < 1e-9,
            "{:?}",
            ground.position()
        );
    }

    #[test]
    fn its_uncertainty_grows_by_the_unknown_pace() {
        let mut st = MissionStation::new(Some(corner()), setup());
        st.reset(&packet(20.0, 0.0, 10.0), 0.0);
        st.predict_to(0.0);
        let c0 = st.position_covariance();
        st.predict_to(4.0);
        let grown = st.position_covariance() - c0;
        let expected = Matrix3::identity() * (PACE_SIGMA * 4.0).powi(2);
        assert!((grown - expected).abs().max() < 1e-9, "{grown}");
    }
}
