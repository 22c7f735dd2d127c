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

impl ApiError {
    /// The setting this error refuses, by its key in the JS API and the page's form (the CLI's long
    /// option in camelCase, e.g. `maxInterval`), or `None` where no one setting is at fault. The
    /// bindings give it to JS as the thrown `Error`'s `setting`, so that the page marks that
    /// control without reading the message.
    ///
    /// ```
    /// use loratrack::{api, Scenario, SenderKind, Simulator, SyntheticChoice};
    /// let mut s = Scenario::default();
    /// s.flight.synthetic = Some(SyntheticChoice::One(1));
    /// // A heartbeat shorter than SF12's duty-cycle interval (about 148 s).
    /// (s.radio.sf, s.radio.bw) = (12, 125.0);
    /// (s.sending.sender, s.sending.max_interval) = (SenderKind::Error, 10.0);
    /// let e = api::simulate(&mut Simulator::new(), &s).unwrap_err();
    /// assert_eq!(e.setting(), Some("maxInterval"));
    /// ```
    pub fn setting(&self) -> Option<&'static str> {
        match self {
            ApiError::Lora(e) => e.setting(),
            ApiError::Model(e) => e.setting(),
            ApiError::Sim(e) => e.setting(),
            ApiError::Codec(_) | ApiError::Invalid(_) => None,
        }
    }

    /// The value of the setting this error names ([`Self::setting`]) with which the run would go
    /// ahead ([`SimError::value_that_fits`]): how many seeds fit a run too long only for its
    /// seeds, how many drones fit a swarm too long only for its drones, or the heartbeat the
    /// slowest drone's data rate needs. The bindings give it to JS as the thrown `Error`'s
    /// `valueThatFits`, so that the page offers it without reading the message.
    ///
    /// ```
    /// use loratrack::{api, Scenario, Simulator, SyntheticChoice};
    /// let mut s = Scenario::default();
    /// s.flight.synthetic = Some(SyntheticChoice::All);
    /// s.run.seeds = 50;
    /// let e = api::simulate(&mut Simulator::new(), &s).unwrap_err();
    /// assert_eq!((e.setting(), e.value_that_fits()), (Some("seeds"), Some(18.0)));
    /// // SF12 at 125 kHz sends a 12-byte state every 148.3 s: the default 10 s heartbeat cannot be kept.
    /// let s = Scenario::from_json(r#"{"synthetic": 1, "sf": 12, "bw": 125, "sender": "error"}"#).unwrap();
    /// let e = api::simulate(&mut Simulator::new(), &s).unwrap_err();
    /// assert_eq!((e.setting(), e.value_that_fits()), (Some("maxInterval"), Some(148.3)));
    /// ```
    pub fn value_that_fits(&self) -> Option<f64> {
        match self {
            ApiError::Sim(e) => e.value_that_fits(),
            _ => None,
        }
    }
}

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
    use crate::sim::{Scenario, SenderKind, Simulator, SyntheticChoice};

    /// The error of a run of synthetic flight 1 with `change` made.
    fn refused(change: impl FnOnce(&mut Scenario)) -> ApiError {
        let mut s = Scenario::default();
        s.flight.synthetic = Some(SyntheticChoice::One(1));
        change(&mut s);
        crate::api::simulate(&mut Simulator::new(), &s).unwrap_err()
    }

    #[test]
    fn an_error_names_the_one_setting_at_fault() {
        let e = refused(|s| s.radio.sf = 13);
        assert_eq!(e.setting(), Some("sf"), "{e}");
        // A limit that depends on another setting: the heartbeat against SF12's interval.
        let e = refused(|s| {
            s.radio.sf = 12;
            s.radio.bw = 125.0;
            s.sending.sender = SenderKind::Error;
            s.sending.max_interval = 10.0;
        });
        assert_eq!(e.setting(), Some("maxInterval"), "{e}");
        assert!(e.to_string().starts_with("maxInterval must be"), "{e}");
        let e = refused(|s| s.radio.duty_cycle = 2.0);
        assert_eq!(e.setting(), Some("dutyCycle"), "{e}");
    }

    #[test]
    fn an_error_of_settings_together_names_none() {
        let e = refused(|s| s.flight.synthetic = None);
        assert!(e.to_string().starts_with("choose a flight"), "{e}");
        assert_eq!(e.setting(), None);
        assert_eq!(
            ApiError::Invalid("unknown setting 'x'".into()).setting(),
            None
        );
    }

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
