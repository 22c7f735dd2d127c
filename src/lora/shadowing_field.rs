//! Log-normal shadowing as a field fixed in space (`--shadowing-model field`): the same fade
//! wherever the drone passes the same place, whatever it sends and when.

use crate::math;
use crate::rng::Rng;
use serde::{Deserialize, Serialize};

/// How shadowing varies (`--shadowing-model`, JS `shadowingModel`; reference §6.2): along the
/// path as [`crate::Shadowing`] draws it, or fixed in space as [`ShadowingField`] holds it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum ShadowingModel {
    /// Along the drone's path, frame by frame: each frame continues the last over the metres
    /// flown, with a fresh draw. Two runs that send at other moments meet other fades.
    #[default]
    Path,
    /// Fixed in space: every frame, uplink or downlink, meets the fade of the place it is sent
    /// from, so runs that differ only in when they send (another sender, data rate, payload or
    /// ADR) meet the same fades (common random numbers), and a drone that comes back meets the
    /// fade it left.
    Field,
}

impl ShadowingModel {
    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            ShadowingModel::Path => "path",
            ShadowingModel::Field => "field",
        }
    }
}

/// How many random Fourier features sum to the field: enough that its values are Gaussian to the
/// eye and its correlation within a few per cent of the exponential at every distance.
pub const FIELD_FEATURES: usize = 128;

/// A stationary field of shadowing (dB) over 3D space with the exponential correlation
/// σ² exp(−r / d) (Gudmundson 1991's along a path, here in every direction), as a sum of random
/// Fourier features (Rahimi & Recht 2007): S(p) = σ √(2/M) Σ cos(k_m · p + φ_m), with each
/// wave vector k_m drawn from the exponential covariance's spectral density, a multivariate
/// Cauchy distribution of scale 1/d (k = z / (|u| d), z ~ N(0, I₃), u ~ N(0, 1)), and each phase
/// φ_m uniform. Over the draws of the field its values are N(0, σ²) in the limit of many
/// features (with M = 128 their spread is σ to within a few per cent, tested) and two places r
/// apart correlate as exp(−r / d); within one field, as in the world, the fades are what they
/// are. The ns-3 `lorawan` module's shadowing is likewise a map fixed in space
/// (`CorrelatedShadowingPropagationLossModel`).
///
/// ```
/// use loratrack::{Rng, ShadowingField};
/// let field = ShadowingField::new(4.0, 110.0, &mut Rng::new(1));
/// // The same place, the same fade; a step away, nearly the same.
/// assert_eq!(field.at([100.0, 20.0, 50.0]), field.at([100.0, 20.0, 50.0]));
/// assert!((field.at([100.0, 20.0, 50.0]) - field.at([100.5, 20.0, 50.0])).abs() < 1.0);
/// ```
#[derive(Clone, Debug)]
pub struct ShadowingField {
    amplitude: f64,
    waves: Vec<([f64; 3], f64)>,
}

impl ShadowingField {
    /// A field of standard deviation `sigma_db` (dB) and decorrelation distance (m), drawn from
    /// `rng`.
    pub fn new(sigma_db: f64, decorrelation_m: f64, rng: &mut Rng) -> Self {
        let waves = if sigma_db == 0.0 {
            Vec::new()
        } else {
            (0..FIELD_FEATURES)
                .map(|_| {
                    let z = [rng.normal(), rng.normal(), rng.normal()];
                    let scale = 1.0 / (rng.normal().abs().max(1e-12) * decorrelation_m);
                    let phase = rng.uniform() * core::f64::consts::TAU;
                    (z.map(|c| c * scale), phase)
                })
                .collect()
        };
        ShadowingField {
            amplitude: sigma_db * (2.0 / FIELD_FEATURES as f64).sqrt(),
            waves,
        }
    }

    /// The shadowing at `pos` (m), dB.
    pub fn at(&self, pos: [f64; 3]) -> f64 {
        self.waves
            .iter()
            .map(|(k, phase)| math::cos(k[0] * pos[0] + k[1] * pos[1] + k[2] * pos[2] + phase))
            .sum::<f64>()
            * self.amplitude
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The field's values at `n` places `step` m apart along x, over `fields` fields.
    fn samples(fields: u64, step: f64) -> Vec<(f64, f64)> {
        (0..fields)
            .flat_map(|seed| {
                let f = ShadowingField::new(4.0, 110.0, &mut Rng::new(seed));
                (0..20).map(move |i| {
                    let p = [i as f64 * 1000.0, 0.0, 30.0];
                    (f.at(p), f.at([p[0] + step, p[1], p[2]]))
                })
            })
            .collect()
    }

    #[test]
    fn values_spread_by_sigma_and_places_correlate_as_the_exponential() {
        for (step, want) in [
            (0.0, 1.0),
            (110.0, (-1.0f64).exp()),
            (330.0, (-3.0f64).exp()),
        ] {
            let s = samples(400, step);
            let n = s.len() as f64;
            let var = s.iter().map(|(a, _)| a * a).sum::<f64>() / n;
            assert!((var.sqrt() - 4.0).abs() < 0.2, "sigma {}", var.sqrt());
            let corr = s.iter().map(|(a, b)| a * b).sum::<f64>() / n / 16.0;
            assert!(
                (corr - want).abs() < 0.06,
                "{step} m: correlation {corr}, want {want}"
            );
        }
    }

    #[test]
    fn no_sigma_no_fade_and_a_field_is_its_seed() {
        assert_eq!(
            ShadowingField::new(0.0, 110.0, &mut Rng::new(1)).at([1.0, 2.0, 3.0]),
            0.0
        );
        let (a, b) = (
            ShadowingField::new(4.0, 110.0, &mut Rng::new(9)),
            ShadowingField::new(4.0, 110.0, &mut Rng::new(9)),
        );
        assert_eq!(a.at([500.0, -70.0, 40.0]), b.at([500.0, -70.0, 40.0]));
    }
}
