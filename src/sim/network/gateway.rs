//! One gateway in the loop: its receiver (demodulation paths, interference), its downlink duty
//! cycle per sub-band, and what it counted.

use crate::lora::{
    DutyCycle, DutyCycleMode, InterferenceModel, Outcome, Receiver, Uplink, Window,
    SX1301_DEMODULATORS,
};
use serde::{Deserialize, Serialize};

/// What one gateway did over a run (JSON `gateways[]`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct GatewayReport {
    /// Metres east of the scenario's origin.
    pub east: f64,
    /// Metres north of the scenario's origin.
    pub north: f64,
    /// Antenna height, m.
    pub height: f64,
    /// Uplinks it received.
    pub heard: usize,
    /// Uplinks only it received (what the network would lose without it).
    pub only_heard: usize,
    /// ADR downlinks it sent.
    pub downlinks_sent: usize,
    /// Downlinks the network server wanted to send through it but its duty cycle forbade in
    /// both receive windows.
    pub downlinks_dropped: usize,
    /// Downlinks the network server held back for a later uplink: its duty cycle forbade RX1,
    /// and the ADR keeps its answers out of RX2 while the gateway's other devices are expected
    /// on air meanwhile (`AdrNetwork::spares_the_gateway`; the tracking-aware ADR, reference
    /// §6.5). Always 0 under LoRaWAN ADR, whose server uses RX2 whenever RX1 is not free.
    pub downlinks_held_back: usize,
    /// Uplinks it would have had to hear while it transmitted a downlink, and so lost (a gateway
    /// is half-duplex, reference §6.3).
    pub missed_while_transmitting: usize,
}

impl GatewayReport {
    /// Adds another run's counts (same gateway).
    pub fn add(&mut self, other: &GatewayReport) {
        self.heard += other.heard;
        self.only_heard += other.only_heard;
        self.downlinks_sent += other.downlinks_sent;
        self.downlinks_dropped += other.downlinks_dropped;
        self.downlinks_held_back += other.downlinks_held_back;
        self.missed_while_transmitting += other.missed_while_transmitting;
    }
}

/// A gateway during one episode.
pub(crate) struct Gateway {
    receiver: Receiver,
    /// Downlink duty cycle in RX1's sub-band (1 %) and RX2's (10 %), once used.
    bands: [Option<DutyCycle>; 2],
}

impl Gateway {
    pub fn new(model: InterferenceModel) -> Self {
        Gateway {
            receiver: Receiver::new(model, SX1301_DEMODULATORS),
            bands: [None, None],
        }
    }

    pub fn start(&mut self, id: u64, uplink: Uplink) {
        self.receiver.start(id, uplink);
    }

    pub fn finish(&mut self, id: u64) -> Outcome {
        self.receiver.finish(id)
    }

    /// Sends a downlink of `time_on_air` s at `t` in `window` if the sub-band's duty cycle
    /// allows it (an off-time of time on air / duty cycle after each, ETSI EN 300 220), deaf to
    /// uplinks meanwhile; whether it went.
    pub fn try_downlink(&mut self, window: Window, t: f64, time_on_air: f64) -> bool {
        let dc = window.sub_band().duty_cycle();
        let band = &mut self.bands[window.index()];
        let rule = match band {
            Some(r) => {
                r.set_time_on_air(time_on_air);
                r
            }
            None => band.insert(
                match DutyCycle::new(DutyCycleMode::PerPacket, dc, time_on_air, 1, t) {
                    Ok(r) => r,
                    Err(_) => return false,
                },
            ),
        };
        if rule.earliest(t) <= t {
            rule.spend(t);
            self.receiver.transmit(t, t + time_on_air);
            true
        } else {
            false
        }
    }
}
