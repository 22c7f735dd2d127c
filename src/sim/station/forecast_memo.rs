//! A station's errors from one received packet on, recalled where another run met that packet.

use super::Received;
use std::sync::Arc;

/// What names the errors a station makes from one received packet on, within one flight and one
/// station's settings: the packet as the station applies it (send time, interval and decoded
/// state, bit for bit, and whether the station trusts the silence after it) and the evaluation
/// time it first serves (its index on the flight's grid).
///
/// A station that forgets the past at each packet ([`Tracker::forgets_the_past`]) steps from the
/// packet to each evaluation time in the same steps whatever came before or comes after, so its
/// error at the k-th time from `first` is the same in every run that delivers this packet and
/// serves that time with it.
///
/// [`Tracker::forgets_the_past`]: super::Tracker::forgets_the_past
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SpanKey {
    sent: u64,
    interval: u64,
    state: [u64; 9],
    silence_trusted: bool,
    first: usize,
}

impl SpanKey {
    /// The key of `r` applied from grid index `first` on.
    pub(crate) fn of(r: &Received, first: usize) -> Self {
        let p = r.packet;
        SpanKey {
            sent: p.sent.to_bits(),
            interval: p.interval.to_bits(),
            state: p.state.map(f64::to_bits),
            silence_trusted: r.silence_trusted,
            first,
        }
    }
}

/// Errors a station made from one packet on, kept for other runs of the same station over the
/// same flight that deliver the same packet (the swarms of a family share them:
/// [`SharedDroneRuns`]). What is recalled is exactly what would be computed.
///
/// [`SharedDroneRuns`]: crate::sim::SharedDroneRuns
pub trait ForecastMemo {
    /// The errors, m, at the evaluation times from the packet `key` names on, where at least
    /// `count` of them are kept (the caller reads the first `count`).
    fn recall(&self, key: &SpanKey, count: usize) -> Option<Arc<[f64]>>;
    /// Keeps `errors`, m, the station's at the evaluation times from the packet `key` names on
    /// (ignored where as many or more are kept already, or where there is no room).
    fn keep(&self, key: SpanKey, errors: &[f64]);
}
