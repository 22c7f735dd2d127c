//! How a swarm deals out spreading factors, and why a `spread` plan may deal fewer than six.

use crate::lora::LoraParams;
use crate::sim::scenario::{SfPlan, Validated};
use crate::sim::station::StationModel;
use crate::sim::SimError;
use serde::Serialize;

/// Why a `spread` plan dealt a swarm fewer SFs than it had drones for (JSON `sfLimit`). The
/// CLI's swarm header and the page's swarm note both say it, so that "all starting on SF7" is
/// never read as the plan ignored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum SfLimit {
    /// ADR moves a drone between data rates, so it must start at one, and at the swarm's
    /// bandwidth only these SFs have one (EU868 at 250 kHz: SF7 alone, DR6).
    Adr,
    /// The region's plan carries the station's frame at the swarm's bandwidth at these SFs only
    /// (a data rate, its payload limit, the dwell time; reference §14): US915 at 125 kHz SF7–SF9
    /// for a 12-byte payload, SF10's frame being over 400 ms.
    Region,
    /// The plan has no duty cycle, so a drone sends at the interval set, and the slower SFs'
    /// frames last longer than that interval (IN865 at 125 kHz and the default 1 s: SF12's
    /// 25-byte frame takes 1.48 s).
    Interval,
}

/// The SFs a swarm deals out in turn, drone i taking entry i mod their number.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct SfDeal {
    /// The SFs, slowest last.
    pub sfs: Vec<i64>,
    /// Why `spread` dealt fewer than six, where that left drones to share an SF that the plan
    /// would have given one of their own.
    pub limit: Option<SfLimit>,
}

impl SfDeal {
    /// The deal of `cfg`'s swarm for `model`'s frames: `fixed`, `sf` alone; `spread`, those of
    /// SF7..SF12 at which the plan carries the frame at the swarm's bandwidth, as a network
    /// server would assign them ([`Validated::drone_radio`]: in EU868 all six). Where none does,
    /// `sf`, which the swarm then refuses with its reason.
    pub fn of(cfg: &Validated, model: StationModel) -> Self {
        let s = cfg.s();
        if s.swarm.sf_plan == SfPlan::Fixed {
            return SfDeal {
                sfs: vec![s.radio.sf],
                limit: None,
            };
        }
        let mut sfs = Vec::new();
        let mut limit = None;
        for sf in 7..=12 {
            let carried = LoraParams::from_settings(sf, s.radio.bw, s.radio.cr)
                .map_err(SimError::from)
                .and_then(|radio| cfg.drone_radio(&radio, model));
            match carried {
                Ok(_) => sfs.push(sf),
                Err(SimError::AdrStart(..)) => limit = Some(SfLimit::Adr),
                Err(SimError::Parameter("interval", ..)) => {
                    limit = limit.or(Some(SfLimit::Interval))
                }
                Err(_) => limit = limit.or(Some(SfLimit::Region)),
            }
        }
        if sfs.is_empty() {
            sfs.push(s.radio.sf);
        }
        SfDeal {
            limit: limit.filter(|_| s.swarm.drones > sfs.len()),
            sfs,
        }
    }

    /// The spreading factor of drone `i`.
    pub fn sf_of(&self, i: usize) -> i64 {
        self.sfs[i % self.sfs.len()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::scenario::Scenario;

    fn deal(edit: impl FnOnce(&mut Scenario)) -> SfDeal {
        let mut s = Scenario::default();
        s.swarm.drones = 12;
        edit(&mut s);
        let cfg = s.validate().unwrap();
        SfDeal::of(&cfg, StationModel::Single(crate::models::ModelKind::Ctra3d))
    }

    #[test]
    fn spread_deals_all_six_sfs_in_eu868_without_a_reason() {
        let d = deal(|_| {});
        assert_eq!((d.sfs, d.limit), ((7..=12).collect(), None));
        assert_eq!(deal(|s| s.radio.sf = 9).sf_of(13), 8);
    }

    #[test]
    fn us915_at_125_khz_deals_sf7_to_sf9_for_the_region() {
        let d = deal(|s| {
            s.access.region = crate::lora::Region::Us915;
            s.radio.bw = 125.0;
        });
        assert_eq!((d.sfs, d.limit), (vec![7, 8, 9], Some(SfLimit::Region)));
    }

    #[test]
    fn adr_at_250_khz_starts_every_drone_on_sf7_for_want_of_other_data_rates() {
        let d = deal(|s| s.network.adr = crate::lora::AdrMode::Tracking);
        assert_eq!((d.sfs, d.limit), (vec![7], Some(SfLimit::Adr)));
    }

    #[test]
    fn without_a_duty_cycle_the_interval_set_bars_the_sfs_whose_frames_outlast_it() {
        // IN865 carries every SF at 125 kHz, but SF12's frame outlasts the default 1 s.
        let d = deal(|s| {
            s.access.region = crate::lora::Region::In865;
            s.radio.bw = 125.0;
        });
        assert_eq!(
            (d.sfs, d.limit),
            (vec![7, 8, 9, 10, 11], Some(SfLimit::Interval))
        );
        let longer = deal(|s| {
            s.access.region = crate::lora::Region::In865;
            s.radio.bw = 125.0;
            s.access.interval = Some(5.0);
        });
        assert_eq!((longer.sfs.len(), longer.limit), (6, None));
    }

    #[test]
    fn a_limit_that_cuts_nothing_is_not_given() {
        // Three drones take SF7-SF9 whether or not the plan has more.
        let d = deal(|s| {
            s.access.region = crate::lora::Region::Us915;
            s.radio.bw = 125.0;
            s.swarm.drones = 3;
        });
        assert_eq!((d.sfs.len(), d.limit), (3, None));
    }

    #[test]
    fn a_fixed_plan_deals_the_chosen_sf_alone() {
        let d = deal(|s| {
            s.swarm.sf_plan = SfPlan::Fixed;
            s.radio.sf = 10;
            s.radio.bw = 125.0;
            s.network.adr = crate::lora::AdrMode::Tracking;
        });
        assert_eq!((d.sfs, d.limit), (vec![10], None));
    }
}
