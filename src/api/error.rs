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

/// The most characters of one quoted piece of input a message repeats.
pub const MAX_ECHO_CHARS: usize = 80;

/// A message safe to print: control characters (an ESC or OSC sequence from a crafted file could
/// rewrite a terminal) escaped as `\u{1b}`, and every quoted piece of input ('…' or `…`) cut to
/// [`MAX_ECHO_CHARS`] characters. The CLI and the JS bindings pass every message through it.
///
/// ```
/// use loratrack::api::clean_message;
/// assert_eq!(clean_message("bad 'a\u{1b}]0;owned\u{7}'"), "bad 'a\\u{1b}]0;owned\\u{7}'");
/// let long = format!("unknown sample '{}'", "x".repeat(500));
/// assert!(clean_message(&long).len() < 120);
/// ```
pub fn clean_message(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len().min(1024));
    let mut quote: Option<char> = None;
    let mut quoted = 0usize;
    let mut previous = ' ';
    for c in msg.chars() {
        // An apostrophe after a letter or digit (the drone's, LoRa's) opens no quote.
        let opens = c == '`' || (c == '\'' && !previous.is_alphanumeric());
        previous = c;
        match quote {
            Some(q) if c == q => {
                quote = None;
                out.push(c);
                continue;
            }
            None if opens => {
                quote = Some(c);
                quoted = 0;
                out.push(c);
                continue;
            }
            _ => {}
        }
        if quote.is_some() {
            quoted += 1;
            if quoted > MAX_ECHO_CHARS {
                if quoted == MAX_ECHO_CHARS + 1 {
                    out.push('…');
                }
                continue;
            }
        }
        if c.is_control() {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_escape_control_characters_and_cut_long_quotes() {
        assert_eq!(clean_message("line\nbreak"), "line\\u{a}break");
        let m = clean_message(&format!(
            "got '{}' and `{}`",
            "a".repeat(200),
            "b".repeat(10)
        ));
        assert_eq!(m, format!("got '{}…' and `bbbbbbbbbb`", "a".repeat(80)));
        assert_eq!(clean_message("it's fine"), "it's fine");
        // An apostrophe is no quote: a long message with one is printed whole...
        let long = format!("the drone's plan {}", "x".repeat(200));
        assert_eq!(clean_message(&long), long);
        // ...while quoted input after it is still cut.
        let m = clean_message(&format!("the drone's file '{}'", "c".repeat(200)));
        assert_eq!(m, format!("the drone's file '{}…'", "c".repeat(80)));
    }
}
