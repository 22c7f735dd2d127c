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

/// Drone `stream`'s link stream.
pub fn link(seed: u64, stream: u64) -> Rng {
    Rng::derive(seed ^ LINK_STREAM, stream)
}

/// The shadowing stream of gateway `g` ≥ 1 for drone `stream`.
pub fn gateway(seed: u64, g: usize, stream: u64) -> Rng {
    Rng::derive(seed ^ GATEWAY_STREAM ^ ((g as u64) << 40), stream)
}

/// Drone `stream`'s channel-hopping stream.
pub fn channel(seed: u64, stream: u64) -> Rng {
    Rng::derive(seed ^ CHANNEL_STREAM, stream)
}

/// Drone `stream`'s clock stream.
pub fn clock(seed: u64, stream: u64) -> Rng {
    Rng::derive(seed ^ CLOCK_STREAM, stream)
}
