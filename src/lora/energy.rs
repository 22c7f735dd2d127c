//! The drone radio's charge: transmit current by transmit power, receive windows, sleep.
//!
//! Currents of the Semtech SX1276 (SX1276/77/78/79 datasheet, rev. 7, May 2020, §2.5.1 "Power
//! Consumption", band 1 at 868 MHz): transmit 20 mA at +7 dBm and 29 mA at +13 dBm (RFO pin),
//! 87 mA at +17 dBm and 120 mA at +20 dBm (PA_BOOST), interpolated linearly in dBm between them
//! and held beyond; receive 11.5 mA at 125 kHz and 12.4 mA at 500 kHz (LoRa, LnaBoost on); sleep
//! 0.2 µA. Only the radio is counted: not the flight controller, not the sensors.
//!
//! A LoRaWAN class A device opens two receive windows after every uplink (LoRaWAN 1.0.3 §3.3):
//! RX1 one second after the uplink ends at the uplink's data rate, RX2 two seconds after it at
//! SF12/125 kHz on 869.525 MHz, the second only when nothing came in the first. An empty window
//! stays open for [`RX_WINDOW_SYMBOLS`] symbols (the time to detect a preamble); a window with a
//! downlink stays open for the downlink's time on air. Raw LoRa (no LoRaWAN overhead, the
//! paper's Table II) opens no window.

use super::{Bandwidth, SpreadingFactor};

/// (transmit power dBm, supply current mA) from the SX1276 datasheet, ascending.
pub const SX1276_TX_CURRENT_MA: [(f64, f64); 4] =
    [(7.0, 20.0), (13.0, 29.0), (17.0, 87.0), (20.0, 120.0)];
/// SX1276 receive current at 125 kHz, mA.
pub const SX1276_RX_CURRENT_125_MA: f64 = 11.5;
/// SX1276 receive current at 500 kHz, mA.
pub const SX1276_RX_CURRENT_500_MA: f64 = 12.4;
/// SX1276 sleep current, mA (0.2 µA).
pub const SX1276_SLEEP_CURRENT_MA: f64 = 0.0002;
/// Symbols an empty receive window stays open: LoRaMac-node's minimum receive-window timeout.
pub const RX_WINDOW_SYMBOLS: f64 = 6.0;

/// Supply current while transmitting at `power_dbm`, mA.
///
/// ```
/// use loratrack::tx_current_ma;
/// assert_eq!(tx_current_ma(13.0), 29.0);
/// assert!((tx_current_ma(14.0) - 43.5).abs() < 1e-12);
/// assert_eq!(tx_current_ma(0.0), 20.0);
/// ```
pub fn tx_current_ma(power_dbm: f64) -> f64 {
    let t = &SX1276_TX_CURRENT_MA;
    if power_dbm <= t[0].0 {
        return t[0].1;
    }
    for w in t.windows(2) {
        let ((p0, i0), (p1, i1)) = (w[0], w[1]);
        if power_dbm <= p1 {
            return i0 + (i1 - i0) * (power_dbm - p0) / (p1 - p0);
        }
    }
    t[t.len() - 1].1
}

/// Supply current while receiving at `bw`, mA (linear in bandwidth between the datasheet's
/// 125 and 500 kHz figures).
pub fn rx_current_ma(bw: Bandwidth) -> f64 {
    let f = (bw.khz() - 125.0) / 375.0;
    SX1276_RX_CURRENT_125_MA + f * (SX1276_RX_CURRENT_500_MA - SX1276_RX_CURRENT_125_MA)
}

/// How long an empty receive window at `sf`, `bw` stays open, s.
pub fn empty_window_s(sf: SpreadingFactor, bw: Bandwidth) -> f64 {
    RX_WINDOW_SYMBOLS * f64::from(1u32 << sf.get()) / bw.hz()
}

/// One uplink's radio activity, for its charge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UplinkActivity {
    /// Transmit power, dBm.
    pub tx_power_dbm: f64,
    /// Time on air, s.
    pub time_on_air: f64,
    /// Seconds with the receiver on, and at which bandwidth, for each window opened.
    pub windows: [(f64, Bandwidth); 2],
}

impl UplinkActivity {
    /// Charge of the uplink and its windows, mC (mA·s).
    pub fn charge_mc(&self) -> f64 {
        let rx: f64 = self
            .windows
            .iter()
            .map(|&(s, bw)| s * rx_current_ma(bw))
            .sum();
        tx_current_ma(self.tx_power_dbm) * self.time_on_air + rx
    }

    /// Seconds the radio is not asleep.
    pub fn active_s(&self) -> f64 {
        self.time_on_air + self.windows.iter().map(|w| w.0).sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_power_costs_more_current() {
        let mut last = 0.0;
        for p in -5..=25 {
            let i = tx_current_ma(f64::from(p));
            assert!(i >= last);
            last = i;
        }
        assert_eq!(tx_current_ma(20.0), 120.0);
        assert_eq!(tx_current_ma(30.0), 120.0);
    }

    #[test]
    fn receive_current_follows_the_datasheet_at_its_bandwidths() {
        assert_eq!(rx_current_ma(Bandwidth::Khz125), 11.5);
        assert!((rx_current_ma(Bandwidth::Khz500) - 12.4).abs() < 1e-12);
    }

    #[test]
    fn an_empty_sf12_window_lasts_six_symbols() {
        let sf12 = SpreadingFactor::new(12).unwrap();
        assert!((empty_window_s(sf12, Bandwidth::Khz125) - 6.0 * 0.032768).abs() < 1e-12);
    }
}
