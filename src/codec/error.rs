use crate::models::ModelKind;
use core::fmt;

/// Why a payload could not be encoded or decoded.
#[derive(Clone, Debug, PartialEq)]
pub enum CodecError {
    /// A payload of the wrong size for the model.
    Length {
        /// The model.
        model: ModelKind,
        /// Bytes given.
        got: usize,
    },
    /// A state with the wrong number of components.
    StateLength {
        /// The model.
        model: ModelKind,
        /// Components given.
        got: usize,
    },
    /// A state component or origin coordinate that is NaN or infinite.
    NonFinite(&'static str),
    /// Text that is not an even number of hexadecimal digits.
    Hex(String),
}

impl fmt::Display for CodecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CodecError::Length { model, got } => write!(
                f,
                "a {} payload is {} bytes, got {got}",
                model.label(),
                model.payload_bytes()
            ),
            CodecError::StateLength { model, got } => write!(
                f,
                "model {model} needs a state of {} numbers, got {got}",
                model.state_len()
            ),
            CodecError::NonFinite(field) => write!(f, "{field} is not a finite number"),
            CodecError::Hex(msg) => write!(f, "invalid hex payload: {msg}"),
        }
    }
}

impl std::error::Error for CodecError {}
