//! Every station of a run against the one with the lowest p75, on the same runs resampled
//! together (`docs/reference.md` §12): what the page's verdict and the CLI's line under the
//! table read.

use super::station::StationModel;
use crate::metrics::Draws;
use serde::Serialize;

/// A station's p75 over the lowest station's of the same run
/// ([`ModelResult::p75_vs_lowest`](crate::ModelResult::p75_vs_lowest)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct VersusLowest {
    /// The station with the lowest p75.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub lowest: StationModel,
    /// p75 / the lowest station's p75, each over every run pooled (≥ 1).
    pub ratio: f64,
    /// 95 % interval of the ratio, every run resampled for both stations at once: wholly
    /// above 1 where the runs tell the two apart.
    pub interval: [f64; 2],
    /// Runs resampled (flights × seeds).
    pub runs: usize,
}

impl VersusLowest {
    /// Whether the lowest station's p75 is clearly lower than this one's: the interval lies
    /// wholly above 1.
    pub fn clearly_higher(&self) -> bool {
        self.interval[0] > 1.0
    }
}

/// A station as the comparison reads it: what a [`ModelResult`](crate::ModelResult) holds, or
/// the page's `versusLowest` is given for the stations its workers ran apart.
#[derive(Clone, Debug)]
pub struct Contender {
    /// The station.
    pub model: StationModel,
    /// Its p75 over every run, m.
    pub p75: f64,
    /// How many errors that p75 rests on (0: the station has none, and no p75).
    pub count: usize,
    /// Its p75 and p95 in each bootstrap draw of the runs
    /// ([`ModelResult::draws`](crate::ModelResult::draws)).
    pub draws: Option<Draws>,
}

/// Each of `stations` against the one with the lowest p75 among those with errors: `None` for
/// that one itself, for every station where there are fewer than two, and for a station whose
/// draws (or the lowest's) are missing or were drawn from another number of runs.
pub fn versus_lowest(stations: &[Contender]) -> Vec<Option<VersusLowest>> {
    let lowest = stations
        .iter()
        .filter(|s| s.count > 0)
        .min_by(|a, b| a.p75.total_cmp(&b.p75));
    stations
        .iter()
        .map(|s| {
            let low = lowest.filter(|l| stations.len() >= 2 && l.model != s.model)?;
            let interval = s.draws.as_ref()?.p75_ratio_interval(low.draws.as_ref()?)?;
            Some(VersusLowest {
                lowest: low.model,
                ratio: s.p75 / low.p75,
                interval,
                runs: low.draws.as_ref()?.runs,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::ModelKind;

    const DR: StationModel = StationModel::Single(ModelKind::Dr);
    const CTRA_PLUS: StationModel = StationModel::Single(ModelKind::CtraPlus);
    const CTRA3D: StationModel = StationModel::Single(ModelKind::Ctra3d);

    fn station(model: StationModel, p75: f64, draws: Option<Vec<f64>>) -> Contender {
        Contender {
            model,
            p75,
            count: usize::from(p75.is_finite()) * 100,
            draws: draws.map(|p75| Draws {
                seed: 1,
                runs: 4,
                p95: p75.clone(),
                p75,
            }),
        }
    }

    #[test]
    fn each_station_is_set_against_the_lowest_and_the_lowest_against_none() {
        let v = versus_lowest(&[
            station(DR, 3.0, Some(vec![3.0, 2.4, 3.3, f64::NAN])),
            station(CTRA3D, 2.0, Some(vec![2.0, 2.0, 2.0, 2.0])),
            station(CTRA_PLUS, 2.1, Some(vec![1.8, 2.2, 2.1, 2.0])),
        ]);
        assert!(v[1].is_none(), "the lowest");
        let dr = v[0].unwrap();
        assert_eq!((dr.lowest, dr.ratio, dr.runs), (CTRA3D, 1.5, 4));
        // The draw without DR's errors is left out; the others give 1.5, 1.2 and 1.65.
        assert!(dr.interval[0] > 1.2 && dr.interval[1] < 1.65, "{dr:?}");
        assert!(dr.clearly_higher());
        let plus = v[2].unwrap();
        assert!(!plus.clearly_higher(), "{plus:?}: 0.9 to 1.1");
    }

    #[test]
    fn without_draws_a_station_alone_or_one_without_errors_nothing_is_paired() {
        let alone = versus_lowest(&[station(DR, 3.0, Some(vec![3.0; 4]))]);
        assert_eq!(alone, vec![None]);
        let v = versus_lowest(&[
            station(DR, 3.0, None),
            station(CTRA3D, 2.0, Some(vec![2.0; 4])),
            // No errors: no p75, never the lowest, and nothing to compare.
            station(StationModel::Imm, f64::NAN, None),
        ]);
        assert_eq!(v, vec![None, None, None]);
        // Draws of another number of runs are not paired.
        let mut other = station(DR, 3.0, Some(vec![3.0; 4]));
        other.draws.as_mut().unwrap().runs = 5;
        let v = versus_lowest(&[other, station(CTRA3D, 2.0, Some(vec![2.0; 4]))]);
        assert_eq!(v, vec![None, None]);
    }
}
