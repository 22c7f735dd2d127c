//! LoRa time on air (Semtech SX1276 datasheet §4.1.1.7; reference §6).

use super::LoraError;
use serde::{Deserialize, Serialize};

/// LoRaWAN MAC overhead in bytes: MHDR 1 + FHDR 7 + FPort 1 + MIC 4 (LoRaWAN 1.0.x §4).
pub const LORAWAN_OVERHEAD_BYTES: usize = 13;

/// Spreading factor 7..=12 (chips per symbol = 2^SF).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct SpreadingFactor(u8);

impl SpreadingFactor {
    /// Validates 7..=12.
    pub fn new(sf: i64) -> Result<Self, LoraError> {
        if (7..=12).contains(&sf) {
            Ok(SpreadingFactor(sf as u8))
        } else {
            Err(LoraError::SpreadingFactor(sf))
        }
    }
    /// The value, 7..=12.
    pub fn get(self) -> u8 {
        self.0
    }
}

/// Channel bandwidth: the three LoRa bandwidths used in EU868.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Bandwidth {
    /// 125 kHz
    Khz125,
    /// 250 kHz
    Khz250,
    /// 500 kHz
    Khz500,
}

impl Bandwidth {
    /// From kHz (125, 250 or 500).
    pub fn from_khz(khz: f64) -> Result<Self, LoraError> {
        [Bandwidth::Khz125, Bandwidth::Khz250, Bandwidth::Khz500]
            .into_iter()
            .find(|b| b.khz() == khz)
            .ok_or(LoraError::Bandwidth(khz))
    }
    /// Bandwidth in Hz.
    pub fn hz(self) -> f64 {
        self.khz() * 1e3
    }
    /// Bandwidth in kHz.
    pub fn khz(self) -> f64 {
        match self {
            Bandwidth::Khz125 => 125.0,
            Bandwidth::Khz250 => 250.0,
            Bandwidth::Khz500 => 500.0,
        }
    }
}

/// Coding rate 4/(4+n), n = 1..=4.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct CodingRate(u8);

impl CodingRate {
    /// Validates n = 1..=4 (4/5 .. 4/8).
    pub fn new(n: i64) -> Result<Self, LoraError> {
        if (1..=4).contains(&n) {
            Ok(CodingRate(n as u8))
        } else {
            Err(LoraError::CodingRate(n))
        }
    }
    /// n in 4/(4+n).
    pub fn get(self) -> u8 {
        self.0
    }
}

/// Low data rate optimisation: forced or automatic (on when a symbol lasts more than 16 ms, as
/// LoRaWAN mandates for SF11/SF12 at 125 kHz).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum LdroMode {
    /// On when T_sym > 16 ms.
    #[default]
    Auto,
    /// Always on.
    On,
    /// Always off.
    Off,
}

/// Everything that fixes a LoRa packet's time on air.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LoraParams {
    /// Spreading factor.
    pub sf: SpreadingFactor,
    /// Bandwidth.
    pub bw: Bandwidth,
    /// Coding rate.
    pub cr: CodingRate,
    /// Programmed preamble length in symbols (LoRaWAN: 8).
    pub preamble: u16,
    /// Implicit header (no PHY header). LoRaWAN uplinks use explicit headers.
    pub implicit_header: bool,
    /// Payload CRC present (LoRaWAN uplinks: on).
    pub crc: bool,
    /// Low data rate optimisation.
    pub ldro: LdroMode,
}

impl LoraParams {
    /// LoRaWAN defaults for a spreading factor and bandwidth: CR 4/5, 8 preamble symbols, explicit
    /// header, CRC on, LDRO automatic.
    pub fn new(sf: SpreadingFactor, bw: Bandwidth) -> Self {
        LoraParams {
            sf,
            bw,
            cr: CodingRate(1),
            preamble: 8,
            implicit_header: false,
            crc: true,
            ldro: LdroMode::Auto,
        }
    }

    /// LoRaWAN defaults (see [`LoraParams::new`]) from raw settings, validated: SF 7..12,
    /// bandwidth 125/250/500 kHz, coding rate index 1..4.
    pub fn from_settings(sf: i64, bw_khz: f64, cr: i64) -> Result<Self, LoraError> {
        let mut p = LoraParams::new(SpreadingFactor::new(sf)?, Bandwidth::from_khz(bw_khz)?);
        p.cr = CodingRate::new(cr)?;
        Ok(p)
    }

    /// Symbol duration T_sym = 2^SF / BW, seconds.
    pub fn symbol_time(&self) -> f64 {
        f64::from(1u32 << self.sf.0) / self.bw.hz()
    }

    /// Whether low data rate optimisation is in effect.
    pub fn low_data_rate_optimize(&self) -> bool {
        match self.ldro {
            LdroMode::On => true,
            LdroMode::Off => false,
            LdroMode::Auto => self.symbol_time() > 0.016,
        }
    }
}

/// Time on air of one packet, and how it was reached.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Airtime {
    /// Time on air, seconds.
    pub time_on_air: f64,
    /// Symbol duration, seconds.
    pub symbol_time: f64,
    /// Number of payload symbols (including the 8 fixed ones of the header block).
    pub payload_symbols: u32,
    /// Bytes in the PHY payload (application payload + overhead).
    pub phy_payload_bytes: usize,
    /// Whether low data rate optimisation was used.
    pub low_data_rate_optimize: bool,
}

/// Time on air of a packet with `phy_payload_bytes` bytes of PHY payload (reference §6):
///
/// ```text
/// T_sym      = 2^SF / BW
/// T_preamble = (n_preamble + 4.25) T_sym
/// n_payload  = 8 + max(ceil((8 PL - 4 SF + 28 + 16 CRC - 20 IH) / (4 (SF - 2 DE))) (CR + 4), 0)
/// ```
///
/// ```
/// use loratrack::{time_on_air, Bandwidth, LoraParams, SpreadingFactor};
/// let p = LoraParams::new(SpreadingFactor::new(7).unwrap(), Bandwidth::Khz125);
/// let t = time_on_air(&p, 14).unwrap();
/// assert!((t.time_on_air - 0.046336).abs() < 1e-9);
/// ```
pub fn time_on_air(p: &LoraParams, phy_payload_bytes: usize) -> Result<Airtime, LoraError> {
    if phy_payload_bytes > 255 {
        return Err(LoraError::PayloadTooLarge(phy_payload_bytes));
    }
    if p.preamble < 6 {
        return Err(LoraError::Preamble(i64::from(p.preamble)));
    }
    let sf = i64::from(p.sf.0);
    let de = i64::from(p.low_data_rate_optimize());
    let numerator = 8 * phy_payload_bytes as i64 - 4 * sf + 28 + 16 * i64::from(p.crc)
        - 20 * i64::from(p.implicit_header);
    let denominator = 4 * (sf - 2 * de);
    // Integer ceiling division: exact, unlike ceil() on a float quotient.
    let blocks = if numerator > 0 {
        (numerator + denominator - 1) / denominator
    } else {
        0
    };
    let payload_symbols = 8 + blocks * (i64::from(p.cr.0) + 4);
    let t_sym = p.symbol_time();
    let t_preamble = (f64::from(p.preamble) + 4.25) * t_sym;
    Ok(Airtime {
        time_on_air: t_preamble + payload_symbols as f64 * t_sym,
        symbol_time: t_sym,
        payload_symbols: payload_symbols as u32,
        phy_payload_bytes,
        low_data_rate_optimize: de == 1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(sf: i64, bw: f64) -> LoraParams {
        LoraParams::new(
            SpreadingFactor::new(sf).unwrap(),
            Bandwidth::from_khz(bw).unwrap(),
        )
    }

    #[test]
    fn independent_reference_values() {
        let cases = [
            (7, 125.0, 14, 0.046336),
            (7, 250.0, 14, 0.023168),
            (8, 125.0, 14, 0.082432),
            (11, 125.0, 14, 0.659456),
            (7, 125.0, 25, 0.061696),
        ];
        for (sf, bw, pl, expected) in cases {
            let t = time_on_air(&params(sf, bw), pl).unwrap().time_on_air;
            assert!((t - expected).abs() < 1e-9, "SF{sf}/{bw}/{pl}B: {t}");
        }
    }

    #[test]
    fn ldro_switches_on_automatically_only_for_long_symbols() {
        assert!(!params(10, 125.0).low_data_rate_optimize());
        assert!(params(11, 125.0).low_data_rate_optimize());
        assert!(params(12, 125.0).low_data_rate_optimize());
        assert!(!params(11, 250.0).low_data_rate_optimize());
        assert!(!params(12, 500.0).low_data_rate_optimize());
    }

    #[test]
    fn airtime_grows_with_sf_and_payload_and_shrinks_with_bandwidth() {
        let t = |sf, bw, pl| time_on_air(&params(sf, bw), pl).unwrap().time_on_air;
        for sf in 7..12 {
            assert!(t(sf + 1, 125.0, 20) > t(sf, 125.0, 20));
        }
        assert!(t(7, 250.0, 20) < t(7, 125.0, 20));
        assert!(t(7, 500.0, 20) < t(7, 250.0, 20));
        assert!(t(9, 125.0, 60) >= t(9, 125.0, 20));
    }

    #[test]
    fn rejects_what_lora_cannot_send() {
        assert_eq!(
            time_on_air(&params(7, 125.0), 256),
            Err(LoraError::PayloadTooLarge(256))
        );
        assert!(SpreadingFactor::new(6).is_err());
        assert!(SpreadingFactor::new(13).is_err());
        assert!(Bandwidth::from_khz(200.0).is_err());
        assert!(CodingRate::new(0).is_err());
    }
}
