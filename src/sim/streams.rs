//! The random streams of a run. Each draw comes from a stream derived from the seed, a purpose
//! and the drone (or flight) it belongs to, so that changing one setting changes only what it
//! should: the sensors' noise never depends on the link, and a second gateway leaves the first
//! gateway's shadowing as it was.

use crate::rng::Rng;

/// The link: the first packet's offset, then the first gateway's shadowing.
pub const LINK_STREAM: u64 = 0x4C49_4E4B; // "LINK"
/// Each packet's uplink channel.
pub const CHANNEL_STREAM: u64 = 0x4348_414E; // "CHAN"
/// A swarm's layout: each drone's first flight and bearing.
pub const LAYOUT_STREAM: u64 = 0x4C41_594F; // "LAYO"
/// Each drone's clock: its drift, then the random delay before each uplink.
pub const CLOCK_STREAM: u64 = 0x434C_4F43; // "CLOC"
/// The shadowing of every gateway after the first.
const GATEWAY_STREAM: u64 = 0x4741_5445; // "GATE"
/// The shadowing each gateway's downlinks meet, apart from the uplinks'.
const DOWNLINK_STREAM: u64 = 0x444F_574E; // "DOWN"

/// One drone's share of a run's randomness: the run's seed and the drone's stream of it (the
/// flight's index in a `simulate` run, the drone's in a swarm). Every draw for that drone (its
/// sensors' noise, its links, its channels, its clock) comes from one of these streams, so a
/// drone's sensors and its links can never be given different seeds.
///
/// ```
/// use loratrack::DroneStreams;
/// let a = DroneStreams { seed: 7, stream: 2 };
/// assert_eq!(a.link().uniform(), a.link().uniform());
/// assert_ne!(a.link().uniform(), DroneStreams { stream: 3, ..a }.link().uniform());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DroneStreams {
    /// The run's seed.
    pub seed: u64,
    /// Which drone (or flight) of the run.
    pub stream: u64,
}

impl DroneStreams {
    /// The sensors' noise.
    pub fn sensors(self) -> Rng {
        Rng::derive(self.seed, self.stream)
    }

    /// The link: the first packet's offset, then the first gateway's shadowing.
    pub fn link(self) -> Rng {
        Rng::derive(self.seed ^ LINK_STREAM, self.stream)
    }

    /// The shadowing of gateway `g` ≥ 1.
    pub fn gateway(self, g: usize) -> Rng {
        Rng::derive(self.seed ^ GATEWAY_STREAM ^ ((g as u64) << 40), self.stream)
    }

    /// The shadowing of gateway `g`'s downlinks (`g` = 0 for the first).
    pub fn downlink(self, g: usize) -> Rng {
        Rng::derive(
            self.seed ^ DOWNLINK_STREAM ^ ((g as u64) << 40),
            self.stream,
        )
    }

    /// Each packet's uplink channel.
    pub fn channel(self) -> Rng {
        Rng::derive(self.seed ^ CHANNEL_STREAM, self.stream)
    }

    /// The clock: its drift, then the random delay before each uplink.
    pub fn clock(self) -> Rng {
        Rng::derive(self.seed ^ CLOCK_STREAM, self.stream)
    }
}
