use core::fmt;
use core::str::FromStr;
use serde::{Deserialize, Serialize};

/// One of the paper's three motion models, chosen at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum ModelKind {
    /// Dead reckoning: uniform rectilinear motion, 6 states, 9-byte payload.
    #[serde(rename = "dr")]
    Dr,
    /// CTRA+: constant turn rate and acceleration, constant pitch; 8 states, 11 bytes.
    #[serde(rename = "ctra-plus")]
    CtraPlus,
    /// 3D-CTRA: CTRA+ with a constant tilt rate; 9 states, 12 bytes.
    #[serde(rename = "3d-ctra")]
    Ctra3d,
}

impl ModelKind {
    /// All models, in the paper's order.
    pub const ALL: [ModelKind; 3] = [ModelKind::Dr, ModelKind::CtraPlus, ModelKind::Ctra3d];

    /// The model's place in [`ModelKind::ALL`] (for arrays indexed by model).
    pub fn index(self) -> usize {
        match self {
            ModelKind::Dr => 0,
            ModelKind::CtraPlus => 1,
            ModelKind::Ctra3d => 2,
        }
    }

    /// Number of state components.
    pub fn state_len(self) -> usize {
        match self {
            ModelKind::Dr => 6,
            ModelKind::CtraPlus => 8,
            ModelKind::Ctra3d => 9,
        }
    }

    /// Payload size in bytes (paper Fig. "payload", reference §5).
    pub fn payload_bytes(self) -> usize {
        match self {
            ModelKind::Dr => 9,
            ModelKind::CtraPlus => 11,
            ModelKind::Ctra3d => 12,
        }
    }

    /// The CLI/JS name: `dr`, `ctra-plus`, `3d-ctra`.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Dr => "dr",
            ModelKind::CtraPlus => "ctra-plus",
            ModelKind::Ctra3d => "3d-ctra",
        }
    }

    /// The paper's name: DR, CTRA+, 3D-CTRA.
    pub fn label(self) -> &'static str {
        match self {
            ModelKind::Dr => "DR",
            ModelKind::CtraPlus => "CTRA+",
            ModelKind::Ctra3d => "3D-CTRA",
        }
    }
}

impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The accepted range of each state component (`x y z theta phi v a omega psi`): name, lowest,
/// highest, unit. Far beyond any drone (positions within 10 000 km, speeds and accelerations up to
/// 1000, rates up to 100 rad/s), yet small enough that every propagation over [`MAX_DT`] stays
/// finite.
pub const STATE_RANGES: [(&str, f64, f64, &str); 9] = [
    ("x", -1e7, 1e7, "m"),
    ("y", -1e7, 1e7, "m"),
    ("z", -1e7, 1e7, "m"),
    ("theta", -1000.0, 1000.0, "rad"),
    ("phi", -1000.0, 1000.0, "rad"),
    ("v", -1000.0, 1000.0, "m/s"),
    ("a", -1000.0, 1000.0, "m/s²"),
    ("omega", -100.0, 100.0, "rad/s"),
    ("psi", -100.0, 100.0, "rad/s"),
];

/// The longest time a model propagates over in one call, s (a day).
pub const MAX_DT: f64 = 86_400.0;

/// Bad input to a model operation.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// A model name that is not `dr`, `ctra-plus` or `3d-ctra`.
    UnknownModel(String),
    /// A state with the wrong number of components.
    StateLength {
        /// The model.
        model: ModelKind,
        /// Components given.
        got: usize,
    },
    /// A state component that is NaN, infinite or outside its physical range.
    OutOfRange {
        /// Index of the component.
        index: usize,
        /// The value given.
        value: f64,
    },
    /// A time step that is negative or not finite.
    TimeStep(f64),
    /// eta outside [0, 1].
    Eta(f64),
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::UnknownModel(m) => {
                write!(f, "unknown model '{m}' (expected dr, ctra-plus or 3d-ctra)")
            }
            ModelError::StateLength { model, got } => write!(
                f,
                "model {model} needs a state of {} numbers, got {got}",
                model.state_len()
            ),
            ModelError::OutOfRange { index, value } => {
                let (name, lo, hi, unit) = STATE_RANGES[*index];
                write!(
                    f,
                    "state component {index} ({name}) must be {lo}..{hi} {unit}, got {}",
                    crate::options::as_given(*value)
                )
            }
            ModelError::TimeStep(dt) => {
                write!(
                    f,
                    "dt must be 0..{MAX_DT} s (a day), got {}",
                    crate::options::as_given(*dt)
                )
            }
            ModelError::Eta(e) => write!(f, "eta must be in [0, 1], got {e}"),
        }
    }
}

impl std::error::Error for ModelError {}

impl ModelError {
    /// The setting this error refuses, by its key in the JS API (as [`crate::LoraError::setting`]).
    pub fn setting(&self) -> Option<&'static str> {
        Some(match self {
            ModelError::UnknownModel(_) => "model",
            ModelError::StateLength { .. } | ModelError::OutOfRange { .. } => "state",
            ModelError::TimeStep(_) => "dt",
            ModelError::Eta(_) => "eta",
        })
    }
}

impl FromStr for ModelKind {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, ModelError> {
        match s.to_ascii_lowercase().as_str() {
            "dr" => Ok(ModelKind::Dr),
            "ctra-plus" | "ctra+" | "ctraplus" => Ok(ModelKind::CtraPlus),
            "3d-ctra" | "3dctra" | "ctra3d" => Ok(ModelKind::Ctra3d),
            _ => Err(ModelError::UnknownModel(s.to_string())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_model_sits_at_its_index_in_all() {
        for (i, m) in ModelKind::ALL.iter().enumerate() {
            assert_eq!(m.index(), i);
        }
    }
}
