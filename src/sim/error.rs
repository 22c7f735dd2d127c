use crate::lora::LoraError;
use crate::trajectory::TrajectoryError;
use core::fmt;

/// Why a simulation could not run.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// The flight could not be read.
    Trajectory(TrajectoryError),
    /// A LoRa setting is invalid.
    Lora(LoraError),
    /// A simulation parameter is out of range (name, value, what is allowed).
    Parameter(&'static str, f64, &'static str),
    /// No flight was chosen, or more than one.
    Source(String),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Trajectory(e) => e.fmt(f),
            SimError::Lora(e) => e.fmt(f),
            SimError::Parameter(name, v, allowed) => write!(f, "{name} must be {allowed}, got {v}"),
            SimError::Source(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for SimError {}

impl From<TrajectoryError> for SimError {
    fn from(e: TrajectoryError) -> Self {
        SimError::Trajectory(e)
    }
}

impl From<LoraError> for SimError {
    fn from(e: LoraError) -> Self {
        SimError::Lora(e)
    }
}
