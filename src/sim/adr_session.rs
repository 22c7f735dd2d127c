//! One drone's ADR over a run: the device, the network's algorithm, and each data rate's time on
//! air and interval.

use super::{LinkSetup, SimError};
use crate::lora::{
    min_interval, time_on_air, AdrDevice, AdrMode, AdrNetwork, AdrParams, Channel, DataRate,
    LinkAdrReq, LoraParams, LorawanAdr, TrackingAdr, UplinkFrame, UplinkReport,
    GATEWAY_TX_POWER_DBM,
};

/// The ADR state of one drone: kept across the flights of a run, as a drone that stays joined to
/// the network between flights.
pub struct AdrSession {
    device: AdrDevice,
    network: Box<dyn AdrNetwork>,
    time_on_air: [f64; 7],
    interval: [f64; 7],
}

impl AdrSession {
    /// A session for `params` (`None` when ADR is off), starting at the data rate of `radio`,
    /// for packets of `bytes` (payload + overhead) under `duty_cycle`, over a channel with
    /// `shadowing_db` of shadowing.
    pub fn new(
        params: &AdrParams,
        radio: &LoraParams,
        bytes: usize,
        duty_cycle: f64,
        shadowing_db: f64,
    ) -> Result<Option<Self>, SimError> {
        if params.mode == AdrMode::Off {
            return Ok(None);
        }
        let start = DataRate::of(radio.sf, radio.bw)
            .ok_or(SimError::AdrStart(radio.sf.get(), radio.bw.khz()))?;
        let mut time_on_air_s = [0.0; 7];
        let mut interval = [0.0; 7];
        for dr in DataRate::ALL {
            let k = usize::from(dr.index());
            let at = LoraParams {
                sf: dr.sf(),
                bw: dr.bw(),
                ..*radio
            };
            time_on_air_s[k] = time_on_air(&at, bytes)?.time_on_air;
            interval[k] = min_interval(time_on_air_s[k], duty_cycle)?;
        }
        let network: Box<dyn AdrNetwork> = match params.mode {
            AdrMode::Lorawan => Box::new(LorawanAdr::new(params.margin_db, params.history)),
            _ => Box::new(TrackingAdr::new(time_on_air_s, interval, shadowing_db)),
        };
        Ok(Some(AdrSession {
            device: AdrDevice::new(start),
            network,
            time_on_air: time_on_air_s,
            interval,
        }))
    }

    /// The same session with another network algorithm (to compare a rule of one's own).
    pub fn with_network(self, network: Box<dyn AdrNetwork>) -> Self {
        AdrSession { network, ..self }
    }

    /// The device's current data rate.
    pub fn dr(&self) -> DataRate {
        self.device.dr()
    }

    /// `link` at the device's current data rate.
    pub fn link_now(&self, link: &LinkSetup) -> LinkSetup {
        let dr = self.dr();
        LinkSetup {
            sf: dr.sf(),
            bw: dr.bw(),
            time_on_air: self.time_on_air(dr),
            interval: self.interval(dr),
            ..link.clone()
        }
    }

    /// Time on air at `dr`, s.
    pub fn time_on_air(&self, dr: DataRate) -> f64 {
        self.time_on_air[usize::from(dr.index())]
    }

    /// The duty-cycle interval at `dr`, s.
    pub fn interval(&self, dr: DataRate) -> f64 {
        self.interval[usize::from(dr.index())]
    }

    /// The device puts its next uplink on air.
    pub fn uplink(&mut self) -> UplinkFrame {
        self.device.uplink()
    }

    /// The network hears `frame` at `rssi_dbm`: whether it answers with a downlink (it must
    /// when asked by `ADRACKReq`, and does when it has a command), and the command.
    pub fn network_hears(
        &mut self,
        frame: &UplinkFrame,
        rssi_dbm: f64,
    ) -> (bool, Option<LinkAdrReq>) {
        let bw = frame.dr.bw();
        let command = self.network.on_uplink(&UplinkReport {
            fcnt: frame.fcnt,
            dr: frame.dr,
            power_reduction_db: frame.power_reduction_db,
            rssi_dbm,
            snr_db: crate::lora::snr_db(rssi_dbm, bw),
        });
        (command.is_some() || frame.adr_ack_req, command)
    }

    /// Whether a downlink at `frame`'s data rate reaches the drone, with the channel's path loss
    /// at `distance_m` and shadowing `shadowing_db` (the reciprocal of the uplink's channel at
    /// the drone's position then).
    pub fn downlink_heard(
        channel: &Channel,
        frame: &UplinkFrame,
        distance_m: f64,
        shadowing_db: f64,
    ) -> bool {
        let rx = GATEWAY_TX_POWER_DBM - channel.path_loss_db(distance_m) + shadowing_db;
        rx >= Channel::sensitivity_dbm(frame.dr.sf(), frame.dr.bw())
    }

    /// The end of the uplink's exchange: a downlink reached the device (with `command`, if any),
    /// or none did.
    pub fn finish(&mut self, heard: Option<Option<LinkAdrReq>>) {
        match heard {
            Some(command) => self.device.downlink(command),
            None => self.device.no_downlink(),
        }
    }
}
