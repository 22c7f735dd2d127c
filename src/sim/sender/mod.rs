//! When the drone sends: the paper's periodic sender, or one that sends only when the station's
//! belief has drifted from the drone's own estimate. The duty-cycle rule that bounds both lives in
//! [`DutyCycle`](crate::lora::DutyCycle); a sender only says whether it *wants* to send.

mod channel_sense;
mod error_triggered;
mod payload;
mod periodic;
mod sending;

pub use channel_sense::{ChannelLoad, ChannelSense, MIN_SUCCESS, SENSE_GAIN};
pub use error_triggered::ErrorTriggered;
pub use payload::{LeanPayload, PayloadChoice, LEAN_SIGNIFICANCE};
pub use periodic::Periodic;
pub use sending::{Sending, DEFAULT_BURST, DEFAULT_MAX_INTERVAL_S, DEFAULT_THRESHOLD_M};

use serde::{Deserialize, Serialize};

/// The sending policy (`--sender`; `error` is [`ErrorTriggered`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum SenderKind {
    /// As often as the duty cycle allows (the paper).
    #[default]
    Periodic,
    /// When the mirrored station's position is more than a threshold (--threshold) from the
    /// drone's own estimate, or when the heartbeat (--max-interval) is due.
    Error,
}

impl SenderKind {
    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            SenderKind::Periodic => "periodic",
            SenderKind::Error => "error",
        }
    }
}

/// A sending policy, asked at every sensor step at which the duty-cycle rule allows a packet.
pub trait Sender {
    /// Whether the drone wants to send at time `t` (s), with its own estimate `own` (the state it
    /// would send: 9 components, the unused ones 0; m, rad, m/s).
    fn wants_to_send(&mut self, t: f64, own: &[f64; 9]) -> bool;
    /// Tells the sender that the packet carrying `state` (decoded, as the station will see it;
    /// 9 components, the unused ones 0) left at `t` (s).
    fn sent(&mut self, state: &[f64; 9], t: f64);
    /// ADR moved the drone to a data rate whose duty-cycle interval is `interval` s.
    fn data_rate_changed(&mut self, _interval: f64) {}
    /// Whether the sender listens to its channel ([`ChannelSense::Cad`]): only then does the
    /// event loop look for other packets on air as each uplink starts.
    fn listens(&self) -> bool {
        false
    }
    /// An uplink starts on a channel that was `busy` with another packet the drone could detect;
    /// told only to a sender that [`Sender::listens`].
    fn channel_sensed(&mut self, _busy: bool) {}
    /// Whether [`Sender::wants_to_send`] looks at the drone's estimate. One that does not lets
    /// the event loop plan an uplink without running the drone's filter up to it, so that a
    /// swarm's filters run ahead on every core rather than in the loop.
    fn reads_estimate(&self) -> bool {
        true
    }
}
