//! The end device's side of ADR (LoRaWAN 1.0.3 §4.3.1.1).

use super::{LinkAdrReq, MAX_POWER_REDUCTION_DB};
use crate::lora::DataRate;

/// Uplinks without any downlink after which the device asks for one (`ADRACKReq`; LoRaWAN
/// RP002-1.0.3 EU868 default).
pub const ADR_ACK_LIMIT: u32 = 64;
/// Further uplinks without an answer after which the device steps its power up to the maximum,
/// then its data rate down, once per this many (RP002-1.0.3 EU868 default).
pub const ADR_ACK_DELAY: u32 = 32;

/// The data rate, power and counters of an ADR-enabled device.
#[derive(Clone, Debug, PartialEq)]
pub struct AdrDevice {
    dr: DataRate,
    power_reduction_db: f64,
    fcnt: u32,
    ack_cnt: u32,
}

/// What the device puts on air for one uplink.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UplinkFrame {
    /// Frame counter.
    pub fcnt: u32,
    /// Data rate.
    pub dr: DataRate,
    /// Power reduction below the maximum, dB.
    pub power_reduction_db: f64,
    /// The `ADRACKReq` bit: the network must answer this uplink with a downlink.
    pub adr_ack_req: bool,
}

impl AdrDevice {
    /// A device starting at `dr` with full power.
    pub fn new(dr: DataRate) -> Self {
        AdrDevice {
            dr,
            power_reduction_db: 0.0,
            fcnt: 0,
            ack_cnt: 0,
        }
    }

    /// The current data rate.
    pub fn dr(&self) -> DataRate {
        self.dr
    }

    /// The current power reduction, dB.
    pub fn power_reduction_db(&self) -> f64 {
        self.power_reduction_db
    }

    /// The next uplink's frame; counts it.
    pub fn uplink(&mut self) -> UplinkFrame {
        let frame = UplinkFrame {
            fcnt: self.fcnt,
            dr: self.dr,
            power_reduction_db: self.power_reduction_db,
            adr_ack_req: self.ack_cnt >= ADR_ACK_LIMIT,
        };
        self.fcnt = self.fcnt.wrapping_add(1);
        self.ack_cnt = self.ack_cnt.saturating_add(1);
        frame
    }

    /// A downlink arrived after the last uplink, with or without a command: the link works, the
    /// counter restarts, and a command applies from the next uplink.
    pub fn downlink(&mut self, command: Option<LinkAdrReq>) {
        self.ack_cnt = 0;
        if let Some(c) = command {
            self.dr = c.dr;
            self.power_reduction_db = c.power_reduction_db.clamp(0.0, MAX_POWER_REDUCTION_DB);
        }
    }

    /// No downlink arrived after the last uplink: past `ADR_ACK_LIMIT + ADR_ACK_DELAY` silent
    /// uplinks, and every `ADR_ACK_DELAY` after, regain the link: full power first, then one data
    /// rate slower.
    pub fn no_downlink(&mut self) {
        let Some(past) = self.ack_cnt.checked_sub(ADR_ACK_LIMIT) else {
            return;
        };
        if past == 0 || past % ADR_ACK_DELAY != 0 {
            return;
        }
        if self.power_reduction_db > 0.0 {
            self.power_reduction_db = 0.0;
        } else if let Some(slower) = self.dr.slower() {
            self.dr = slower;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_silent_link_steps_the_data_rate_down_every_ack_delay() {
        let mut d = AdrDevice::new(DataRate::DR6);
        let mut changes = Vec::new();
        for k in 1..=(ADR_ACK_LIMIT + 3 * ADR_ACK_DELAY) {
            let before = d.dr();
            d.uplink();
            d.no_downlink();
            if d.dr() != before {
                changes.push(k);
            }
        }
        let first = ADR_ACK_LIMIT + ADR_ACK_DELAY;
        assert_eq!(
            changes,
            vec![first, first + ADR_ACK_DELAY, first + 2 * ADR_ACK_DELAY]
        );
        assert_eq!(d.dr().index(), 3);
    }

    #[test]
    fn full_power_comes_back_before_a_slower_rate() {
        let mut d = AdrDevice::new(DataRate::DR6);
        d.downlink(Some(LinkAdrReq {
            dr: DataRate::DR6,
            power_reduction_db: 6.0,
        }));
        for _ in 0..(ADR_ACK_LIMIT + ADR_ACK_DELAY) {
            d.uplink();
            d.no_downlink();
        }
        assert_eq!((d.dr(), d.power_reduction_db()), (DataRate::DR6, 0.0));
    }

    #[test]
    fn ack_req_is_set_from_the_limit_and_cleared_by_any_downlink() {
        let mut d = AdrDevice::new(DataRate::DR5);
        for _ in 0..ADR_ACK_LIMIT {
            assert!(!d.uplink().adr_ack_req);
            d.no_downlink();
        }
        assert!(d.uplink().adr_ack_req);
        d.downlink(None);
        assert!(!d.uplink().adr_ack_req);
        assert_eq!(d.dr(), DataRate::DR5);
    }
}
