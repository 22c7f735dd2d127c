//! `predict`: noise-free propagation of a state under one model (reference §9).

use super::ApiError;
use crate::models::{with_model, ModelError, ModelKind, MotionModel, MAX_DT, STATE_RANGES};
use nalgebra::SVector;
use serde::{Deserialize, Serialize};

/// The most prediction steps one call may run (`dt / step`), so no input can hang the caller.
pub const MAX_STEPS: f64 = 1e7;

/// Input of `predict`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct PredictParams {
    /// `dr`, `ctra-plus` or `3d-ctra`.
    pub model: ModelKind,
    /// The state, reference §2 order and units.
    pub state: Vec<f64>,
    /// Time to propagate over, s (≥ 0).
    pub dt: f64,
    /// Run in steps of this length (s), multiplying psi by eta after each, as the station does.
    #[serde(default)]
    pub step: Option<f64>,
    /// Tilt-rate decay per step, [0, 1]; only with `step` (default 0.9, paper Table I).
    #[serde(default)]
    pub eta: Option<f64>,
}

/// Output of `predict`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct PredictReport {
    /// The model.
    pub model: ModelKind,
    /// The propagated state.
    pub state: Vec<f64>,
}

/// Checks a state's length for `model` and each component against [`STATE_RANGES`].
pub fn validate_state(model: ModelKind, state: &[f64]) -> Result<(), ModelError> {
    if state.len() != model.state_len() {
        return Err(ModelError::StateLength {
            model,
            got: state.len(),
        });
    }
    let outside = state
        .iter()
        .zip(STATE_RANGES)
        .position(|(v, (_, lo, hi, _))| {
            // NaN fails the range test too.
            !(lo..=hi).contains(v)
        });
    match outside {
        Some(index) => Err(ModelError::OutOfRange {
            index,
            value: state[index],
        }),
        None => Ok(()),
    }
}

fn run<const N: usize, M: MotionModel<N>>(
    model: M,
    state: &[f64],
    dt: f64,
    steps: Option<(f64, f64)>,
) -> Vec<f64> {
    let mut s = SVector::<f64, N>::from_column_slice(state);
    match steps {
        None => s = model.propagate(&s, dt),
        Some((step, eta)) => {
            // Whole steps, then a partial one. A ratio within 1e-9 (relative) of a whole number
            // is that number, so rounding in dt/step never adds a spurious near-zero step; any
            // other positive ratio, however small (a step 1e9 times dt), takes at least one step.
            let n = step_count(dt / step);
            for i in 0..n {
                let h = step.min(dt - i as f64 * step);
                s = model.propagate(&s, h);
                model.decay_tilt_rate(&mut s, eta);
            }
        }
    }
    s.iter().copied().collect()
}

/// How many steps of length `step` cover `ratio = dt / step`.
fn step_count(ratio: f64) -> u64 {
    if ratio <= 0.0 {
        return 0;
    }
    let whole = ratio.round();
    if whole >= 1.0 && (ratio - whole).abs() <= 1e-9 * whole {
        whole as u64
    } else {
        ratio.ceil() as u64
    }
}

/// Propagates `state` over `dt` with the chosen model.
pub fn predict(p: &PredictParams) -> Result<PredictReport, ApiError> {
    validate_state(p.model, &p.state)?;
    if !(0.0..=MAX_DT).contains(&p.dt) {
        return Err(ModelError::TimeStep(p.dt).into());
    }
    let steps = match (p.step, p.eta) {
        (None, None) => None,
        (None, Some(_)) => {
            return Err(ApiError::Invalid(
                "`eta` needs `step` (the decay is applied after each step)".into(),
            ))
        }
        (Some(step), eta) => {
            if !(step.is_finite() && step > 0.0) {
                return Err(ApiError::Invalid(format!(
                    "step must be a number of seconds > 0, got {step}"
                )));
            }
            if p.dt / step > MAX_STEPS {
                return Err(ApiError::Invalid(format!(
                    "dt / step exceeds {MAX_STEPS} steps"
                )));
            }
            let eta = eta.unwrap_or(0.9);
            if !(0.0..=1.0).contains(&eta) {
                return Err(ModelError::Eta(eta).into());
            }
            Some((step, eta))
        }
    };
    let state = with_model!(p.model, run(&p.state, p.dt, steps));
    Ok(PredictReport {
        model: p.model,
        state,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_far_longer_than_dt_still_moves_the_state() {
        let p = |step: Option<f64>| {
            predict(&PredictParams {
                model: ModelKind::Ctra3d,
                state: vec![0.0, 0.0, 0.0, 0.0, 0.1, 8.0, 0.5, 0.2, 0.1],
                dt: 2.0,
                step,
                eta: Some(0.9),
            })
            .unwrap()
            .state
        };
        // One step of 2 s either way: a step of 2e9 s is cut to dt, as a step of 2 s is.
        assert_eq!(p(Some(2e9)), p(Some(2.0)));
        assert!(p(Some(2e9))[0] > 10.0, "the drone moved about 17 m");
    }

    #[test]
    fn whole_ratios_take_no_spurious_step_and_any_positive_ratio_takes_one() {
        assert_eq!(step_count(3.0 + 1e-12), 3);
        assert_eq!(step_count(3.0 - 1e-12), 3);
        assert_eq!(step_count(1e-9), 1);
        assert_eq!(step_count(1e-300), 1);
        assert_eq!(step_count(0.0), 0);
        assert_eq!(step_count(2.5), 3);
    }
}
