//! One station's outcome pooled over every flight of a run.

use super::caveats::{Caveats, Saturation};
use super::packet::Transmission;
use super::radio::Frame;
use super::report::{
    packet_mean, Boxplots, DataRateUse, Delivery, Energy, FrameTiming, ModelResult, ModelSeries,
};
use super::sender::SenderKind;
use super::station::{StationModel, StationTrack};
use crate::lora::DataRate;
use crate::metrics::{
    bootstrap_sorted, sort_total, station_draws, Consistency, SeedSpan, Summary, WholeFlightError,
};
use crate::models::ModelKind;
use std::collections::BTreeMap;

/// At most this many points per time series returned for plotting.
pub(crate) const MAX_SERIES_POINTS: usize = 3000;

/// Errors, coverage and packet counts of one station, gathered run by run (each flight of each
/// seed).
#[derive(Default)]
pub(crate) struct Pooled {
    /// How the runs' drone sent: what the lost packets cost depends on it ([`Caveats::of`]).
    sender: SenderKind,
    e3: Vec<f64>,
    /// Where each run's 3D errors end in `e3`: the units the intervals resample.
    run_ends: Vec<usize>,
    /// Evaluation times with no packet yet, run by run.
    untracked: Vec<usize>,
    /// Each seed's runs (`run_ends` indices), once a seed's flights are all added: the units the
    /// whole-flight draws resample.
    seeds: Vec<SeedSpan>,
    ex: Vec<f64>,
    ey: Vec<f64>,
    ez: Vec<f64>,
    consistency: Consistency,
    probability_sum: Option<[f64; 3]>,
    sent: usize,
    received: usize,
    /// Of `received`, those that saturated a payload field.
    saturation: Saturation,
    /// Of `sent`, those with a smaller payload than the model's own.
    lean: usize,
    /// The shortest lean frame at each data rate (spreading factor, bandwidth in kHz).
    lean_frames: BTreeMap<(u8, u64), FrameTiming>,
    /// Charge and awake time summed over every uplink, and seconds flown.
    charge_mc: f64,
    active_s: f64,
    flight_time: f64,
    /// From each flight's first packet sent to its last, s, summed, and the gaps between
    /// them: the mean time between packets is their ratio.
    sending_span: f64,
    gaps: usize,
    /// Packets and receptions per data rate, slowest first.
    rates: RateTally,
}

/// Packets and receptions per data rate, slowest first (higher SF, then narrower band): a
/// result's `dataRateUse`, a station's or a swarm drone's.
#[derive(Clone, Debug, Default)]
pub(crate) struct RateTally {
    rates: BTreeMap<(u8, u64), DataRateUse>,
    frames: FrameTally,
}

impl RateTally {
    /// Counts one transmission at its rate.
    pub fn add(&mut self, t: &Transmission) {
        self.frames.add(t);
        let key = (12 - t.sf.get(), t.bw.khz() as u64);
        let e = self.rates.entry(key).or_insert_with(|| DataRateUse {
            dr: t.data_rate().map(DataRate::index),
            sf: t.sf.get(),
            bw: t.bw.khz(),
            packets: 0,
            received: 0,
            time_on_air: t.time_on_air,
            interval: t.interval,
        });
        e.packets += 1;
        e.received += usize::from(t.received);
        // A lean payload's frame is shorter: the rate's own is the longest.
        e.time_on_air = e.time_on_air.max(t.time_on_air);
        e.interval = e.interval.max(t.interval);
    }

    /// The time on air of every transmission counted, s.
    pub fn airtime(&self) -> f64 {
        self.frames.airtime()
    }

    /// The rates used, slowest first.
    pub fn into_vec(self) -> Vec<DataRateUse> {
        self.rates.into_values().collect()
    }
}

/// Transmissions by rate and frame length, for their time on air: a count times each length,
/// where a sum of as many equal lengths would round differently from run to run.
#[derive(Clone, Debug, Default)]
struct FrameTally(BTreeMap<(u8, u64, u64), usize>);

impl FrameTally {
    fn add(&mut self, t: &Transmission) {
        let key = (12 - t.sf.get(), t.bw.khz() as u64, t.time_on_air.to_bits());
        *self.0.entry(key).or_insert(0) += 1;
    }

    fn airtime(&self) -> f64 {
        self.0
            .iter()
            .map(|(&(_, _, bits), &n)| n as f64 * f64::from_bits(bits))
            .sum()
    }
}

impl Pooled {
    /// An empty pool for a station whose drone sends by `sender`.
    pub fn new(sender: SenderKind) -> Self {
        Pooled {
            sender,
            ..Pooled::default()
        }
    }

    /// Adds one drone's transmissions and station track over `flight_time` s.
    pub fn add(&mut self, tx: &[Transmission], st: StationTrack, flight_time: f64) {
        self.sent += tx.len();
        self.received += tx.iter().filter(|t| t.received).count();
        self.lean += tx.iter().filter(|t| t.payload.is_some()).count();
        self.flight_time += flight_time;
        // From first to last, whatever order they came in: the gaps between them sum to it.
        let sent = tx.iter().map(|t| t.sent);
        if let (Some(first), Some(last)) = (sent.clone().reduce(f64::min), sent.reduce(f64::max)) {
            self.sending_span += last - first;
            self.gaps += tx.len() - 1;
        }
        for t in tx {
            self.charge_mc += t.charge_mc;
            self.active_s += t.active_s;
            self.rates.add(t);
            self.saturation.count(t);
            if t.payload.is_some() {
                self.add_lean_frame(t);
            }
        }
        let [ex, ey, ez] = st.error_axes;
        for (pool, run) in [
            (&mut self.e3, st.error3d),
            (&mut self.ex, ex),
            (&mut self.ey, ey),
            (&mut self.ez, ez),
        ] {
            append(pool, run);
        }
        self.run_ends.push(self.e3.len());
        self.untracked.push(st.untracked);
        self.consistency.merge(&st.consistency);
        if let Some(p) = st.probability_sum {
            let sum = self.probability_sum.get_or_insert([0.0; 3]);
            for k in 0..3 {
                sum[k] += p[k];
            }
        }
    }

    /// Marks the runs added since the last call (or the first run) as one seed's flights.
    pub fn end_seed(&mut self) {
        let first = self.seeds.last().map_or(0, |s| s.end);
        self.seeds.push(first..self.run_ends.len());
    }

    /// The energy of what was added.
    pub fn energy(&self) -> Energy {
        Energy::from_sums(self.sent, self.charge_mc, self.active_s, self.flight_time)
    }

    /// Each run's 3D errors in ascending order, in the order the runs were added (runs without
    /// errors left empty): the samples the intervals resample, this station's alone (`ci95`)
    /// and drawn alike for every station of the run ([`Draws`]). `None` with fewer than two
    /// runs that have errors (one run cannot show its own spread), so that a single long flight
    /// is not copied. Read before `e3` itself is sorted.
    fn run_errors(&self) -> Option<Vec<Vec<f64>>> {
        let spans: Vec<(usize, usize)> = self
            .run_ends
            .iter()
            .scan(0, |from, &to| Some((std::mem::replace(from, to), to)))
            .collect();
        if spans.iter().filter(|(a, b)| b > a).count() < 2 {
            return None;
        }
        Some(
            spans
                .into_iter()
                .map(|(a, b)| {
                    let mut run = self.e3[a..b].to_vec();
                    sort_total(&mut run);
                    run
                })
                .collect(),
        )
    }

    /// Keeps `t`'s frame when it is the shortest lean one at its rate so far.
    fn add_lean_frame(&mut self, t: &Transmission) {
        let timing = FrameTiming {
            time_on_air: t.time_on_air,
            interval: t.interval,
        };
        let key = (t.sf.get(), t.bw.khz() as u64);
        let shortest = self.lean_frames.entry(key).or_insert(timing);
        if timing.time_on_air < shortest.time_on_air {
            *shortest = timing;
        }
    }

    /// The result row of `model`, whose drone started each flight with `start` (its time on air
    /// and interval are the row's) and whose filters repaired their covariance
    /// `filter_recoveries` times; `network` the gateways' counts and the duplicates of this
    /// station's run; `seed` draws the intervals' resamples.
    pub fn finish(
        mut self,
        model: StationModel,
        start: &Frame,
        filter_recoveries: u64,
        network: &Delivery,
        seed: u64,
    ) -> ModelResult {
        let Frame {
            time_on_air,
            interval,
            ..
        } = *start;
        let lean_frame = self
            .lean_frames
            .get(&(start.sf.get(), start.bw.khz() as u64))
            .copied();
        let energy = self.energy();
        let runs = self.run_errors();
        let delivery = self.delivery(network);
        let model_probability = self.model_probability();
        let airtime = self.rates.airtime();
        let data_rate_use = self.rates.into_vec();
        let (s3, sx, sy, sz) = (
            Summary::of(&mut self.e3),
            Summary::of(&mut self.ex),
            Summary::of(&mut self.ey),
            Summary::of(&mut self.ez),
        );
        // Summary::of left e3 sorted: the pooled sample the intervals need, not sorted twice.
        let refs: Option<Vec<&[f64]>> = runs
            .as_ref()
            .map(|runs| runs.iter().map(Vec::as_slice).collect());
        let ci95 = refs
            .as_ref()
            .and_then(|refs| bootstrap_sorted(refs, &self.e3, seed));
        let (draws, whole_flight_draws) = refs.map_or((None, None), |refs| {
            station_draws(&refs, &self.e3, &self.untracked, &self.seeds, seed)
        });
        let mut result = ModelResult {
            model,
            payload_bytes: model.payload_bytes(),
            lean_packets: self.lean,
            time_on_air,
            interval,
            mean_interval: packet_mean(&data_rate_use, |u| u.interval),
            mean_time_on_air: packet_mean(&data_rate_use, |u| u.time_on_air),
            sent_every: if self.gaps == 0 {
                f64::NAN
            } else {
                self.sending_span / self.gaps as f64
            },
            sent_slower: false,
            lean_frame,
            airtime,
            error3d: s3,
            whole_flight: WholeFlightError::of_sorted(&self.e3, self.untracked.iter().sum()),
            whole_flight_draws,
            caveats: Caveats::of(self.received, self.sent, self.sender, self.saturation),
            ci95,
            // Set across the stations, once all are pooled (versus_lowest).
            p75_vs_lowest: None,
            draws,
            error_x: sx,
            error_y: sy,
            error_z: sz,
            // Summary::of left each sample sorted.
            boxplot: Boxplots::of_sorted(&self.e3, &self.ex, &self.ey, &self.ez),
            filter_recoveries,
            coverage95: self.consistency.coverage95(),
            under_bound95: self.consistency.under_bound95(),
            nees: self.consistency.mean_nees(),
            data_rate_use,
            delivery,
            energy,
            model_probability,
        };
        // Decided once from the fields it compares; the CLI and the page read the flag.
        result.sent_slower = result.sends_slower();
        result
    }

    /// This station's packets, with the network's duplicates and gateway counts.
    fn delivery(&self, network: &Delivery) -> Delivery {
        Delivery {
            packets_sent: self.sent,
            packets_received: self.received,
            delivery_ratio: super::report::ratio(self.received, self.sent),
            duplicates: network.duplicates,
            gateways: network.gateways.clone(),
        }
    }

    /// A multiple-model station's mean probability of each model over the evaluation times.
    fn model_probability(&self) -> Option<BTreeMap<&'static str, f64>> {
        let n = self.e3.len().max(1) as f64;
        self.probability_sum.map(|sum| {
            ModelKind::ALL
                .iter()
                .zip(sum)
                .map(|(m, s)| (m.name(), s / n))
                .collect()
        })
    }
}

/// Seconds on air of `tx`, summed per data rate and frame length (packets × time on air, slowest
/// rate first), as a station's result counts it.
pub(crate) fn airtime<'a>(tx: impl Iterator<Item = &'a Transmission>) -> f64 {
    let mut frames = FrameTally::default();
    tx.for_each(|t| frames.add(t));
    frames.airtime()
}

/// Keep every this many samples of `len` so that at most [`MAX_SERIES_POINTS`] remain.
pub(crate) fn series_stride(len: usize) -> usize {
    len.div_ceil(MAX_SERIES_POINTS).max(1)
}

/// Component `k` (0 x, 1 y, 2 z) of every `every`-th point.
pub(crate) fn axis_every(points: &[[f64; 3]], k: usize, every: usize) -> Vec<f64> {
    points.iter().step_by(every).map(|p| p[k]).collect()
}

/// Appends `run` to `pool`, taking it whole when the pool is empty: a long flight's errors are
/// then never held twice.
fn append(pool: &mut Vec<f64>, run: Vec<f64>) {
    if pool.is_empty() {
        *pool = run;
    } else {
        pool.extend_from_slice(&run);
    }
}

/// The samples of a station's error series that its plot keeps: every one up to
/// [`MAX_SERIES_POINTS`]; beyond, the flight is cut into `MAX_SERIES_POINTS / 2` runs of
/// consecutive samples and each keeps its lowest and its highest error, in time order (min-max
/// decimation, as plotting libraries thin a line to its envelope). Keeping every k-th sample
/// instead showed a long flight's saw-tooth error, which falls at each packet a few seconds
/// apart, at arbitrary points of its teeth: an hour at SF7 was sampled every 1.2 s, 10⁶ rows
/// every 13 s, and the peaks a reader looks for were mostly not among them.
pub(crate) fn series_picks(errors: &[f64]) -> Vec<usize> {
    if errors.len() <= MAX_SERIES_POINTS {
        return (0..errors.len()).collect();
    }
    let run = errors.len().div_ceil(MAX_SERIES_POINTS / 2);
    let by_error = |a: &(usize, &f64), b: &(usize, &f64)| a.1.total_cmp(b.1);
    let mut picks = Vec::with_capacity(MAX_SERIES_POINTS);
    for (r, chunk) in errors.chunks(run).enumerate() {
        let low = chunk
            .iter()
            .enumerate()
            .min_by(by_error)
            .map_or(0, |(i, _)| i);
        let high = chunk
            .iter()
            .enumerate()
            .max_by(by_error)
            .map_or(0, |(i, _)| i);
        let (first, second) = (low.min(high), low.max(high));
        picks.push(r * run + first);
        if second != first {
            picks.push(r * run + second);
        }
    }
    picks
}

/// The plotted series of one station on one flight, at most [`MAX_SERIES_POINTS`] points of it
/// ([`series_picks`]).
pub(crate) fn model_series(
    model: StationModel,
    st: &StationTrack,
    tx: &[Transmission],
) -> ModelSeries {
    let picks = series_picks(&st.error3d);
    let pick = |v: &[f64]| picks.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let axis = |k: usize| {
        picks
            .iter()
            .map(|&i| st.estimate[i][k])
            .collect::<Vec<f64>>()
    };
    ModelSeries {
        model,
        t: pick(&st.times),
        samples: st.error3d.len(),
        error3d: pick(&st.error3d),
        bound95: pick(&st.bound95),
        x: axis(0),
        y: axis(1),
        z: axis(2),
        arrivals: tx
            .iter()
            .filter(|t| t.received)
            .map(|t| t.arrival)
            .collect(),
        lost: tx.iter().filter(|t| !t.received).map(|t| t.sent).collect(),
        arrival_dr: dr_of(tx.iter().filter(|t| t.received)),
        lost_dr: dr_of(tx.iter().filter(|t| !t.received)),
    }
}

fn dr_of<'a>(tx: impl Iterator<Item = &'a Transmission>) -> Vec<Option<u8>> {
    tx.map(|t| t.data_rate().map(DataRate::index)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_series_is_plotted_whole() {
        let errors: Vec<f64> = (0..MAX_SERIES_POINTS).map(|i| (i % 31) as f64).collect();
        assert_eq!(
            series_picks(&errors),
            (0..MAX_SERIES_POINTS).collect::<Vec<_>>()
        );
    }

    #[test]
    fn a_long_saw_tooth_keeps_every_run_s_lowest_and_highest_error_in_time_order() {
        // An hour at 10 Hz of an error that grows for 3.1 s and falls at each packet, its peaks
        // rising slowly: every 12th sample (the stride that fits) would land on the teeth anywhere.
        let errors: Vec<f64> = (0..36_000)
            .map(|i| (i % 31) as f64 * 0.1 + i as f64 * 1e-4)
            .collect();
        let picks = series_picks(&errors);
        assert!(picks.len() <= MAX_SERIES_POINTS, "{}", picks.len());
        assert!(picks.windows(2).all(|w| w[0] < w[1]), "in time order");
        let run = errors.len().div_ceil(MAX_SERIES_POINTS / 2);
        for (r, chunk) in errors.chunks(run).enumerate() {
            let kept: Vec<f64> = picks
                .iter()
                .filter(|&&i| i / run == r)
                .map(|&i| errors[i])
                .collect();
            let high = chunk.iter().copied().fold(f64::MIN, f64::max);
            let low = chunk.iter().copied().fold(f64::MAX, f64::min);
            assert!(
                kept.contains(&high) && kept.contains(&low),
                "run {r}: {kept:?}"
            );
        }
        let top = errors.iter().copied().fold(f64::MIN, f64::max);
        assert!(
            picks.iter().any(|&i| errors[i] == top),
            "the largest error is plotted"
        );
    }
}
