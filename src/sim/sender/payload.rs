//! Which payload a packet takes (`--payload`): the model's own (the paper), or the smallest of
//! the paper's three that carries every manoeuvre field worth sending (reference §5, "Lean
//! payloads").

use crate::models::ModelKind;
use serde::{Deserialize, Serialize};

/// How large a manoeuvre field (a, ω, ψ) must be, in standard deviations of the drone filter's
/// settled estimate of it, to be worth its bytes: 10 (3D-CTRA with the paper's noise: 1.8 m/s²,
/// 0.17 rad/s, 0.17 rad/s; the synthetic set's rms manoeuvres are 0.92 m/s², 0.27 and
/// 0.12 rad/s).
///
/// Not the statistical test (where a field stands out from its noise: about 2 σ) but the
/// manoeuvres that move a forecast over a whole interval, where the bytes decide how long
/// that interval is. Chosen on the whole synthetic set, seeds 1–16, 1 km: the IMM's p75 against
/// the best single model's at SF11 without overhead was 1.054× at 2 σ, 1.037× at 5 σ, 1.018×
/// at 10 σ and 1.019× at 20 σ; at 20 σ the richer models' p75 at SF7 / 250 kHz with LoRaWAN's
/// overhead rose by a tenth (IMM 1.88 → 2.08 m), and leaving out every field whose frame it
/// shortens, 2.65 m (docs/beyond-the-paper.md, "Lean payloads").
pub const LEAN_SIGNIFICANCE: f64 = 10.0;

/// The payload rule (`--payload`; the lean rule's significance: [`LEAN_SIGNIFICANCE`], its
/// frames: [`LeanPayload`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum PayloadChoice {
    /// Every packet carries the model's own payload: 9, 11 or 12 bytes (the paper, Table II).
    #[default]
    Full,
    /// Each packet carries the smallest of the paper's payloads (DR's 9 bytes, CTRA+'s 11)
    /// that leaves out only manoeuvre fields within 10 standard deviations of zero, where its
    /// frame takes less time on air.
    Lean,
}

impl PayloadChoice {
    /// `--payload`'s help, with the significance the rule uses ([`LEAN_SIGNIFICANCE`]).
    #[cfg(cli)]
    pub fn cli_help() -> String {
        format!(
            "Payload: full (the model's own 9, 11 or 12 bytes, the paper) or lean (the smallest \
             of the three that carries every manoeuvre field over {LEAN_SIGNIFICANCE} standard \
             deviations of the drone's estimate, where its frame is shorter on air: the next \
             packet then comes sooner)."
        )
    }

    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            PayloadChoice::Full => "full",
            PayloadChoice::Lean => "lean",
        }
    }
}

/// The lean payload rule for a drone filtering with `model`: which of the paper's payloads each
/// packet takes.
///
/// A packet may leave out a, ω (the DR payload) or ψ (the CTRA+ payload) when each field left
/// out lies within [`LEAN_SIGNIFICANCE`] standard deviations of zero; the station decodes the
/// shorter payload by its length and reads the missing fields as 0. The duty cycle's off-time
/// follows the packet sent, so a shorter frame brings the next packet sooner. Of the payloads
/// allowed, the one with the shortest frame is sent, the richer on a tie: a LoRa frame grows
/// in blocks of 4 · (SF − 2 DE) bits, so at SF7 / 250 kHz without overhead 9 and 12 bytes take
/// the same time on air and nothing is left out.
///
/// ```
/// use loratrack::{LeanPayload, ModelKind};
/// let lean = LeanPayload::new(ModelKind::Ctra3d, [0.18, 0.017, 0.017]);
/// let straight = [0.0, 0.0, 50.0, 1.0, 0.0, 8.0, 0.1, 0.01, 0.0];
/// let turning = [0.0, 0.0, 50.0, 1.0, 0.0, 8.0, 0.1, 0.3, 0.0];
/// // Where 9 and 11 bytes take 3 blocks and 12 bytes 4, both go with CTRA+'s payload (the
/// // richer of the two shortest); where each byte counts, the straight leg goes with DR's.
/// let blocks = |kind: ModelKind| if kind == ModelKind::Ctra3d { 4.0 } else { 3.0 };
/// assert_eq!(lean.choose(&straight, blocks), ModelKind::CtraPlus);
/// assert_eq!(lean.choose(&turning, blocks), ModelKind::CtraPlus);
/// let bytes = |kind: ModelKind| kind.payload_bytes() as f64;
/// assert_eq!(lean.choose(&straight, bytes), ModelKind::Dr);
/// assert_eq!(lean.choose(&turning, bytes), ModelKind::CtraPlus);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeanPayload {
    model: ModelKind,
    /// The drone filter's settled standard deviation of a (m/s²), ω and ψ (rad/s).
    manoeuvre_sd: [f64; 3],
}

impl LeanPayload {
    /// The rule for a drone filtering with `model`, whose settled estimate of a, ω and ψ has
    /// the standard deviations `manoeuvre_sd` (m/s², rad/s, rad/s; [`DroneCovariances`]).
    ///
    /// [`DroneCovariances`]: crate::sim::station::DroneCovariances
    pub fn new(model: ModelKind, manoeuvre_sd: [f64; 3]) -> Self {
        LeanPayload {
            model,
            manoeuvre_sd,
        }
    }

    /// The payload for a packet carrying `estimate` (9 components, a ω ψ at 6–8), of those
    /// whose frame `time_on_air` (s) is least.
    pub fn choose(
        &self,
        estimate: &[f64; 9],
        mut time_on_air: impl FnMut(ModelKind) -> f64,
    ) -> ModelKind {
        let own = self.model.state_len();
        let negligible = |kind: ModelKind| {
            (kind.state_len()..own)
                .all(|i| estimate[i].abs() < LEAN_SIGNIFICANCE * self.manoeuvre_sd[i - 6])
        };
        let mut best = (self.model, time_on_air(self.model));
        // From the richer to the poorer, so that a tie keeps the richer.
        for kind in [ModelKind::CtraPlus, ModelKind::Dr] {
            if kind.state_len() >= own || !negligible(kind) {
                continue;
            }
            let t = time_on_air(kind);
            if t < best.1 {
                best = (kind, t);
            }
        }
        best.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--payload lean`'s help is the variant's doc, written with the significance.
    #[cfg(cli)]
    #[test]
    fn the_cli_help_states_the_lean_significance() {
        let value = clap::ValueEnum::to_possible_value(&PayloadChoice::Lean).unwrap();
        let help = value.get_help().unwrap().to_string();
        let said = format!("within {LEAN_SIGNIFICANCE} standard deviations of zero");
        assert!(help.contains(&said), "{help}");
    }

    const SD: [f64; 3] = [0.2, 0.02, 0.02];

    fn state(a: f64, omega: f64, psi: f64) -> [f64; 9] {
        [0.0, 0.0, 50.0, 0.5, 0.0, 8.0, a, omega, psi]
    }

    #[test]
    fn a_manoeuvre_past_its_significance_keeps_its_field() {
        let lean = LeanPayload::new(ModelKind::Ctra3d, SD);
        let bytes = |k: ModelKind| k.payload_bytes() as f64;
        assert_eq!(lean.choose(&state(0.5, 0.05, 0.05), bytes), ModelKind::Dr);
        assert_eq!(
            lean.choose(&state(2.5, 0.05, 0.05), bytes),
            ModelKind::CtraPlus
        );
        assert_eq!(
            lean.choose(&state(0.5, -0.25, 0.05), bytes),
            ModelKind::CtraPlus
        );
        assert_eq!(
            lean.choose(&state(0.5, 0.05, -0.25), bytes),
            ModelKind::Ctra3d
        );
    }

    #[test]
    fn nothing_is_left_out_where_the_frame_would_not_shorten() {
        let lean = LeanPayload::new(ModelKind::Ctra3d, SD);
        assert_eq!(
            lean.choose(&state(0.0, 0.0, 0.0), |_| 1.0),
            ModelKind::Ctra3d
        );
    }

    #[test]
    fn a_ctra_plus_drone_may_only_drop_to_dr() {
        let lean = LeanPayload::new(ModelKind::CtraPlus, SD);
        let bytes = |k: ModelKind| k.payload_bytes() as f64;
        // Its ψ slot is unused (0 in the estimate) and never read.
        assert_eq!(lean.choose(&state(0.1, 0.0, 9.0), bytes), ModelKind::Dr);
        assert_eq!(
            lean.choose(&state(3.0, 0.0, 0.0), bytes),
            ModelKind::CtraPlus
        );
        let dr = LeanPayload::new(ModelKind::Dr, SD);
        assert_eq!(dr.choose(&state(0.0, 0.0, 0.0), bytes), ModelKind::Dr);
    }
}
