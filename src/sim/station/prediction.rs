//! How the station extrapolates between packets: the paper's literal prediction, or one bounded by
//! what a quadcopter can do and by how long a manoeuvre lasts (`--prediction paper|bounded`).

use super::HeadingNoise;
use crate::filter::SigmaParams;
use crate::math::exp;
use crate::models::{each_of_pair, Heading, ModelKind, MotionModel, A, OMEGA, PHI, PSI, V};
use crate::trajectory::Cornering;
use core::f64::consts::FRAC_PI_2;
use nalgebra::{SMatrix, SVector};
use serde::{Deserialize, Serialize};

/// The station's prediction rule (`--prediction`). The bounded one's limits are [`Bounds`], its
/// estimate once a packet is overdue [`StationPredictor`](super::StationPredictor)'s; the
/// variants' docs are `--prediction`'s help.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum Prediction {
    /// The paper (§III-B; reference §4): constant acceleration and turn rate for as long as no packet
    /// comes, only psi decaying by eta per step. Reproduces the paper's numbers; the default.
    #[default]
    Paper,
    /// The same equations, with the speed held in [0, 20 m/s] (25.5 for a plane's plan) and the
    /// pitch within ±90° (exactly: a step that reaches a limit is split there and the rate that
    /// drives past it set to 0), the
    /// acceleration fading from the packet on (time constant 2 s), and, once a packet is overdue,
    /// the speed and turn rate decaying toward 0 too and the estimate following the model from
    /// its own last value.
    Bounded,
}

impl Prediction {
    /// The CLI/JS name: `paper` or `bounded`.
    pub fn name(self) -> &'static str {
        match self {
            Prediction::Paper => "paper",
            Prediction::Bounded => "bounded",
        }
    }

    /// The station's sigma points (reference §4, "The station's sigma points").
    ///
    /// - Paper: the drone's, kappa = 3 − n (points at ±√3 σ). For n > 3 the centre weight is
    ///   negative (−1 for DR's 6 states, −2 for 3D-CTRA's 9), which is harmless over one 0.1 s
    ///   filter step but not over a whole send interval: once the heading's spread grows, the
    ///   points bend apart and the negatively weighted centre pushes the mean off every one of
    ///   them (3D-CTRA's p75 at SF10 / 125 kHz, 1 km, was 84.0 m against DR's 47.1 m;
    ///   docs/mission.md).
    /// - Bounded: kappa = 0 (van der Merwe 2004, §3.2: kappa ≥ 0 keeps every weight
    ///   non-negative), so the predicted mean is a weighted average of where the points fly.
    ///   Where packets come every 2 s this changes the p75 by under 2 %; at SF8–SF12 the richer
    ///   models' p75 falls by a quarter to a half.
    pub fn sigma_params(self) -> SigmaParams {
        match self {
            Prediction::Paper => SigmaParams::default(),
            Prediction::Bounded => SigmaParams {
                kappa: Some(0.0),
                ..SigmaParams::default()
            },
        }
    }
}

/// The limits of [`Prediction::Bounded`]. None binds while packets arrive on time unless the
/// received state itself runs into a physical limit (a braking drone stops instead of reversing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Top speed, m/s. 20 m/s: a fast consumer quadcopter's top speed, above every flight in
    /// the data (synthetic max 14.6 m/s, the Canberra flight 12.2 m/s) and below the codec's
    /// 25.5 m/s ceiling; a plane's is [`PLANE_V_MAX`] ([`Bounds::for_vehicle`]).
    pub v_max: f64,
    /// Largest |flight-path angle|, rad: pi/2, the codec's pitch range (a vertical climb); a
    /// constant tilt rate would otherwise fly the station's drone through loops.
    pub phi_max: f64,
    /// Time constant of the acceleration's decay from the packet on, s. A quadcopter reaches its
    /// cruise speed or stops within 1–3 s (synthetic flights: speed changes last 1–4 s), so an
    /// acceleration seen 2 s ago has most likely ended.
    pub tau_a: f64,
    /// Time constant of the turn rate's decay once a packet is overdue, s. Turns last longer
    /// than speed changes (synthetic banked turns and helices: 4–14 s).
    pub tau_omega: f64,
    /// Time constant of the speed's decay once a packet is overdue, s. Over a long gap the drone's
    /// velocity decorrelates (it turns, stops, climbs), so the expected displacement saturates at
    /// about v·tau_v instead of growing without bound (an Ornstein–Uhlenbeck velocity, as in
    /// Singer's model). 5 s: about one manoeuvre of the synthetic flights (4–14 s); on the paper
    /// grid at 3 km it minimises the mean error of every model (3 s and 10 s are within 25 %).
    pub tau_v: f64,
    /// How long the speed is held before it decays, s, when no packet is overdue yet: 15 s, the
    /// longest manoeuvre of the synthetic flights (4–14 s), after which the drone has most
    /// likely braked, turned or climbed. At SF10–SF12 the grace time (1.5 intervals of 29–148 s)
    /// would otherwise hold a packet's speed for 44–222 s. With it (16 seeds, 1 km) the
    /// synthetic set's p75 at SF10–SF12 moved −7 % to +0.9 % (3D-CTRA at SF12 with the overhead
    /// 118.0 → 109.5 m); on the real Canberra flight (16 seeds) the richer models' p95 fell from
    /// 1.18–1.35× DR's to 0.98–1.12× at SF10, from 1.38–1.72× to 1.12–1.21× at SF11 and from
    /// 4.2–4.8× to 2.0–2.3× at SF12. Held for 10 s the real flight's ratios fell further but the
    /// synthetic set's SF10 p75 rose 2–5 % (4 seeds); for 20 or 25 s they fell less. Below SF10
    /// a packet is older than 15 s only late in an interval (SF9: its last quarter) or after a
    /// loss, and the p75 moved by under 0.3 % (reference §4).
    pub speed_memory: f64,
    /// How many nominal send intervals may pass after a packet before it counts as overdue.
    /// 1.5: a periodic packet is at most one interval plus a sensor step plus its time on air
    /// late, so the decay starts only after a loss.
    pub grace_intervals: f64,
    /// The spread, m/s, of the speed about 0 that an overdue speed decays toward: as the decay
    /// forgets the speed it restores this much uncertainty, so the station's covariance grows
    /// with its ignorance instead of shrinking with the speed (Singer 1970: the discrete
    /// Gauss–Markov step x ← ρx + w, Var w = (1 − ρ²)σ²). 5 m/s: the root mean square speed
    /// of the synthetic set is 5.4 m/s, of the Canberra flight 3.7 m/s.
    pub sigma_v: f64,
    /// The same for the acceleration, m/s²: 1.5 (synthetic set 0.92, Canberra 1.8 rms).
    pub sigma_a: f64,
    /// The same for the turn rate, rad/s: 0.5 (synthetic set 0.27, Canberra 0.73 rms).
    pub sigma_omega: f64,
    /// The acceleration DR leaves out, m/s² rms per axis (tangential a, centripetal v·omega,
    /// vertical v·psi): 1.2 (synthetic set 0.98, Canberra 1.39). See
    /// [`Bounds::model_error_variance`].
    pub unmodelled_acceleration: f64,
    /// The jerk CTRA+ and 3D-CTRA leave out, m/s³ per axis: 0.3, half the synthetic set's rms
    /// jerk (0.59), since a jerk seldom lasts a whole gap. With [`Bounds::unmodelled_speed`]
    /// calibrated so that the 95 % region covers 93–97 % of the synthetic set at every EU868
    /// data rate, at 1 and 3 km (reference §4, "Honest uncertainty"); the Canberra flight,
    /// jerkier (3.4 rms), is covered less at SF7 (83–89 %, 64 seeds).
    pub unmodelled_jerk: f64,
    /// The speed, m/s, at which every model's error grows at most: 2. A manoeuvre the packet did
    /// not show changes the velocity by a few m/s and ends (speed changes last 1–4 s), so past a
    /// few seconds the position drifts off linearly, not with the square (DR) or cube (CTRA+,
    /// 3D-CTRA) of the age. Until 2026-12-04 only the speed limit capped them: over the
    /// synthetic set (8 seeds) CTRA+'s and 3D-CTRA's region covered 83–91 % at SF7/125 kHz–SF9
    /// and DR's 97–100 % from SF8 on; with this cap every model covers 93–97 % at every rate
    /// but SF12 on some seeds and SF7/250 kHz without the overhead (reference §4).
    pub unmodelled_speed: f64,
    /// The direct noise on heading and pitch: q, or chosen per flight ([`HeadingNoise`]).
    pub heading_noise: HeadingNoise,
}

/// A plane's top speed for the bounded and mission stations, m/s: the payload's ceiling (the
/// codec's speed byte, 0–25.5 m/s), since a plane flies at up to its `AIRSPEED_MAX` (ArduPlane's
/// default 22 m/s) and faster over the ground with the wind. Held to a quadcopter's 20 m/s, the
/// mission station paced a 24 m/s plane's survey 4 m/s slow from each packet (p75 at SF9 8.1 m
/// against 0.56 m; docs/beyond-the-paper.md, "A mission-aware station").
pub const PLANE_V_MAX: f64 = 25.5;

impl Bounds {
    /// The bounds for a drone flown as `vehicle` (the plan's,
    /// [`FlightPlan::cornering`](crate::FlightPlan::cornering); a multicopter without a plan): a
    /// plane's top speed is [`PLANE_V_MAX`], every other bound the default's.
    ///
    /// ```
    /// use loratrack::{Bounds, Cornering, PLANE_V_MAX};
    /// assert_eq!(Bounds::for_vehicle(Cornering::Multicopter), Bounds::default());
    /// assert_eq!(Bounds::for_vehicle(Cornering::FixedWing).v_max, PLANE_V_MAX);
    /// ```
    pub fn for_vehicle(vehicle: Cornering) -> Bounds {
        match vehicle {
            Cornering::Multicopter => Bounds::default(),
            Cornering::FixedWing => Bounds {
                v_max: PLANE_V_MAX,
                ..Bounds::default()
            },
        }
    }
}

impl Default for Bounds {
    fn default() -> Self {
        Bounds {
            v_max: 20.0,
            phi_max: FRAC_PI_2,
            tau_a: 2.0,
            tau_omega: 4.0,
            tau_v: 5.0,
            speed_memory: 15.0,
            grace_intervals: 1.5,
            sigma_v: 5.0,
            sigma_a: 1.5,
            sigma_omega: 0.5,
            unmodelled_acceleration: 1.2,
            unmodelled_jerk: 0.3,
            unmodelled_speed: 2.0,
            heading_noise: HeadingNoise::Fixed,
        }
    }
}

/// Which limit a bounded step ran into.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Limit {
    Speed(f64),
    Pitch(f64),
}

/// A motion model whose speed and pitch stay within [`Bounds`]: a step that would cross a limit
/// is propagated exactly to the moment it reaches it, the limit is held (a → 0 at the speed
/// limit, psi → 0 at the pitch limit) and the rest of the step follows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded<M> {
    /// The model that does the propagation.
    pub model: M,
    /// The limits.
    pub bounds: Bounds,
}

impl<M> Bounded<M> {
    /// The earliest limit reached within `left` seconds, and when (on a tie the speed's).
    fn next_limit<const N: usize>(&self, x: &SVector<f64, N>, left: f64) -> Option<(f64, Limit)> {
        let b = &self.bounds;
        let hit = |value: f64, rate: f64, lo: f64, hi: f64| -> Option<(f64, f64)> {
            let (t, bound) = if rate < 0.0 && value > lo {
                ((lo - value) / rate, lo)
            } else if rate > 0.0 && value < hi {
                ((hi - value) / rate, hi)
            } else {
                return None;
            };
            (t < left).then_some((t, bound))
        };
        // Written out rather than as a chain of options: every sigma point of every bounded
        // station step asks, twice (`tail_holds`, then the propagation).
        let speed = if N > A {
            hit(x[V], x[A], 0.0, b.v_max).map(|(t, v)| (t, Limit::Speed(v)))
        } else {
            None
        };
        let pitch = if N > PSI {
            hit(x[PHI], x[PSI], -b.phi_max, b.phi_max).map(|(t, p)| (t, Limit::Pitch(p)))
        } else {
            None
        };
        match (speed, pitch) {
            (Some(s), Some(p)) => Some(if p.0 < s.0 { p } else { s }),
            (s, p) => s.or(p),
        }
    }

    /// Whether the speed of `x` is at or past a limit with the acceleration pushing further.
    fn speed_held<const N: usize>(&self, x: &SVector<f64, N>) -> bool {
        N > A && ((x[V] <= 0.0 && x[A] < 0.0) || (x[V] >= self.bounds.v_max && x[A] > 0.0))
    }

    /// Whether the pitch of `x` is at or past a limit with the tilt rate pushing further.
    fn pitch_held<const N: usize>(&self, x: &SVector<f64, N>) -> bool {
        let max = self.bounds.phi_max;
        N > PSI && ((x[PHI] <= -max && x[PSI] < 0.0) || (x[PHI] >= max && x[PSI] > 0.0))
    }

    /// Whether `x` moves over `dt` exactly as the unbounded model moves it: no rate held, no limit
    /// reached.
    fn free<const N: usize>(&self, x: &SVector<f64, N>, dt: f64) -> bool {
        !self.speed_held(x) && !self.pitch_held(x) && self.next_limit(x, dt).is_none()
    }

    /// Stops the rates that would push a state further past a limit it is already at or beyond.
    /// The values themselves are left alone: a sigma point with a negative speed describes the
    /// same motion as the opposite course, and clamping it would bias a hovering drone's mean.
    fn hold<const N: usize>(&self, mut x: SVector<f64, N>) -> SVector<f64, N> {
        if self.speed_held(&x) {
            x[A] = 0.0;
        }
        if self.pitch_held(&x) {
            x[PSI] = 0.0;
        }
        x
    }
}

impl<const N: usize, M: MotionModel<N>> MotionModel<N> for Bounded<M> {
    const KIND: ModelKind = M::KIND;

    fn propagate(&self, s: &SVector<f64, N>, dt: f64) -> SVector<f64, N> {
        let mut x = self.hold(*s);
        let mut left = dt;
        // Each limit, once reached, stops its own rate, so at most two events occur.
        for _ in 0..2 {
            let Some((t, limit)) = self.next_limit(&x, left) else {
                break;
            };
            x = self.model.propagate(&x, t);
            match limit {
                Limit::Speed(v) => (x[V], x[A]) = (v, 0.0),
                Limit::Pitch(p) => (x[PHI], x[PSI]) = (p, 0.0),
            }
            left -= t;
        }
        self.model.propagate(&x, left)
    }

    const SHARES_HEADING: bool = M::SHARES_HEADING;

    /// The model's own tail, where it holds: for a state that moves freely over `dt`
    /// ([`Self::tail_holds`]).
    const LINEAR_TAIL: Option<&'static [(usize, usize)]> = M::LINEAR_TAIL;

    /// [`Self::propagate`], passing the heading on where no limit is reached within `dt` (the
    /// common case), so that a bounded station's sigma points share headings as the model's do.
    fn propagate_with(&self, s: &SVector<f64, N>, heading: &Heading, dt: f64) -> SVector<f64, N> {
        let x = self.hold(*s);
        match self.next_limit(&x, dt) {
            None => self.model.propagate_with(&x, heading, dt),
            Some(_) => self.propagate(s, dt),
        }
    }

    /// The model's batched pair where both points move freely (3D-CTRA computes the pair's six
    /// arc integrals together), each point alone where either is held or reaches a limit.
    fn propagate_pair(
        &self,
        states: [&SVector<f64, N>; 2],
        headings: [&Heading; 2],
        dt: f64,
    ) -> [SVector<f64, N>; 2] {
        if states.iter().all(|s| self.free(s, dt)) {
            self.model.propagate_pair(states, headings, dt)
        } else {
            each_of_pair(self, states, headings, dt)
        }
    }

    /// Where no rate is held and no limit reached within `dt`, the step is the model's.
    fn tail_holds(&self, state: &SVector<f64, N>, dt: f64) -> bool {
        self.free(state, dt) && self.model.tail_holds(state, dt)
    }

    fn decay_tilt_rate(&self, state: &mut SVector<f64, N>, eta: f64) {
        self.model.decay_tilt_rate(state, eta);
    }
}

impl Bounds {
    /// The variance per axis, m², of what `kind`'s extrapolation leaves out after `age` s without
    /// a packet: the first derivative the model holds at zero, held for the whole gap. DR
    /// extrapolates a constant velocity, so an acceleration a moves the drone a·age²/2 off it;
    /// CTRA+ and 3D-CTRA extrapolate a constant acceleration and turn rate, so a jerk j moves it
    /// j·age³/6 off. A bounded station adds it to the position covariance it reports: the
    /// filter's own covariance grows only with the drone's process noise, which describes the
    /// 10 Hz filter's steps, not minutes of extrapolation (without it the 95 % region covered
    /// 51 % of the synthetic set at 5 km). At most (unmodelled_speed·age)², binding from 3.3 s
    /// on for DR and from 6.3 s on for CTRA+ and 3D-CTRA at the defaults (reference §4).
    pub fn model_error_variance(&self, kind: ModelKind, age: f64) -> f64 {
        let off = match kind {
            ModelKind::Dr => self.unmodelled_acceleration * age * age / 2.0,
            ModelKind::CtraPlus | ModelKind::Ctra3d => self.unmodelled_jerk * age * age * age / 6.0,
        };
        // What a model missed is a manoeuvre, which ends: past it the drone drifts off linearly.
        // Held for minutes (SF12), a quadratic or cubic error claimed tens of kilometres.
        let off = off.min(self.unmodelled_speed * age);
        off * off
    }

    /// The manoeuvre decay of a bounded station after a step that took the time since the last
    /// packet from `age_before` to `age_after` (s), with `grace` s before a packet is overdue. A
    /// first-order Gauss–Markov (Singer 1970) model of how a manoeuvre, and the motion itself,
    /// decorrelate: each decaying value x ← ρx with ρ = e^(−τ/tau) over the part τ of the step
    /// it decays in, and the covariance transformed alike (P ← DPDᵀ).
    ///
    /// - The acceleration decays from the packet on (tau_a): on a multicopter it is mostly
    ///   short-lived, a speed change of 1–4 s or the noise of a hovering drone, so holding it
    ///   for a whole interval overshoots (reference §4, "Manoeuvres only when significant").
    /// - The turn rate decays only once the packet is overdue (tau_omega): turns last longer
    ///   than the interval, and decaying it from the packet on cost the synthetic set at SF9
    ///   (3D-CTRA p75 +11 %). Decaying it after 8 or 15 s where the grace time is longer (SF10–SF12)
    ///   cost the real Canberra flight too: a held turn keeps a loitering drone's estimate near
    ///   where it was.
    /// - The speed decays once the packet is overdue or older than [`Bounds::speed_memory`],
    ///   whichever comes first (tau_v).
    /// - Once overdue, the forgotten part's uncertainty is restored on the diagonal
    ///   ((1 − ρ²)σ², [`Bounds::sigma_v`] …). Within the grace time it is not: the position's
    ///   model error ([`Bounds::model_error_variance`]) covers a change within an interval, and
    ///   restoring it there widened the 95 % region (coverage95 0.984 at 1 km) and spread the
    ///   sigma points so that the unscented mean hedged more (SF9 p75 +14 %).
    pub fn decay_manoeuvre<const N: usize>(
        &self,
        x: &mut SVector<f64, N>,
        p: &mut SMatrix<f64, N, N>,
        age_before: f64,
        age_after: f64,
        grace: f64,
    ) {
        let decays = [
            (V, self.tau_v, self.sigma_v, grace.min(self.speed_memory)),
            (A, self.tau_a, self.sigma_a, 0.0),
            (OMEGA, self.tau_omega, self.sigma_omega, grace),
        ];
        let overdue = age_after > grace;
        for (i, tau, sigma, from) in decays {
            let decaying = age_after - age_before.max(from);
            if i >= N || decaying <= 0.0 {
                continue;
            }
            let rho = exp(-decaying / tau);
            x[i] *= rho;
            for k in 0..N {
                p[(i, k)] *= rho;
                p[(k, i)] *= rho;
            }
            if overdue {
                p[(i, i)] += (1.0 - rho * rho) * sigma * sigma;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{SigmaPoints, Ukf};
    use crate::models::{Ctra3d, CtraPlus, Dr, ANGLES, THETA, X, Z};

    /// `--prediction bounded`'s help is the variant's doc, written with the numbers.
    #[cfg(cli)]
    #[test]
    fn the_cli_help_states_the_default_bounds() {
        let value = clap::ValueEnum::to_possible_value(&Prediction::Bounded).unwrap();
        let help = value.get_help().unwrap().to_string();
        let b = Bounds::default();
        for said in [
            format!("[0, {} m/s]", b.v_max),
            format!("±{}°", b.phi_max.to_degrees().round()),
            format!("time constant {} s", b.tau_a),
        ] {
            assert!(help.contains(&said), "{said}: {help}");
        }
    }

    fn bounded<M>(model: M) -> Bounded<M> {
        Bounded {
            model,
            bounds: Bounds::default(),
        }
    }

    #[test]
    fn equals_the_model_when_no_limit_is_reached() {
        let s = SVector::<f64, 9>::from([1.0, 2.0, 30.0, 0.3, 0.1, 8.0, 0.5, 0.3, 0.05]);
        let a = Ctra3d.propagate(&s, 2.0);
        let b = bounded(Ctra3d).propagate(&s, 2.0);
        assert_eq!(a, b);
    }

    #[test]
    fn a_braking_drone_stops_instead_of_reversing() {
        // v = 4 m/s braking at 2 m/s²: it stops after 2 s, having flown 4 m, and stays there.
        let s = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.0, 4.0, -2.0, 0.0]);
        let out = bounded(CtraPlus).propagate(&s, 10.0);
        assert!((out[X] - 4.0).abs() < 1e-12, "x {}", out[X]);
        assert_eq!((out[V], out[A]), (0.0, 0.0));
        let paper = CtraPlus.propagate(&s, 10.0);
        assert!(
            paper[V] < 0.0 && paper[X] < 0.0,
            "the paper's model flies backwards"
        );
    }

    #[test]
    fn speed_never_exceeds_v_max() {
        let s = SVector::<f64, 9>::from([0.0, 0.0, 0.0, 0.0, 0.0, 15.0, 3.0, 0.2, 0.0]);
        let out = bounded(Ctra3d).propagate(&s, 60.0);
        assert_eq!(out[V], Bounds::default().v_max);
    }

    #[test]
    fn pitch_stops_at_the_vertical() {
        // A steady pull-up at 0.5 rad/s reaches the vertical after pi s and then climbs straight up.
        let s = SVector::<f64, 9>::from([0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.5]);
        let out = bounded(Ctra3d).propagate(&s, 10.0);
        assert_eq!(out[PHI], FRAC_PI_2);
        assert_eq!(out[PSI], 0.0);
        let reached = Ctra3d.propagate(&s, core::f64::consts::PI);
        assert!((out[Z] - (reached[Z] + 5.0 * (10.0 - core::f64::consts::PI))).abs() < 1e-9);
    }

    #[test]
    fn dr_is_unchanged() {
        let s = SVector::<f64, 6>::from([1.0, 2.0, 3.0, 0.6, 0.2, 5.0]);
        assert_eq!(bounded(Dr).propagate(&s, 7.0), Dr.propagate(&s, 7.0));
    }

    #[test]
    fn the_acceleration_fades_from_the_packet_on_and_the_turn_only_once_overdue() {
        let b = Bounds::default();
        let mut x = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 1.0, 0.4]);
        let mut p = SMatrix::<f64, 8, 8>::identity();
        b.decay_manoeuvre(&mut x, &mut p, 1.0, 2.0, 3.0);
        // Within the grace time: the acceleration and its variance shrink, nothing is restored,
        // and the speed and turn rate are held.
        let rho = exp(-1.0 / b.tau_a);
        assert!((x[A] - rho).abs() < 1e-15);
        assert!((p[(A, A)] - rho * rho).abs() < 1e-15);
        assert_eq!((x[V], x[OMEGA], p[(OMEGA, OMEGA)]), (5.0, 0.4, 1.0));
        // Half of this step is past the grace time: the turn rate decays over that half only.
        let (a_before, var_before) = (x[A], p[(A, A)]);
        b.decay_manoeuvre(&mut x, &mut p, 2.5, 3.5, 3.0);
        assert!((x[OMEGA] - 0.4 * exp(-0.5 / b.tau_omega)).abs() < 1e-15);
        let rho = exp(-1.0 / b.tau_a);
        assert!((x[A] - a_before * rho).abs() < 1e-15);
        // Overdue, the variance regains what the decay forgot.
        let restored = var_before * rho * rho + (1.0 - rho * rho) * b.sigma_a * b.sigma_a;
        assert!((p[(A, A)] - restored).abs() < 1e-15);
        assert!((p[(X, A)] - 0.0).abs() < 1e-15 && p[(V, A)] == 0.0);
        assert_eq!(x[THETA], 0.0);
    }

    #[test]
    fn at_slow_rates_the_speed_fades_after_its_memory_though_no_packet_is_overdue() {
        // SF12: a 60 s grace time. The speed is held for speed_memory, then decays; the turn
        // rate is held until the packet is overdue, and nothing is restored before then.
        let b = Bounds::default();
        let grace = 60.0;
        let mut x = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 0.0, 0.4]);
        let mut p = SMatrix::<f64, 8, 8>::identity();
        b.decay_manoeuvre(&mut x, &mut p, 0.0, b.speed_memory, grace);
        assert_eq!((x[V], p[(V, V)]), (5.0, 1.0));
        b.decay_manoeuvre(&mut x, &mut p, b.speed_memory, b.speed_memory + 5.0, grace);
        let rho = exp(-5.0 / b.tau_v);
        assert!((x[V] - 5.0 * rho).abs() < 1e-15);
        assert!((p[(V, V)] - rho * rho).abs() < 1e-15);
        assert_eq!((x[OMEGA], p[(OMEGA, OMEGA)]), (0.4, 1.0));
    }

    #[test]
    fn a_long_silence_leaves_the_manoeuvre_as_uncertain_as_the_flights_are() {
        // However sure the last packet was, after many time constants the speed's variance is
        // its stationary spread, not zero.
        let b = Bounds::default();
        let mut x = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 1.0, 0.4]);
        let mut p = SMatrix::<f64, 8, 8>::identity() * 1e-4;
        b.decay_manoeuvre(&mut x, &mut p, 0.0, 200.0, 1.0);
        assert!((p[(V, V)] - b.sigma_v * b.sigma_v).abs() < 1e-6);
        assert!((p[(OMEGA, OMEGA)] - b.sigma_omega * b.sigma_omega).abs() < 1e-6);
    }

    #[test]
    fn the_model_error_grows_with_the_first_derivative_each_model_leaves_out() {
        let b = Bounds::default();
        // DR: a·t²/2; CTRA: j·t³/6, so doubling the age multiplies the spread by 4 and 8 (within
        // the first seconds, before a missed manoeuvre has ended).
        let dr = |t| b.model_error_variance(ModelKind::Dr, t).sqrt();
        let ct = |t| b.model_error_variance(ModelKind::Ctra3d, t).sqrt();
        assert!((dr(2.0) - b.unmodelled_acceleration * 2.0).abs() < 1e-12);
        assert!((dr(3.0) / dr(1.5) - 4.0).abs() < 1e-12);
        assert!((ct(4.0) / ct(2.0) - 8.0).abs() < 1e-12);
        assert_eq!(b.model_error_variance(ModelKind::CtraPlus, 0.0), 0.0);
    }

    #[test]
    fn the_model_error_claims_no_more_than_a_drift_the_speed_limit_allows() {
        let b = Bounds::default();
        // 95 s without a packet (the real flight at SF12): j·t³/6 alone put 43 km on each axis,
        // a 95 % bound of 130 km for a drone that flies at most 20 m/s.
        assert!(b.unmodelled_speed < b.v_max);
        for kind in ModelKind::ALL {
            let off = b.model_error_variance(kind, 95.0).sqrt();
            assert!(
                (off - b.unmodelled_speed * 95.0).abs() < 1e-9,
                "{kind:?}: {off}"
            );
        }
    }

    #[test]
    fn a_manoeuvre_a_model_missed_drifts_it_off_linearly_once_it_has_ended() {
        let b = Bounds::default();
        let dr = |t| b.model_error_variance(ModelKind::Dr, t).sqrt();
        let ct = |t| b.model_error_variance(ModelKind::CtraPlus, t).sqrt();
        // a·t²/2 up to 3.3 s and j·t³/6 up to 6.3 s at the defaults, then s·t.
        let dr_knee = 2.0 * b.unmodelled_speed / b.unmodelled_acceleration;
        let ct_knee = (6.0 * b.unmodelled_speed / b.unmodelled_jerk).sqrt();
        assert!(
            (dr(0.5 * dr_knee) - b.unmodelled_acceleration * (0.5 * dr_knee).powi(2) / 2.0).abs()
                < 1e-12
        );
        assert!(
            (ct(0.5 * ct_knee) - b.unmodelled_jerk * (0.5 * ct_knee).powi(3) / 6.0).abs() < 1e-12
        );
        assert!((dr(20.0) / dr(10.0) - 2.0).abs() < 1e-12);
        assert!((ct(20.0) / ct(10.0) - 2.0).abs() < 1e-12);
        assert!(
            dr_knee > 2.0 && dr_knee < ct_knee && ct_knee < 10.0,
            "{dr_knee} {ct_knee}"
        );
    }

    /// A model's propagation without its linear tail: the filter takes the general sums.
    struct General<M>(M);
    impl<const N: usize, M: MotionModel<N>> MotionModel<N> for General<M> {
        const KIND: ModelKind = M::KIND;
        const SHARES_HEADING: bool = M::SHARES_HEADING;
        fn propagate(&self, s: &SVector<f64, N>, dt: f64) -> SVector<f64, N> {
            self.0.propagate(s, dt)
        }
        fn propagate_with(&self, s: &SVector<f64, N>, h: &Heading, dt: f64) -> SVector<f64, N> {
            self.0.propagate_with(s, h, dt)
        }
    }

    /// A bounded station's filter at `state` with a covariance of about `spread`² per
    /// component, and whether the model's linear tail holds at every sigma point over `dt`.
    fn filter<const N: usize, M: MotionModel<N> + Copy>(
        model: M,
        state: [f64; 9],
        spread: f64,
        dt: f64,
    ) -> (Ukf<N>, bool) {
        let x = SVector::<f64, N>::from_fn(|i, _| state[i]);
        let p = SMatrix::<f64, N, N>::from_fn(|i, j| {
            let s2 = spread * spread;
            if i == j {
                s2 * (1.0 + 0.1 * i as f64)
            } else {
                0.1 * s2 / (1.0 + (i + j) as f64)
            }
        });
        let q = SMatrix::<f64, N, N>::identity() * 0.01;
        let ukf = Ukf::new(x, p, q, Prediction::Bounded.sigma_params(), ANGLES).unwrap();
        let gamma = (N as f64).sqrt(); // kappa = 0
        let l = nalgebra::Cholesky::new(p).unwrap().l();
        let holds = SigmaPoints::tail_holds(&bounded(model), &x, &l, gamma, dt);
        (ukf, holds)
    }

    /// Predicts `ukf` over `dt` through the bounded model, in closed form where it holds and
    /// through the general sums, and checks that both agree.
    fn closed_equals_general<const N: usize, M: MotionModel<N> + Copy>(
        model: M,
        ukf: &Ukf<N>,
        dt: f64,
    ) {
        let (mut closed, mut general) = (ukf.clone(), ukf.clone());
        closed.predict(&bounded(model), dt);
        general.predict(&General(bounded(model)), dt);
        assert!(
            (closed.x - general.x).norm() < 1e-9,
            "{:?}: {} vs {}",
            M::KIND,
            closed.x,
            general.x
        );
        assert!((closed.p - general.p).norm() < 1e-9, "{:?}", M::KIND);
    }

    #[test]
    fn a_freely_moving_bounded_station_predicts_as_the_general_sums_do() {
        let cruising = [10.0, -5.0, 40.0, 3.0, 0.1, 8.0, 0.3, 0.2, 0.05];
        for dt in [0.1, 1.0] {
            let (ukf, holds) = filter::<6, _>(Dr, cruising, 0.7, dt);
            assert!(holds);
            closed_equals_general(Dr, &ukf, dt);
            let (ukf, holds) = filter::<8, _>(CtraPlus, cruising, 0.3, dt);
            assert!(holds);
            closed_equals_general(CtraPlus, &ukf, dt);
            let (ukf, holds) = filter::<9, _>(Ctra3d, cruising, 0.3, dt);
            assert!(holds);
            closed_equals_general(Ctra3d, &ukf, dt);
        }
    }

    #[test]
    fn where_a_sigma_point_reaches_a_limit_the_tail_does_not_hold() {
        // Braking at 1 m/s² from 0.5 m/s: the centre stops within 1 s; climbing at 0.3 rad/s
        // from 1.5 rad, the pitch reaches the vertical within 0.3 s.
        let braking = [0.0, 0.0, 10.0, 0.0, 0.0, 0.5, -1.0, 0.0, 0.0];
        let (ukf, holds) = filter::<8, _>(CtraPlus, braking, 0.05, 1.0);
        assert!(!holds);
        closed_equals_general(CtraPlus, &ukf, 1.0);
        let climbing = [0.0, 0.0, 10.0, 0.0, 1.5, 5.0, 0.0, 0.0, 0.3];
        let (ukf, holds) = filter::<9, _>(Ctra3d, climbing, 0.01, 1.0);
        assert!(!holds);
        closed_equals_general(Ctra3d, &ukf, 1.0);
        // The same states over a step too short to reach either limit.
        assert!(filter::<8, _>(CtraPlus, braking, 0.05, 0.1).1);
        assert!(filter::<9, _>(Ctra3d, climbing, 0.01, 0.1).1);
    }
}
