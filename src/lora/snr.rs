//! Signal-to-noise ratio at the gateway, as a network server's ADR sees it.
//!
//! Reception itself is decided by the gateway sensitivities of [`Channel`](super::Channel). The
//! ADR algorithms reason in SNR against the demodulation floors, as LoRaWAN network servers do;
//! with the noise figure below the floors sit 5.5 dB above those sensitivities, the same offset
//! the ns-3 `lorawan` module has between its `AdrComponent` and its gateway PHY.

use super::{Bandwidth, SpreadingFactor};
use crate::math;

/// Receiver noise figure, dB (ns-3 `lorawan` `AdrComponent::NF`; typical of the SX1301).
pub const NOISE_FIGURE_DB: f64 = 6.0;

/// Thermal noise density at 290 K, dBm/Hz.
const THERMAL_NOISE_DBM_PER_HZ: f64 = -174.0;

/// The lowest SNR at which each spreading factor SF7..SF12 demodulates, dB (Semtech SX1276
/// datasheet Table 13; the ns-3 `AdrComponent` threshold table).
const DEMODULATION_FLOOR_DB: [f64; 6] = [-7.5, -10.0, -12.5, -15.0, -17.5, -20.0];

/// Noise power in the channel, dBm: −174 dBm/Hz + 10 log10(BW / 1 Hz) + noise figure.
///
/// ```
/// use loratrack::{noise_floor_dbm, Bandwidth};
/// assert!((noise_floor_dbm(Bandwidth::Khz125) - (-117.03)).abs() < 0.01);
/// ```
pub fn noise_floor_dbm(bw: Bandwidth) -> f64 {
    THERMAL_NOISE_DBM_PER_HZ + 10.0 * math::log10(bw.hz()) + NOISE_FIGURE_DB
}

/// The SNR of a packet received at `rx_dbm` in bandwidth `bw`, dB.
pub fn snr_db(rx_dbm: f64, bw: Bandwidth) -> f64 {
    rx_dbm - noise_floor_dbm(bw)
}

/// The demodulation floor of a spreading factor, dB.
pub fn demodulation_floor_db(sf: SpreadingFactor) -> f64 {
    DEMODULATION_FLOOR_DB[usize::from(sf.get() - 7)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lora::Channel;

    #[test]
    fn doubling_the_bandwidth_costs_three_db_of_snr() {
        let d = snr_db(-120.0, Bandwidth::Khz125) - snr_db(-120.0, Bandwidth::Khz250);
        assert!((d - 10.0 * 2f64.log10()).abs() < 1e-12);
    }

    #[test]
    fn floors_sit_a_constant_offset_above_the_gateway_sensitivity() {
        for n in 7..=12 {
            let sf = SpreadingFactor::new(n).unwrap();
            let floor_dbm = noise_floor_dbm(Bandwidth::Khz125) + demodulation_floor_db(sf);
            let offset = floor_dbm - Channel::sensitivity_dbm(sf, Bandwidth::Khz125);
            assert!((offset - 5.47).abs() < 0.01, "SF{n}: {offset}");
        }
    }
}
