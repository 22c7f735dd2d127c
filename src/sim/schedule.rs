//! Swarm schedules: pure ALOHA (each drone sends when its duty cycle and clock let it), or a
//! slotted frame on shared GPS time in which no two drones on one channel are ever on air
//! together, whatever their spreading factors (SFs are only nearly orthogonal: the rejection
//! matrix lets a strong packet on one SF destroy a weak one on another). `docs/reference.md` §13.
//!
//! Each SF's drones are dealt round-robin over the channels. On one channel every drone gets a
//! period that is a power-of-two multiple of one base period, so the periods nest and one
//! hyperperiod (the longest period) repeats the whole pattern; the base is chosen among the
//! drones' duty-cycle intervals to slow them least (each period is at least the drone's
//! duty-cycle interval, at most twice it). Drones are then placed first-fit, shortest period
//! first, at the earliest offset where all their slots (time on air + guard) fall in free time.
//! When the channel is too full, every period grows by the same factor until all fit.

use crate::math::pow;
use serde::{Deserialize, Serialize};

/// How a swarm's drones share the air (`--schedule`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum Schedule {
    /// Each drone sends when its duty cycle allows, after its random delay (pure ALOHA).
    #[default]
    Aloha,
    /// Each drone has a slot in a frame on GPS time; no two slots overlap on one SF and channel.
    Slotted,
}

impl Schedule {
    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            Schedule::Aloha => "aloha",
            Schedule::Slotted => "slotted",
        }
    }
}

/// The collision probability of one packet among `n` periodic senders that share an SF and hop
/// at random over `channels` channels, each on air a fraction `duty_cycle` of the time: another
/// sender's packet overlaps it with probability 2·DC (a window of two packet lengths) and lands
/// on its channel with probability 1/C, so P = 1 − (1 − 2·DC/C)^(n−1) (pure ALOHA; reference §10).
///
/// ```
/// let p = loratrack::aloha_collision_rate(0.01, 3, 12);
/// assert!((p - (1.0 - (1.0f64 - 0.02 / 3.0).powi(11))).abs() < 1e-15);
/// ```
pub fn aloha_collision_rate(duty_cycle: f64, channels: u8, n: usize) -> f64 {
    if n <= 1 {
        return 0.0;
    }
    1.0 - pow(1.0 - 2.0 * duty_cycle / f64::from(channels), (n - 1) as f64)
}

/// The start-time uncertainty of one drone in a slot, s: a GPS receiver's pulse per second is
/// within a microsecond of GPS time, but the microcontroller that starts the radio on it adds up
/// to about a millisecond.
pub const START_UNCERTAINTY_S: f64 = 1e-3;

/// The guard between two slots, s: both neighbours' start uncertainty, plus what each clock
/// can drift (`clock_drift_ppm`) in the second between two GPS pulses.
pub fn guard_s(clock_drift_ppm: f64) -> f64 {
    2.0 * (START_UNCERTAINTY_S + clock_drift_ppm * 1e-6)
}

/// One drone's place in a slotted schedule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slot {
    /// Start of its first slot, s after time 0.
    pub offset: f64,
    /// The frame its slot repeats in, s: its sending interval.
    pub frame: f64,
    /// Its channel.
    pub channel: u8,
}

/// What the schedule needs of one drone: its spreading factor, its packets' time on air and
/// the shortest interval its rule allows (time on air / duty cycle), s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Airtime {
    /// Spreading factor.
    pub sf: u8,
    /// Time on air of each packet, s.
    pub time_on_air: f64,
    /// The shortest interval between its packets' starts, s.
    pub interval: f64,
}

/// Slots for every drone (in the order given) over `channels` channels, with guards for clocks
/// that drift up to `clock_drift_ppm`.
pub fn assign(drones: &[Airtime], channels: u8, clock_drift_ppm: f64) -> Vec<Slot> {
    let guard = guard_s(clock_drift_ppm);
    let c = usize::from(channels.max(1));
    let mut on: Vec<Vec<usize>> = vec![Vec::new(); c];
    for sf in 7..=12u8 {
        let group = (0..drones.len()).filter(|&i| drones[i].sf == sf);
        for (j, i) in group.enumerate() {
            on[j % c].push(i);
        }
    }
    let mut slots = vec![
        Slot {
            offset: 0.0,
            frame: 0.0,
            channel: 0,
        };
        drones.len()
    ];
    for (ch, members) in on.iter().enumerate() {
        let need: Vec<f64> = members.iter().map(|&i| drones[i].interval).collect();
        let len: Vec<f64> = members
            .iter()
            .map(|&i| drones[i].time_on_air + guard)
            .collect();
        let periods = nested_periods(&need);
        let load: f64 = len.iter().zip(&periods).map(|(l, p)| l / p).sum();
        let mut scale = load.max(1.0);
        let offsets = loop {
            let scaled: Vec<f64> = periods.iter().map(|p| p * scale).collect();
            if let Some(o) = pack(&scaled, &len) {
                break o;
            }
            scale *= 1.02;
        };
        for (j, &i) in members.iter().enumerate() {
            slots[i] = Slot {
                offset: offsets[j],
                frame: periods[j] * scale,
                channel: ch as u8,
            };
        }
    }
    slots
}

/// Periods at least `need` each, all power-of-two multiples of one base (so they nest), with
/// the base among the needs that slows the drones least (smallest mean period / need).
fn nested_periods(need: &[f64]) -> Vec<f64> {
    let fit = |base: f64| -> Vec<f64> {
        need.iter()
            .map(|&n| {
                let p = base * pow2((n / base).log2().ceil() as i32);
                // Rounding in log2 must not leave a period a hair under its need.
                if p < n {
                    p * 2.0
                } else {
                    p
                }
            })
            .collect()
    };
    let cost = |p: &[f64]| -> f64 { p.iter().zip(need).map(|(p, n)| p / n).sum() };
    // Each distinct need once, in order (drones share an SF's need: trying every drone's made
    // a channel of thousands quadratic), so the first of equal costs is the same base.
    let mut bases: Vec<f64> = Vec::new();
    for &n in need {
        if !bases.contains(&n) {
            bases.push(n);
        }
    }
    bases
        .into_iter()
        .map(fit)
        .min_by(|a, b| cost(a).total_cmp(&cost(b)))
        .unwrap_or_default()
}

fn pow2(e: i32) -> f64 {
    2f64.powi(e)
}

/// First-fit offsets for slots of `len` repeating every `period` (nested periods), shortest
/// period first; `None` when one does not fit.
///
/// Every slot placed before one of period `p` repeats with a period that divides `p`, so what is
/// busy repeats every `p`: the slot need only fit in [0, `p`), against the placed slots' repeats
/// there. (Checking every repeat over the longest period, with candidates from all of them, made
/// a packer quadratic in the repeats: 18 s for 64 random swarms of up to 160 drones.)
///
/// A candidate refused for a slot length stays refused while slots are placed (the busy time only
/// grows), so each length's search starts where the last slot of that length went, until the
/// busy intervals are rebuilt for a longer period: first fit in one pass over the busy intervals
/// per length, where searching from 0 each time was quadratic in the drones (a capacity search
/// at TTN's fair use, a slot per 4270 s, packed 8640 drones per try: 5 s for a swarm of 50).
fn pack(period: &[f64], len: &[f64]) -> Option<Vec<f64>> {
    let order = packing_order(period, len);
    let mut offsets = vec![0.0; period.len()];
    let mut placed: Vec<usize> = Vec::new();
    // The placed slots' busy intervals within [0, `span`), sorted by start (so by end too).
    let (mut busy, mut span): (Vec<(f64, f64)>, f64) = (Vec::new(), 0.0);
    // Per slot length, the index in `busy` of the last slot of that length placed in this span.
    let mut fitted: Vec<(f64, usize)> = Vec::new();
    for i in order {
        let (p, l) = (period[i], len[i]);
        if p > span {
            busy = repeats_within(&placed, &offsets, period, len, p);
            span = p;
            fitted.clear();
        }
        let from = fitted.iter().find(|f| f.0 == l).map(|f| f.1);
        // Candidates: 0 and each busy interval's end, ascending; near-equal ones count once.
        let mut last = f64::NEG_INFINITY;
        let (o, at) = from
            .is_none()
            .then_some((0.0, None))
            .into_iter()
            .chain((from.unwrap_or(0)..busy.len()).map(|j| (busy[j].1 % p, Some(j))))
            .filter(|&(o, _)| o + l <= p + 1e-12)
            .filter(|&(o, _)| {
                let new = (o - last).abs() >= 1e-12;
                last = if new { o } else { last };
                new
            })
            .find_map(|(o, j)| fits_after(&busy, o, l, j).map(|at| (o, at)))?;
        busy.insert(at, (o, o + l));
        for f in fitted.iter_mut().filter(|f| f.1 >= at) {
            f.1 += 1;
        }
        match fitted.iter_mut().find(|f| f.0 == l) {
            Some(f) => f.1 = at,
            None => fitted.push((l, at)),
        }
        placed.push(i);
        offsets[i] = o;
    }
    Some(offsets)
}

/// The order slots are placed in: shortest period first, the longest slot first among equals.
fn packing_order(period: &[f64], len: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..period.len()).collect();
    order.sort_by(|&a, &b| {
        period[a]
            .total_cmp(&period[b])
            .then(len[b].total_cmp(&len[a]))
    });
    order
}

/// Where [o, o + `l`) goes in `busy` if it is free there, else `None`; `after` the index of the
/// busy interval whose end `o` is, when it is one. Busy intervals are disjoint and longer than
/// 1e-12, so a slot starting at interval j's end can overlap only interval j + 1 ([`is_free`]'s
/// test there, with its tolerance) and goes in at j + 1; from 0 or a wrapped end (one at the
/// period), [`is_free`] and a search.
fn fits_after(busy: &[(f64, f64)], o: f64, l: f64, after: Option<usize>) -> Option<usize> {
    match after {
        Some(j) if busy[j].1 == o => busy
            .get(j + 1)
            .is_none_or(|&(s, _)| s >= o + l - 1e-12)
            .then_some(j + 1),
        _ => is_free(busy, o, l).then(|| busy.partition_point(|&(s, _)| s < o)),
    }
}

/// The busy intervals of the `placed` slots' repeats within [0, `span`), sorted by start.
fn repeats_within(
    placed: &[usize],
    offsets: &[f64],
    period: &[f64],
    len: &[f64],
    span: f64,
) -> Vec<(f64, f64)> {
    let mut busy: Vec<(f64, f64)> = placed
        .iter()
        .flat_map(|&j| {
            let repeats = (span / period[j]).round() as usize;
            (0..repeats).map(move |r| {
                let start = offsets[j] + r as f64 * period[j];
                (start, start + len[j])
            })
        })
        .collect();
    busy.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    busy
}

/// Whether [start, start + len) overlaps none of `busy` (sorted, disjoint).
fn is_free(busy: &[(f64, f64)], start: f64, len: f64) -> bool {
    let end = start + len;
    let at = busy.partition_point(|&(_, e)| e <= start + 1e-12);
    busy.get(at).is_none_or(|&(s, _)| s >= end - 1e-12)
}

/// The most drones a capacity search tries.
pub const MAX_SWARM_SEARCHED: usize = 100_000;

/// One value per spreading factor, SF7 first: a time on air or interval (s), or a duty cycle.
pub type PerSf = [f64; 6];

/// The largest swarm whose packets collide at most `target` (a fraction) by the pure-ALOHA
/// formula ([`aloha_collision_rate`], per SF group, weighted
/// by the packets each group sends), with drone `i` on SF `sf_of(i)` over `channels` channels.
pub fn largest_aloha(
    sf_of: impl Fn(usize) -> u8,
    time_on_air: &PerSf,
    used: &PerSf,
    channels: u8,
    target: f64,
) -> usize {
    let mut n = [0usize; 6];
    for drones in 1..=MAX_SWARM_SEARCHED {
        n[usize::from(sf_of(drones - 1) - 7)] += 1;
        let (mut lost, mut sent) = (0.0, 0.0);
        for k in (0..6).filter(|&k| n[k] > 0) {
            let rate = n[k] as f64 * used[k] / time_on_air[k];
            sent += rate;
            lost += rate * aloha_collision_rate(used[k], channels, n[k]);
        }
        if lost > target * sent {
            return drones - 1;
        }
    }
    MAX_SWARM_SEARCHED
}

/// The largest swarm a slotted schedule serves with no collisions and no drone slowed by
/// crowding: every drone keeps its nested period (at most twice its shortest `interval`).
pub fn largest_slotted(
    sf_of: impl Fn(usize) -> u8,
    time_on_air: &PerSf,
    interval: &PerSf,
    channels: u8,
    clock_drift_ppm: f64,
) -> usize {
    let swarm = |n: usize| -> Vec<Airtime> {
        (0..n)
            .map(|i| {
                let k = usize::from(sf_of(i) - 7);
                Airtime {
                    sf: sf_of(i),
                    time_on_air: time_on_air[k],
                    interval: interval[k],
                }
            })
            .collect()
    };
    let uncrowded = |n: usize| {
        let drones = swarm(n);
        assign(&drones, channels, clock_drift_ppm)
            .iter()
            .zip(&drones)
            .all(|(s, d)| s.frame <= 2.0 * d.interval * (1.0 + 1e-9))
    };
    // A channel holds at most interval / time on air drones of one SF; search below that bound.
    let most = (0..6)
        .filter(|&k| time_on_air[k] > 0.0)
        .map(|k| interval[k] / time_on_air[k])
        .fold(0.0, f64::max);
    let (mut lo, mut hi) = (0, (f64::from(channels) * most).ceil() as usize + 1);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if uncrowded(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;

    fn swarm(n: usize) -> Vec<Airtime> {
        (0..n)
            .map(|i| {
                let sf = 7 + (i % 6) as u8;
                let time_on_air = 0.0617 * f64::from(1u32 << (sf - 7));
                Airtime {
                    sf,
                    time_on_air,
                    interval: time_on_air / 0.01,
                }
            })
            .collect()
    }

    #[test]
    fn every_period_is_at_least_the_duty_cycle_interval_and_at_most_twice_it() {
        let drones = swarm(12);
        for (d, slot) in drones.iter().zip(assign(&drones, 1, 20.0)) {
            let need = d.interval;
            assert!(
                slot.frame >= need - 1e-9 && slot.frame <= 2.0 * need,
                "{slot:?}"
            );
        }
    }

    #[test]
    fn a_crowded_channel_slows_every_drone_alike() {
        let crowded: Vec<Airtime> = (0..200)
            .map(|_| Airtime {
                sf: 7,
                time_on_air: 0.0617,
                interval: 6.17,
            })
            .collect();
        let s = assign(&crowded, 1, 20.0);
        let busy = 200.0 * (0.0617 + guard_s(20.0));
        assert!(
            s[0].frame >= busy - 1e-9 && s[0].frame <= busy * 1.03,
            "{}",
            s[0].frame
        );
    }

    #[test]
    fn capacities_grow_with_channels_and_aloha_serves_fewer_at_one_percent() {
        let toa = [0.0617, 0.1132, 0.2058, 0.3707, 0.8233, 1.4828];
        let used = [0.01; 6];
        let interval = toa.map(|t| t / 0.01);
        let spread = |i: usize| 7 + (i % 6) as u8;
        let a1 = largest_aloha(spread, &toa, &used, 1, 0.01);
        let a10 = largest_aloha(spread, &toa, &used, 1, 0.10);
        let a10_3 = largest_aloha(spread, &toa, &used, 3, 0.10);
        let slotted = largest_slotted(spread, &toa, &interval, 1, 20.0);
        assert!(a1 < a10 && a10 < a10_3, "{a1} {a10} {a10_3}");
        assert!(slotted > a10, "{slotted} {a10}");
        assert!(slotted <= 100, "{slotted}");
    }

    #[test]
    fn spreads_each_sf_over_the_channels() {
        let s = assign(&swarm(36), 3, 20.0);
        let on = |sf: u8, ch: u8| {
            swarm(36)
                .iter()
                .zip(&s)
                .filter(|(a, x)| a.sf == sf && x.channel == ch)
                .count()
        };
        assert_eq!((on(7, 0), on(7, 1), on(7, 2)), (2, 2, 2));
    }

    /// The packer as first written: every slot searched from 0, every need tried as the base.
    /// What `pack` and `nested_periods` must still return, bit for bit.
    mod searched_from_zero {
        pub fn pack(period: &[f64], len: &[f64]) -> Option<Vec<f64>> {
            let order = super::super::packing_order(period, len);
            let mut offsets = vec![0.0; period.len()];
            let mut placed: Vec<usize> = Vec::new();
            let (mut busy, mut span): (Vec<(f64, f64)>, f64) = (Vec::new(), 0.0);
            for i in order {
                let (p, l) = (period[i], len[i]);
                if p > span {
                    busy = super::super::repeats_within(&placed, &offsets, period, len, p);
                    span = p;
                }
                let mut last = f64::NEG_INFINITY;
                let o = core::iter::once(0.0)
                    .chain(busy.iter().map(|&(_, end)| end % p))
                    .filter(|&o| o + l <= p + 1e-12)
                    .filter(|&o| {
                        let new = (o - last).abs() >= 1e-12;
                        last = if new { o } else { last };
                        new
                    })
                    .find(|&o| super::super::is_free(&busy, o, l))?;
                let at = busy.partition_point(|&(s, _)| s < o);
                busy.insert(at, (o, o + l));
                placed.push(i);
                offsets[i] = o;
            }
            Some(offsets)
        }

        pub fn nested_periods(need: &[f64]) -> Vec<f64> {
            let fit = |base: f64| -> Vec<f64> {
                need.iter()
                    .map(|&n| {
                        let p = base * super::super::pow2((n / base).log2().ceil() as i32);
                        if p < n {
                            p * 2.0
                        } else {
                            p
                        }
                    })
                    .collect()
            };
            let cost = |p: &[f64]| -> f64 { p.iter().zip(need).map(|(p, n)| p / n).sum() };
            need.iter()
                .map(|&b| fit(b))
                .min_by(|a, b| cost(a).total_cmp(&cost(b)))
                .unwrap_or_default()
        }
    }

    proptest::proptest! {
        #[test]
        fn the_packer_places_every_slot_where_a_search_from_zero_does(
            drones in proptest::collection::vec((7u8..=12, 0.5f64..1.5, 0usize..4), 1..160),
            scale in 0.3f64..3.0,
        ) {
            // Each SF's time on air (with some spread, as payloads differ) and an interval
            // from a 1 %, 0.1 % or fair-use-like duty cycle, some channels crowded (scale < 1).
            let duty = [0.01, 0.001, 0.0003, 0.05];
            let need: Vec<f64> = drones
                .iter()
                .map(|&(sf, k, d)| 0.0617 * f64::from(1u32 << (sf - 7)) * k / duty[d])
                .collect();
            let len: Vec<f64> = drones
                .iter()
                .map(|&(sf, k, _)| 0.0617 * f64::from(1u32 << (sf - 7)) * k + guard_s(20.0))
                .collect();
            let periods = nested_periods(&need);
            proptest::prop_assert_eq!(&periods, &searched_from_zero::nested_periods(&need));
            let scaled: Vec<f64> = periods.iter().map(|p| p * scale).collect();
            proptest::prop_assert_eq!(pack(&scaled, &len), searched_from_zero::pack(&scaled, &len));
        }
    }
}
