//! The network server: between the gateways and the station. It keeps the first copy of each
//! uplink (the station sees a packet once), records which gateways heard it, runs ADR from the
//! best SNR across gateways, and answers through the gateway that heard the uplink best, in RX1
//! or, when that gateway's duty cycle forbids RX1, in RX2 (LoRaWAN network servers such as The
//! Things Stack and ChirpStack pick the downlink gateway by uplink SNR the same way).

use super::gateway::GatewayReport;
use super::CrowdLoad;
use crate::lora::{
    snr_db, tracking_ack_limits, AckLimits, AdrMode, AdrNetwork, AdrParams, Channel, ChannelAccess,
    InterferenceModel, LinkAdrReq, UplinkFrame, UplinkReport, Window,
};
use crate::sim::radio::DroneRadio;
use crate::sim::scenario::{GatewaySite, Validated};

/// What a network is built from: its gateways, the link budget and reception rules they share,
/// the server's ADR settings, and how the drones speak.
#[derive(Clone, Debug)]
pub struct NetworkSetup {
    /// The gateways, in the scenario's frame.
    pub sites: Vec<GatewaySite>,
    /// Antenna height of a site given none, m.
    pub default_height: f64,
    /// ADR settings, run for each drone whose radio adapts.
    pub adr: AdrParams,
    /// Link budget shared by every link.
    pub channel: Channel,
    /// Reception rules of every gateway.
    pub interference: InterferenceModel,
    /// Whether the drones speak LoRaWAN (open class A receive windows; counted in their
    /// energy). Raw LoRa, the paper's Table II, does not.
    pub lorawan: bool,
    /// Whether the drones listen before they talk (reference §15).
    pub listen_before_talk: bool,
}

/// The most of the other devices' frames a downlink may be expected to cost, where the ADR
/// spares the gateway ([`AdrNetwork::spares_the_gateway`]): a lone drone's answers go in RX2 as
/// LoRaWAN's do, a swarm's wait for RX1. Not tuned: at SF7/250 kHz (a frame every 3.1 s) one other
/// drone puts 0.38 frames on air during RX2's 1.15 s answer, two 0.77, eleven 4.2; no other value
/// was tried (docs/beyond-the-paper.md, "Half-duplex gateways").
pub const MAX_FRAMES_MISSED_PER_ANSWER: f64 = 0.5;

/// Everything that lasts across the episodes (flights) of a run: the gateways and their counts,
/// each drone's radio, and the server's ADR state per drone.
pub struct Network {
    /// The gateways, in the scenario's frame.
    pub sites: Vec<GatewaySite>,
    /// Default antenna height of a site given none, m.
    pub default_height: f64,
    /// Each drone's radio.
    pub radios: Vec<DroneRadio>,
    adr: Vec<Option<Box<dyn AdrNetwork>>>,
    /// Per gateway, what it did.
    pub gateways: Vec<GatewayReport>,
    /// Link budget shared by every link.
    pub channel: Channel,
    /// Reception rules of every gateway.
    pub interference: InterferenceModel,
    /// Whether the drones speak LoRaWAN (open class A receive windows; counted in their
    /// energy). Raw LoRa, the paper's Table II, does not.
    pub lorawan: bool,
    /// Receptions beyond the first of each packet, removed by the server.
    pub duplicates: usize,
    /// Whether the drones listen before they talk (reference §15).
    pub listen_before_talk: bool,
    /// The other devices' traffic, as the server hears it (ADR).
    crowd: CrowdLoad,
}

impl Network {
    /// The network `setup` describes, for drones with `radios`; for each drone whose radio
    /// adapts, the server runs ADR (the channel's shadowing informs the tracking-aware choice).
    pub fn new(setup: NetworkSetup, mut radios: Vec<DroneRadio>) -> Self {
        let NetworkSetup {
            sites,
            default_height,
            adr,
            channel,
            interference,
            lorawan,
            listen_before_talk,
        } = setup;
        let limits = match adr.mode {
            AdrMode::Tracking => tracking_ack_limits(radios.len(), sites.len()),
            _ => AckLimits::LORAWAN,
        };
        for r in &mut radios {
            r.set_ack_limits(limits);
        }
        let algorithms = radios
            .iter()
            .map(|r| r.rates().map(|t| t.network(&adr, channel.params(), limits)))
            .collect();
        let drones = radios.len();
        let gateways = sites
            .iter()
            .map(|s| {
                let [east, north, height] = s.position(default_height);
                GatewayReport {
                    east,
                    north,
                    height,
                    ..GatewayReport::default()
                }
            })
            .collect();
        Network {
            sites,
            default_height,
            radios,
            adr: algorithms,
            gateways,
            channel,
            interference,
            lorawan,
            duplicates: 0,
            listen_before_talk,
            crowd: CrowdLoad::new(drones),
        }
    }

    /// The network of a validated scenario for drones with `radios`: its gateways (the one
    /// default gateway `east` m east of the origin when none is given), ADR, channel, reception
    /// rules, and whether drones listen before they talk.
    pub fn of(cfg: &Validated, east: f64, radios: Vec<DroneRadio>) -> Self {
        let s = cfg.s();
        let setup = NetworkSetup {
            sites: cfg.sites(east),
            default_height: s.channel.gateway_height,
            adr: cfg.adr,
            channel: cfg.channel,
            interference: cfg.interference,
            lorawan: s.radio.overhead > 0,
            listen_before_talk: s.access.access == ChannelAccess::Lbt,
        };
        Network::new(setup, radios)
    }

    /// Replaces drone `drone`'s ADR algorithm (to compare a rule of one's own).
    pub fn set_adr_network(&mut self, drone: usize, network: Box<dyn AdrNetwork>) {
        if let Some(slot) = self.adr.get_mut(drone) {
            *slot = Some(network);
        }
    }

    /// The gateways' antennas for a drone whose flight frame puts the scenario's origin at
    /// `origin` (x, y), m.
    pub fn gateways_at(&self, origin: [f64; 2]) -> Vec<[f64; 3]> {
        self.sites
            .iter()
            .map(|s| {
                let [e, n, h] = s.position(self.default_height);
                [origin[0] + e, origin[1] + n, h]
            })
            .collect()
    }

    /// The server's view of one uplink's copies: counts them per gateway and as duplicates.
    pub(crate) fn count_copies(&mut self, heard_by: u32) {
        let copies = heard_by.count_ones() as usize;
        for (g, report) in self.gateways.iter_mut().enumerate() {
            if heard_by & (1 << g) != 0 {
                report.heard += 1;
                if copies == 1 {
                    report.only_heard += 1;
                }
            }
        }
        self.duplicates += copies.saturating_sub(1);
    }

    /// ADR for drone `drone`'s received uplink: whether the server answers with a downlink (it
    /// must when asked by `ADRACKReq`, and does when it has a command), and the command. The
    /// server first counts the frame toward the crowd ([`CrowdLoad`]).
    pub(crate) fn adr_hears(
        &mut self,
        drone: usize,
        up: &AdrUplink<'_>,
    ) -> (bool, Option<LinkAdrReq>) {
        let Some(Some(algorithm)) = self.adr.get_mut(drone) else {
            return (false, None);
        };
        let frame = up.frame;
        let toa = self.radios[drone]
            .rates()
            .map_or([0.0; 7], |t| t.time_on_air);
        self.crowd.heard(
            drone,
            frame.fcnt,
            frame.dr,
            toa[usize::from(frame.dr.index())],
            up.time,
        );
        let crowd_loss = up
            .channels
            .map_or([0.0; 7], |c| self.crowd.loss(drone, &toa, c));
        let command = algorithm.on_uplink(&UplinkReport {
            fcnt: frame.fcnt,
            dr: frame.dr,
            power_reduction_db: frame.power_reduction_db,
            rssi_dbm: up.rssi_dbm,
            snr_db: snr_db(up.rssi_dbm, frame.dr.bw()),
            adr_ack_req: frame.adr_ack_req,
            speed_mps: up.speed_mps,
            crowd_loss,
        });
        (command.is_some() || frame.adr_ack_req, command)
    }

    /// Whether the server may answer drone `drone` in `window` with a downlink `seconds` long:
    /// always in RX1, and in RX2 unless its ADR spares the gateway and the other devices are
    /// expected to have more than [`MAX_FRAMES_MISSED_PER_ANSWER`] frames on air meanwhile.
    pub(crate) fn may_answer_in(&self, drone: usize, window: Window, seconds: f64) -> bool {
        let spares = matches!(self.adr.get(drone), Some(Some(a)) if a.spares_the_gateway());
        window == Window::Rx1
            || !spares
            || self.crowd.others_on_air(drone, seconds) <= MAX_FRAMES_MISSED_PER_ANSWER
    }
}

/// One received ADR uplink, as the server learns of it.
pub(crate) struct AdrUplink<'a> {
    /// The frame's ADR fields.
    pub frame: &'a UplinkFrame,
    /// Received power at the gateway that heard it best, dBm.
    pub rssi_dbm: f64,
    /// The speed its payload reports, m/s.
    pub speed_mps: f64,
    /// When it ended, s (the episode's time axis).
    pub time: f64,
    /// The channels the drone hops over at random (ALOHA), or `None` for a drone keeping a
    /// slot of a schedule, which meets no other frame.
    pub channels: Option<u8>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lora::{DataRate, LoraParams};
    use crate::sim::scenario::Scenario;
    use std::sync::{Arc, Mutex};

    /// An ADR network that only writes down each report's crowd loss at the frame's rate.
    struct Recorder(Arc<Mutex<Vec<f64>>>);
    impl AdrNetwork for Recorder {
        fn on_uplink(&mut self, up: &UplinkReport) -> Option<LinkAdrReq> {
            let loss = up.crowd_loss[usize::from(up.dr.index())];
            self.0.lock().unwrap().push(loss);
            None
        }
    }

    /// `drones` drones at SF7 / 250 kHz with tracking ADR, one gateway 1 km east (the scenario's
    /// network, as `simulate` and `swarm` build it).
    fn network(drones: usize) -> Network {
        network_with(drones, AdrMode::Tracking)
    }

    /// [`network`] with ADR `adr`.
    fn network_with(drones: usize, adr: AdrMode) -> Network {
        let settings = serde_json::json!({"adr": adr, "sf": 7, "bw": 250});
        let cfg = Scenario::default()
            .with(&settings)
            .unwrap()
            .validate()
            .unwrap();
        let radio = LoraParams::new(DataRate::DR6.sf(), DataRate::DR6.bw());
        let radios = (0..drones)
            .map(|_| DroneRadio::new(&radio, 12, 0.01, adr).unwrap())
            .collect();
        Network::of(&cfg, 1000.0, radios)
    }

    /// Every drone of `net` heard `rounds` times, one frame each every 2 s, on `channels`;
    /// what drone 0's network was told.
    fn hear_all(net: &mut Network, rounds: u32, channels: Option<u8>) -> Vec<f64> {
        let seen = Arc::new(Mutex::new(Vec::new()));
        net.set_adr_network(0, Box::new(Recorder(Arc::clone(&seen))));
        for k in 0..rounds {
            for drone in 0..net.radios.len() {
                let frame = net.radios[drone].uplink().adr.unwrap();
                let up = AdrUplink {
                    frame: &frame,
                    rssi_dbm: -100.0,
                    speed_mps: 5.0,
                    time: 2.0 * f64::from(k) + 0.01 * drone as f64,
                    channels,
                };
                net.adr_hears(drone, &up);
            }
        }
        seen.lock().map(|v| v.clone()).unwrap()
    }

    #[test]
    fn a_tracking_network_keeps_its_answers_out_of_rx2_in_a_crowd_and_lorawans_does_not() {
        // RX2's 17-byte SF12 answer: 1.15 s on air.
        let rx2 = 1.15;
        let mut alone = network(1);
        hear_all(&mut alone, 10, Some(1));
        assert!(
            alone.may_answer_in(0, Window::Rx2, rx2),
            "no one else to miss"
        );
        // Eleven others, each every 2 s: about 6 of their frames on air during the answer.
        let mut crowd = network(12);
        hear_all(&mut crowd, 10, Some(1));
        assert!(crowd.may_answer_in(1, Window::Rx1, rx2));
        assert!(!crowd.may_answer_in(1, Window::Rx2, rx2));
        // Before the server has heard the others, it knows of no crowd.
        assert!(network(12).may_answer_in(1, Window::Rx2, rx2));
        let mut lorawan = network_with(12, AdrMode::Lorawan);
        hear_all(&mut lorawan, 10, Some(1));
        assert!(lorawan.may_answer_in(1, Window::Rx2, rx2));
    }

    #[test]
    fn the_server_tells_adr_the_crowds_collision_chance_and_a_lone_drone_none() {
        let alone = hear_all(&mut network(1), 10, Some(1));
        assert!(alone.iter().all(|&c| c == 0.0), "{alone:?}");
        let crowd = hear_all(&mut network(20), 10, Some(1));
        // Once the others' rates are known: 19 drones on air 1 % of the time each (0.0205 s
        // every 2 s here, a little more), one channel: about 1 − e^(−0.38).
        let last = *crowd.last().unwrap();
        assert!(crowd[0] == 0.0 && last > 0.25 && last < 0.4, "{crowd:?}");
        // Three channels share the same load three ways.
        let three = *hear_all(&mut network(20), 10, Some(3)).last().unwrap();
        assert!((three - (1.0 - (1.0 - last).powf(1.0 / 3.0))).abs() < 1e-9);
        // Drones keeping slots of a schedule meet no one.
        let slotted = hear_all(&mut network(20), 10, None);
        assert!(slotted.iter().all(|&c| c == 0.0));
    }
}
