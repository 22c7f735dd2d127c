use crate::codec::CodecError;
use crate::lora::LoraError;
use crate::models::ModelError;
use crate::sim::SimError;
use core::fmt;

/// Any error an API operation can return: one variant per domain, plus malformed input.
#[derive(Clone, Debug, PartialEq)]
pub enum ApiError {
    /// The LoRa link (airtime, duty cycle, channel).
    Lora(LoraError),
    /// Motion models (state shape, time step, eta).
    Model(ModelError),
    /// The payload codec.
    Codec(CodecError),
    /// The simulation (flight, parameters).
    Sim(SimError),
    /// Input that does not have the expected shape or range.
    Invalid(String),
}

impl fmt::Display for ApiError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ApiError::Lora(e) => e.fmt(f),
            ApiError::Model(e) => e.fmt(f),
            ApiError::Codec(e) => e.fmt(f),
            ApiError::Sim(e) => e.fmt(f),
            ApiError::Invalid(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for ApiError {}

impl From<LoraError> for ApiError {
    fn from(e: LoraError) -> Self {
        ApiError::Lora(e)
    }
}

impl From<ModelError> for ApiError {
    fn from(e: ModelError) -> Self {
        ApiError::Model(e)
    }
}

impl From<CodecError> for ApiError {
    fn from(e: CodecError) -> Self {
        ApiError::Codec(e)
    }
}

impl From<SimError> for ApiError {
    fn from(e: SimError) -> Self {
        ApiError::Sim(e)
    }
}
