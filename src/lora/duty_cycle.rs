//! EU868 duty-cycle limits (ETSI EN 300 220-2 §7.2.3; LoRaWAN RP002 §2.4; SPEC §6).

use super::LoraError;
use serde::Serialize;

/// EU868 sub-bands with their duty-cycle limit. The limit is per sub-band: hopping among
/// 868.1/868.3/868.5 MHz (all in [`SubBand::G1`]) does not raise it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SubBand {
    /// 868.0–868.6 MHz, 1 % (the three default LoRaWAN channels).
    G1,
    /// 868.7–869.2 MHz, 0.1 %.
    G2,
    /// 869.4–869.65 MHz, 10 % (also used for the RX2 downlink).
    G3,
}

impl SubBand {
    /// The band's duty-cycle limit as a fraction.
    pub fn duty_cycle(self) -> f64 {
        match self {
            SubBand::G1 => 0.01,
            SubBand::G2 => 0.001,
            SubBand::G3 => 0.1,
        }
    }
    /// Band edges in MHz.
    pub fn range_mhz(self) -> (f64, f64) {
        match self {
            SubBand::G1 => (868.0, 868.6),
            SubBand::G2 => (868.7, 869.2),
            SubBand::G3 => (869.4, 869.65),
        }
    }
}

/// The Things Network's fair-use policy: at most 30 s of uplink airtime per device per day.
/// Shown as information; loratrack does not enforce it.
pub const TTN_FAIR_USE_SECONDS_PER_DAY: f64 = 30.0;

/// Minimum interval between transmissions (s) that keeps a device within `duty_cycle`:
/// the radio may be on air for at most that fraction of the time, so
/// `interval = time_on_air / duty_cycle`.
///
/// ```
/// use loratrack::min_interval;
/// assert!((min_interval(0.0412, 0.01).unwrap() - 4.12).abs() < 1e-12);
/// ```
pub fn min_interval(time_on_air: f64, duty_cycle: f64) -> Result<f64, LoraError> {
    if !(duty_cycle > 0.0 && duty_cycle <= 1.0) {
        return Err(LoraError::DutyCycle(duty_cycle));
    }
    Ok(time_on_air / duty_cycle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interval_is_airtime_over_duty_cycle() {
        assert!((min_interval(0.1, 0.01).unwrap() - 10.0).abs() < 1e-12);
        assert!((min_interval(0.1, SubBand::G3.duty_cycle()).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_impossible_duty_cycles() {
        assert!(min_interval(0.1, 0.0).is_err());
        assert!(min_interval(0.1, 1.5).is_err());
        assert!(min_interval(0.1, f64::NAN).is_err());
    }
}
