//! What a single-model station predicts after each packet, remembered across runs.
//!
//! A single-model station forgets everything on a packet: from then until the next packet it
//! only predicts, so its estimates depend on that packet alone (its state, send and arrival
//! times, the interval it came at) and on the evaluation grid. Moving the gateway changes which
//! packets arrive, never when the drone sends them or what they carry, so a link change reuses
//! every chain and only pays for the evaluation. The numbers are the same as without the cache
//! (tests/integration/station.rs checks).

use super::{score_station, start_from, Estimate, Received, Scoring, StationTrack, Tracker};
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
        let mut cursor = Cursor::new(self);
        let track = score_station(
            flight,
            transmissions,
            scoring,
            None,
            &mut |t, received, fresh| {
                if fresh.is_some() {
                    cursor.turn_to(key_of(received));
                } else if cursor.current.is_none() {
                    // Before any packet (which scoring never asks for) the chain of no packet.
                    cursor.turn_to(NO_PACKET);
                }
                cursor.estimate(t, received, new_tracker)
            },
        );
        cursor.put_back();
        track
    }
}

/// The key of the chain before any packet.
const NO_PACKET: PacketKey = (0, 0, 0, false);

/// The key of `received`'s chain.
fn key_of(received: &Received) -> PacketKey {
    let packet = received.packet;
    (
        packet.sent.to_bits(),
        packet.arrival.to_bits(),
        packet.interval.to_bits(),
        received.silence_trusted,
    )
}

/// Where a station's pass over the evaluation grid stands in a flight's chains: the packet being
/// served with its chain, held out of the map while it is served (the map is hashed once per
/// packet, not at every grid time: SipHash was 8 % of a warm run in WebAssembly), how far into
/// it, the grid times served since the packet, and a live tracker once the chain runs out.
struct Cursor<'a> {
    chains: &'a mut FlightChains,
    current: Option<(PacketKey, Chain)>,
    k: usize,
    served: Vec<f64>,
    live: Option<Box<dyn Tracker>>,
}

impl<'a> Cursor<'a> {
    fn new(chains: &'a mut FlightChains) -> Self {
        Cursor {
            chains,
            current: None,
            k: 0,
            served: Vec::new(),
            live: None,
        }
    }

    /// Puts the chain being served back into the map.
    fn put_back(&mut self) {
        if let Some((key, chain)) = self.current.take() {
            self.chains.chains.insert(key, chain);
        }
    }

    /// Serves the chain of `key` from its start (a new one if none is remembered).
    fn turn_to(&mut self, key: PacketKey) {
        self.put_back();
        self.k = 0;
        self.served.clear();
        self.live = None;
        let chain = self.chains.chains.remove(&key).unwrap_or_default();
        self.current = Some((key, chain));
    }

    /// The estimate at grid time `t` after `received`: the chain's next where it has one, else
    /// a live tracker's (replayed from the packet over the grid times already served), which the
    /// chain then keeps.
    fn estimate(
        &mut self,
        t: f64,
        received: &Received,
        new_tracker: &dyn Fn() -> Box<dyn Tracker>,
    ) -> Estimate {
        let chain = &mut self.current.get_or_insert_with(Default::default).1;
        let e = match chain.estimates.get(self.k) {
            Some(e) => *e,
            None => {
                let served = &self.served;
                let tracker = self.live.get_or_insert_with(|| {
                    let mut tr = new_tracker();
                    start_from(tr.as_mut(), received);
                    for &s in served {
                        tr.predict_to(s);
                    }
                    tr
                });
                tracker.predict_to(t);
                let e = Estimate::of(tracker.as_ref());
                chain.estimates.push(e);
                self.chains.stored += 1;
                e
            }
        };
        self.served.push(t);
        self.k += 1;
        e
    }
}
