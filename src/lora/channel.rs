//! Link budget: log-distance path loss and gateway sensitivity (reference §6, ns-3 `lorawan` defaults).

use super::{Bandwidth, LoraError, ShadowingModel, SpreadingFactor};
use crate::math;
use serde::{Deserialize, Serialize};

/// Channel parameters. Defaults are those of the ns-3 `lorawan` module (Magrin et al., ICC 2017),
/// which the paper's evaluation used.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct ChannelParams {
    /// End-device transmit power, dBm (ns-3 default 14 dBm, the EU868 ERP limit).
    pub tx_power_dbm: f64,
    /// Path loss at the 1 m reference distance, dB (ns-3 `LogDistancePropagationLossModel` as
    /// configured by the lorawan examples: 7.7 dB).
    pub reference_loss_db: f64,
    /// Path-loss exponent (ns-3 lorawan examples: 3.76, an urban macro-cell value).
    pub path_loss_exponent: f64,
    /// Standard deviation of log-normal shadowing, dB; 0 disables shadowing.
    pub shadowing_sigma_db: f64,
    /// Decorrelation distance of shadowing along the flight path, m (Gudmundson 1991; ns-3 uses 110 m).
    pub decorrelation_distance: f64,
    /// Whether shadowing varies along the path or is fixed in space.
    pub shadowing_model: ShadowingModel,
    /// Gateway antenna height above ground (z = 0), m.
    pub gateway_height: f64,
}

impl Default for ChannelParams {
    fn default() -> Self {
        use crate::options as opt;
        ChannelParams {
            tx_power_dbm: opt::TX_POWER.default,
            reference_loss_db: 7.7,
            path_loss_exponent: opt::PATH_LOSS_EXPONENT.default,
            shadowing_sigma_db: opt::SHADOWING.default,
            decorrelation_distance: 110.0,
            shadowing_model: ShadowingModel::Path,
            gateway_height: opt::GATEWAY_HEIGHT.default,
        }
    }
}

/// Gateway sensitivity at 125 kHz for SF7..SF12, dBm (SX1301 datasheet, as used by ns-3 lorawan).
const SENSITIVITY_125_KHZ: [f64; 6] = [-130.0, -132.5, -135.0, -137.5, -140.0, -142.5];

/// A validated link budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channel {
    params: ChannelParams,
}

impl Channel {
    /// Validates every parameter against its physical range (each named in the error), so that
    /// every derived number (range, received power) is finite.
    pub fn new(params: ChannelParams) -> Result<Self, LoraError> {
        use crate::options as opt;
        opt::TX_POWER.check(params.tx_power_dbm)?;
        opt::PATH_LOSS_EXPONENT.check(params.path_loss_exponent)?;
        opt::SHADOWING.check(params.shadowing_sigma_db)?;
        opt::GATEWAY_HEIGHT.check(params.gateway_height)?;
        // Not settings of a run (the ns-3 values stay fixed), but a caller may change them.
        let checks = [
            (
                "referenceLoss",
                params.reference_loss_db,
                (0.0..=100.0).contains(&params.reference_loss_db),
                "0..100 dB",
            ),
            (
                "decorrelationDistance",
                params.decorrelation_distance,
                (1.0..=100_000.0).contains(&params.decorrelation_distance),
                "1..100000 m",
            ),
        ];
        for (name, value, ok, allowed) in checks {
            if !ok {
                return Err(LoraError::Parameter(name, value, allowed));
            }
        }
        Ok(Channel { params })
    }

    /// The parameters.
    pub fn params(&self) -> &ChannelParams {
        &self.params
    }

    /// Log-distance path loss PL(d) = PL(1 m) + 10 n log10(d / 1 m), dB. Distances under 1 m are
    /// treated as 1 m (the model is not defined in the near field).
    pub fn path_loss_db(&self, distance_m: f64) -> f64 {
        let d = distance_m.max(1.0);
        self.params.reference_loss_db + 10.0 * self.params.path_loss_exponent * math::log10(d)
    }

    /// Mean received power at a 3D distance, dBm (before shadowing).
    pub fn mean_rx_power_dbm(&self, distance_m: f64) -> f64 {
        self.params.tx_power_dbm - self.path_loss_db(distance_m)
    }

    /// Gateway sensitivity, dBm: the 125 kHz figure plus 10 log10(BW / 125 kHz) for the extra
    /// noise a wider band lets in.
    pub fn sensitivity_dbm(sf: SpreadingFactor, bw: Bandwidth) -> f64 {
        SENSITIVITY_125_KHZ[usize::from(sf.get() - 7)] + 10.0 * math::log10(bw.khz() / 125.0)
    }

    /// The 3D distance at which the mean received power equals the sensitivity (m): with
    /// shadowing off, packets are received exactly up to here.
    pub fn range_m(&self, sf: SpreadingFactor, bw: Bandwidth) -> f64 {
        let budget = self.params.tx_power_dbm
            - self.params.reference_loss_db
            - Self::sensitivity_dbm(sf, bw);
        math::pow(10.0, budget / (10.0 * self.params.path_loss_exponent))
    }

    /// Whether a packet arrives: received power (mean + shadowing) ≥ sensitivity.
    pub fn received(
        &self,
        sf: SpreadingFactor,
        bw: Bandwidth,
        distance_m: f64,
        shadowing_db: f64,
    ) -> bool {
        super::audible(self.mean_rx_power_dbm(distance_m) + shadowing_db, sf, bw)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sf(n: i64) -> SpreadingFactor {
        SpreadingFactor::new(n).unwrap()
    }

    #[test]
    fn sf7_125khz_range_is_about_4_2_km_with_defaults() {
        let c = Channel::new(ChannelParams::default()).unwrap();
        let r = c.range_m(sf(7), Bandwidth::Khz125);
        assert!((r - 4200.0).abs() < 100.0, "range {r}");
    }

    #[test]
    fn range_grows_with_sf_and_shrinks_with_bandwidth() {
        let c = Channel::new(ChannelParams::default()).unwrap();
        for n in 7..12 {
            assert!(c.range_m(sf(n + 1), Bandwidth::Khz125) > c.range_m(sf(n), Bandwidth::Khz125));
        }
        assert!(c.range_m(sf(7), Bandwidth::Khz250) < c.range_m(sf(7), Bandwidth::Khz125));
        assert!(c.range_m(sf(7), Bandwidth::Khz500) < c.range_m(sf(7), Bandwidth::Khz250));
    }

    #[test]
    fn without_shadowing_delivery_is_a_step_at_the_range() {
        let c = Channel::new(ChannelParams::default()).unwrap();
        let r = c.range_m(sf(9), Bandwidth::Khz250);
        assert!(c.received(sf(9), Bandwidth::Khz250, r * 0.999, 0.0));
        assert!(!c.received(sf(9), Bandwidth::Khz250, r * 1.001, 0.0));
    }

    #[test]
    fn rejects_non_finite_or_out_of_range_parameters() {
        let bad = ChannelParams {
            path_loss_exponent: f64::NAN,
            ..Default::default()
        };
        assert!(Channel::new(bad).is_err());
        let bad = ChannelParams {
            shadowing_sigma_db: -1.0,
            ..Default::default()
        };
        assert!(Channel::new(bad).is_err());
    }
}
