//! How much work a run's stations are, and how to split them over parallel workers so that the
//! slowest finishes soonest (the page's worker pool; natively, the order of the parallel jobs).
//!
//! A station's run is its drone's filter run (the model whose payload it receives) and its own
//! prediction. Stations whose drones send the same model share one drone run where they run
//! together (3D-CTRA, the IMM and the mission station all receive the 3D-CTRA payload), so a
//! group of stations costs each distinct drone run once.

use super::StationModel;
use crate::models::ModelKind;

/// The work of a drone's filter run (sensors and UKF at 10 Hz) for a drone sending `kind`'s
/// payload, in milliseconds over the whole synthetic set in WebAssembly (Node 20, one thread,
/// 2026-11-30: each station run with a new seed, less the same run again with its drone run
/// cached; rounded, ±30 % between runs on this 2-core machine). Only the ratios matter.
pub(crate) fn drone_run_work(kind: ModelKind) -> u32 {
    match kind {
        ModelKind::Dr => 70,
        ModelKind::CtraPlus => 130,
        ModelKind::Ctra3d => 200,
    }
}

/// The work of a station's own prediction over the same set and measured alike, between the
/// paper's station and the bounded one (the IMM's bounded members cost it nearly twice its
/// paper members: 610 against 340 ms).
fn prediction_work(station: StationModel) -> u32 {
    match station {
        StationModel::Single(ModelKind::Dr) => 65,
        StationModel::Single(ModelKind::CtraPlus) => 100,
        StationModel::Single(ModelKind::Ctra3d) => 140,
        StationModel::Mission => 190,
        StationModel::Imm => 450,
    }
}

/// The work of running `stations` together, in the units of a drone filter run's cost
/// (milliseconds over the whole set in WebAssembly): each distinct drone run once and every
/// station's prediction.
///
/// ```
/// use loratrack::{station_work, ModelKind, StationModel};
/// let ctra3d = StationModel::Single(ModelKind::Ctra3d);
/// // The IMM receives 3D-CTRA's payload: beside 3D-CTRA it adds only its own prediction.
/// let together = station_work(&[ctra3d, StationModel::Imm]);
/// assert!(together < station_work(&[ctra3d]) + station_work(&[StationModel::Imm]));
/// ```
pub fn station_work(stations: &[StationModel]) -> u32 {
    let mut drones: Vec<ModelKind> = stations.iter().map(|s| s.sent_model()).collect();
    drones.sort_unstable();
    drones.dedup();
    drones.into_iter().map(drone_run_work).sum::<u32>()
        + stations.iter().copied().map(prediction_work).sum::<u32>()
}

/// Above this many stations the split is greedy (each station, costliest first, to the least
/// loaded group) instead of searched: the search walks every partition of the stations (203
/// for 6, 115 975 for 10), and no model list names more than the five stations there are.
const SEARCHED_UP_TO: usize = 8;

/// `stations` split into at most `workers` groups (at least one) so that the most work any
/// group holds ([`station_work`]) is least; among equal splits, the one with least work in
/// all (fewer drone runs made twice), then fewer groups. Groups are ordered by their first
/// station, each in `stations`' order; the same list always splits the same way, so a worker
/// that ran a station before runs it again and its caches serve it.
///
/// The paper's three on two workers go as DR with CTRA+ and 3D-CTRA alone (365 against 340),
/// not DR with 3D-CTRA (475 against 230): on the page, every panel of the whole set was drawn
/// again 1365 ms after an SF change instead of 1742 ms (docs/performance.md, 2026-11-30).
///
/// ```
/// use loratrack::{split_stations, StationModel};
/// let [dr, ctra_plus, ctra3d] = StationModel::PAPER;
/// assert_eq!(split_stations(&StationModel::PAPER, 2), vec![vec![dr, ctra_plus], vec![ctra3d]]);
/// assert_eq!(split_stations(&StationModel::PAPER, 1), vec![vec![dr, ctra_plus, ctra3d]]);
/// ```
pub fn split_stations(stations: &[StationModel], workers: usize) -> Vec<Vec<StationModel>> {
    let workers = workers.max(1);
    let labels = if stations.len() <= SEARCHED_UP_TO {
        best_partition(stations, workers)
    } else {
        greedy(stations, workers)
    };
    groups(stations, &labels)
}

/// The groups `labels` name, each its stations in `stations`' order.
fn groups(stations: &[StationModel], labels: &[usize]) -> Vec<Vec<StationModel>> {
    (0..group_count(labels))
        .map(|g| members(stations, labels, g))
        .collect()
}

/// How many groups `labels` name (groups are numbered from 0 without gaps).
fn group_count(labels: &[usize]) -> usize {
    labels.iter().max().map_or(0, |&g| g + 1)
}

/// The stations of group `g`, in `stations`' order.
fn members(stations: &[StationModel], labels: &[usize], g: usize) -> Vec<StationModel> {
    stations
        .iter()
        .zip(labels)
        .filter(|&(_, &l)| l == g)
        .map(|(&s, _)| s)
        .collect()
}

/// A split's score, the least the best: the most work in a group, then the work in all, then
/// the number of groups.
fn score(stations: &[StationModel], labels: &[usize]) -> (u32, u32, usize) {
    let work: Vec<u32> = groups(stations, labels)
        .iter()
        .map(|g| station_work(g))
        .collect();
    let most = work.iter().copied().max().unwrap_or(0);
    (most, work.iter().sum(), work.len())
}

/// A split's score ([`score`]) and the group of each station.
type Scored = ((u32, u32, usize), Vec<usize>);

/// Every partition into at most `workers` groups, as restricted growth strings (station i joins
/// a group already named or the next new one, so each partition is visited once, groups
/// numbered in order of their first station); the best by [`score`], the first found on ties.
fn best_partition(stations: &[StationModel], workers: usize) -> Vec<usize> {
    fn visit(
        i: usize,
        used: usize,
        labels: &mut Vec<usize>,
        (stations, workers): (&[StationModel], usize),
        best: &mut Option<Scored>,
    ) {
        if i == labels.len() {
            let s = score(stations, labels);
            if best.as_ref().is_none_or(|(b, _)| s < *b) {
                *best = Some((s, labels.clone()));
            }
            return;
        }
        for g in 0..(used + 1).min(workers) {
            labels[i] = g;
            visit(i + 1, used.max(g + 1), labels, (stations, workers), best);
        }
    }
    let mut labels = vec![0; stations.len()];
    let mut best = None;
    visit(0, 0, &mut labels, (stations, workers), &mut best);
    best.map_or(labels, |(_, l)| l)
}

/// Longest processing time first: each station, costliest alone first, to the group with the
/// least work so far (the first on ties), then groups renumbered by their first station.
fn greedy(stations: &[StationModel], workers: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..stations.len()).collect();
    order.sort_by_key(|&i| core::cmp::Reverse(station_work(&stations[i..=i])));
    let mut groups: Vec<Vec<StationModel>> = vec![Vec::new(); workers.min(stations.len())];
    let mut labels = vec![0; stations.len()];
    for i in order {
        let g = (0..groups.len())
            .min_by_key(|&g| station_work(&groups[g]))
            .unwrap_or(0);
        groups[g].push(stations[i]);
        labels[i] = g;
    }
    // Renumbered in order of first appearance.
    let mut names: Vec<Option<usize>> = vec![None; groups.len()];
    let mut next = 0;
    for l in labels.iter_mut() {
        let name = *names[*l].get_or_insert_with(|| {
            next += 1;
            next - 1
        });
        *l = name;
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;

    const DR: StationModel = StationModel::Single(ModelKind::Dr);
    const CTRA_PLUS: StationModel = StationModel::Single(ModelKind::CtraPlus);
    const CTRA3D: StationModel = StationModel::Single(ModelKind::Ctra3d);
    const ALL: [StationModel; 5] = [
        DR,
        CTRA_PLUS,
        CTRA3D,
        StationModel::Imm,
        StationModel::Mission,
    ];

    fn most_work(split: &[Vec<StationModel>]) -> u32 {
        split.iter().map(|g| station_work(g)).max().unwrap()
    }

    #[test]
    fn stations_sharing_a_drone_run_cost_it_once() {
        let apart = station_work(&[CTRA3D]) + station_work(&[StationModel::Mission]);
        let together = station_work(&[CTRA3D, StationModel::Mission]);
        assert_eq!(apart - together, drone_run_work(ModelKind::Ctra3d));
        assert_eq!(
            station_work(&[DR, CTRA_PLUS]),
            station_work(&[DR]) + station_work(&[CTRA_PLUS])
        );
    }

    #[test]
    fn the_paper_three_on_two_workers_leave_3d_ctra_alone() {
        assert_eq!(
            split_stations(&StationModel::PAPER, 2),
            vec![vec![DR, CTRA_PLUS], vec![CTRA3D]]
        );
    }

    #[test]
    fn every_station_is_in_one_group_in_its_order_and_no_group_is_empty() {
        for n in 1..=ALL.len() {
            for workers in 1..=9 {
                let stations = &ALL[..n];
                let split = split_stations(stations, workers);
                assert!(split.len() <= workers.min(n) && split.iter().all(|g| !g.is_empty()));
                let mut seen: Vec<StationModel> = split.concat();
                seen.sort();
                let mut want = stations.to_vec();
                want.sort();
                assert_eq!(seen, want, "{n} stations on {workers} workers");
                // Groups by their first station, each in the request's order.
                let position = |s: &StationModel| stations.iter().position(|t| t == s).unwrap();
                for g in &split {
                    assert!(g.windows(2).all(|w| position(&w[0]) < position(&w[1])));
                }
                assert!(split
                    .windows(2)
                    .all(|w| position(&w[0][0]) < position(&w[1][0])));
            }
        }
    }

    #[test]
    fn the_search_finds_no_split_worse_than_the_greedy_one_or_the_round_robin() {
        for n in 2..=ALL.len() {
            for workers in 2..=4 {
                let stations = &ALL[..n];
                let best = most_work(&split_stations(stations, workers));
                let greedy_split = groups(stations, &greedy(stations, workers));
                assert!(best <= most_work(&greedy_split));
                let round_robin: Vec<Vec<StationModel>> = (0..workers.min(n))
                    .map(|w| (w..n).step_by(workers).map(|i| stations[i]).collect())
                    .collect();
                assert!(best <= most_work(&round_robin), "{n} on {workers}");
            }
        }
    }

    #[test]
    fn one_worker_or_one_station_is_one_group() {
        assert_eq!(split_stations(&ALL, 1), vec![ALL.to_vec()]);
        assert_eq!(split_stations(&ALL, 0), vec![ALL.to_vec()]);
        assert_eq!(split_stations(&[CTRA3D], 8), vec![vec![CTRA3D]]);
        assert!(split_stations(&[], 2).is_empty());
    }

    #[test]
    fn a_long_list_is_split_greedily_into_groups_of_like_work() {
        let stations: Vec<StationModel> = ALL.iter().cycle().take(12).copied().collect();
        let split = split_stations(&stations, 3);
        assert_eq!(split.len(), 3);
        assert_eq!(split.concat().len(), 12);
        let work: Vec<u32> = split.iter().map(|g| station_work(g)).collect();
        let (least, most) = (work.iter().min().unwrap(), work.iter().max().unwrap());
        assert!(
            most - least <= prediction_work(StationModel::Imm) + 200,
            "{work:?}"
        );
    }
}
