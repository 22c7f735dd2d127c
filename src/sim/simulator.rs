//! Runs simulations and caches what does not depend on the link.

use super::config::{SimConfig, SyntheticChoice, TrajectorySource};
use super::drone::{run_drone, DroneTrack};
use super::link::{schedule_transmissions, LinkSetup, Transmission};
use super::parallel::par_map_ticking;
use super::pooled::{axis_every, model_series, series_stride, Pooled};
use super::report::{ModelSeries, RunConfig, Series, SimReport};
use super::sender::SenderKind;
use super::station::{
    new_tracker, track_station, Bounds, FlightChains, Prediction, StationModel, StationSetup,
    StationTrack,
};
use super::{AdrSession, SimError};
use crate::lora::{min_interval, time_on_air, Channel};
use crate::math::pow;
use crate::models::ModelKind;
use crate::rng::Rng;
use crate::trajectory::{
    canberra_flight, parse_csv, synthetic_flight, synthetic_set, Trajectory, TrajectoryError,
};
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Mutex;

/// One flight's transmissions, station track and (first flight, when asked) plotted series.
type FlightRun = (Vec<Transmission>, StationTrack, Option<ModelSeries>);

/// Separates the link's random stream from the sensors' for the same seed.
const LINK_STREAM: u64 = 0x4C49_4E4B; // "LINK"
/// The most drone and station filter steps one run may take per model, summed over its flights:
/// twice what the page's largest setting needs (the whole 44-minute set with 100 Hz sensors and
/// T = 0.01 s is 528 000), and about a second of work per model natively.
pub const MAX_FILTER_STEPS: u64 = 1_000_000;
/// Cache sizes; past them the cache starts afresh (a page rarely alternates between more).
const MAX_CACHED_FLIGHTS: usize = 4;
const MAX_CACHED_DRONE_RUNS: usize = 24;
const MAX_CACHED_STATIONS: usize = 6;

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
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum FlightKey {
    Synthetic(SyntheticChoice),
    Sample(String),
    Csv(u64, usize),
}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct DroneKey {
    flights: FlightKey,
    model: ModelKind,
    sensor_rate: u64,
    q: u64,
    seed: u64,
}

/// FNV-1a: a stable 64-bit hash of CSV text for the cache key.
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
    drones: HashMap<DroneKey, Rc<Vec<DroneTrack>>>,
    stations: HashMap<StationKey, Rc<Vec<Mutex<FlightChains>>>>,
    drone_runs: u64,
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

    fn flights(
        &mut self,
        source: &TrajectorySource,
    ) -> Result<(FlightKey, Rc<Vec<Trajectory>>), SimError> {
        let key = match source {
            TrajectorySource::Synthetic(c) => FlightKey::Synthetic(*c),
            TrajectorySource::Sample(name) => FlightKey::Sample(name.to_ascii_lowercase()),
            TrajectorySource::Csv(text, _) => FlightKey::Csv(fnv1a(text), text.len()),
        };
        if let Some(f) = self.flights.get(&key) {
            return Ok((key, Rc::clone(f)));
        }
        let flights = match source {
            TrajectorySource::Synthetic(SyntheticChoice::All) => synthetic_set(),
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
        };
        if self.flights.len() >= MAX_CACHED_FLIGHTS {
            self.flights.clear();
        }
        let flights = Rc::new(flights);
        self.flights.insert(key.clone(), Rc::clone(&flights));
        Ok((key, flights))
    }

    /// The drone runs of every flight for one model, from the cache or computed; `tick` is
    /// called once per flight.
    fn drone_tracks(
        &mut self,
        key: DroneKey,
        flights: &[Trajectory],
        cfg: &SimConfig,
        tick: &mut dyn FnMut(),
    ) -> Rc<Vec<DroneTrack>> {
        if let Some(d) = self.drones.get(&key) {
            flights.iter().for_each(|_| tick());
            return Rc::clone(d);
        }
        let tracks: Vec<DroneTrack> = par_map_ticking(
            0..flights.len(),
            |i| {
                run_drone(
                    &flights[i],
                    key.model,
                    cfg.sensor_rate,
                    cfg.q,
                    &cfg.r_diagonal,
                    cfg.seed,
                    i as u64,
                )
            },
            tick,
        );
        self.drone_runs += tracks.len() as u64;
        if self.drones.len() >= MAX_CACHED_DRONE_RUNS {
            self.drones.clear();
        }
        let tracks = Rc::new(tracks);
        self.drones.insert(key, Rc::clone(&tracks));
        tracks
    }

    /// The remembered station predictions for `key`, one entry per flight.
    fn station_chains(&mut self, key: StationKey, flights: usize) -> Rc<Vec<Mutex<FlightChains>>> {
        if let Some(c) = self.stations.get(&key) {
            return Rc::clone(c);
        }
        if self.stations.len() >= MAX_CACHED_STATIONS {
            self.stations.clear();
        }
        let chains = Rc::new((0..flights).map(|_| Mutex::default()).collect::<Vec<_>>());
        self.stations.insert(key, Rc::clone(&chains));
        chains
    }

    /// Runs one simulation.
    pub fn run(&mut self, cfg: &SimConfig) -> Result<SimReport, SimError> {
        self.run_with_progress(cfg, &mut |_, _| {})
    }

    /// Runs one simulation, calling `progress(done, total)` after each flight's drone filter and
    /// each flight's station (total = 2 × flights × models), so a long run can show how far it is.
    pub fn run_with_progress(
        &mut self,
        cfg: &SimConfig,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<SimReport, SimError> {
        let (flight_key, flights) = self.flights(&cfg.source)?;
        let flight_time: f64 = flights.iter().map(Trajectory::duration).sum();
        let steps = flight_time * (cfg.sensor_rate + 1.0 / cfg.step);
        if steps > MAX_FILTER_STEPS as f64 {
            return Err(SimError::TooLong { flight_time, steps });
        }
        let total = 2 * flights.len() * cfg.models.len();
        let mut done = 0;
        let mut tick = || {
            done += 1;
            progress(done, total);
        };
        let (sf, bw) = (cfg.radio.sf, cfg.radio.bw);
        let mut results = Vec::new();
        let mut series_models = Vec::new();
        for &model in &cfg.models {
            let sent_model = model.sent_model();
            let toa = time_on_air(&cfg.radio, model.payload_bytes() + cfg.overhead)?.time_on_air;
            let interval = min_interval(toa, cfg.duty_cycle)?;
            let link = LinkSetup {
                sf,
                bw,
                channel: cfg.channel,
                time_on_air: toa,
                interval,
                distance: cfg.distance,
                bearing: 0.0,
            };
            let sending = &cfg.sending;
            if sending.sender == SenderKind::Error && sending.max_interval < interval {
                return Err(SimError::Parameter(
                    "maxInterval",
                    sending.max_interval,
                    "at least the duty-cycle interval of every chosen model",
                ));
            }
            let setup = StationSetup {
                prediction: cfg.prediction,
                bounds: Bounds::default(),
                step: cfg.step,
                eta: cfg.eta,
                q: cfg.q,
                r_diagonal: cfg.r_diagonal,
                interval,
            };
            let key = DroneKey {
                flights: flight_key.clone(),
                model: sent_model,
                sensor_rate: cfg.sensor_rate.to_bits(),
                q: cfg.q.to_bits(),
                seed: cfg.seed,
            };
            let chains = match model {
                StationModel::Single(m) => Some(self.station_chains(
                    StationKey {
                        drone: key.clone(),
                        model: m,
                        prediction: cfg.prediction,
                        step: cfg.step.to_bits(),
                        eta: cfg.eta.to_bits(),
                        q: cfg.q.to_bits(),
                    },
                    flights.len(),
                )),
                // An IMM's probabilities carry over from packet to packet: nothing to reuse.
                StationModel::Imm => None,
            };
            let drones = self.drone_tracks(key, &flights, cfg, &mut tick);
            let bytes = model.payload_bytes() + cfg.overhead;
            let shadowing = cfg.channel.params().shadowing_sigma_db;
            let mut adr = AdrSession::new(&cfg.adr, &cfg.radio, bytes, cfg.duty_cycle, shadowing)?;
            let (flight_set, drone_set): (&[Trajectory], &[DroneTrack]) = (&flights, &drones);
            let chains: Option<&[Mutex<FlightChains>]> = chains.as_deref().map(|c| c.as_slice());
            let one = |i: usize, adr: Option<&mut AdrSession>| -> Result<FlightRun, SimError> {
                let (flight, drone) = (&flight_set[i], &drone_set[i]);
                // The same stream for every station: stations that send the same payload see
                // the same packets, so their comparison is paired.
                let mut rng = Rng::derive(cfg.seed ^ LINK_STREAM, i as u64);
                // With ADR a flight starts at the rate the last one ended with.
                let link = adr.as_ref().map_or(link.clone(), |a| a.link_now(&link));
                let mut rule = sending.rule(cfg.duty_cycle, link.time_on_air, flight.t[0])?;
                let mut sender = sending.sender(model, setup, sending.max_interval);
                let tx = schedule_transmissions(
                    flight,
                    drone,
                    &link,
                    sender.as_mut(),
                    &mut rule,
                    &mut rng,
                    adr,
                );
                let with_series = cfg.series && i == 0;
                let st = match chains {
                    Some(c) => c[i].lock().unwrap_or_else(|e| e.into_inner()).track(
                        flight,
                        &|| new_tracker(model, setup),
                        &tx,
                        cfg.step,
                        with_series,
                    ),
                    None => {
                        let mut tracker = new_tracker(model, setup);
                        track_station(flight, tracker.as_mut(), &tx, cfg.step, with_series)
                    }
                };
                let series = with_series.then(|| model_series(model, &st, &tx));
                Ok((tx, st, series))
            };
            let runs: Vec<Result<FlightRun, SimError>> = match adr.as_mut() {
                // ADR state passes from one flight to the next: fly them in order.
                Some(session) => (0..flights.len())
                    .map(|i| {
                        let r = one(i, Some(&mut *session));
                        tick();
                        r
                    })
                    .collect(),
                None => par_map_ticking(0..flights.len(), |i| one(i, None), &mut tick),
            };
            let mut pooled = Pooled::default();
            for run in runs {
                let (tx, st, series) = run?;
                series_models.extend(series);
                pooled.add(&tx, st);
            }
            let recoveries = drones.iter().map(|d| d.recoveries).sum();
            results.push(pooled.finish(model, toa, interval, recoveries));
        }
        let series = cfg.series.then(|| {
            let f = &flights[0];
            let every = series_stride(f.t.len());
            let axis = |k: usize| axis_every(&f.pos, k, every);
            Series {
                flight: f.name.clone(),
                t: f.t.iter().step_by(every).copied().collect(),
                x: axis(0),
                y: axis(1),
                z: axis(2),
                gateway: [
                    f.pos[0][0] + cfg.distance,
                    f.pos[0][1],
                    cfg.channel.params().gateway_height,
                ],
                models: series_models,
            }
        });
        let ch = cfg.channel.params();
        Ok(SimReport {
            config: RunConfig {
                trajectory: match &cfg.source {
                    TrajectorySource::Synthetic(SyntheticChoice::All) => "synthetic all".into(),
                    _ => flights[0].name.clone(),
                },
                flights: flights.len(),
                flight_time,
                models: cfg.models.clone(),
                prediction: cfg.prediction,
                sending: cfg.sending,
                adr: cfg.adr.mode,
                adr_margin: cfg.adr.margin_db,
                adr_history: cfg.adr.history,
                sf: sf.get(),
                bandwidth_khz: bw.khz(),
                distance: cfg.distance,
                seed: cfg.seed,
                overhead: cfg.overhead,
                cr: cfg.radio.cr.get(),
                duty_cycle: cfg.duty_cycle,
                tx_power: ch.tx_power_dbm,
                path_loss_exponent: ch.path_loss_exponent,
                shadowing: ch.shadowing_sigma_db,
                gateway_height: ch.gateway_height,
                sensor_rate: cfg.sensor_rate,
                step: cfg.step,
                eta: cfg.eta,
                eta_per_second: pow(cfg.eta, 1.0 / cfg.step),
                q: cfg.q,
                sensitivity_dbm: Channel::sensitivity_dbm(sf, bw),
                range_m: cfg.channel.range_m(sf, bw),
            },
            results,
            series,
        })
    }
}
