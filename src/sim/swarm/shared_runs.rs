//! The drones' own filter runs, computed once for every swarm that flies them alike, and their
//! stations' errors from each packet on, computed once for every swarm that delivers it.

use crate::models::ModelKind;
use crate::sim::drone::{run_drone, DroneTrack, Sensing};
use crate::sim::station::{ForecastMemo, SpanKey};
use crate::trajectory::Trajectory;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Bytes a stored estimate takes: nine `f64`s.
const BYTES_PER_STEP: usize = 9 * 8;
/// Bytes a run's stations' errors may take per sensor step in each of their two generations
/// ([`Forecasts`], [`SharedDroneRuns::with_station_errors`]): eight errors' worth with their
/// keys, so where the station's step T is the sensor period (the paper's 0.1 s at 10 Hz) a
/// generation holds about six swarms' errors. `sweep --swarm` (two swarms at a time, each
/// drone in 28 swarms a family): with four errors' worth 32.5 s, with eight 30.1 s, with twelve
/// 29.7 s, with all kept 29.6 s, against 42.6 s without (2026-12-05).
const FORECAST_BYTES_PER_STEP: usize = 8 * 8;
/// Bytes one kept packet's errors take beyond the errors themselves: its key and its handle.
const FORECAST_ENTRY_BYTES: usize =
    core::mem::size_of::<(u32, SpanKey)>() + core::mem::size_of::<Arc<[f64]>>() + 16;

/// Where a run is looked for: the drone's seed, stream and model, and its flight's samples, first
/// and last time and first and last position (bits), which tell apart the flights of one drone
/// (chained flights, or a flight chosen) without comparing them whole.
type RunKey = (u64, u64, ModelKind, [u64; 8]);

fn flight_key(f: &Trajectory) -> [u64; 8] {
    let (first, last) = (f.pos.first(), f.pos.last());
    let bits = |p: Option<&[f64; 3]>, i: usize| p.map_or(0, |p| p[i].to_bits());
    [
        f.t.len() as u64,
        f.t.first().map_or(0, |t| t.to_bits()),
        f.t.last().map_or(0, |t| t.to_bits()),
        bits(first, 0),
        bits(first, 1),
        bits(last, 0),
        bits(last, 1),
        bits(last, 2),
    ]
}

/// A drone's run once made, or `None` where the budget was spent; the first to ask makes it.
type Slot = OnceLock<Option<Arc<SharedRun>>>;

/// One drone's filter run, with what it was run on.
pub(super) struct SharedRun {
    flight: Arc<Trajectory>,
    sensing: Sensing,
    /// The estimate at every sensor step.
    pub track: DroneTrack,
    /// Its stations' errors from the packets they received.
    forecasts: Mutex<Forecasts>,
}

impl SharedRun {
    /// The errors station `station` ([`SharedDroneRuns::station`]) made from each packet of this
    /// drone it received, shared with every swarm that runs that station over this drone.
    pub fn forecasts(&self, station: u32) -> RunForecasts<'_> {
        RunForecasts { run: self, station }
    }
}

/// A run's stations' errors from each packet on, in two generations: where the newer outgrows its
/// bytes it becomes the older, and the older is dropped. So what the swarms flying this drone
/// now deliver stays, what the swarms before them delivered goes, and a drone's errors take at
/// most twice a generation's bytes.
struct Forecasts {
    newer: HashMap<(u32, SpanKey), Arc<[f64]>>,
    older: HashMap<(u32, SpanKey), Arc<[f64]>>,
    /// Bytes the newer generation holds.
    bytes: usize,
    /// Bytes a generation may hold.
    room: usize,
}

impl Forecasts {
    fn new(room: usize) -> Self {
        Forecasts {
            newer: HashMap::new(),
            older: HashMap::new(),
            bytes: 0,
            room,
        }
    }

    fn keep(&mut self, key: (u32, SpanKey), errors: Arc<[f64]>) {
        let bytes = FORECAST_ENTRY_BYTES + 8 * errors.len();
        if bytes > self.room {
            return;
        }
        if self.bytes + bytes > self.room {
            self.older = std::mem::take(&mut self.newer);
            self.bytes = 0;
        }
        self.bytes += bytes;
        if let Some(replaced) = self.newer.insert(key, errors) {
            self.bytes -= FORECAST_ENTRY_BYTES + 8 * replaced.len();
        }
    }
}

/// One station's errors over one drone's run ([`SharedRun::forecasts`]).
pub(super) struct RunForecasts<'a> {
    run: &'a SharedRun,
    station: u32,
}

impl ForecastMemo for RunForecasts<'_> {
    fn recall(&self, key: &SpanKey, count: usize) -> Option<Arc<[f64]>> {
        let key = (self.station, *key);
        let mut f = self.run.forecasts.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(errors) = f.newer.get(&key) {
            return (errors.len() >= count).then(|| Arc::clone(errors));
        }
        // Met again: it belongs to the swarms flying now.
        let errors = f.older.remove(&key)?;
        f.keep(key, Arc::clone(&errors));
        (errors.len() >= count).then_some(errors)
    }

    fn keep(&self, key: SpanKey, errors: &[f64]) {
        let key = (self.station, key);
        let mut f = self.run.forecasts.lock().unwrap_or_else(|e| e.into_inner());
        if f.newer
            .get(&key)
            .is_some_and(|kept| kept.len() >= errors.len())
        {
            return;
        }
        f.keep(key, errors.into());
    }
}

/// Drone filter runs shared by swarms that differ only in what the network does.
///
/// A drone's on-board filter sees its flight and its sensors (its seed, stream and sensing
/// settings), never the network: swarms that differ in size, schedule, channels, SF plan, sender
/// or duty-cycle rule fly drone i alike, so its estimates are computed once and read by each.
/// `sweep --swarm` runs 112 swarms of 1 … 500 drones over the same 500 drones, and its crowd
/// comparison flies the same 72 drones per seed under each sender and duty-cycle rule it compares
/// (16 swarms a seed). A run is found by the drone's seed,
/// stream, model and flight, and used only when its flight and sensing are exactly the ones asked
/// for (otherwise the swarm runs that drone's filter live, as without sharing).
///
/// Each run also keeps its stations' errors from the packets they received: a station that
/// forgets the past at each packet (the paper's, or a bounded one with a fixed heading noise)
/// errs alike from a packet in every swarm that delivers it, and swarms that differ in size or
/// channels deliver most packets alike (`sweep --swarm`: half its stations' evaluation times).
/// Those errors are recalled instead of computed again ([`ForecastMemo`]); the reports are the
/// same, bit for bit.
///
/// Stored estimates cost 72 bytes a sensor step (216 kB for a drone flying 300 s at 10 Hz), which
/// a single swarm does not need: the live filter keeps only a window; its stations' errors up
/// to 128 more. So runs are shared only within `budget` bytes; past it, drones run live.
pub struct SharedDroneRuns {
    runs: Mutex<HashMap<RunKey, Arc<Slot>>>,
    /// Each station's settings (model and setup, in words) and its number.
    stations: Mutex<HashMap<String, u32>>,
    /// Whether runs keep their stations' errors.
    station_errors: bool,
    bytes: AtomicUsize,
    budget: usize,
}

impl SharedDroneRuns {
    /// No runs yet; at most `budget` bytes of estimates will be kept.
    pub fn new(budget: usize) -> Self {
        SharedDroneRuns {
            runs: Mutex::new(HashMap::new()),
            stations: Mutex::new(HashMap::new()),
            station_errors: false,
            bytes: AtomicUsize::new(0),
            budget,
        }
    }

    /// The same, each run keeping its stations' errors too (within the budget, which sets
    /// aside their room): for swarms that deliver most packets alike (the same drones in swarms
    /// of other sizes or channel counts), not for swarms whose drones send otherwise.
    pub fn with_station_errors(self) -> Self {
        SharedDroneRuns {
            station_errors: true,
            ..self
        }
    }

    /// Whether runs keep their stations' errors ([`SharedDroneRuns::with_station_errors`]).
    pub(super) fn keeps_station_errors(&self) -> bool {
        self.station_errors
    }

    /// Bytes held for estimates and set aside for their stations' errors.
    pub fn bytes(&self) -> usize {
        self.bytes.load(Ordering::Relaxed)
    }

    /// The number of the station `settings` describes (its model and setup, `Debug`-printed:
    /// every number to the bit), the same for every swarm that runs it.
    pub(super) fn station(&self, settings: String) -> u32 {
        let mut stations = self.stations.lock().unwrap_or_else(|e| e.into_inner());
        let next = stations.len() as u32;
        *stations.entry(settings).or_insert(next)
    }

    /// The run of a drone flying `flight` with `model` and `sensing`: computed on first asking
    /// (a second asker waits for it rather than computing it again), `None` where the budget is
    /// spent or the run found for this drone was made on another flight or sensing.
    pub(super) fn get(
        &self,
        flight: &Arc<Trajectory>,
        model: ModelKind,
        sensing: &Sensing,
    ) -> Option<Arc<SharedRun>> {
        let key = (
            sensing.streams.seed,
            sensing.streams.stream,
            model,
            flight_key(flight),
        );
        let cell = {
            // A panic elsewhere while the map was held leaves it whole: each entry is inserted
            // in one step.
            let mut runs = self.runs.lock().unwrap_or_else(|e| e.into_inner());
            Arc::clone(runs.entry(key).or_default())
        };
        let run = cell.get_or_init(|| {
            // As the sensors count them (`drone.rs`).
            let steps = (flight.duration() / (1.0 / sensing.rate) + 1e-9).floor() as usize + 1;
            let room = if self.station_errors {
                steps * FORECAST_BYTES_PER_STEP
            } else {
                0
            };
            let bytes = steps * BYTES_PER_STEP + 2 * room;
            if self.bytes.fetch_add(bytes, Ordering::Relaxed) + bytes > self.budget {
                self.bytes.fetch_sub(bytes, Ordering::Relaxed);
                return None;
            }
            Some(Arc::new(SharedRun {
                flight: Arc::clone(flight),
                sensing: *sensing,
                track: run_drone(flight, model, sensing),
                forecasts: Mutex::new(Forecasts::new(room)),
            }))
        });
        run.as_ref()
            .filter(|r| {
                r.sensing == *sensing && (Arc::ptr_eq(&r.flight, flight) || *r.flight == **flight)
            })
            .cloned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::streams::DroneStreams;
    use crate::trajectory::synthetic_flight;

    fn sensing(stream: u64) -> Sensing {
        Sensing::paper(1, stream)
    }

    #[test]
    fn a_drone_is_run_once_and_equals_its_own_run() {
        let flight = Arc::new(synthetic_flight(2).unwrap());
        let runs = SharedDroneRuns::new(usize::MAX);
        let a = runs.get(&flight, ModelKind::Ctra3d, &sensing(3)).unwrap();
        let again = Arc::new((*flight).clone());
        let b = runs.get(&again, ModelKind::Ctra3d, &sensing(3)).unwrap();
        assert!(
            Arc::ptr_eq(&a, &b),
            "the same drone on an equal flight shares its run"
        );
        assert_eq!(a.track, run_drone(&flight, ModelKind::Ctra3d, &sensing(3)));
        assert_eq!(runs.bytes(), a.track.states.len() * BYTES_PER_STEP);
    }

    #[test]
    fn another_flight_or_sensing_of_the_same_drone_is_never_served_the_stored_run() {
        let flight = Arc::new(synthetic_flight(2).unwrap());
        let other = Arc::new(synthetic_flight(3).unwrap());
        let runs = SharedDroneRuns::new(usize::MAX);
        let first = runs.get(&flight, ModelKind::Dr, &sensing(0)).unwrap();
        // The same drone on another flight is another run.
        let second = runs.get(&other, ModelKind::Dr, &sensing(0)).unwrap();
        assert_eq!(second.track, run_drone(&other, ModelKind::Dr, &sensing(0)));
        assert_ne!(first.track, second.track);
        // A flight that differs only within (same samples, ends and end points) is not served
        // the stored run.
        let mut inside = (*flight).clone();
        inside.pos[1][0] += 1.0;
        assert!(runs
            .get(&Arc::new(inside), ModelKind::Dr, &sensing(0))
            .is_none());
        let faster = Sensing {
            rate: 20.0,
            ..sensing(0)
        };
        assert!(runs.get(&flight, ModelKind::Dr, &faster).is_none());
        // Another model or stream is another drone run.
        assert!(runs.get(&flight, ModelKind::Ctra3d, &sensing(0)).is_some());
        let streams = DroneStreams { seed: 2, stream: 0 };
        assert!(runs
            .get(
                &flight,
                ModelKind::Dr,
                &Sensing {
                    streams,
                    ..sensing(0)
                }
            )
            .is_some());
    }

    #[test]
    fn a_runs_station_errors_keep_the_latest_generations_within_their_room() {
        use crate::sim::station::{Received, SpanKey};
        let flight = Arc::new(synthetic_flight(1).unwrap());
        let runs = SharedDroneRuns::new(usize::MAX).with_station_errors();
        let run = runs.get(&flight, ModelKind::Dr, &sensing(0)).unwrap();
        let room = run.forecasts.lock().unwrap().room;
        let steps = run.track.states.len();
        assert_eq!(room, steps * FORECAST_BYTES_PER_STEP);
        assert_eq!(runs.bytes(), steps * (BYTES_PER_STEP + 2 * room / steps));
        let entry = |n: usize| FORECAST_ENTRY_BYTES + 8 * n;
        // Errors of `n` evaluation times from the packet sent at `sent` s.
        let packet = crate::sim::station::tests::frames("1").remove(0);
        let key = |sent: f64| {
            let p = crate::sim::Transmission {
                sent,
                ..packet.clone()
            };
            SpanKey::of(
                &Received {
                    packet: &p,
                    silence_trusted: true,
                },
                0,
            )
        };
        let (paper, bounded) = (runs.station("paper".into()), runs.station("bounded".into()));
        assert_eq!(
            runs.station("paper".into()),
            paper,
            "a station keeps its number"
        );
        let memo = run.forecasts(paper);
        // Errors of 100 times each, enough for two and a half generations: the first two go to
        // the older generation as the newer fills, and the first is dropped when it fills again.
        let each = (room / 2) / entry(100);
        for k in 0..5 * each {
            memo.keep(key(k as f64), &vec![k as f64; 100]);
        }
        let held = |k: usize| memo.recall(&key(k as f64), 100).is_some();
        assert!(!held(0), "the oldest went");
        assert!(held(5 * each - 1), "the newest stayed");
        // A recalled error is the one kept, and at most as many times as were kept are recalled.
        assert_eq!(
            &*memo.recall(&key((5 * each - 1) as f64), 100).unwrap(),
            &vec![(5 * each - 1) as f64; 100][..]
        );
        assert!(memo.recall(&key((5 * each - 1) as f64), 101).is_none());
        // Another station's errors from the same packet are its own.
        assert!(run
            .forecasts(bounded)
            .recall(&key((5 * each - 1) as f64), 1)
            .is_none());
        // A longer run of errors replaces a shorter; one larger than the room is not kept.
        memo.keep(key(-1.0), &[1.0; 10]);
        memo.keep(key(-1.0), &[2.0; 20]);
        assert_eq!(memo.recall(&key(-1.0), 15).unwrap().len(), 20);
        memo.keep(key(-2.0), &vec![0.0; room / 8]);
        assert!(memo.recall(&key(-2.0), 1).is_none());
        let f = run.forecasts.lock().unwrap();
        let bytes = |m: &HashMap<(u32, SpanKey), Arc<[f64]>>| {
            m.values().map(|e| entry(e.len())).sum::<usize>()
        };
        assert!(bytes(&f.newer) <= room && bytes(&f.older) <= room);
        assert_eq!(bytes(&f.newer), f.bytes);
    }

    #[test]
    fn past_the_budget_drones_are_not_stored() {
        let flight = Arc::new(synthetic_flight(1).unwrap());
        let one = run_drone(&flight, ModelKind::Dr, &sensing(0)).states.len() * BYTES_PER_STEP;
        let runs = SharedDroneRuns::new(one + one / 2);
        assert!(runs.get(&flight, ModelKind::Dr, &sensing(0)).is_some());
        assert!(runs.get(&flight, ModelKind::Dr, &sensing(1)).is_none());
        assert_eq!(runs.bytes(), one);
    }
}
