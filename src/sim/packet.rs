//! One uplink of a drone's state, as the network saw it.

use crate::codec::SaturatedFields;
use crate::lora::{Bandwidth, DataRate, Outcome, SpreadingFactor};
use crate::models::ModelKind;

/// One transmission of the drone's state.
#[derive(Clone, Debug, PartialEq)]
pub struct Transmission {
    /// When the drone sent it (a sensor step), s.
    pub sent: f64,
    /// When it finished arriving (sent + time on air), s.
    pub arrival: f64,
    /// Whether at least one gateway received it (the network server then passes it to the
    /// station, once).
    pub received: bool,
    /// What became of it: [`Outcome::Received`] if any gateway received it, else the furthest
    /// any gateway got (collided after locking on, no demodulator, on air while the gateway sent
    /// a downlink, or below every sensitivity).
    pub outcome: Outcome,
    /// Which gateways received it (bit g for gateway g).
    pub heard_by: u32,
    /// The state the station decodes (quantised), padded to 9.
    pub state: [f64; 9],
    /// The fields of the drone's estimate that lay beyond the payload's ranges and were sent as
    /// their edge: `state` is not where the drone believed it was.
    pub saturated: SaturatedFields,
    /// 3D distance to the gateway that heard it best (the nearest when none did), m.
    pub distance: f64,
    /// The best received power over the gateways, including shadowing, dBm.
    pub rx_power_dbm: f64,
    /// Spreading factor it was sent with.
    pub sf: SpreadingFactor,
    /// Bandwidth it was sent with.
    pub bw: Bandwidth,
    /// Uplink channel index.
    pub channel: u8,
    /// Its time on air, s.
    pub time_on_air: f64,
    /// The duty-cycle interval at that data rate, s (what the station expects until the next).
    pub interval: f64,
    /// The smaller payload it carried instead of the model's own ([`LeanPayload`]); `None`:
    /// its own.
    ///
    /// [`LeanPayload`]: crate::LeanPayload
    pub payload: Option<ModelKind>,
    /// The radio's charge for this uplink and its receive windows, mC.
    pub charge_mc: f64,
    /// Seconds the radio was awake for it (on air and listening).
    pub active_s: f64,
}

impl Transmission {
    /// Its EU868 data rate, if the SF and bandwidth form one.
    pub fn data_rate(&self) -> Option<DataRate> {
        DataRate::of(self.sf, self.bw)
    }
}
