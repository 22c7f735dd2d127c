//! The network: gateways that receive, a network server that keeps one copy of each uplink and
//! runs ADR, and the one event loop that moves every drone and every gateway through time.
//!
//! * [`gateway`]: one gateway's receiver and downlink duty cycle, and what it counted.
//! * [`server`]: the network server: first copy of each packet, ADR from the best SNR, which
//!   gateway answers in which receive window.
//! * [`event_loop`]: [`run_episode`], the loop itself: N ≥ 1 drones, M ≥ 1 gateways, one time axis.
//!
//! `simulate` is this loop with one drone; `swarm` is the same loop with many.

mod event_loop;
mod gateway;
mod server;

pub use event_loop::run_episode;

pub use gateway::GatewayReport;
pub use server::Network;

use crate::lora::DutyCycle;
use crate::sim::clock::Timing;
use crate::sim::drone::Estimates;
use crate::sim::flier::Flier;
use crate::sim::sender::Sender;
use crate::sim::Transmission;
use crate::trajectory::Trajectory;

/// One drone (drone 0 of `net`) alone with the network's gateways, placed as `simulate` places
/// them (relative to the flight's first point), on one channel: its uplinks over `flight`.
/// The random streams are `seed`'s for flight `stream`, and the timing exact, as in `simulate`
/// by default.
pub fn fly_alone(
    net: &mut Network,
    flight: &Trajectory,
    estimates: Estimates<'_>,
    sender: Box<dyn Sender>,
    rule: DutyCycle,
    seed: u64,
    stream: u64,
) -> Vec<Transmission> {
    let gateways = net.gateways_at([flight.pos[0][0], flight.pos[0][1]]);
    let interval = net.radios[0].current().interval;
    let mut flier = Flier::new(
        0,
        flight,
        estimates,
        sender,
        rule,
        &gateways,
        &net.channel,
        (seed, stream),
        1,
        interval,
        Timing::EXACT,
    );
    run_episode(net, core::slice::from_mut(&mut flier));
    flier.tx
}
