//! The end device's side of ADR (LoRaWAN 1.0.3 §4.3.1.1).

use super::{LinkAdrReq, MAX_POWER_REDUCTION_DB};
use crate::lora::DataRate;

/// Uplinks without any downlink after which the device asks for one (`ADRACKReq`; LoRaWAN
/// RP002-1.0.3 EU868 default).
pub const ADR_ACK_LIMIT: u32 = 64;
/// Further uplinks without an answer after which the device steps its power up to the maximum,
/// then its data rate down, once per this many (RP002-1.0.3 EU868 default).
pub const ADR_ACK_DELAY: u32 = 32;

/// When a device that hears no downlink asks for one and then backs off on its own, in uplinks
/// (LoRaWAN 1.1 `ADR_ACK_LIMIT`, `ADR_ACK_DELAY`; the network may set both, as powers of two, with
/// `ADRParamSetupReq`, §5.12).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AckLimits {
    /// Silent uplinks after which the device sets `ADRACKReq`.
    pub limit: u32,
    /// Further silent uplinks after which it regains the link: full power, then one data rate
    /// slower, once per this many.
    pub delay: u32,
}

impl AckLimits {
    /// The regional defaults, 64 and 32 (RP002-1.0.3 EU868): what [`LorawanAdr`] devices use.
    ///
    /// [`LorawanAdr`]: super::LorawanAdr
    pub const LORAWAN: AckLimits = AckLimits {
        limit: ADR_ACK_LIMIT,
        delay: ADR_ACK_DELAY,
    };

    /// How many data rates a device has backed off on its own after `silent` uplinks without a
    /// downlink (power first, so the first step counts as one here too).
    pub fn steps(self, silent: u32) -> u32 {
        match silent.checked_sub(self.limit) {
            Some(past) if past >= self.delay => past / self.delay,
            _ => 0,
        }
    }
}

/// The data rate, power and counters of an ADR-enabled device.
#[derive(Clone, Debug, PartialEq)]
pub struct AdrDevice {
    dr: DataRate,
    power_reduction_db: f64,
    fcnt: u32,
    ack_cnt: u32,
    limits: AckLimits,
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
    /// A device starting at `dr` with full power and the regional back-off
    /// ([`AckLimits::LORAWAN`]).
    pub fn new(dr: DataRate) -> Self {
        AdrDevice {
            dr,
            power_reduction_db: 0.0,
            fcnt: 0,
            ack_cnt: 0,
            limits: AckLimits::LORAWAN,
        }
    }

    /// The network set the back-off (LoRaWAN 1.1 `ADRParamSetupReq`).
    pub fn set_limits(&mut self, limits: AckLimits) {
        self.limits = limits;
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
            adr_ack_req: self.ack_cnt >= self.limits.limit,
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

    /// No downlink arrived after the last uplink: past `limit + delay` silent uplinks
    /// ([`AckLimits`]), and every `delay` after, regain the link: full power first, then one data
    /// rate slower.
    pub fn no_downlink(&mut self) {
        let silent = self.ack_cnt;
        if silent == 0 || self.limits.steps(silent) == self.limits.steps(silent - 1) {
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
    fn limits_the_network_set_shorten_the_back_off() {
        let mut d = AdrDevice::new(DataRate::DR6);
        d.set_limits(AckLimits { limit: 2, delay: 2 });
        let mut changes = Vec::new();
        for k in 1..=8 {
            let before = d.dr();
            let frame = d.uplink();
            assert_eq!(frame.adr_ack_req, k > 2, "uplink {k}");
            d.no_downlink();
            if d.dr() != before {
                changes.push(k);
            }
        }
        assert_eq!(changes, vec![4, 6, 8]);
        assert_eq!(AckLimits::LORAWAN.steps(95), 0);
        assert_eq!(AckLimits::LORAWAN.steps(96), 1);
        assert_eq!(AckLimits { limit: 2, delay: 2 }.steps(8), 3);
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
