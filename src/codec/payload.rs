//! Encoding and decoding of a model state.

use super::{CodecError, Encoding, SaturatedFields, FIELDS};
use crate::math::wrap_angle;
use crate::models::{ModelKind, PHI, PSI, THETA};
use core::f64::consts::{FRAC_PI_2, PI};
use serde::Serialize;

/// An encoded payload and the fields that did not fit their range.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Encoded {
    /// The payload, 9/11/12 bytes.
    pub bytes: Vec<u8>,
    /// The fields whose value was beyond their range and was sent as its edge.
    pub saturated: SaturatedFields,
}

/// Rewrites a pitch beyond ±π/2 as the identical motion with theta + π, π − phi, −psi.
fn canonical_pitch(state: &mut [f64]) {
    let phi = wrap_angle(state[PHI]);
    if phi.abs() > FRAC_PI_2 {
        state[THETA] = wrap_angle(state[THETA] + PI);
        state[PHI] = wrap_angle(PI - phi);
        if state.len() > PSI {
            state[PSI] = -state[PSI];
        }
    } else {
        state[PHI] = phi;
    }
}

/// Quantises `state` (the model's components in reference §2 order) relative to `origin` (m).
///
/// ```
/// use loratrack::{encode, decode, ModelKind};
/// let s = [12.3, -40.0, 55.5, 0.5, 0.1, 7.2, 0.3, 0.2, -0.1];
/// let e = encode(ModelKind::Ctra3d, &s, [0.0; 3]).unwrap();
/// assert_eq!(e.bytes.len(), 12);
/// let back = decode(ModelKind::Ctra3d, &e.bytes, [0.0; 3]).unwrap();
/// assert!((back[0] - 12.3).abs() <= 0.1 + 1e-9);
/// ```
pub fn encode(model: ModelKind, state: &[f64], origin: [f64; 3]) -> Result<Encoded, CodecError> {
    if state.len() != model.state_len() {
        return Err(CodecError::StateLength {
            model,
            got: state.len(),
        });
    }
    if let Some(i) = state.iter().position(|v| !v.is_finite()) {
        return Err(CodecError::NonFinite(FIELDS[i].name));
    }
    if origin.iter().any(|v| !v.is_finite()) {
        return Err(CodecError::NonFinite("origin"));
    }
    let mut s = state.to_vec();
    for (k, o) in origin.iter().enumerate() {
        s[k] -= o;
    }
    canonical_pitch(&mut s);
    let mut bytes = Vec::with_capacity(model.payload_bytes());
    let mut saturated = SaturatedFields::default();
    for (i, (value, field)) in s.iter().zip(FIELDS.iter()).enumerate() {
        let raw = (value / field.step).round();
        let (lo, hi) = field.encoding.code_range();
        let code = match field.encoding {
            Encoding::Circle => (raw as i64).rem_euclid(256),
            _ => {
                if raw < lo as f64 || raw > hi as f64 {
                    saturated.insert(i);
                }
                raw.clamp(lo as f64, hi as f64) as i64
            }
        };
        match field.encoding {
            Encoding::I16 => bytes.extend_from_slice(&(code as i16).to_be_bytes()),
            Encoding::I8 => bytes.push(code as i8 as u8),
            Encoding::U8 | Encoding::Circle => bytes.push(code as u8),
        }
    }
    Ok(Encoded { bytes, saturated })
}

/// Decodes a payload into the model's state (reference §2 order), positions relative to `origin`.
pub fn decode(model: ModelKind, bytes: &[u8], origin: [f64; 3]) -> Result<Vec<f64>, CodecError> {
    if bytes.len() != model.payload_bytes() {
        return Err(CodecError::Length {
            model,
            got: bytes.len(),
        });
    }
    if origin.iter().any(|v| !v.is_finite()) {
        return Err(CodecError::NonFinite("origin"));
    }
    let mut state = Vec::with_capacity(model.state_len());
    let mut at = 0;
    for field in &FIELDS[..model.state_len()] {
        let code = match field.encoding {
            Encoding::I16 => i64::from(i16::from_be_bytes([bytes[at], bytes[at + 1]])),
            Encoding::I8 => i64::from(bytes[at] as i8),
            Encoding::U8 => i64::from(bytes[at]),
            Encoding::Circle => i64::from(bytes[at] as i8),
        };
        at += field.encoding.bytes();
        // The encoder never writes -128 / -32768; a received one is read as the range edge.
        let code = match field.encoding {
            Encoding::Circle => code,
            e => code.clamp(e.code_range().0, e.code_range().1),
        };
        let mut value = code as f64 * field.step;
        if field.encoding == Encoding::Circle {
            value = wrap_angle(value);
        }
        state.push(value);
    }
    for (k, o) in origin.iter().enumerate() {
        state[k] += o;
    }
    Ok(state)
}

/// Variance of the quantisation error of each field, step²/12 (uniform error), in the squared
/// units of the state. The station adds this to R as the covariance of a decoded state.
pub fn quantization_variance(model: ModelKind) -> Vec<f64> {
    FIELDS[..model.state_len()]
        .iter()
        .map(|f| f.step * f.step / 12.0)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::OMEGA;

    #[test]
    fn wrong_length_names_the_expected_size() {
        let err = decode(ModelKind::Dr, &[0u8; 12], [0.0; 3]).unwrap_err();
        assert_eq!(err.to_string(), "a DR payload is 9 bytes, got 12");
    }

    #[test]
    fn out_of_range_values_saturate_and_are_reported() {
        let s = [9000.0, 0.0, 0.0, 0.0, 0.0, 40.0, -9.0, 0.0];
        let e = encode(ModelKind::CtraPlus, &s, [0.0; 3]).unwrap();
        assert_eq!(e.saturated.names().collect::<Vec<_>>(), ["x", "v", "a"]);
        let back = decode(ModelKind::CtraPlus, &e.bytes, [0.0; 3]).unwrap();
        assert!((back[0] - FIELDS[0].max()).abs() < 1e-9);
        assert!((back[5] - 25.5).abs() < 1e-9);
    }

    #[test]
    fn a_loop_is_rewritten_as_the_same_motion() {
        // phi = 2.0 rad (past vertical) heading east = phi = pi - 2 heading west, psi reversed.
        let s = [0.0, 0.0, 0.0, 0.0, 2.0, 5.0, 0.0, 0.0, 0.3];
        let e = encode(ModelKind::Ctra3d, &s, [0.0; 3]).unwrap();
        assert!(e.saturated.is_empty());
        let d = decode(ModelKind::Ctra3d, &e.bytes, [0.0; 3]).unwrap();
        assert!((wrap_angle(d[THETA] - PI)).abs() < 0.02);
        assert!((d[PHI] - (PI - 2.0)).abs() < 0.01);
        assert!((d[PSI] + 0.3).abs() < 0.01);
        assert!((d[OMEGA]).abs() < 1e-12);
    }

    #[test]
    fn non_finite_state_is_an_error() {
        let s = [0.0, f64::NAN, 0.0, 0.0, 0.0, 1.0];
        assert_eq!(
            encode(ModelKind::Dr, &s, [0.0; 3]),
            Err(CodecError::NonFinite("y"))
        );
    }
}
