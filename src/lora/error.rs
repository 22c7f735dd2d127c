use core::fmt;

/// What LoRa cannot do: each variant names the offending value.
#[derive(Clone, Debug, PartialEq)]
pub enum LoraError {
    /// Spreading factor outside 7..=12.
    SpreadingFactor(i64),
    /// Bandwidth other than 125, 250 or 500 kHz.
    Bandwidth(f64),
    /// Coding rate index outside 1..=4 (4/5 .. 4/8).
    CodingRate(i64),
    /// PHY payload (application payload + overhead) over 255 bytes.
    PayloadTooLarge(usize),
    /// Preamble length outside 6..=65535 symbols.
    Preamble(i64),
    /// Duty cycle outside [`MIN_DUTY_CYCLE`](super::MIN_DUTY_CYCLE), 1].
    DutyCycle(f64),
    /// A parameter that is not a finite number in its range: name, value, the range.
    Parameter(&'static str, f64, &'static str),
    /// A setting outside the limits declared in [`crate::options`].
    OutOfRange(crate::options::OutOfRange),
}

impl From<crate::options::OutOfRange> for LoraError {
    fn from(e: crate::options::OutOfRange) -> Self {
        LoraError::OutOfRange(e)
    }
}

impl fmt::Display for LoraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoraError::SpreadingFactor(sf) => {
                write!(f, "spreading factor must be 7..12, got {sf}")
            }
            LoraError::Bandwidth(bw) => {
                write!(f, "bandwidth must be 125, 250 or 500 kHz, got {bw}")
            }
            LoraError::CodingRate(cr) => {
                write!(f, "coding rate must be 1..4 (4/5..4/8), got {cr}")
            }
            LoraError::PayloadTooLarge(n) => write!(
                f,
                "PHY payload of {n} bytes (payload + overhead) exceeds LoRa's 255-byte maximum"
            ),
            LoraError::Preamble(n) => {
                write!(f, "preamble must be 6..65535 symbols, got {n}")
            }
            LoraError::DutyCycle(d) => {
                write!(
                    f,
                    "dutyCycle must be a fraction in {}..1, got {}",
                    crate::options::as_given(super::MIN_DUTY_CYCLE),
                    crate::options::as_given(*d)
                )
            }
            LoraError::OutOfRange(e) => e.fmt(f),
            LoraError::Parameter(name, v, allowed) => {
                write!(
                    f,
                    "{name} must be {allowed}, got {}",
                    crate::options::as_given(*v)
                )
            }
        }
    }
}

impl std::error::Error for LoraError {}

impl LoraError {
    /// The setting this error refuses, by its key in the JS API and the page's form (the CLI's long
    /// option in camelCase), so that a caller can point at it without reading the message.
    pub fn setting(&self) -> Option<&'static str> {
        Some(match self {
            LoraError::SpreadingFactor(_) => "sf",
            LoraError::Bandwidth(_) => "bw",
            LoraError::CodingRate(_) => "cr",
            // The application payload is fixed per model; the overhead is what a caller chose.
            LoraError::PayloadTooLarge(_) => "overhead",
            LoraError::Preamble(_) => "preamble",
            LoraError::DutyCycle(_) => "dutyCycle",
            LoraError::Parameter(name, ..) => name,
            LoraError::OutOfRange(e) => e.option.key,
        })
    }
}
