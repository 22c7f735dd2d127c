//! The mission-aware station (`--model mission`): between packets it flies the drone's plan
//! instead of extrapolating a manoeuvre (reference §16; the paper's future work, §V, names a
//! movement model that uses mission-level information).

use super::{Prediction, StationPredictor, StationSetup, Tracker};
use crate::math::exp;
use crate::models::Ctra3d;
use crate::trajectory::FlightPlan;
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
}

/// The mission-aware station: each packet that places the drone within the tolerance of its plan
/// is projected onto the plan, and the station then flies the plan from there — at the packet's
/// speed, giving way to each leg's planned speed over [`PACE_TIME`], with the packet's offset
/// from the plan closing over [`OFFSET_TIME`]. A packet off the plan (or no plan) hands the
/// estimate to a bounded 3D-CTRA station, which runs beside it on every packet, until a packet
/// is back on the plan. The drone sends the 12-byte 3D-CTRA payload.
///
/// Its covariance on the plan: the packet's (the drone filter's settled covariance, as the
/// bounded station's), plus ([`PACE_SIGMA`]·τ)² in every direction, τ s after the packet.
pub struct MissionStation {
    plan: Option<MissionPlan>,
    fallback: StationPredictor<9, Ctra3d>,
    step: f64,
    /// The bounded station's top speed, m/s: a packet's speed is held within it on the plan too.
    speed_limit: f64,
    following: Option<Following>,
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

    /// The speed along the plan `tau` s after the packet, at `along` m.
    fn pace(plan: &FlightPlan, f: &Following, tau: f64, along: f64) -> f64 {
        match plan.speed_at(along) {
            Some(v) => v + (f.speed - v) * exp(-tau / PACE_TIME),
            None => f.speed,
        }
    }
}

impl Tracker for MissionStation {
    fn reset(&mut self, state: &[f64; 9], sent: f64) {
        self.fallback.reset(state, sent);
        let Some(mp) = &self.plan else {
            return;
        };
        let p = [state[0], state[1], state[2]];
        let plan = &mp.plan;
        // Near where the station expected the drone, so that a path that crosses itself is
        // followed on the right pass; anywhere on the plan otherwise.
        let near = self.following.map(|f| {
            let margin = SEARCH_MARGIN + SEARCH_SPEED * (sent - f.sent).max(0.0);
            plan.nearest(&p, f.along - margin, f.along + margin)
        });
        let found = match near {
            Some(n) if n.off <= mp.tolerance => n,
            _ => plan.nearest(&p, 0.0, plan.length()),
        };
        if found.off > mp.tolerance {
            self.following = None;
            return;
        }
        let on = plan.point_at(found.along);
        self.following = Some(Following {
            sent,
            offset: core::array::from_fn(|k| p[k] - on[k]),
            speed: state[5].clamp(0.0, self.speed_limit),
            covariance: self.fallback.position_covariance(),
            t: sent,
            along: found.along,
        });
    }

    fn predict_to(&mut self, t: f64) {
        self.fallback.predict_to(t);
        let (Some(mp), Some(f)) = (&self.plan, &mut self.following) else {
            return;
        };
        while f.t < t {
            let dt = self.step.min(t - f.t);
            // The midpoint's pace: second order in dt.
            let v = Self::pace(&mp.plan, f, f.t + dt / 2.0 - f.sent, f.along);
            f.along = (f.along + v * dt).min(mp.plan.length());
            f.t += dt;
        }
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

    /// East 100 m at 10 m/s, then north 100 m at 5 m/s, 20 m up.
    fn corner() -> MissionPlan {
        MissionPlan {
            plan: FlightPlan::new(
                vec![[0.0, 0.0, 20.0], [100.0, 0.0, 20.0], [100.0, 100.0, 20.0]],
                vec![Some(10.0), Some(5.0)],
            )
            .unwrap(),
            tolerance: 10.0,
        }
    }

    /// A 3D-CTRA state at (x, y, 20) heading east at `v` m/s.
    fn packet(x: f64, y: f64, v: f64) -> [f64; 9] {
        [x, y, 20.0, 0.0, 0.0, v, 0.0, 0.0, 0.0]
    }

    #[test]
    fn follows_the_plan_round_a_corner_at_the_planned_speeds() {
        let mut st = MissionStation::new(Some(corner()), setup());
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
