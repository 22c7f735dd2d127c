//! `encode` / `decode`: the state payload as hex (reference §5, §8).

use super::ApiError;
use crate::codec::{self, CodecError};
use crate::models::ModelKind;
use serde::{Deserialize, Serialize};

/// Input of `encode`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct EncodeParams {
    /// The model (fixes the payload size).
    pub model: ModelKind,
    /// The state, reference §2 order.
    pub state: Vec<f64>,
    /// Origin both ends agree on, ENU m (default 0,0,0).
    #[serde(default)]
    pub origin: Option<[f64; 3]>,
}

/// Output of `encode`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct EncodeReport {
    /// The payload as lowercase hex.
    pub hex: String,
    /// Fields that were out of range and saturated.
    pub saturated: Vec<&'static str>,
}

/// Input of `decode`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DecodeParams {
    /// The model (fixes the payload size).
    pub model: ModelKind,
    /// The payload as hex (upper or lower case).
    pub hex: String,
    /// Origin both ends agree on, ENU m (default 0,0,0).
    #[serde(default)]
    pub origin: Option<[f64; 3]>,
}

/// Output of `decode`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DecodeReport {
    /// The model.
    pub model: ModelKind,
    /// The decoded state.
    pub state: Vec<f64>,
}

fn to_hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Parses hex digits (0-9, a-f, A-F) two per byte; anything else — a sign, a space, a
/// non-ASCII character — is refused with its position counted in characters.
fn from_hex(text: &str) -> Result<Vec<u8>, CodecError> {
    let digits: Vec<char> = text.trim().chars().collect();
    if let Some(i) = digits.iter().position(|c| !c.is_ascii_hexdigit()) {
        return Err(CodecError::Hex(format!(
            "'{}' at position {i} is not a hex digit (0-9, a-f)",
            digits[i]
        )));
    }
    if digits.len() % 2 != 0 {
        return Err(CodecError::Hex(format!(
            "odd number of digits ({})",
            digits.len()
        )));
    }
    Ok(digits
        .chunks(2)
        .map(|pair| {
            // Both are ASCII hex digits, so each converts.
            let d = |c: char| c.to_digit(16).unwrap_or(0) as u8;
            (d(pair[0]) << 4) | d(pair[1])
        })
        .collect())
}

/// Encodes a state into the model's payload.
pub fn encode(p: &EncodeParams) -> Result<EncodeReport, ApiError> {
    let e = codec::encode(p.model, &p.state, p.origin.unwrap_or([0.0; 3]))?;
    Ok(EncodeReport {
        hex: to_hex(&e.bytes),
        saturated: e.saturated.names().collect(),
    })
}

/// Decodes a payload into the model's state.
pub fn decode(p: &DecodeParams) -> Result<DecodeReport, ApiError> {
    let bytes = from_hex(&p.hex)?;
    let state = codec::decode(p.model, &bytes, p.origin.unwrap_or([0.0; 3]))?;
    Ok(DecodeReport {
        model: p.model,
        state,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_round_trip_and_bad_hex_is_an_error() {
        assert_eq!(
            from_hex(&to_hex(&[0, 1, 0xab, 0xff])).unwrap(),
            vec![0, 1, 0xab, 0xff]
        );
        assert!(from_hex("abc").is_err());
        assert!(from_hex("zz").is_err());
        assert!(from_hex("é1").is_err());
    }
}
