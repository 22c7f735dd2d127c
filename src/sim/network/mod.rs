//! The network: gateways that receive, a network server that keeps one copy of each uplink and
//! runs ADR, and the one event loop that moves every drone and every gateway through time.
//!
//! * `gateway`: one gateway's receiver and downlink duty cycle, and what it counted.
//! * `server`: the network server: first copy of each packet, ADR from the best SNR, which
//!   gateway answers in which receive window.
//! * `crowd`: what the server knows of the other devices' traffic, and so of a frame's chance to
//!   collide at each data rate (tracking ADR reads losses through it).
//! * `event_loop`: [`run_episode`], the loop itself: N ≥ 1 drones, M ≥ 1 gateways, one time axis.
//!
//! `simulate` is this loop with one drone; `swarm` is the same loop with many.

mod crowd;
mod event_loop;
mod gateway;
mod server;

pub use crowd::CrowdLoad;
pub use event_loop::run_episode;

pub use gateway::GatewayReport;
pub use server::{Network, NetworkSetup};

use crate::sim::clock::Timing;
use crate::sim::flier::{Aboard, Air, Flier};
use crate::sim::{DroneStreams, Transmission};

/// One drone (drone 0 of `net`) flying with `aboard`, alone with the network's gateways, placed
/// as `simulate` places them (relative to the flight's first point), on one channel: its
/// uplinks. It draws from `streams`, and the timing is exact, as in `simulate` by default.
pub fn fly_alone(
    net: &mut Network,
    aboard: Aboard<'_>,
    streams: DroneStreams,
) -> Vec<Transmission> {
    let first = aboard.flight.pos[0];
    let gateways = net.gateways_at([first[0], first[1]]);
    let air = Air {
        gateways: &gateways,
        channel: &net.channel,
        streams,
        channels: 1,
        interval: net.radios[0].current().interval,
        timing: Timing::EXACT,
    };
    let mut flier = Flier::new(0, aboard, &air);
    // A lone flier's episode asks no progress, so it always flies to its end.
    let whole = run_episode(net, core::slice::from_mut(&mut flier), &mut |_| true);
    debug_assert!(whole);
    flier.tx
}
