//! The drones' own filter runs, computed once for every swarm that flies them alike.

use crate::models::ModelKind;
use crate::sim::drone::{run_drone, DroneTrack, Sensing};
use crate::trajectory::Trajectory;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Bytes a stored estimate takes: nine `f64`s.
const BYTES_PER_STEP: usize = 9 * 8;

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
/// Stored estimates cost 72 bytes a sensor step (216 kB for a drone flying 300 s at 10 Hz), which
/// a single swarm does not need: the live filter keeps only a window. So runs are shared only
/// within `budget` bytes; past it, drones run live.
pub struct SharedDroneRuns {
    runs: Mutex<HashMap<RunKey, Arc<Slot>>>,
    bytes: AtomicUsize,
    budget: usize,
}

impl SharedDroneRuns {
    /// No runs yet; at most `budget` bytes of estimates will be kept.
    pub fn new(budget: usize) -> Self {
        SharedDroneRuns {
            runs: Mutex::new(HashMap::new()),
            bytes: AtomicUsize::new(0),
            budget,
        }
    }

    /// Bytes of estimates held.
    pub fn bytes(&self) -> usize {
        self.bytes.load(Ordering::Relaxed)
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
            let bytes = steps * BYTES_PER_STEP;
            if self.bytes.fetch_add(bytes, Ordering::Relaxed) + bytes > self.budget {
                self.bytes.fetch_sub(bytes, Ordering::Relaxed);
                return None;
            }
            Some(Arc::new(SharedRun {
                flight: Arc::clone(flight),
                sensing: *sensing,
                track: run_drone(flight, model, sensing),
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
    fn past_the_budget_drones_are_not_stored() {
        let flight = Arc::new(synthetic_flight(1).unwrap());
        let one = run_drone(&flight, ModelKind::Dr, &sensing(0)).states.len() * BYTES_PER_STEP;
        let runs = SharedDroneRuns::new(one + one / 2);
        assert!(runs.get(&flight, ModelKind::Dr, &sensing(0)).is_some());
        assert!(runs.get(&flight, ModelKind::Dr, &sensing(1)).is_none());
        assert_eq!(runs.bytes(), one);
    }
}
