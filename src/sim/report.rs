//! The JSON shapes of `simulate` and `sweep` (reference §9): a contract, changed only additively.

use super::caveats::Caveats;
use super::network::{GatewayReport, Network};
use super::packet::Transmission;
use super::scenario::Scenario;
use super::station::StationModel;
use super::versus_lowest::{versus_lowest, Contender, VersusLowest};
use crate::lora::SX1276_SLEEP_CURRENT_MA;
use crate::metrics::{Boxplot, Draws, Intervals, Summary, WholeFlightDraws, WholeFlightError};
use crate::trajectory::Cornering;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Echo of the settings (every key of [`Scenario`], flat, as given), plus what the run covered.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct RunConfig {
    /// The settings. In `simulate` the swarm keys say what was flown: one drone (`drones` 1,
    /// `sfPlan` `fixed`, `duration` the flight time).
    #[serde(flatten)]
    pub settings: Scenario,
    /// Flight(s) simulated, by name.
    pub trajectory: String,
    /// Number of flights.
    pub flights: usize,
    /// Seconds of flight simulated (all flights).
    pub flight_time: f64,
    /// Stations run.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName[]"))]
    pub models: Vec<StationModel>,
    /// Bandwidth, kHz (as `bw`).
    pub bandwidth_khz: f64,
    /// Tilt decay per second, eta^(1/T).
    pub eta_per_second: f64,
    /// Gateway sensitivity for this SF and bandwidth, dBm.
    pub sensitivity_dbm: f64,
    /// Range where the mean received power meets the sensitivity, m.
    pub range_m: f64,
    /// The regional plan's data rate at `sf`/`bw` (with ADR: the start), `null` for raw LoRa
    /// outside the plan's data rates (EU868 allows it: the paper's SF8 at 250 kHz).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub data_rate: Option<u8>,
    /// The most seeds these flights take at these sensor and station rates within the work
    /// limit (`MAX_FILTER_STEPS`), at most the seeds setting's 100: how far `seeds` may be raised
    /// (the whole synthetic set at the defaults: 18).
    pub max_seeds: u32,
    /// How the drone's plan (`plan`) is flown and followed: as a multicopter flies it, or as a
    /// plane does ([`Cornering::FixedWing`]: `vehicle` `fixed-wing`, or a QGroundControl `.plan`
    /// for a fixed-wing vehicle with `vehicle` `auto`); `null` without a plan.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Cornering | null"))]
    pub plan_cornering: Option<Cornering>,
}

/// The drone radio's charge (SX1276 currents; `docs/reference.md` §7).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Energy {
    /// Mean charge of one uplink with its receive windows, mC (`null` when no uplink was sent:
    /// there is no uplink to average, and 0 would read as free).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub charge_per_uplink: f64,
    /// Charge per hour of tracking (uplinks, windows and sleep between), mAh (`null` for no
    /// flight time; a flight with no uplink slept throughout).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub charge_per_hour: f64,
}

impl Energy {
    /// The charge of `tx` over `flight_time` s of flight (sleeping when not sending or
    /// listening); no charge per uplink (NaN) without an uplink, no charge per hour (NaN)
    /// without flight time.
    pub fn of<'a>(tx: impl Iterator<Item = &'a Transmission>, flight_time: f64) -> Self {
        let (mut n, mut charge, mut active) = (0usize, 0.0, 0.0);
        for t in tx {
            n += 1;
            charge += t.charge_mc;
            active += t.active_s;
        }
        Self::from_sums(n, charge, active, flight_time)
    }

    /// The same from `n` uplinks' summed charge (mC) and awake time (s).
    ///
    /// ```
    /// use loratrack::Energy;
    /// let silent = Energy::from_sums(0, 0.0, 0.0, 3600.0);
    /// assert!(silent.charge_per_uplink.is_nan());
    /// assert!((silent.charge_per_hour - 0.0002).abs() < 1e-12); // the radio asleep for the hour
    /// ```
    pub fn from_sums(n: usize, charge: f64, active: f64, flight_time: f64) -> Self {
        let sleep = SX1276_SLEEP_CURRENT_MA * (flight_time - active).max(0.0);
        Energy {
            charge_per_uplink: if n == 0 { f64::NAN } else { charge / n as f64 },
            // mA·s over the flight, per second of flight, is the mean current in mA, which is
            // the charge per hour in mAh.
            charge_per_hour: if flight_time > 0.0 {
                (charge + sleep) / flight_time
            } else {
                f64::NAN
            },
        }
    }
}

/// Packets and copies over the whole network (JSON, at the top of `simulate` and `swarm`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Delivery {
    /// Uplinks sent by every drone.
    pub packets_sent: usize,
    /// Distinct uplinks the network server passed on (each once, however many gateways heard it).
    pub packets_received: usize,
    /// `packetsReceived / packetsSent` (`null` when nothing was sent: no share of nothing).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    #[serde(deserialize_with = "nan_for_null")]
    pub delivery_ratio: f64,
    /// Copies the server removed: receptions beyond the first of each packet.
    pub duplicates: usize,
    /// Per gateway.
    pub gateways: Vec<GatewayReport>,
}

/// Equal counts: the ratio follows from them (and NaN, for nothing sent, equals nothing).
impl PartialEq for Delivery {
    fn eq(&self, other: &Self) -> bool {
        (self.packets_sent, self.packets_received, self.duplicates)
            == (other.packets_sent, other.packets_received, other.duplicates)
            && self.gateways == other.gateways
    }
}

impl Default for Delivery {
    /// Nothing sent, so no delivery ratio.
    fn default() -> Self {
        Delivery {
            packets_sent: 0,
            packets_received: 0,
            delivery_ratio: f64::NAN,
            duplicates: 0,
            gateways: Vec::new(),
        }
    }
}

impl Delivery {
    /// What `net` counted: copies removed and per-gateway counts (the packet counts are the
    /// stations' to add).
    pub fn counted(net: &Network) -> Self {
        Delivery {
            duplicates: net.duplicates,
            gateways: net.gateways.clone(),
            ..Delivery::default()
        }
    }

    /// The network's totals over `runs` (each station's, or each flight's): packets, copies and
    /// every gateway's counts added up. A `simulate` report's top-level counts are its stations'
    /// pooled this way, and the page's worker pool, which runs the stations apart, pools their
    /// results with it too (JS `poolDelivery`).
    ///
    /// ```
    /// use loratrack::Delivery;
    /// let run = |packets_sent, packets_received| Delivery {
    ///     packets_sent,
    ///     packets_received,
    ///     ..Delivery::default()
    /// };
    /// let total = Delivery::pooled(&[run(10, 9), run(30, 21)]);
    /// assert_eq!((total.packets_sent, total.packets_received), (40, 30));
    /// assert_eq!(total.delivery_ratio, 0.75);
    /// ```
    pub fn pooled<'a>(runs: impl IntoIterator<Item = &'a Delivery>) -> Delivery {
        let mut total = Delivery::default();
        runs.into_iter().for_each(|r| total.add(r));
        total
    }

    /// Adds another run's counts (same gateways).
    pub fn add(&mut self, other: &Delivery) {
        self.packets_sent += other.packets_sent;
        self.packets_received += other.packets_received;
        self.duplicates += other.duplicates;
        if self.gateways.is_empty() {
            self.gateways = other.gateways.clone();
        } else {
            for (a, b) in self.gateways.iter_mut().zip(&other.gateways) {
                a.add(b);
            }
        }
        self.delivery_ratio = ratio(self.packets_received, self.packets_sent);
    }
}

/// `n / of`, NaN (JSON `null`) when `of` is 0: a share of no packets is not 0 %.
pub fn ratio(n: usize, of: usize) -> f64 {
    if of == 0 {
        f64::NAN
    } else {
        n as f64 / of as f64
    }
}

/// Reads a number that JSON carries as `null` where the core wrote NaN ([`ratio`]), so that a
/// report read back (the page's pooled stations, `poolDelivery`) keeps its NaN.
fn nan_for_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// Per-axis and 3D boxplots.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Boxplots {
    /// 3D error.
    pub error3d: Boxplot,
    /// |x error|.
    pub error_x: Boxplot,
    /// |y error|.
    pub error_y: Boxplot,
    /// |z error|.
    pub error_z: Boxplot,
}

impl Boxplots {
    /// Boxplots of the four error samples, each already in ascending order.
    pub fn of_sorted(e3: &[f64], ex: &[f64], ey: &[f64], ez: &[f64]) -> Self {
        Boxplots {
            error3d: Boxplot::of_sorted(e3),
            error_x: Boxplot::of_sorted(ex),
            error_y: Boxplot::of_sorted(ey),
            error_z: Boxplot::of_sorted(ez),
        }
    }
}

/// One model's outcome.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct ModelResult {
    /// The station: `dr`, `ctra-plus`, `3d-ctra` or `imm`.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub model: StationModel,
    /// Payload, bytes.
    pub payload_bytes: usize,
    /// Packets that left out the manoeuvre fields within their significance and went with
    /// DR's or CTRA+'s smaller payload (`--payload lean`, reference §5); 0 with the full payload.
    pub lean_packets: usize,
    /// Time on air of one packet (payload + overhead), s (with ADR: at the starting data rate).
    /// With lean payloads a full packet's; the shortest lean one is the next field's.
    pub time_on_air: f64,
    /// Interval between transmissions under the duty cycle, s (with ADR: at the starting data
    /// rate). With lean payloads a full packet's; the shortest lean one is the next field's.
    pub interval: f64,
    /// The duty-cycle interval over the packets sent, s: the mean of `dataRateUse`'s intervals,
    /// each rate's weighted by its packets. With ADR it says how often the drone could send
    /// where `interval` is the starting rate's; at a fixed rate it is `interval`. `null` when no
    /// packet was sent.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub mean_interval: f64,
    /// The time on air over the packets sent, s, weighted alike (`null` when none was sent).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub mean_time_on_air: f64,
    /// The mean time between two packets the drone sent in one flight, s (`null` where no
    /// flight sent two): how often it did send, where `interval` is how often it may. Longer
    /// than the interval where a packet waits for a sensor step (reference §6.4: at 1 Hz SF7's
    /// 3.08 s become 4 s), where error-triggered sending waits for its threshold, where ADR
    /// slowed the rate or a random delay falls between packets.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub sent_every: f64,
    /// Whether the packets went notably less often than the interval the tables show
    /// (`meanInterval`, or `interval` where none was sent): `sentEvery` over `SENT_EVERY_NOTED`
    /// times it (src/sim/report.rs), so that the interval alone would mislead a reader counting
    /// packets.
    /// Decided once, here; the CLI's line under a station and the page's "sent every" read it.
    pub sent_slower: bool,
    /// With `--payload lean`, the shortest frame a lean packet took at the starting data rate
    /// (reference §5); `null` when no lean packet went there.
    pub lean_frame: Option<FrameTiming>,
    /// Total time on air of the packets sent over all flights, s.
    pub airtime: f64,
    /// 3D error, m, at the evaluation times after each flight's first packet arrived.
    pub error3d: Summary,
    /// The share of the flight time with a packet, and the 3D error's percentiles over the
    /// whole flight time (time before a flight's first packet counting as the largest error).
    pub whole_flight: WholeFlightError,
    /// `wholeFlight`'s p75 in each bootstrap draw of whole seeds, from which `sweep --distances`
    /// pairs an ADR mode with the best fixed rate (`docs/reference.md` §12); `None` for a single
    /// seed. Not serialised: the documents pair them in the process that ran them.
    #[serde(skip)]
    pub whole_flight_draws: Option<WholeFlightDraws>,
    /// What these numbers rest on, where a reader could be misled: too few packets received, an
    /// error-triggered drone whose packets were lost ([`Caveats`]).
    pub caveats: Caveats,
    /// 95 % intervals of `error3d`'s statistics, by bootstrap over the runs (flights × seeds)
    /// pooled in it (`docs/reference.md` §12); `null` for a single run, which cannot show its
    /// own spread.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Intervals | null"))]
    pub ci95: Option<Intervals>,
    /// This station's p75 against the lowest station's on the same runs, with the ratio's 95 %
    /// interval from resampling both together (`docs/reference.md` §12); `null` for the lowest
    /// station itself, a station alone, a single run, or errors in fewer than two runs.
    #[cfg_attr(
        all(test, not(target_arch = "wasm32")),
        ts(type = "VersusLowest | null")
    )]
    pub p75_vs_lowest: Option<VersusLowest>,
    /// The p75 and p95 of each bootstrap draw of the runs, drawn alike for every station of the
    /// run (and of any run of the same seeds and flights), from which `p75VsLowest` is paired
    /// (`docs/reference.md` §12; the page pairs the stations its workers ran apart with
    /// `versusLowest`); `null` where `ci95` is.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Draws | null"))]
    pub draws: Option<Draws>,
    /// |x error|, m.
    pub error_x: Summary,
    /// |y error|, m.
    pub error_y: Summary,
    /// |z error|, m.
    pub error_z: Summary,
    /// Boxplot statistics of the same samples.
    pub boxplot: Boxplots,
    /// Covariance repairs in the drone filter (0 in a healthy run).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number"))]
    pub filter_recoveries: u64,
    /// Fraction of evaluated steps whose true position lay inside the station's 95 % position
    /// ellipsoid (chi-square, 3 degrees of freedom); a consistent station scores near 0.95,
    /// an overconfident one lower. `null` when nothing was evaluated.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub coverage95: f64,
    /// Fraction of the same steps whose error was no longer than the station's own 95 % bound
    /// (`bound95` of the series, the error chart's band: docs/reference.md §12); an honest
    /// station's Gaussian error scores near 0.95. `null` when nothing was evaluated.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub under_bound95: f64,
    /// Mean normalised estimation error squared of the station's position (Bar-Shalom et al.
    /// 2001, §5.4) over the same steps: 3 for a station whose covariance is honest, above 3 when
    /// it claims too little uncertainty, below 3 too much. `null` when nothing was evaluated.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub nees: f64,
    /// The packets sent at each data rate (one entry without ADR), slowest rate first.
    pub data_rate_use: Vec<DataRateUse>,
    /// Packets, copies and gateways of this station's run.
    #[serde(flatten)]
    pub delivery: Delivery,
    /// The drone radio's charge.
    pub energy: Energy,
    /// IMM only: the mean probability of each member over the evaluated steps.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(
        all(test, not(target_arch = "wasm32")),
        ts(type = "Partial<Record<MotionModelName, number>>", optional)
    )]
    pub model_probability: Option<BTreeMap<&'static str, f64>>,
}

/// How much longer than the duty-cycle interval the packets' mean spacing (`sentEvery`) must be
/// before the CLI's line under a station and the page's interval cell say how often they went:
/// above the 3.5 % a 10 Hz sensor step adds at most to an EU868 interval at 250 kHz (SF7, DR's 9
/// bytes: 2.83 → 2.9 s with LoRaWAN's overhead, 2.06 → 2.1 s without), so the defaults and the
/// paper's settings show the interval alone; at 500 kHz DR's 1.41 s become 1.5 s (6 %), and at
/// 1 Hz SF7's 3.08 s become 4 s (30 %), which are said.
pub const SENT_EVERY_NOTED: f64 = 1.05;

/// Sets [`ModelResult::p75_vs_lowest`] across the stations of one run.
pub(crate) fn set_versus_lowest(results: &mut [ModelResult]) {
    let stations: Vec<Contender> = results
        .iter()
        .map(|r| Contender {
            model: r.model,
            p75: r.error3d.p75,
            count: r.error3d.count,
            draws: r.draws.clone(),
        })
        .collect();
    for (r, v) in results.iter_mut().zip(versus_lowest(&stations)) {
        r.p75_vs_lowest = v;
    }
}

impl ModelResult {
    /// The 95 % interval of this station's statistic over `other`'s, by `interval`
    /// ([`Draws::p75_ratio_interval`] or [`Draws::p95_ratio_interval`]): their runs resampled
    /// alike, which pairs them where both ran on the same flights and seeds (`docs/reference.md`
    /// §12); `None` where either has too few runs, or they were drawn otherwise.
    pub fn paired_interval(
        &self,
        other: &ModelResult,
        interval: fn(&Draws, &Draws) -> Option<[f64; 2]>,
    ) -> Option<[f64; 2]> {
        interval(self.draws.as_ref()?, other.draws.as_ref()?)
    }

    /// The duty-cycle interval the tables show, s: the mean over the packets sent
    /// (`meanInterval`, which with ADR spans the rates used), or the starting rate's where the
    /// drone sent nothing.
    pub fn interval_shown(&self) -> f64 {
        if self.mean_interval.is_finite() {
            self.mean_interval
        } else {
            self.interval
        }
    }

    /// Whether packets spaced `sent_every` s apart went notably less often than
    /// [`Self::interval_shown`]: the value of the field `sent_slower`.
    ///
    /// ```
    /// use loratrack::{api, Scenario, Simulator};
    /// // At 1 Hz a packet waits for a whole-second sensor step: 3D-CTRA's 3.08 s become 4 s.
    /// let s = Scenario::from_json(r#"{"synthetic": 1, "sensorRate": 1, "model": "3d-ctra"}"#).unwrap();
    /// let r = &api::simulate(&mut Simulator::new(), &s).unwrap().results[0];
    /// assert!((r.sent_every - 4.0).abs() < 1e-9 && r.sent_slower);
    /// // At the default 10 Hz, 3.1 s: the interval alone says it.
    /// let s = Scenario::from_json(r#"{"synthetic": 1, "model": "3d-ctra"}"#).unwrap();
    /// let r = &api::simulate(&mut Simulator::new(), &s).unwrap().results[0];
    /// assert!((r.sent_every - 3.1).abs() < 1e-9 && !r.sent_slower);
    /// ```
    pub(crate) fn sends_slower(&self) -> bool {
        self.sent_every > SENT_EVERY_NOTED * self.interval_shown()
    }
}

/// One model's time series over the first flight (for plots). In JavaScript every list of
/// numbers here is a `Float64Array` (`src/wasm.rs`); in the CLI's JSON, an array. At most 3000
/// evaluation times: a longer flight is cut into 1500 runs of them and each keeps its lowest and
/// highest error (min-max decimation), so that a plot of the series shows the error's envelope.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct ModelSeries {
    /// The station.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub model: StationModel,
    /// Evaluation times, s.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub t: Vec<f64>,
    /// The station's evaluation times on this flight, all of them: more than `t` holds when the
    /// series was thinned to its envelope (a flight of more than 3000).
    pub samples: usize,
    /// 3D error at each time, m.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub error3d: Vec<f64>,
    /// The station's own 95 % bound on that error at each time, m: the length an error with its
    /// position covariance stays under 95 % of the time ([`crate::bound_95`]).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub bound95: Vec<f64>,
    /// Estimated x, y, z at each time, m.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub x: Vec<f64>,
    /// See `x`.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub y: Vec<f64>,
    /// See `x`.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub z: Vec<f64>,
    /// Arrival times of received packets, s.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub arrivals: Vec<f64>,
    /// Send times of lost packets, s.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub lost: Vec<f64>,
    /// The EU868 data rate of each received packet (`null` for an SF/bandwidth that is none).
    pub arrival_dr: Vec<Option<u8>>,
    /// The data rate of each lost packet.
    pub lost_dr: Vec<Option<u8>>,
}

/// How many packets went at one data rate.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DataRateUse {
    /// EU868 data rate index (`null` when the SF and bandwidth form none, e.g. SF8 at 500 kHz).
    pub dr: Option<u8>,
    /// Spreading factor.
    pub sf: u8,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Packets sent at it.
    pub packets: usize,
    /// Of those, received.
    pub received: usize,
    /// Time on air of one packet at it, s: its longest (with `--payload lean` some are shorter).
    pub time_on_air: f64,
    /// The duty-cycle interval after that longest packet, s (reference §6.1): with ADR each
    /// rate's own, where the result's `interval` is the starting rate's.
    pub interval: f64,
}

/// The mean of `field` over `rates`' packets, each rate weighted by the packets sent at it; NaN
/// (JSON `null`) when none was sent.
pub(crate) fn packet_mean(rates: &[DataRateUse], field: impl Fn(&DataRateUse) -> f64) -> f64 {
    // One rate: its own value, bit for bit (n·x / n need not be x).
    if let [one] = rates {
        return field(one);
    }
    let sent: usize = rates.iter().map(|u| u.packets).sum();
    let total: f64 = rates.iter().map(|u| u.packets as f64 * field(u)).sum();
    total / sent as f64
}

/// One frame length's cost on air: how long the packet occupies the channel and the duty-cycle
/// interval it imposes before the next (reference §6.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct FrameTiming {
    /// Time on air, s.
    pub time_on_air: f64,
    /// The shortest interval the duty cycle allows after it, s.
    pub interval: f64,
}

/// Ground truth and every model's estimates over the first flight. In JavaScript `t`, `x`, `y`
/// and `z` (and each model's series) are `Float64Array`s; in the CLI's JSON, arrays.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Series {
    /// The flight.
    pub flight: String,
    /// Truth sample times, s (decimated to at most a few thousand points).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub t: Vec<f64>,
    /// True x, m.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub x: Vec<f64>,
    /// True y, m.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub y: Vec<f64>,
    /// True z, m.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Float64Array"))]
    pub z: Vec<f64>,
    /// The first gateway's position x, y, z, m (the flight's frame).
    pub gateway: [f64; 3],
    /// Every gateway's position x, y, z, m.
    pub gateways: Vec<[f64; 3]>,
    /// The waypoints of the plan the mission station flies over this flight, m (only when a
    /// mission station ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    pub plan: Option<Vec<[f64; 3]>>,
    /// Per model.
    pub models: Vec<ModelSeries>,
}

/// The output of `simulate`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SimReport {
    /// Settings and coverage.
    pub config: RunConfig,
    /// Packets and gateways over every station's run (each station's run is its own: the drone
    /// sends that station's payload).
    #[serde(flatten)]
    pub delivery: Delivery,
    /// One entry per model.
    pub results: Vec<ModelResult>,
    /// Time series of the first flight, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub series: Option<Series>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_delivery_of_nothing_sent_has_no_ratio_and_reads_back_from_its_json() {
        let none = Delivery::pooled(&[Delivery::default(), Delivery::default()]);
        assert!(none.delivery_ratio.is_nan());
        let json = serde_json::to_string(&none).unwrap();
        assert!(json.contains(r#""deliveryRatio":null"#), "{json}");
        // The page pools its workers' results through this JSON (`poolDelivery`).
        let back: Delivery = serde_json::from_str(&json).unwrap();
        assert!(back.delivery_ratio.is_nan());
        assert_eq!(back, none);
    }

    fn rate(dr: u8, packets: usize, interval: f64) -> DataRateUse {
        DataRateUse {
            dr: Some(dr),
            sf: 12 - dr,
            bw: 125.0,
            packets,
            received: packets,
            time_on_air: interval / 100.0,
            interval,
        }
    }

    #[test]
    fn the_packet_mean_weighs_each_rate_by_its_packets_and_keeps_a_lone_rate_bit_for_bit() {
        let used = [rate(0, 1, 148.28), rate(5, 9, 3.08)];
        let mean = packet_mean(&used, |u| u.interval);
        assert!((mean - (148.28 + 9.0 * 3.08) / 10.0).abs() < 1e-12);
        // 3 × 0.1 / 3 is not 0.1 in floating point; one rate is returned as it is.
        let one = [rate(6, 3, 0.1)];
        assert_eq!(
            packet_mean(&one, |u| u.interval).to_bits(),
            0.1f64.to_bits()
        );
        assert!(packet_mean(&[], |u| u.interval).is_nan());
    }
}
