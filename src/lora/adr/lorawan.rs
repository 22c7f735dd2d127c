//! Semtech's recommended network-server ADR ("LoRaWAN – simple rate adaptation recommended
//! algorithm", Semtech 2016), as the ns-3 `lorawan` `AdrComponent` runs it. The Things Stack runs
//! the same idea with other steps (2.5 dB a data rate, 2 dB a power index, a 15 dB margin) and
//! the same DR5 ceiling.

use super::{AdrNetwork, LinkAdrReq, UplinkReport, MAX_POWER_REDUCTION_DB, TX_POWER_STEP_DB};
use crate::lora::{demodulation_floor_db, DataRate};
use std::collections::VecDeque;

/// The fastest data rate LoRaWAN's ADR asks for: DR5, SF7 at 125 kHz.
///
/// The Things Stack's EU868 band caps ADR there (`MaxADRDataRateIndex`), as does the ns-3
/// `lorawan` `AdrComponent` (SF7 at 125 kHz); DR6 (SF7 / 250 kHz) is on one default channel only
/// (868.3 MHz), so a device ADR moved there would give up the other two. A device already above
/// it (one that starts at DR6) is left there: the server never lowers a data rate.
pub const LORAWAN_ADR_MAX_DR: DataRate = DataRate::DR5;

/// The LoRaWAN network server's ADR.
///
/// Once `history` uplinks at the device's current data rate and power have arrived, the margin
/// is `max SNR − demodulation floor − device margin`; each whole 3 dB of it first raises the data
/// rate (up to [`LORAWAN_ADR_MAX_DR`], DR5), then lowers the power by 3 dB; a negative margin
/// raises the power back. It never lowers the data rate: that is the device's own back-off
/// ([`AdrDevice::no_downlink`](super::AdrDevice::no_downlink)). The history restarts whenever the
/// device's data rate or power changes, since older SNRs describe other settings.
#[derive(Clone, Debug)]
pub struct LorawanAdr {
    margin_db: f64,
    history: usize,
    snrs: VecDeque<f64>,
    settings: Option<(DataRate, f64)>,
}

impl LorawanAdr {
    /// With a device margin (dB) and a history length (uplinks, at least 1).
    pub fn new(margin_db: f64, history: usize) -> Self {
        LorawanAdr {
            margin_db,
            history: history.max(1),
            snrs: VecDeque::new(),
            settings: None,
        }
    }
}

impl AdrNetwork for LorawanAdr {
    fn on_uplink(&mut self, up: &UplinkReport) -> Option<LinkAdrReq> {
        let now = (up.dr, up.power_reduction_db);
        if self.settings != Some(now) {
            self.settings = Some(now);
            self.snrs.clear();
        }
        self.snrs.push_back(up.snr_db);
        if self.snrs.len() > self.history {
            self.snrs.pop_front();
        }
        if self.snrs.len() < self.history {
            return None;
        }
        let best = self.snrs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let margin = best - demodulation_floor_db(up.dr.sf()) - self.margin_db;
        let mut steps = (margin / TX_POWER_STEP_DB).floor() as i64;
        let (mut dr, mut reduction) = now;
        while steps > 0 {
            if let Some(faster) = dr.faster().filter(|&f| f <= LORAWAN_ADR_MAX_DR) {
                dr = faster;
            } else if reduction + TX_POWER_STEP_DB <= MAX_POWER_REDUCTION_DB {
                reduction += TX_POWER_STEP_DB;
            } else {
                break;
            }
            steps -= 1;
        }
        while steps < 0 && reduction > 0.0 {
            reduction = (reduction - TX_POWER_STEP_DB).max(0.0);
            steps += 1;
        }
        (dr, reduction).ne(&now).then_some(LinkAdrReq {
            dr,
            power_reduction_db: reduction,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(fcnt: u32, dr: DataRate, reduction: f64, snr: f64) -> UplinkReport {
        UplinkReport {
            fcnt,
            dr,
            power_reduction_db: reduction,
            rssi_dbm: snr - 117.0,
            snr_db: snr,
            adr_ack_req: false,
            speed_mps: 0.0,
            crowd_loss: [0.0; 7],
        }
    }

    #[test]
    fn waits_for_a_full_history_then_spends_the_margin_on_rate_first() {
        let mut adr = LorawanAdr::new(10.0, 4);
        let dr0 = DataRate::DR0;
        // SF12 floor −20 dB: SNR 2 → margin 12 → 4 steps → DR4.
        for k in 0..3 {
            assert_eq!(adr.on_uplink(&report(k, dr0, 0.0, 2.0)), None);
        }
        let cmd = adr.on_uplink(&report(3, dr0, 0.0, 2.0)).unwrap();
        assert_eq!((cmd.dr.index(), cmd.power_reduction_db), (4, 0.0));
    }

    #[test]
    fn margin_beyond_the_fastest_rate_lowers_the_power() {
        let mut adr = LorawanAdr::new(10.0, 1);
        // DR6 floor −7.5: SNR 10 → margin 7.5 → 2 steps, both into power.
        let cmd = adr.on_uplink(&report(0, DataRate::DR6, 0.0, 10.0)).unwrap();
        assert_eq!((cmd.dr, cmd.power_reduction_db), (DataRate::DR6, 6.0));
    }

    #[test]
    fn never_asks_for_dr6_however_large_the_margin() {
        let mut adr = LorawanAdr::new(10.0, 1);
        // DR4 (SF8, floor −10): SNR 11 → margin 11 → 3 steps: one to DR5, two into power.
        let cmd = adr
            .on_uplink(&report(0, DataRate::new(4).unwrap(), 0.0, 11.0))
            .unwrap();
        assert_eq!((cmd.dr, cmd.power_reduction_db), (DataRate::DR5, 6.0));
        let mut adr = LorawanAdr::new(10.0, 1);
        let cmd = adr.on_uplink(&report(0, DataRate::DR5, 0.0, 20.0)).unwrap();
        assert_eq!((cmd.dr, cmd.power_reduction_db), (DataRate::DR5, 12.0));
    }

    #[test]
    fn a_negative_margin_restores_power_but_never_slows_the_rate() {
        let mut adr = LorawanAdr::new(10.0, 1);
        let cmd = adr
            .on_uplink(&report(0, DataRate::DR5, 9.0, -30.0))
            .unwrap();
        assert_eq!((cmd.dr, cmd.power_reduction_db), (DataRate::DR5, 0.0));
        assert_eq!(adr.on_uplink(&report(1, DataRate::DR5, 0.0, -30.0)), None);
    }
}
