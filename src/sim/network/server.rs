//! The network server: between the gateways and the station. It keeps the first copy of each
//! uplink (the station sees a packet once), records which gateways heard it, runs ADR from the
//! best SNR across gateways, and answers through the gateway that heard the uplink best, in RX1
//! or, when that gateway's duty cycle forbids RX1, in RX2 (LoRaWAN network servers such as The
//! Things Stack and ChirpStack pick the downlink gateway by uplink SNR the same way).

use super::gateway::GatewayReport;
use crate::lora::{
    snr_db, tracking_ack_limits, AckLimits, AdrMode, AdrNetwork, AdrParams, Channel, ChannelAccess,
    InterferenceModel, LinkAdrReq, UplinkFrame, UplinkReport,
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

    /// ADR for drone `drone`'s received `frame` at `rssi_dbm` (the best gateway's), whose payload
    /// reports `speed_mps`: whether the server answers with a downlink (it must when asked by
    /// `ADRACKReq`, and does when it has a command), and the command.
    pub(crate) fn adr_hears(
        &mut self,
        drone: usize,
        frame: &UplinkFrame,
        rssi_dbm: f64,
        speed_mps: f64,
    ) -> (bool, Option<LinkAdrReq>) {
        let Some(Some(algorithm)) = self.adr.get_mut(drone) else {
            return (false, None);
        };
        let command = algorithm.on_uplink(&UplinkReport {
            fcnt: frame.fcnt,
            dr: frame.dr,
            power_reduction_db: frame.power_reduction_db,
            rssi_dbm,
            snr_db: snr_db(rssi_dbm, frame.dr.bw()),
            adr_ack_req: frame.adr_ack_req,
            speed_mps,
        });
        (command.is_some() || frame.adr_ack_req, command)
    }
}
