//! Runs simulations and caches what does not depend on the link.

use super::cache_budget::{Ledger, MAX_CACHE_BYTES};
use super::drone::{run_drones, DroneTrack};
use super::pooled::{axis_every, series_stride, Pooled};
use super::report::{
    set_versus_lowest, Delivery, ModelResult, ModelSeries, RunConfig, Series, SimReport,
};
use super::scenario::{SfPlan, SwarmSettings, SyntheticChoice, TrajectorySource, Validated};
use super::schedule::Schedule;
use super::sender::ChannelSense;
use super::station::{
    drone_run_work, station_work, Estimate, FlightChains, HeadingNoise, Prediction, StationModel,
    MAX_GRIDS,
};
use super::station_run::{FlightRun, StationPlan, StationRun};
use super::streams::DroneStreams;
use super::{LongRun, SimError};
use crate::lora::Channel;
use crate::math::pow;
use crate::models::ModelKind;
use crate::options::{DISTANCE, MAX_FILTER_STEPS, SEEDS};
use crate::parallel::{
    enough_tasks, par_map, par_map_costliest_first, par_map_owned, par_map_progressing, ticks,
};
use crate::trajectory::{
    canberra_flight, fly_plan, parse_csv, parse_csv_with_progress, parse_plan_as, synthetic_flight,
    Cornering, FlightPlan, Trajectory, TrajectoryError, SYNTHETIC_FLIGHTS,
};
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::Mutex;

/// Cache sizes by count; past them the cache starts afresh (a page rarely alternates between
/// more). Together the caches also stay within [`MAX_CACHE_BYTES`], least recently used out.
/// Drone runs have no count of their own: a key is one seed's, so a run of 64 seeds and three
/// drone filters asks for 192, and a count of 24 emptied the cache eight times within that one
/// run, leaving the next run (another data rate, the same drones) to compute every one again
/// (`npm run reproduce`: 95.6 s of CPU, 64.8 s with the bytes alone deciding).
const MAX_CACHED_FLIGHTS: usize = 4;
const MAX_CACHED_STATIONS: usize = 6;
/// How many streamed keys are noted ([`Simulator::note_streamed`]): a run's keys at the most
/// seeds and every drone filter, so that a run asking for them again finds all of them noted.
const MAX_STREAMED_NOTES: usize = ModelKind::ALL.len() * SEEDS.max as usize;
/// A run's drone runs may take at most this fraction (1/n) of [`MAX_CACHE_BYTES`] together: a
/// 10⁶-row flight at 25 Hz (40 000 s; 29 MB per model at 10 Hz) streams its drones instead.
const MAX_DRONE_SHARE: usize = 4;
/// Bytes of one remembered drone estimate.
const DRONE_STEP_BYTES: usize = core::mem::size_of::<[f64; 9]>();
/// A station's remembered predictions may take at most this fraction (1/n) of
/// [`MAX_CACHE_BYTES`]: a long flight's (a 10⁶-row CSV at 25 Hz: ~200 MB) would otherwise evict
/// its own drone runs and every other station's, and be evicted by the next station's.
const MAX_STATION_SHARE: usize = 4;

/// A cached entry, for the byte budget.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Entry {
    Flights(FlightKey),
    CsvText(u64),
    Drones(DroneKey),
    Stations(StationKey),
}

/// A single-model station setting whose per-packet predictions can be reused
/// ([`FlightChains`]): the drone run it receives from and everything its prediction uses.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct StationKey {
    drone: DroneKey,
    model: ModelKind,
    prediction: Prediction,
    step: u64,
    eta: u64,
    q: u64,
    /// Whether the drone sends on error: a bounded station then follows its model.
    error_triggered: bool,
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum FlightKey {
    Synthetic(SyntheticChoice),
    Sample(String),
    /// One id per distinct CSV text this simulator has seen ([`Simulator::text_id`]).
    Csv(u64),
    /// A plan's text flown ([`fly_plan`]), by the same ids, and the vehicle it is flown as
    /// where set.
    Plan(u64, Option<Cornering>),
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct DroneKey {
    flights: FlightKey,
    model: ModelKind,
    sensor_rate: u64,
    q: u64,
    seed: u64,
}

/// FNV-1a: a 64-bit hash of CSV text, to find a remembered text quickly (equal texts are then
/// compared byte for byte).
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Runs simulations, keeping parsed flights and drone-side filter runs for reuse: a second
/// call that differs only in link or station settings costs only the link and the station.
#[derive(Default)]
pub struct Simulator {
    flights: HashMap<FlightKey, Rc<Vec<Trajectory>>>,
    /// The CSV texts behind `FlightKey::Csv` ids, with their hash: a hit compares the bytes, so
    /// two texts that share a hash never share results.
    csv_texts: Vec<(u64, Arc<str>, u64)>,
    next_csv_id: u64,
    drones: HashMap<DroneKey, Rc<Vec<DroneTrack>>>,
    /// Keys whose drone runs a run streamed because not all of its keys fitted
    /// ([`Simulator::drone_sets`]): asked for again, they are remembered.
    streamed: Vec<DroneKey>,
    stations: HashMap<StationKey, Rc<Vec<Mutex<FlightChains>>>>,
    drone_runs: u64,
    ledger: Ledger<Entry>,
    /// Told as each run ends, whoever started it ([`Simulator::on_each_run`]).
    run_done: Option<Box<dyn FnMut()>>,
}

/// The drone runs to compute, `missing`, grouped into the tasks that compute them over each of
/// `n` flights: keys that differ only in their model read the same sensors (the noise depends on
/// the seed and the flight alone), so one task per seed and flight reads them once for all of its
/// models (`run_drones`): a tenth of a whole-set run. With fewer such tasks than two per core
/// (one flight, say) each key keeps a task of its own, so that the models' filters run side by
/// side. Each group: its seed and its members' indices in `missing`.
fn sensor_groups(missing: &[&DroneKey], n: usize) -> Vec<(u64, Vec<usize>)> {
    let mut seeds: Vec<(u64, Vec<usize>)> = Vec::new();
    for (m, key) in missing.iter().enumerate() {
        match seeds.iter_mut().find(|(seed, _)| *seed == key.seed) {
            Some((_, members)) => members.push(m),
            None => seeds.push((key.seed, vec![m])),
        }
    }
    if enough_tasks(seeds.len() * n) {
        seeds
    } else {
        missing
            .iter()
            .enumerate()
            .map(|(m, key)| (key.seed, vec![m]))
            .collect()
    }
}

/// The distinct keys of `keys` whose drone runs (`steps` estimates each) may be remembered: as
/// many as fit in [`MAX_DRONE_SHARE`] of the budget together, the costliest filters first, since
/// they are what a later run with other link settings saves most by finding (a 10⁶-row flight at
/// 25 Hz, 29 MB per model: 3D-CTRA's and CTRA+'s, not DR's); and every distinct key.
fn remembered_keys(keys: &[DroneKey], steps: usize) -> (Vec<&DroneKey>, Vec<&DroneKey>) {
    let mut distinct: Vec<&DroneKey> = Vec::new();
    for key in keys {
        if !distinct.contains(&key) {
            distinct.push(key);
        }
    }
    let mut fit = distinct.clone();
    // Stable: keys of equal cost keep their order.
    fit.sort_by_key(|k| core::cmp::Reverse(drone_run_work(k.model)));
    let room = MAX_CACHE_BYTES / MAX_DRONE_SHARE;
    fit.truncate(room / steps.saturating_mul(DRONE_STEP_BYTES).max(1));
    (fit, distinct)
}

/// The sensor steps of all `flights` together: what one key's drone runs hold.
fn sensor_steps(flights: &[Trajectory], cfg: &Validated) -> usize {
    let rate = cfg.s().drone.sensor_rate;
    flights
        .iter()
        .map(|f| (f.duration() * rate + 1e-9).floor() as usize + 1)
        .sum()
}

/// The drone runs of every flight for each of `missing`, in its order and each in flight order,
/// computed in one parallel batch of [`sensor_groups`]; `tick` is called once per key and flight.
/// `None` where a tick asked to stop ([`par_map_ticking`](crate::parallel)).
fn run_missing(
    missing: &[&DroneKey],
    flights: &[Trajectory],
    cfg: &Validated,
    tick: &mut dyn FnMut() -> bool,
) -> Option<Vec<Vec<DroneTrack>>> {
    let n = flights.len();
    let seeds = sensor_groups(missing, n);
    let computed = par_map_costliest_first(
        seeds.len() * n,
        |k| {
            seeds[k / n]
                .1
                .iter()
                .map(|&m| drone_run_work(missing[m].model))
                .sum()
        },
        |k| {
            let ((seed, members), i) = (&seeds[k / n], k % n);
            let models: Vec<ModelKind> = members.iter().map(|&m| missing[m].model).collect();
            let streams = DroneStreams {
                seed: *seed,
                stream: i as u64,
            };
            run_drones(&flights[i], &models, &cfg.sensing(streams))
        },
        &mut |k| ticks(seeds[k / n].1.len(), tick),
    )?;
    // Task k is group k / n on flight k % n, its tracks in member order: dealt out in task
    // order, each key's tracks come in flight order.
    let mut tracks: Vec<Vec<DroneTrack>> = missing.iter().map(|_| Vec::with_capacity(n)).collect();
    for (k, task) in computed.into_iter().enumerate() {
        for (&m, track) in seeds[k / n].1.iter().zip(task) {
            tracks[m].push(track);
        }
    }
    Some(tracks)
}

impl Simulator {
    /// An empty simulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many drone-side filter runs (one per flight and model) this simulator has computed;
    /// lets tests and benchmarks check that the cache works.
    pub fn drone_runs(&self) -> u64 {
        self.drone_runs
    }

    /// Bytes its caches hold (an estimate from their sizes), at most [`MAX_CACHE_BYTES`] once a
    /// run is over.
    pub fn cached_bytes(&self) -> usize {
        self.ledger.total()
    }

    /// Calls `done` each time a run of this simulator ends, successful or not, including the
    /// runs a sweep makes on it (`api::sweep_paper` and the like), so that the CLI can count a
    /// sweep's runs while the person who started it waits.
    pub fn on_each_run(&mut self, done: impl FnMut() + 'static) {
        self.run_done = Some(Box::new(done));
    }

    /// Records `entry` at `bytes`, then forgets the least recently used entries (never `entry`)
    /// until the caches fit the budget.
    fn remember(&mut self, entry: Entry, bytes: usize) {
        self.ledger.insert(entry.clone(), bytes);
        while let Some(old) = self.ledger.over_budget(MAX_CACHE_BYTES, &entry) {
            self.ledger.remove(&old);
            match old {
                Entry::Flights(k) => drop(self.flights.remove(&k)),
                Entry::CsvText(id) => self.csv_texts.retain(|(_, _, i)| *i != id),
                Entry::Drones(k) => drop(self.drones.remove(&k)),
                Entry::Stations(k) => drop(self.stations.remove(&k)),
            }
        }
    }

    /// The id of `text` (a CSV flight or a plan) whose hash is `hash`: the id it was given before
    /// if the same text is remembered, otherwise a fresh one (the oldest text is forgotten past
    /// the cache size).
    fn text_id(&mut self, text: &Arc<str>, hash: u64) -> u64 {
        if let Some((_, _, id)) = self
            .csv_texts
            .iter()
            .find(|(h, t, _)| *h == hash && t == text)
        {
            let id = *id;
            self.ledger.touch(&Entry::CsvText(id));
            return id;
        }
        if self.csv_texts.len() >= MAX_CACHED_FLIGHTS {
            let (_, _, id) = self.csv_texts.remove(0);
            self.ledger.remove(&Entry::CsvText(id));
        }
        let id = self.next_csv_id;
        self.next_csv_id += 1;
        self.csv_texts.push((hash, Arc::clone(text), id));
        self.remember(Entry::CsvText(id), text.len());
        id
    }

    /// Reads CSV `text` (named `name`) into the flight cache, calling `progress(lines read,
    /// lines)` as it goes, so that a following `simulate` of the same text starts at once. A
    /// page calls it first for a large file, to show how far the reading is. The flight's row
    /// count; [`SimError::Stopped`] where `progress` returned `false` (nothing is cached then).
    pub fn load_csv(
        &mut self,
        text: Arc<str>,
        name: String,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<usize, SimError> {
        let source = TrajectorySource::Csv(text, name);
        let (_, flights) = self.flights(&source, progress)?;
        Ok(flights.iter().map(|f| f.t.len()).sum())
    }

    /// The flights of `source`, from the cache or read (a CSV text with `progress`, which may stop
    /// the reading: [`SimError::Stopped`]).
    fn flights(
        &mut self,
        source: &TrajectorySource,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<(FlightKey, Rc<Vec<Trajectory>>), SimError> {
        let key = match source {
            TrajectorySource::Synthetic(c) => FlightKey::Synthetic(*c),
            TrajectorySource::Sample(name) => FlightKey::Sample(name.to_ascii_lowercase()),
            TrajectorySource::Csv(text, _) => FlightKey::Csv(self.text_id(text, fnv1a(text))),
            TrajectorySource::Plan(text, _, vehicle) => {
                FlightKey::Plan(self.text_id(text, fnv1a(text)), *vehicle)
            }
        };
        if let Some(f) = self.flights.get(&key) {
            let f = Rc::clone(f);
            self.ledger.touch(&Entry::Flights(key.clone()));
            return Ok((key, f));
        }
        let flights = match source {
            TrajectorySource::Csv(text, name) => {
                vec![parse_csv_with_progress(text, name, progress)?.ok_or(SimError::Stopped)?]
            }
            _ => load_flights(source)?,
        };
        if self.flights.len() >= MAX_CACHED_FLIGHTS {
            self.flights
                .keys()
                .for_each(|k| self.ledger.remove(&Entry::Flights(k.clone())));
            self.flights.clear();
        }
        // Time, position, velocity, acceleration and direction of motion per sample.
        let bytes = flights.iter().map(|f| f.t.len() * 12 * 8).sum();
        let flights = Rc::new(flights);
        self.flights.insert(key.clone(), Rc::clone(&flights));
        self.remember(Entry::Flights(key.clone()), bytes);
        Ok((key, flights))
    }

    /// The drone runs of every flight for each of `keys` (in their order; a key may repeat),
    /// from the cache or computed, every missing (key, flight) pair in one parallel batch;
    /// `tick` is called once per key and flight. Where they fit in [`MAX_DRONE_SHARE`] of the
    /// budget together, every key is remembered. Where they do not (a 10⁶-row flight at 25 Hz:
    /// 29 MB per model), a run streams them (`None`: each station's event loop runs that drone's
    /// filter as it reads it, [`Estimates::Live`](super::Estimates), holding only a few
    /// estimates), so that a single run, the CLI's, holds no more than it needs; a key asked for
    /// again is remembered if it is among the costliest that fit ([`remembered_keys`]), since
    /// a second run on the same drones (the page's distance and SF charts) will likely not be
    /// the last. `None` where a tick asked to stop: nothing computed is remembered then.
    fn drone_sets(
        &mut self,
        keys: &[DroneKey],
        flights: &[Trajectory],
        cfg: &Validated,
        tick: &mut dyn FnMut() -> bool,
    ) -> Option<Vec<Option<Rc<Vec<DroneTrack>>>>> {
        let n = flights.len();
        let (fit, all) = remembered_keys(keys, sensor_steps(flights, cfg));
        let kept: Vec<&DroneKey> = if fit.len() == all.len() {
            fit
        } else {
            fit.into_iter()
                .filter(|k| self.drones.contains_key(k) || self.streamed.contains(k))
                .collect()
        };
        self.note_streamed(&all, &kept);
        // The cached ones are held here first: remembering the new ones may evict them.
        let mut sets: HashMap<DroneKey, Rc<Vec<DroneTrack>>> = HashMap::new();
        let mut missing: Vec<&DroneKey> = Vec::new();
        for key in kept {
            if let Some(d) = self.drones.get(key) {
                sets.insert(key.clone(), Rc::clone(d));
                self.ledger.touch(&Entry::Drones(key.clone()));
            } else {
                missing.push(key);
            }
        }
        let computed = run_missing(&missing, flights, cfg, tick)?;
        if !ticks((keys.len() - missing.len()) * n, tick) {
            return None;
        }
        let live = keys
            .iter()
            .filter(|k| !sets.contains_key(k) && !missing.contains(k));
        self.drone_runs += ((missing.len() + live.count()) * n) as u64;
        for (key, tracks) in missing.into_iter().zip(computed) {
            let tracks = Rc::new(tracks);
            sets.insert(key.clone(), Rc::clone(&tracks));
            self.remember_drones(key.clone(), tracks);
        }
        Some(keys.iter().map(|key| sets.get(key).cloned()).collect())
    }

    /// Notes the keys of `all` that a run streams (neither `kept` nor cached), so that a run
    /// asking for them again remembers them, and forgets the notes of `kept`; at most
    /// [`MAX_STREAMED_NOTES`] notes, the oldest dropped first.
    fn note_streamed(&mut self, all: &[&DroneKey], kept: &[&DroneKey]) {
        self.streamed.retain(|k| !kept.contains(&k));
        for &key in all {
            if !kept.contains(&key)
                && !self.drones.contains_key(key)
                && !self.streamed.contains(key)
            {
                self.streamed.push(key.clone());
            }
        }
        let over = self.streamed.len().saturating_sub(MAX_STREAMED_NOTES);
        self.streamed.drain(..over);
    }

    /// Keeps one key's drone runs in the cache; the byte budget forgets the least recently used.
    fn remember_drones(&mut self, key: DroneKey, tracks: Rc<Vec<DroneTrack>>) {
        let bytes = tracks.iter().map(|t| t.states.len()).sum::<usize>() * DRONE_STEP_BYTES;
        self.drones.insert(key.clone(), tracks);
        self.remember(Entry::Drones(key), bytes);
    }

    /// The remembered station predictions for `key`, one entry per flight; `grid` is the
    /// number of evaluation times over all the flights. `None` when they would take more than
    /// [`MAX_STATION_SHARE`] of the budget: the station then predicts afresh.
    fn station_chains(
        &mut self,
        key: StationKey,
        flights: usize,
        grid: f64,
    ) -> Option<Rc<Vec<Mutex<FlightChains>>>> {
        if let Some(c) = self.stations.get(&key) {
            let c = Rc::clone(c);
            self.ledger.touch(&Entry::Stations(key));
            return Some(c);
        }
        // At most MAX_GRIDS grids' worth of estimates per flight (FlightChains).
        let bytes = (grid * MAX_GRIDS * core::mem::size_of::<Estimate>() as f64) as usize;
        if bytes > MAX_CACHE_BYTES / MAX_STATION_SHARE {
            return None;
        }
        if self.stations.len() >= MAX_CACHED_STATIONS {
            self.stations
                .keys()
                .for_each(|k| self.ledger.remove(&Entry::Stations(k.clone())));
            self.stations.clear();
        }
        let chains = Rc::new((0..flights).map(|_| Mutex::default()).collect::<Vec<_>>());
        self.stations.insert(key.clone(), Rc::clone(&chains));
        self.remember(Entry::Stations(key), bytes);
        Some(chains)
    }

    /// The remembered predictions of station `p` receiving from drone runs `key`: a single-model
    /// station's ([`Self::station_chains`]); `None` for the others, whose IMM probabilities or
    /// place on the plan carry over from packet to packet, so nothing can be reused.
    fn chains_for(
        &mut self,
        p: &StationPlan,
        key: &DroneKey,
        cfg: &Validated,
        flights: usize,
        grid: f64,
    ) -> Option<Rc<Vec<Mutex<FlightChains>>>> {
        let StationModel::Single(model) = p.model else {
            return None;
        };
        let s = cfg.s();
        // An adaptive heading noise makes a packet's predictions depend on the packets before
        // it (the hedge they chose), so they are not the packet's alone to remember.
        if p.setup.bounds.heading_noise == HeadingNoise::Adaptive {
            return None;
        }
        let station = StationKey {
            drone: key.clone(),
            model,
            prediction: s.station.prediction,
            step: s.station.step.to_bits(),
            eta: s.station.eta.to_bits(),
            q: s.drone.q.to_bits(),
            error_triggered: p.setup.error_triggered,
        };
        self.station_chains(station, flights, grid)
    }

    /// Runs one simulation.
    pub fn run(&mut self, cfg: &Validated) -> Result<SimReport, SimError> {
        self.run_with_progress(cfg, &mut |_, _| {})
    }

    /// Runs one simulation: the event loop with one drone over each flight, for each station
    /// and each of the `seeds` seeds (their runs pooled). Calls `progress(done, total)` after
    /// each flight's drone filter and each flight's station (total = 2 × flights × models ×
    /// seeds), so a long run can show how far it is.
    pub fn run_with_progress(
        &mut self,
        cfg: &Validated,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<SimReport, SimError> {
        self.run_stoppable(cfg, &mut |done, total| {
            progress(done, total);
            true
        })
    }

    /// [`Simulator::run_with_progress`], where `progress` also says whether to go on: once it
    /// returns `false` the run stops at the next flight it would start (in WebAssembly, where
    /// flights run in turn; natively, at the end of the batch under way) with
    /// [`SimError::Stopped`]. No drone run of a stopped batch is remembered, and the stations'
    /// remembered predictions are extended only by whole flights, so the next run gives a fresh
    /// simulator's numbers. The page stops a run a newer one replaced this way
    /// (`docs/reference.md` §9): its worker could otherwise only be terminated, which would throw
    /// away its caches.
    pub fn run_stoppable(
        &mut self,
        cfg: &Validated,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<SimReport, SimError> {
        let report = self.run_flights(cfg, progress);
        if let Some(done) = &mut self.run_done {
            done();
        }
        report
    }

    /// [`Simulator::run_stoppable`]'s run.
    fn run_flights(
        &mut self,
        cfg: &Validated,
        progress: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Result<SimReport, SimError> {
        let s = cfg.s();
        let source = simulated_source(cfg)?;
        let (flight_key, flights) = self.flights(source, &mut |_, _| true)?;
        let flight_time: f64 = flights.iter().map(Trajectory::duration).sum();
        let seeds = u64::from(s.run.seeds.max(1));
        check_steps(cfg, flight_time, seeds)?;
        let total = 2 * flights.len() * cfg.models.len() * seeds as usize;
        let mut done = 0;
        let mut tick = || {
            done += 1;
            progress(done, total)
        };
        // Each station's radio, setup and plans, checked before any work.
        let stations = cfg
            .models
            .iter()
            .map(|&model| StationPlan::new(cfg, model, &flights))
            .collect::<Result<Vec<_>, _>>()?;
        // The first flight's plan, for the series, when a mission station runs.
        let series_plan = stations
            .iter()
            .find_map(|p| p.plans[0].as_ref())
            .map(|first| first.plan.waypoints().to_vec());
        // Each seed is the same run with other random draws (sensor noise, send offsets,
        // shadowing): its flights join the pool as runs of their own. Station-major order.
        let pairs: Vec<(&StationPlan, u64)> = stations
            .iter()
            .flat_map(|p| (0..seeds).map(move |j| (p, s.run.seed.wrapping_add(j))))
            .collect();
        let drone_key = |p: &StationPlan, seed: u64| DroneKey {
            flights: flight_key.clone(),
            model: p.model.sent_model(),
            sensor_rate: s.drone.sensor_rate.to_bits(),
            q: s.drone.q.to_bits(),
            seed,
        };
        let keys: Vec<DroneKey> = pairs.iter().map(|&(p, seed)| drone_key(p, seed)).collect();
        let drones = self
            .drone_sets(&keys, &flights, cfg, &mut tick)
            .ok_or(SimError::Stopped)?;
        let grid = flight_time / s.station.step + flights.len() as f64;
        let chains: Vec<_> = pairs
            .iter()
            .zip(&keys)
            .map(|(&(p, _), key)| self.chains_for(p, key, cfg, flights.len(), grid))
            .collect();
        let runs: Vec<StationRun> = pairs
            .iter()
            .zip(&drones)
            .zip(&chains)
            .map(|((&(plan, seed), d), c)| StationRun {
                plan,
                cfg,
                flights: &flights,
                drones: d.as_deref().map(|d| d.as_slice()),
                chains: c.as_deref().map(|c| c.as_slice()),
                seed,
            })
            .collect();
        let flown = fly_all(&runs, flights.len(), &mut tick).ok_or(SimError::Stopped)?;
        let (results, series_models) = pool(cfg, &stations, flown, &flights)?;
        let delivery = Delivery::pooled(results.iter().map(|r| &r.delivery));
        let series = s
            .run
            .series
            .then(|| plotted(cfg, &flights[0], series_plan, series_models));
        Ok(SimReport {
            config: run_config(cfg, source, &flights),
            delivery,
            results,
            series,
        })
    }
}

/// The flight(s) a `simulate` run flies; refuses a swarm's settings, which one drone alone
/// cannot honour.
fn simulated_source(cfg: &Validated) -> Result<&TrajectorySource, SimError> {
    let s = cfg.s();
    // Every field named, so that a swarm setting added later cannot slip past this check unnamed
    // (it had compared the whole struct).
    let SwarmSettings {
        drones,
        duration,
        sf_plan,
    } = &s.swarm;
    let plain = SwarmSettings::default();
    // How many drones fly, for how long and at which SFs; how they share the air: the schedule,
    // the channels, what survives when two frames meet, and whether a drone listens for the
    // others' (one drone's network hears no other frame: its drone, listening or not, always
    // finds the channel free).
    SimError::unless_read(
        false,
        &[
            ("drones", *drones != plain.drones),
            ("duration", *duration != plain.duration),
            ("sfPlan", *sf_plan != plain.sf_plan),
            ("schedule", s.access.schedule != Schedule::Aloha),
            ("channels", cfg.channels != s.access.region.channels()),
            ("capture", !s.network.capture),
            ("interSf", !s.network.inter_sf),
            (
                "channelSense",
                s.sending.channel_sense != ChannelSense::default(),
            ),
        ],
        "a swarm setting",
        "simulate flies one drone over its flight, with the air to itself",
    )?;
    // A swarm reads it with listed gateways too: its drones' distance from the centre.
    SimError::unless_read(
        s.network.gateways.is_empty(),
        &[("distance", s.channel.distance != DISTANCE.default)],
        "where the one default gateway stands, and the listed gateways replace it",
        "leave `distance` out",
    )?;
    cfg.source.as_ref().ok_or_else(|| {
        SimError::Source(
            "choose a flight: `trajectory` (CSV), `synthetic` (all or 1..30), `sample` (canberra) or a `plan` to fly"
                .into(),
        )
    })
}

/// Refuses a run whose flights (`flight_time` s, flown once per seed of `seeds`) would take
/// more than [`MAX_FILTER_STEPS`] filter steps, the drone's and the station's.
fn check_steps(cfg: &Validated, flight_time: f64, seeds: u64) -> Result<(), SimError> {
    let steps = steps_per_seed(cfg, flight_time) * seeds as f64;
    if steps > MAX_FILTER_STEPS as f64 {
        return Err(SimError::TooLong {
            flight_time: flight_time * seeds as f64,
            steps,
            run: LongRun::Simulate {
                seeds,
                fit: seeds_that_fit(cfg, flight_time),
            },
        });
    }
    Ok(())
}

/// The drone's and the station's filter steps per model in one seed of `flight_time` s.
fn steps_per_seed(cfg: &Validated, flight_time: f64) -> f64 {
    let s = cfg.s();
    flight_time * (s.drone.sensor_rate + 1.0 / s.station.step)
}

/// The most seeds of `flight_time` s that fit within [`MAX_FILTER_STEPS`] at `cfg`'s rates, at
/// most the seeds setting's own limit: the report's `maxSeeds` and a refusal's "at most N seeds".
fn seeds_that_fit(cfg: &Validated, flight_time: f64) -> u32 {
    (MAX_FILTER_STEPS as f64 / steps_per_seed(cfg, flight_time))
        .floor()
        .min(SEEDS.max) as u32
}

/// What a `simulate` run flew (JSON `config`): the settings, with one drone on its SF for the
/// flight time of `flights` (from `source`), and the link they imply.
fn run_config(cfg: &Validated, source: &TrajectorySource, flights: &[Trajectory]) -> RunConfig {
    let s = cfg.s();
    let flight_time: f64 = flights.iter().map(Trajectory::duration).sum();
    let (sf, bw) = (cfg.radio.sf, cfg.radio.bw);
    let mut settings = s.clone();
    settings.swarm = SwarmSettings {
        drones: 1,
        duration: flight_time,
        sf_plan: SfPlan::Fixed,
    };
    RunConfig {
        settings,
        trajectory: match source {
            TrajectorySource::Synthetic(SyntheticChoice::All) => "synthetic all".into(),
            _ => flights[0].name.clone(),
        },
        flights: flights.len(),
        flight_time,
        models: cfg.models.clone(),
        bandwidth_khz: bw.khz(),
        eta_per_second: pow(s.station.eta, 1.0 / s.station.step),
        sensitivity_dbm: Channel::sensitivity_dbm(sf, bw),
        range_m: cfg.channel.range_m(sf, bw),
        data_rate: s.access.region.rate(sf.get(), bw).map(|r| r.dr),
        max_seeds: seeds_that_fit(cfg, flight_time),
        plan_cornering: cfg.plan.as_ref().map(FlightPlan::cornering),
    }
}

/// The series a page plots: `flight` (decimated), the gateways beside it, the drone's plan and
/// each station's series on it.
fn plotted(
    cfg: &Validated,
    flight: &Trajectory,
    plan: Option<Vec<[f64; 3]>>,
    models: Vec<ModelSeries>,
) -> Series {
    let s = cfg.s();
    let every = series_stride(flight.t.len());
    let axis = |k: usize| axis_every(&flight.pos, k, every);
    let origin = flight.pos[0];
    let gateways: Vec<[f64; 3]> = cfg
        .sites(s.channel.distance)
        .iter()
        .map(|g| {
            let [e, n, h] = g.position(s.channel.gateway_height);
            [origin[0] + e, origin[1] + n, h]
        })
        .collect();
    Series {
        flight: flight.name.clone(),
        t: flight.t.iter().step_by(every).copied().collect(),
        x: axis(0),
        y: axis(1),
        z: axis(2),
        gateway: gateways[0],
        gateways,
        plan,
        models,
    }
}

/// Each station's result from its runs' flights (`flown`, station-major as [`fly_all`] gives
/// them: every seed's flights join one pool), and the plotted series that came with them.
fn pool(
    cfg: &Validated,
    stations: &[StationPlan],
    flown: Vec<Vec<Result<FlightRun, SimError>>>,
    flights: &[Trajectory],
) -> Result<(Vec<ModelResult>, Vec<ModelSeries>), SimError> {
    let s = cfg.s();
    let per_station = flown.len() / stations.len().max(1);
    let mut flown = flown.into_iter();
    let mut gathered = Vec::with_capacity(stations.len());
    let mut series = Vec::new();
    for station in stations {
        let mut pooled = Pooled::new(s.sending.sender);
        let mut counted = Delivery::default();
        let mut recoveries = 0;
        for one_seed in flown.by_ref().take(per_station) {
            for (i, flight) in one_seed.into_iter().enumerate() {
                let run = flight?;
                series.extend(run.series);
                pooled.add(&run.tx, run.track, flights[i].duration());
                if let Some(n) = run.delivery {
                    counted.add(&n);
                }
                recoveries += run.recoveries;
            }
            pooled.end_seed();
        }
        gathered.push((station, pooled, counted, recoveries));
    }
    // Each station's errors sorted and resampled on a core of its own: on one long flight
    // that was a second of one core while the other idled.
    let mut results = par_map_owned(gathered, |(station, pooled, counted, recoveries)| {
        pooled.finish(
            station.model,
            &station.start.current(),
            recoveries,
            &counted,
            s.run.seed,
        )
    });
    set_versus_lowest(&mut results);
    Ok((results, series))
}

/// Every run's flights: the runs whose drones adapt their data rate fly theirs in order
/// ([`StationRun::fly_in_order`]), those runs side by side; every other run joins the first run
/// whose drone sends the same transmissions ([`StationRun::sends_as`]), and each such group's
/// flights are one parallel batch, the costliest groups first. One list of flights per run, in
/// flight order; `tick` once per run and flight. `None` where a tick asked to stop.
fn fly_all(
    runs: &[StationRun],
    flights: usize,
    tick: &mut dyn FnMut() -> bool,
) -> Option<Vec<Vec<Result<FlightRun, SimError>>>> {
    let fixed_rate = (0..runs.len()).filter(|&r| !runs[r].adaptive());
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for r in fixed_rate {
        match groups.iter_mut().find(|g| runs[g[0]].sends_as(&runs[r])) {
            Some(g) => g.push(r),
            None => groups.push(vec![r]),
        }
    }
    let jobs: Vec<(usize, usize)> = (0..groups.len())
        .flat_map(|g| (0..flights).map(move |i| (g, i)))
        .collect();
    let cost = |g: &[usize]| {
        let stations: Vec<StationModel> = g.iter().map(|&r| runs[r].plan.model).collect();
        station_work(&stations)
    };
    let flown = par_map_costliest_first(
        jobs.len(),
        |k| cost(&groups[jobs[k].0]),
        |k| {
            let (g, i) = jobs[k];
            let members: Vec<&StationRun> = groups[g].iter().map(|&r| &runs[r]).collect();
            members[0].fly_shared(i, &members)
        },
        // One tick per run and flight: a group's job is as many.
        &mut |k| ticks(groups[jobs[k].0].len(), tick),
    )?;
    // Back to one list per run: group g's job for flight i holds its members' flights in order.
    let mut per_run: Vec<Vec<Result<FlightRun, SimError>>> =
        (0..runs.len()).map(|_| Vec::new()).collect();
    for ((g, _), members) in jobs.into_iter().zip(flown) {
        for (&r, run) in groups[g].iter().zip(members) {
            per_run[r].push(run);
        }
    }
    // Each seed's adaptive drone is a run of its own: natively they fly side by side.
    let adaptive: Vec<usize> = (0..runs.len()).filter(|&r| runs[r].adaptive()).collect();
    let in_order = par_map_progressing(
        0..adaptive.len(),
        |k, tick| runs[adaptive[k]].fly_in_order(tick),
        tick,
    )?;
    for (r, flown) in adaptive.into_iter().zip(in_order) {
        per_run[r] = flown;
    }
    Some(per_run)
}

/// Reads or builds the flights `source` names.
pub(crate) fn load_flights(source: &TrajectorySource) -> Result<Vec<Trajectory>, SimError> {
    Ok(match source {
        // Each flight on its own core: 264 000 samples, 12 % of a one-thread whole-set run.
        TrajectorySource::Synthetic(SyntheticChoice::All) => {
            par_map(1..SYNTHETIC_FLIGHTS + 1, synthetic_flight)
                .into_iter()
                .flatten()
                .collect()
        }
        TrajectorySource::Synthetic(SyntheticChoice::One(i)) => {
            vec![synthetic_flight(*i).ok_or(TrajectoryError::SyntheticIndex(*i as i64))?]
        }
        TrajectorySource::Sample(name) if name.eq_ignore_ascii_case("canberra") => {
            vec![canberra_flight()]
        }
        TrajectorySource::Sample(name) => {
            return Err(TrajectoryError::UnknownSample(name.clone()).into())
        }
        TrajectorySource::Csv(text, name) => vec![parse_csv(text, name)?],
        TrajectorySource::Plan(text, name, vehicle) => {
            vec![fly_plan(&parse_plan_as(text, *vehicle)?, name)?]
        }
    })
}

/// A network of the run's gateways for one drone with radio `radio`.
#[cfg(test)]
mod tests {
    use super::*;

    /// A drone key of the Canberra flight for `model` and `seed`.
    fn key(model: ModelKind, seed: u64) -> DroneKey {
        DroneKey {
            flights: FlightKey::Sample("canberra".into()),
            model,
            sensor_rate: 10f64.to_bits(),
            q: 0.1f64.to_bits(),
            seed,
        }
    }

    #[test]
    fn texts_that_share_a_hash_never_share_an_id() {
        let mut sim = Simulator::new();
        let a = sim.text_id(&"t,x,y,z\n0,0,0,0\n".into(), 42);
        let b = sim.text_id(&"t,x,y,z\n0,1,0,0\n".into(), 42);
        assert_ne!(
            a, b,
            "a hash collision must not give the first file's results"
        );
        assert_eq!(
            sim.text_id(&"t,x,y,z\n0,0,0,0\n".into(), 42),
            a,
            "the same text keeps its key"
        );
    }

    #[test]
    fn a_stopped_csv_reading_caches_nothing_and_the_next_reads_it_whole() {
        let text: Arc<str> = ("t,x,y,z\n".to_string()
            + &(0..500)
                .map(|i| format!("{},{},0,10\n", f64::from(i) * 0.1, i))
                .collect::<String>())
            .into();
        let mut sim = Simulator::new();
        let stopped = sim.load_csv(Arc::clone(&text), "f.csv".into(), &mut |_, _| false);
        assert!(matches!(stopped, Err(SimError::Stopped)), "{stopped:?}");
        let mut asked = 0;
        let rows = sim.load_csv(Arc::clone(&text), "f.csv".into(), &mut |_, _| {
            asked += 1;
            true
        });
        assert_eq!(rows.unwrap(), 500);
        assert!(asked > 50, "read again, not from a cache: {asked} reports");
        let mut again = 0;
        sim.load_csv(text, "f.csv".into(), &mut |_, _| {
            again += 1;
            true
        })
        .unwrap();
        assert_eq!(again, 0, "a whole reading is cached");
    }

    #[test]
    fn many_flights_read_each_seeds_sensors_once_and_one_flight_keeps_a_task_per_model() {
        let keys = [
            key(ModelKind::Dr, 1),
            key(ModelKind::Ctra3d, 1),
            key(ModelKind::Dr, 2),
            key(ModelKind::CtraPlus, 1),
        ];
        let missing: Vec<&DroneKey> = keys.iter().collect();
        assert_eq!(
            sensor_groups(&missing, 1000),
            vec![(1, vec![0, 1, 3]), (2, vec![2])]
        );
        assert_eq!(
            sensor_groups(&missing, 1),
            vec![(1, vec![0]), (1, vec![1]), (2, vec![2]), (1, vec![3])]
        );
    }

    #[test]
    fn each_run_is_told_as_it_ends_failed_runs_too() {
        use std::cell::Cell;
        let ended = Rc::new(Cell::new(0));
        let mut sim = Simulator::new();
        let counter = Rc::clone(&ended);
        sim.on_each_run(move || counter.set(counter.get() + 1));
        let mut p = crate::sim::Scenario::default();
        p.flight.synthetic = Some(SyntheticChoice::One(1));
        sim.run(&p.validate().unwrap()).unwrap();
        sim.run(&p.validate().unwrap()).unwrap();
        assert_eq!(ended.get(), 2, "a second run, from the caches, ends too");
        p.swarm.drones = 2;
        assert!(sim.run(&p.validate().unwrap()).is_err());
        assert_eq!(ended.get(), 3);
    }

    #[test]
    fn the_costliest_drone_runs_that_fit_are_the_ones_remembered() {
        let keys = [
            key(ModelKind::Dr, 1),
            key(ModelKind::CtraPlus, 1),
            key(ModelKind::Ctra3d, 1),
            key(ModelKind::Dr, 1),
        ];
        let two = MAX_CACHE_BYTES / MAX_DRONE_SHARE / DRONE_STEP_BYTES / 2;
        let (fit, all) = remembered_keys(&keys, two);
        assert_eq!(all, vec![&keys[0], &keys[1], &keys[2]]);
        assert_eq!(fit, vec![&keys[2], &keys[1]]);
        assert_eq!(remembered_keys(&keys, 10).0.len(), 3);
        assert!(remembered_keys(&keys, 4 * two).0.is_empty());
    }
}
