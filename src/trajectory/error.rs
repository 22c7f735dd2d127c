use core::fmt;

/// Why a trajectory could not be read. Line numbers count from 1, the header being line 1.
#[derive(Clone, Debug, PartialEq)]
pub enum TrajectoryError {
    /// No text at all.
    Empty,
    /// A header and no data rows.
    HeaderOnly,
    /// Fewer data rows than a filter can start on.
    TooFewRows {
        /// Rows found.
        rows: usize,
        /// Rows needed.
        min: usize,
    },
    /// More rows than loratrack accepts.
    TooManyRows {
        /// Maximum accepted.
        max: usize,
    },
    /// A required column is missing from the header.
    MissingColumn {
        /// The header's line (after any comment and blank lines), 1-based.
        line: usize,
        /// The column (`t`, `x`, …).
        column: &'static str,
        /// The header as read.
        header: String,
    },
    /// A row with a different number of fields than the header.
    FieldCount {
        /// Line number.
        line: usize,
        /// Fields found.
        got: usize,
        /// Fields in the header.
        expected: usize,
    },
    /// A field that is not a number.
    NotANumber {
        /// Line number.
        line: usize,
        /// Column name.
        column: String,
        /// The text.
        text: String,
    },
    /// A NaN or infinite value.
    NonFinite {
        /// Line number.
        line: usize,
        /// Column name.
        column: String,
    },
    /// A time that is not after the previous row's.
    TimeNotIncreasing {
        /// Line number.
        line: usize,
    },
    /// A time step shorter than [`MIN_TIME_STEP`](super::MIN_TIME_STEP).
    TimeStep {
        /// Line number.
        line: usize,
        /// The step, s.
        step: f64,
    },
    /// A CSV text larger than [`MAX_CSV_BYTES`](super::MAX_CSV_BYTES).
    TooLarge {
        /// Its size, bytes.
        bytes: usize,
    },
    /// A value beyond what a drone flight can have (|coordinate| over 1000 km, a flight over a day,
    /// a speed over 300 m/s).
    Absurd {
        /// Line number.
        line: usize,
        /// What is absurd.
        what: String,
    },
    /// Columns that do not fit together (built in code rather than read from CSV).
    Inconsistent(String),
    /// A synthetic flight number outside 1..=30.
    SyntheticIndex(i64),
    /// A built-in sample name that does not exist.
    UnknownSample(String),
}

/// At most 60 characters of `text`, so an error never echoes a whole file.
fn excerpt(text: &str) -> String {
    let mut chars = text.chars();
    let head: String = chars.by_ref().take(60).collect();
    if chars.next().is_some() {
        format!("{head}…")
    } else {
        head
    }
}

impl fmt::Display for TrajectoryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TrajectoryError::Empty => write!(f, "the CSV is empty"),
            TrajectoryError::HeaderOnly => write!(f, "the CSV has a header but no data rows"),
            TrajectoryError::TooFewRows { rows, min } => {
                write!(f, "the CSV has {rows} data rows; at least {min} are needed")
            }
            TrajectoryError::TooManyRows { max } => write!(f, "the CSV has more than {max} data rows"),
            TrajectoryError::MissingColumn {
                line,
                column,
                header,
            } => write!(
                f,
                "line {line}: no '{column}' column in the header '{}' (need t, x, y, z, or t, lat, lon, alt for a GPS log; aliases like t_seconds, x_m are accepted)",
                excerpt(header)
            ),
            TrajectoryError::FieldCount { line, got, expected } => {
                write!(f, "line {line}: {got} fields, but the header has {expected}")
            }
            TrajectoryError::NotANumber { line, column, text } => {
                write!(f, "line {line}: column '{column}' is not a number: '{text}'")
            }
            TrajectoryError::NonFinite { line, column } => {
                write!(f, "line {line}: column '{column}' is not a finite number")
            }
            TrajectoryError::TimeNotIncreasing { line } => {
                write!(f, "line {line}: time is not strictly increasing")
            }
            TrajectoryError::TimeStep { line, step } => write!(
                f,
                "line {line}: time step of {step:e} s; steps must be at least {} s",
                super::MIN_TIME_STEP
            ),
            TrajectoryError::TooLarge { bytes } => write!(
                f,
                "the CSV is {:.1} MiB; at most {} MiB is read",
                *bytes as f64 / (1024.0 * 1024.0),
                super::MAX_CSV_BYTES >> 20
            ),
            TrajectoryError::Absurd { line, what } => write!(f, "line {line}: {what}"),
            TrajectoryError::Inconsistent(what) => write!(f, "inconsistent trajectory: {what}"),
            TrajectoryError::SyntheticIndex(i) => {
                write!(f, "synthetic flight must be 1..30 or all, got {i}")
            }
            TrajectoryError::UnknownSample(s) => {
                write!(f, "unknown sample '{s}' (available: canberra)")
            }
        }
    }
}

impl std::error::Error for TrajectoryError {}

impl TrajectoryError {
    /// The setting this error refuses, by its key in the JS API (as [`crate::LoraError::setting`]):
    /// the flight given as `trajectory` (a CSV), `synthetic` or `sample`.
    pub fn setting(&self) -> &'static str {
        match self {
            TrajectoryError::SyntheticIndex(_) => "synthetic",
            TrajectoryError::UnknownSample(_) => "sample",
            _ => "trajectory",
        }
    }
}
