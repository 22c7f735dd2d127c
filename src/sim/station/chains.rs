//! What a single-model station predicts after each packet, remembered across runs.
//!
//! A single-model station forgets everything on a packet: from then until the next packet it
//! only predicts, so its estimates depend on that packet alone (its state, send and arrival
//! times, the interval it came at) and on the evaluation grid. Moving the gateway changes which
//! packets arrive, never when the drone sends them or what they carry, so a link change reuses
//! every chain and only pays for the evaluation. The numbers are the same as without the cache
//! (tests/integration/station.rs checks).

use super::{score_station, start_from, Estimate, Scoring, StationTrack, Tracker};
use crate::sim::packet::Transmission;
use crate::trajectory::Trajectory;
use std::collections::HashMap;

/// A packet as the station sees it: send time, arrival time and interval, bit for bit, and
/// whether the station trusts the silence after it.
type PacketKey = (u64, u64, u64, bool);

/// The estimates of one packet's predictions, from the first grid time it is applied at.
#[derive(Default)]
struct Chain {
    estimates: Vec<Estimate>,
}

/// The chains of one flight, for one station setting.
#[derive(Default)]
pub(crate) struct FlightChains {
    chains: HashMap<PacketKey, Chain>,
    /// Estimates held over all chains.
    stored: usize,
}

/// A flight keeps at most this many times its evaluation grid in estimates (about four send
/// schedules' worth, ~0.5 KB per second of flight); past it, it starts afresh.
pub(crate) const MAX_GRIDS: f64 = 4.0;

impl FlightChains {
    /// [`track_station`](super::track_station) for a fresh single-model station made by
    /// `new_tracker`, reusing and extending the remembered chains.
    pub(crate) fn track(
        &mut self,
        flight: &Trajectory,
        new_tracker: &dyn Fn() -> Box<dyn Tracker>,
        transmissions: &[Transmission],
        scoring: Scoring,
    ) -> StationTrack {
        let grid = (flight.duration() / scoring.step).max(1.0);
        if self.stored as f64 > MAX_GRIDS * grid {
            self.chains.clear();
            self.stored = 0;
        }
        // The packet being served with its chain, held out of the map while it is served (the
        // map is hashed once per packet, not at every grid time: SipHash was 8 % of a warm run
        // in WebAssembly), how far into it, and a live tracker once the chain runs out
        // (replayed from the packet over the grid times already served).
        let mut current: Option<(PacketKey, Chain)> = None;
        let mut k = 0;
        let mut served: Vec<f64> = Vec::new();
        let mut live: Option<Box<dyn Tracker>> = None;
        let (chains, stored) = (&mut self.chains, &mut self.stored);
        let track = score_station(
            flight,
            transmissions,
            scoring,
            None,
            &mut |t, received, fresh| {
                let chain = if fresh.is_some() {
                    let packet = received.packet;
                    let key = (
                        packet.sent.to_bits(),
                        packet.arrival.to_bits(),
                        packet.interval.to_bits(),
                        received.silence_trusted,
                    );
                    if let Some((served_key, chain)) = current.take() {
                        chains.insert(served_key, chain);
                    }
                    k = 0;
                    served.clear();
                    live = None;
                    &mut current
                        .insert((key, chains.remove(&key).unwrap_or_default()))
                        .1
                } else {
                    // Before any packet (which scoring never asks for) the chain of no packet.
                    &mut current
                        .get_or_insert_with(|| {
                            let key = (0, 0, 0, false);
                            (key, chains.remove(&key).unwrap_or_default())
                        })
                        .1
                };
                let e = match chain.estimates.get(k) {
                    Some(e) => *e,
                    None => {
                        let tracker = live.get_or_insert_with(|| {
                            let mut tr = new_tracker();
                            start_from(tr.as_mut(), received);
                            for &s in &served {
                                tr.predict_to(s);
                            }
                            tr
                        });
                        tracker.predict_to(t);
                        let e = Estimate::of(tracker.as_ref());
                        chain.estimates.push(e);
                        *stored += 1;
                        e
                    }
                };
                served.push(t);
                k += 1;
                e
            },
        );
        if let Some((key, chain)) = current {
            chains.insert(key, chain);
        }
        track
    }
}
