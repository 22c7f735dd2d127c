use core::fmt;
use core::str::FromStr;
use serde::{Deserialize, Serialize};

/// One of the paper's three motion models, chosen at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
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

    /// Number of state components.
    pub fn state_len(self) -> usize {
        match self {
            ModelKind::Dr => 6,
            ModelKind::CtraPlus => 8,
            ModelKind::Ctra3d => 9,
        }
    }

    /// Payload size in bytes (paper Fig. "payload", SPEC §5).
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
    /// A state component that is NaN or infinite.
    NonFinite {
        /// Index of the component.
        index: usize,
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
            ModelError::NonFinite { index } => {
                write!(f, "state component {index} is not a finite number")
            }
            ModelError::TimeStep(dt) => {
                write!(
                    f,
                    "time step must be a finite number of seconds >= 0, got {dt}"
                )
            }
            ModelError::Eta(e) => write!(f, "eta must be in [0, 1], got {e}"),
        }
    }
}

impl std::error::Error for ModelError {}

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
