//! Where the gateways stand (`--gateway E,N[,H]`, JS `gateways: [{east, north, height}]`).

use crate::options::{GATEWAYS, GATEWAY_COORDINATE, GATEWAY_HEIGHT};
use crate::sim::SimError;
use serde::{Deserialize, Serialize};

/// One gateway in the scenario's frame: metres east and north of the origin (for `simulate` the
/// flight's first point, for `swarm` the point the drones are spread around) and its antenna
/// height above ground, m (`None`: the `gatewayHeight` setting).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct GatewaySite {
    /// Metres east of the origin.
    pub east: f64,
    /// Metres north of the origin.
    pub north: f64,
    /// Antenna height, m; `None` for the `gatewayHeight` setting.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    pub height: Option<f64>,
}

impl GatewaySite {
    /// Parses `E,N` or `E,N,H` (metres), as `--gateway` takes it.
    ///
    /// ```
    /// use loratrack::GatewaySite;
    /// let g = GatewaySite::parse("5000,-20,30").unwrap();
    /// assert_eq!((g.east, g.north, g.height), (5000.0, -20.0, Some(30.0)));
    /// assert!(GatewaySite::parse("1,2,3,4").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, String> {
        let parts: Result<Vec<f64>, _> = text.split(',').map(|p| p.trim().parse::<f64>()).collect();
        let shown: String = text.chars().take(40).collect();
        match parts.as_deref() {
            Ok([east, north]) => Ok(GatewaySite {
                east: *east,
                north: *north,
                height: None,
            }),
            Ok([east, north, height]) => Ok(GatewaySite {
                east: *east,
                north: *north,
                height: Some(*height),
            }),
            _ => Err(format!(
                "gateway must be E,N or E,N,H in metres (east, north, antenna height), got '{shown}'"
            )),
        }
    }

    /// Checks the coordinates and height against their limits.
    pub fn validate(&self) -> Result<(), SimError> {
        GATEWAY_COORDINATE.check(self.east)?;
        GATEWAY_COORDINATE.check(self.north)?;
        if let Some(h) = self.height {
            GATEWAY_HEIGHT.check(h)?;
        }
        Ok(())
    }

    /// `E,N` or `E,N,H` as [`Self::parse`] reads it back, each number in the shortest text that
    /// reads back to the same bits (the command line that reruns a scenario).
    ///
    /// ```
    /// use loratrack::GatewaySite;
    /// let g = GatewaySite { east: -500.0, north: 0.1 + 0.2, height: Some(30.0) };
    /// assert_eq!(g.text(), "-500,0.30000000000000004,30");
    /// assert_eq!(GatewaySite::parse(&g.text()).unwrap(), g);
    /// ```
    pub fn text(&self) -> String {
        match self.height {
            Some(h) => format!("{},{},{h}", self.east, self.north),
            None => format!("{},{}", self.east, self.north),
        }
    }

    /// The antenna's position x (east), y (north), z (height), m, with `default_height` m for
    /// a gateway given none.
    pub fn position(&self, default_height: f64) -> [f64; 3] {
        [self.east, self.north, self.height.unwrap_or(default_height)]
    }
}

/// Checks the number of gateways (1..16) and each one.
pub fn validate_sites(sites: &[GatewaySite]) -> Result<(), SimError> {
    if !sites.is_empty() {
        GATEWAYS.check(sites.len() as f64)?;
    }
    sites.iter().try_for_each(GatewaySite::validate)
}

/// Refuses a default antenna height (`gatewayHeight`, m) changed from its default where no
/// gateway takes it: every listed gateway gives its own (the one default gateway, when none is
/// listed, takes it).
pub(crate) fn check_default_height(sites: &[GatewaySite], height: f64) -> Result<(), SimError> {
    SimError::unless_read(
        sites.is_empty() || sites.iter().any(|g| g.height.is_none()),
        &[("gatewayHeight", height != GATEWAY_HEIGHT.default)],
        "the antenna height of every gateway not given its own",
        "every listed gateway gives its own height; leave `gatewayHeight` out",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site(height: Option<f64>) -> GatewaySite {
        GatewaySite {
            east: 500.0,
            north: 0.0,
            height,
        }
    }

    #[test]
    fn a_default_height_is_refused_only_where_every_listed_gateway_gives_its_own() {
        let changed = GATEWAY_HEIGHT.default + 10.0;
        let refused = check_default_height(&[site(Some(20.0))], changed).unwrap_err();
        assert_eq!(refused.setting(), Some("gatewayHeight"));
        // The one default gateway, or a listed one without a height, takes it.
        assert!(check_default_height(&[], changed).is_ok());
        assert!(check_default_height(&[site(Some(20.0)), site(None)], changed).is_ok());
        // Left at its default, it is no setting of the user's.
        assert!(check_default_height(&[site(Some(20.0))], GATEWAY_HEIGHT.default).is_ok());
    }
}
