//! Regional plans: which LoRa data rates a region's uplinks may use, how large a payload each
//! carries, how long one uplink may stay on air (dwell time), what limits how often a device
//! sends (a duty cycle, or nothing), its uplink channels and its largest transmit power.
//!
//! Source: LoRa Alliance, *RP002-1.0.4 LoRaWAN Regional Parameters* (2022): §2.3 EU863-870
//! (Tables 14 data rates, 17 maximum payload size), §2.5 US902-928 (Tables 31, 35), §2.7 AU915-928
//! (Tables 48, 52, UplinkDwellTime = 1), §2.9 AS923 (Tables 67, 71, UplinkDwellTime = 1), §2.11
//! IN865-867 (Tables 83, 86). Payload limits are N, the largest application payload (FRMPayload)
//! without FOpts. Dwell time: FCC 47 CFR §15.247 (400 ms per channel), ARIB STD-T108 (AS923).
//! `docs/reference.md` §14.

use super::Bandwidth;
use serde::{Deserialize, Serialize};

/// A LoRaWAN regional plan (`--region`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum Region {
    /// Europe, 863–870 MHz: duty cycles per sub-band (the paper's plan).
    #[default]
    Eu868,
    /// North America, 902–928 MHz: no duty cycle, 400 ms dwell time, hopping over 8 channels
    /// of a sub-band.
    Us915,
    /// Australia, 915–928 MHz: as US915 with SF11 and SF12 (DR0, DR1) barred by the dwell time.
    Au915,
    /// Asia, 923 MHz: 400 ms dwell time and a 1 % duty cycle where listen-before-talk is not
    /// used.
    As923,
    /// India, 865–867 MHz: no duty cycle, no dwell time.
    In865,
}

/// One uplink data rate of a plan: its index, spreading factor, bandwidth and largest
/// application payload (`None`: not usable under the dwell time).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct PlanRate {
    /// DR index in the plan.
    pub dr: u8,
    /// Spreading factor.
    pub sf: u8,
    /// Bandwidth.
    #[serde(serialize_with = "khz")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number"))]
    pub bw: Bandwidth,
    /// Largest FRMPayload, bytes; `None` (`null`) where the plan bars the rate.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub max_payload: Option<usize>,
}

fn khz<S: serde::Serializer>(bw: &Bandwidth, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(bw.khz())
}

/// A plan as the page and `limits()` show it: every number [`Region`]'s methods give.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Plan {
    /// The CLI/JS name.
    pub region: Region,
    /// The name people write.
    pub label: &'static str,
    /// Uplink data rates, slowest first.
    pub rates: Vec<PlanRate>,
    /// Longest time on air of one uplink, s (`null`: no limit).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub dwell_time: Option<f64>,
    /// Duty cycle of the uplink channels (`null`: none; the sending interval is a setting).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub duty_cycle: Option<f64>,
    /// Uplink channels hopped over.
    pub channels: u8,
    /// Largest transmit power (EIRP), dBm.
    pub max_eirp_dbm: f64,
    /// Whether LoRa outside the data rates is allowed (EU868).
    pub raw_lora: bool,
}

const fn rate(dr: u8, sf: u8, bw: Bandwidth, max_payload: Option<usize>) -> PlanRate {
    PlanRate {
        dr,
        sf,
        bw,
        max_payload,
    }
}

use Bandwidth::{Khz125 as K125, Khz250 as K250, Khz500 as K500};

const EU868: &[PlanRate] = &[
    rate(0, 12, K125, Some(51)),
    rate(1, 11, K125, Some(51)),
    rate(2, 10, K125, Some(51)),
    rate(3, 9, K125, Some(115)),
    rate(4, 8, K125, Some(242)),
    rate(5, 7, K125, Some(242)),
    rate(6, 7, K250, Some(242)),
];
const US915: &[PlanRate] = &[
    rate(0, 10, K125, Some(11)),
    rate(1, 9, K125, Some(53)),
    rate(2, 8, K125, Some(125)),
    rate(3, 7, K125, Some(242)),
    rate(4, 8, K500, Some(242)),
];
/// AU915 and AS923 with UplinkDwellTime = 1 (their defaults).
const DWELL_LIMITED: &[PlanRate] = &[
    rate(0, 12, K125, None),
    rate(1, 11, K125, None),
    rate(2, 10, K125, Some(11)),
    rate(3, 9, K125, Some(53)),
    rate(4, 8, K125, Some(125)),
    rate(5, 7, K125, Some(242)),
];
const AU915_500: PlanRate = rate(6, 8, K500, Some(242));
const AS923_250: PlanRate = rate(6, 7, K250, Some(242));

/// Why a plan refuses a packet.
#[derive(Clone, Debug, PartialEq)]
pub enum RegionError {
    /// The plan has no uplink data rate at this SF and bandwidth.
    NoDataRate {
        /// The plan.
        region: Region,
        /// Spreading factor.
        sf: u8,
        /// Bandwidth, kHz.
        bw_khz: f64,
    },
    /// The plan bars this data rate (the dwell time leaves no room for it).
    Barred {
        /// The plan.
        region: Region,
        /// The data rate.
        rate: PlanRate,
    },
    /// The payload is larger than the data rate carries.
    PayloadTooLarge {
        /// The plan.
        region: Region,
        /// The data rate.
        rate: PlanRate,
        /// The payload, bytes.
        payload: usize,
        /// The limit, bytes.
        limit: usize,
    },
    /// The frame stays on air longer than the dwell time.
    OverDwellTime {
        /// The plan.
        region: Region,
        /// The data rate.
        rate: PlanRate,
        /// Its time on air, s.
        time_on_air: f64,
        /// The dwell time, s.
        dwell: f64,
    },
}

impl core::fmt::Display for RegionError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RegionError::NoDataRate { region, sf, bw_khz } => write!(
                f,
                "{} has no uplink data rate at SF{sf}/{bw_khz} kHz (it offers {})",
                region.label(),
                region.rate_list()
            ),
            RegionError::Barred { region, rate } => write!(
                f,
                "{} bars {} (SF{}/{} kHz) for uplinks: its 400 ms dwell time leaves no room for it",
                region.label(),
                rate_name(rate),
                rate.sf,
                rate.bw.khz()
            ),
            RegionError::PayloadTooLarge {
                region,
                rate,
                payload,
                limit,
            } => write!(
                f,
                "a {payload}-byte payload is over {}'s limit of {limit} bytes at {} (SF{}/{} kHz)",
                region.label(),
                rate_name(rate),
                rate.sf,
                rate.bw.khz()
            ),
            RegionError::OverDwellTime {
                region,
                rate,
                time_on_air,
                dwell,
            } => write!(
                f,
                "the frame takes {:.1} ms on air at {} {} (SF{}/{} kHz): over the {:.0} ms dwell time",
                time_on_air * 1e3,
                region.label(),
                rate_name(rate),
                rate.sf,
                rate.bw.khz(),
                dwell * 1e3
            ),
        }
    }
}

impl std::error::Error for RegionError {}

fn rate_name(rate: &PlanRate) -> String {
    format!("DR{}", rate.dr)
}

impl Region {
    /// Every plan, in the order the CLI lists them.
    pub const ALL: [Region; 5] = [
        Region::Eu868,
        Region::Us915,
        Region::Au915,
        Region::As923,
        Region::In865,
    ];

    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            Region::Eu868 => "eu868",
            Region::Us915 => "us915",
            Region::Au915 => "au915",
            Region::As923 => "as923",
            Region::In865 => "in865",
        }
    }

    /// The name people write: `EU868`.
    pub fn label(self) -> &'static str {
        match self {
            Region::Eu868 => "EU868",
            Region::Us915 => "US915",
            Region::Au915 => "AU915",
            Region::As923 => "AS923",
            Region::In865 => "IN865",
        }
    }

    /// Everything about the plan, as one value.
    pub fn plan(self) -> Plan {
        Plan {
            region: self,
            label: self.label(),
            rates: self.rates(),
            dwell_time: self.dwell_time(),
            duty_cycle: self.duty_cycle(),
            channels: self.channels(),
            max_eirp_dbm: self.max_eirp_dbm(),
            raw_lora: self.allows_raw_lora(),
        }
    }

    /// The uplink LoRa data rates, slowest first.
    pub fn rates(self) -> Vec<PlanRate> {
        match self {
            Region::Eu868 => EU868.to_vec(),
            Region::Us915 => US915.to_vec(),
            Region::Au915 => [DWELL_LIMITED, &[AU915_500]].concat(),
            Region::As923 => [DWELL_LIMITED, &[AS923_250]].concat(),
            // IN865's DR0–DR5 and their payloads are EU868's (Tables 83, 86); it has no DR6.
            Region::In865 => EU868[..6].to_vec(),
        }
    }

    /// The data rate at `sf` and `bw`, if the plan has one (barred ones included).
    pub fn rate(self, sf: u8, bw: Bandwidth) -> Option<PlanRate> {
        self.rates().into_iter().find(|r| r.sf == sf && r.bw == bw)
    }

    fn rate_list(self) -> String {
        self.rates()
            .iter()
            .filter(|r| r.max_payload.is_some())
            .map(|r| format!("DR{} SF{}/{}", r.dr, r.sf, r.bw.khz()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The longest an uplink may stay on air, s, where the plan limits it.
    pub fn dwell_time(self) -> Option<f64> {
        match self {
            Region::Us915 | Region::Au915 | Region::As923 => Some(0.4),
            Region::Eu868 | Region::In865 => None,
        }
    }

    /// The duty cycle of the uplink channels, where the plan has one (EU868's 868.0–868.6 MHz
    /// sub-band, AS923 without listen-before-talk); `None`: the sending interval is a setting.
    pub fn duty_cycle(self) -> Option<f64> {
        match self {
            Region::Eu868 | Region::As923 => Some(0.01),
            Region::Us915 | Region::Au915 | Region::In865 => None,
        }
    }

    /// Uplink channels a device hops over: EU868 and IN865 three default channels, US915 and
    /// AU915 the eight 125 kHz channels of one sub-band, AS923 its two default channels.
    pub fn channels(self) -> u8 {
        match self {
            Region::Eu868 | Region::In865 => 3,
            Region::Us915 | Region::Au915 => 8,
            Region::As923 => 2,
        }
    }

    /// The largest transmit power (EIRP), dBm.
    pub fn max_eirp_dbm(self) -> f64 {
        match self {
            Region::Eu868 | Region::As923 => 16.0,
            Region::Us915 | Region::Au915 | Region::In865 => 30.0,
        }
    }

    /// Whether LoRa outside the plan's data rates is allowed: in EU868 ETSI EN 300 220 limits
    /// the duty cycle, not the modulation, so raw LoRa at any SF and bandwidth that fits the
    /// sub-band may be sent (the paper's SF8 at 250 kHz is no LoRaWAN data rate).
    pub fn allows_raw_lora(self) -> bool {
        self == Region::Eu868
    }

    /// The data rate a frame of `payload` application bytes on air for `time_on_air` s uses at
    /// `sf`/`bw` (`None`: raw LoRa outside the data rates, where [`allows_raw_lora`]), or why
    /// the plan refuses it.
    ///
    /// [`allows_raw_lora`]: Region::allows_raw_lora
    pub fn check(
        self,
        sf: u8,
        bw: Bandwidth,
        payload: usize,
        time_on_air: f64,
    ) -> Result<Option<PlanRate>, RegionError> {
        let Some(rate) = self.rate(sf, bw) else {
            if self.allows_raw_lora() {
                return Ok(None);
            }
            return Err(RegionError::NoDataRate {
                region: self,
                sf,
                bw_khz: bw.khz(),
            });
        };
        let limit = rate
            .max_payload
            .ok_or(RegionError::Barred { region: self, rate })?;
        if let Some(dwell) = self.dwell_time() {
            if time_on_air > dwell {
                return Err(RegionError::OverDwellTime {
                    region: self,
                    rate,
                    time_on_air,
                    dwell,
                });
            }
        }
        if payload > limit {
            return Err(RegionError::PayloadTooLarge {
                region: self,
                rate,
                payload,
                limit,
            });
        }
        Ok(Some(rate))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn us915_offers_sf7_to_sf10_at_125_khz_and_sf8_at_500() {
        let us = Region::Us915;
        assert_eq!(us.rate(10, K125).unwrap().dr, 0);
        assert_eq!(us.rate(9, K125).unwrap().dr, 1);
        assert_eq!(us.rate(8, K500).unwrap().dr, 4);
        assert!(us.rate(11, K125).is_none());
        assert!(us.rate(12, K125).is_none());
        let e = us.check(12, K125, 12, 1.0).unwrap_err().to_string();
        assert!(
            e.contains("US915 has no uplink data rate at SF12/125 kHz"),
            "{e}"
        );
    }

    #[test]
    fn eu868_allows_raw_lora_outside_its_data_rates_as_the_paper_sends() {
        assert_eq!(Region::Eu868.check(8, K250, 12, 0.03), Ok(None));
        assert!(Region::In865.check(8, K250, 12, 0.03).is_err());
    }

    #[test]
    fn eu868_matches_the_data_rates_the_simulation_always_used() {
        for r in Region::Eu868.rates() {
            let dr = super::super::DataRate::new(r.dr).unwrap();
            assert_eq!((dr.sf().get(), dr.bw()), (r.sf, r.bw));
        }
        assert_eq!(Region::Eu868.dwell_time(), None);
        assert_eq!(Region::Eu868.duty_cycle(), Some(0.01));
    }

    fn airtime(sf: i64, payload: usize) -> f64 {
        let radio = super::super::LoraParams::from_settings(sf, 125.0, 1).unwrap();
        super::super::time_on_air(&radio, payload + 13)
            .unwrap()
            .time_on_air
    }

    #[test]
    fn a_frame_over_the_dwell_time_is_refused_with_the_reason() {
        // 3D-CTRA's 12 bytes with LoRaWAN's 13 at US915 DR0 do not fit; DR's 9 and CTRA+'s 11 do.
        let e = Region::Us915
            .check(10, K125, 12, airtime(10, 12))
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "the frame takes 411.6 ms on air at US915 DR0 (SF10/125 kHz): over the 400 ms dwell time"
        );
        assert!(Region::Us915.check(10, K125, 11, airtime(10, 11)).is_ok());
        assert!(Region::Us915.check(10, K125, 9, airtime(10, 9)).is_ok());
    }

    #[test]
    fn dwell_limited_plans_bar_sf11_and_sf12() {
        for region in [Region::Au915, Region::As923] {
            assert!(matches!(
                region.check(12, K125, 9, 0.3),
                Err(RegionError::Barred { .. })
            ));
            assert!(region.check(10, K125, 12, 0.3).is_err(), "N = 11 at DR2");
            assert!(region.check(10, K125, 11, 0.3).is_ok());
        }
    }

    #[test]
    fn every_plan_has_a_fastest_rate_that_carries_our_largest_payload() {
        for region in Region::ALL {
            let usable: Vec<PlanRate> = region
                .rates()
                .into_iter()
                .filter(|r| r.max_payload.is_some_and(|n| n >= 12))
                .collect();
            assert!(!usable.is_empty(), "{region:?}");
        }
    }
}
