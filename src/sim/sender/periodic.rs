//! The paper's sender: every packet the duty cycle allows.

use super::Sender;

/// Sends whenever the duty-cycle rule allows (paper §IV-A: "as often as the duty cycle allows").
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Periodic;

impl Sender for Periodic {
    fn wants_to_send(&mut self, _t: f64, _own: &[f64; 9]) -> bool {
        true
    }

    fn sent(&mut self, _state: &[f64; 9], _t: f64) {}

    fn reads_estimate(&self) -> bool {
        false
    }
}
