//! A drone's radio over a run: a fixed data rate (the paper), or one an ADR device moves, with
//! the time on air and duty-cycle interval of each.

use super::SimError;
use crate::lora::{
    min_interval, time_on_air, AckLimits, AdrDevice, AdrMode, AdrNetwork, AdrParams, Bandwidth,
    ChannelParams, DataRate, LinkAdrReq, LoraParams, LorawanAdr, SpreadingFactor, TrackingAdr,
    UplinkFrame,
};
use crate::models::ModelKind;

/// Time on air and duty-cycle interval of one packet size at every EU868 data rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RateTable {
    /// Time on air per data rate, s.
    pub time_on_air: [f64; 7],
    /// Duty-cycle interval per data rate, s.
    pub interval: [f64; 7],
}

impl RateTable {
    /// The table for packets of `bytes` (payload + overhead) sent with `radio`'s coding rate
    /// and header settings under `duty_cycle`.
    pub fn new(radio: &LoraParams, bytes: usize, duty_cycle: f64) -> Result<Self, SimError> {
        let mut t = RateTable {
            time_on_air: [0.0; 7],
            interval: [0.0; 7],
        };
        for dr in DataRate::ALL {
            let k = usize::from(dr.index());
            let at = LoraParams {
                sf: dr.sf(),
                bw: dr.bw(),
                ..*radio
            };
            t.time_on_air[k] = time_on_air(&at, bytes)?.time_on_air;
            t.interval[k] = min_interval(t.time_on_air[k], duty_cycle)?;
        }
        Ok(t)
    }

    /// The network server's ADR algorithm for a device sending these packets over `channel`
    /// (its shadowing's spread and decorrelation inform the tracking-aware choice), whose
    /// back-off the server set to `limits`.
    pub fn network(
        &self,
        params: &AdrParams,
        channel: &ChannelParams,
        limits: AckLimits,
    ) -> Box<dyn AdrNetwork> {
        match params.mode {
            AdrMode::Lorawan => Box::new(LorawanAdr::new(params.margin_db, params.history)),
            _ => Box::new(
                TrackingAdr::new(
                    self.time_on_air,
                    self.interval,
                    channel.shadowing_sigma_db,
                    channel.decorrelation_distance,
                )
                .with_ack_limits(limits),
            ),
        }
    }
}

/// What one uplink goes out with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Spreading factor.
    pub sf: SpreadingFactor,
    /// Bandwidth.
    pub bw: Bandwidth,
    /// Time on air, s.
    pub time_on_air: f64,
    /// The duty-cycle interval at this data rate, s.
    pub interval: f64,
    /// Transmit power below the configured one, dB (ADR).
    pub power_reduction_db: f64,
    /// The ADR frame (counter, `ADRACKReq`), when ADR is on.
    pub adr: Option<UplinkFrame>,
    /// A smaller payload than the drone's model sends ([`LeanPayload`]); `None`: its own.
    ///
    /// [`LeanPayload`]: crate::LeanPayload
    pub payload: Option<ModelKind>,
}

/// A drone's radio: kept across the flights (episodes) of a run, as a drone that stays joined.
#[derive(Clone, Debug)]
pub struct DroneRadio {
    fixed: Frame,
    device: Option<(AdrDevice, RateTable)>,
    /// Coding rate and header settings, bytes per frame and duty cycle, for a shorter frame.
    params: LoraParams,
    bytes: usize,
    duty_cycle: f64,
}

impl DroneRadio {
    /// A radio at `radio`'s SF and bandwidth sending `bytes` under `duty_cycle`; with ADR on it
    /// starts there (which must be an EU868 data rate).
    pub fn new(
        radio: &LoraParams,
        bytes: usize,
        duty_cycle: f64,
        adr: AdrMode,
    ) -> Result<Self, SimError> {
        let toa = time_on_air(radio, bytes)?.time_on_air;
        let fixed = Frame {
            sf: radio.sf,
            bw: radio.bw,
            time_on_air: toa,
            interval: min_interval(toa, duty_cycle)?,
            power_reduction_db: 0.0,
            adr: None,
            payload: None,
        };
        let device = match adr {
            AdrMode::Off => None,
            _ => {
                let start = DataRate::of(radio.sf, radio.bw)
                    .ok_or(SimError::AdrStart(radio.sf.get(), radio.bw.khz()))?;
                Some((
                    AdrDevice::new(start),
                    RateTable::new(radio, bytes, duty_cycle)?,
                ))
            }
        };
        Ok(DroneRadio {
            fixed,
            device,
            params: *radio,
            bytes,
            duty_cycle,
        })
    }

    /// `frame` carrying `payload` instead of `own`'s payload: its time on air and duty-cycle
    /// interval at the frame's data rate with that many fewer bytes.
    pub fn with_payload(
        &self,
        frame: &Frame,
        own: ModelKind,
        payload: ModelKind,
    ) -> Result<Frame, SimError> {
        let at = LoraParams {
            sf: frame.sf,
            bw: frame.bw,
            ..self.params
        };
        let bytes = self.bytes + payload.payload_bytes() - own.payload_bytes();
        let time_on_air = time_on_air(&at, bytes)?.time_on_air;
        Ok(Frame {
            time_on_air,
            interval: min_interval(time_on_air, self.duty_cycle)?,
            payload: (payload != own).then_some(payload),
            ..*frame
        })
    }

    /// Whether an ADR device drives the data rate.
    pub fn adaptive(&self) -> bool {
        self.device.is_some()
    }

    /// The network set the ADR device's back-off (LoRaWAN 1.1 `ADRParamSetupReq`); no-op for a
    /// fixed rate.
    pub fn set_ack_limits(&mut self, limits: AckLimits) {
        if let Some((d, _)) = &mut self.device {
            d.set_limits(limits);
        }
    }

    /// The rates table (ADR only).
    pub fn rates(&self) -> Option<&RateTable> {
        self.device.as_ref().map(|(_, t)| t)
    }

    /// The frame the next uplink would go with now, without counting it.
    pub fn current(&self) -> Frame {
        match &self.device {
            None => self.fixed,
            Some((d, t)) => {
                let k = usize::from(d.dr().index());
                Frame {
                    sf: d.dr().sf(),
                    bw: d.dr().bw(),
                    time_on_air: t.time_on_air[k],
                    interval: t.interval[k],
                    power_reduction_db: d.power_reduction_db(),
                    adr: None,
                    payload: None,
                }
            }
        }
    }

    /// The next uplink's frame; the ADR device counts it.
    pub fn uplink(&mut self) -> Frame {
        let mut f = self.current();
        if let Some((d, _)) = &mut self.device {
            let frame = d.uplink();
            f.power_reduction_db = frame.power_reduction_db;
            f.adr = Some(frame);
        }
        f
    }

    /// The end of an uplink's exchange: a downlink reached the device (with `command`, if any),
    /// or none did.
    pub fn exchange_done(&mut self, heard: Option<Option<LinkAdrReq>>) {
        if let Some((d, _)) = &mut self.device {
            match heard {
                Some(command) => d.downlink(command),
                None => d.no_downlink(),
            }
        }
    }
}
