//! The end-to-end tracking simulation (paper §IV; SPEC §1, §4, §6):
//! ground truth → noisy sensors → drone UKF → duty-cycled transmissions → codec → channel →
//! station predictor → error against ground truth every T.
//!
//! The drone side ([`drone::DroneTrack`]) depends only on the flight, the model, the sensors and
//! the seed; the link and station sides are cheap. [`Simulator`] caches drone tracks, so changing
//! only link parameters (SF, bandwidth, distance, overhead, channel) never re-runs a drone filter.

mod adr_session;
mod config;
mod drone;
mod error;
mod link;
mod parallel;
mod pooled;
mod report;
pub mod sender;
mod simulator;
pub mod station;
pub mod swarm;

pub use adr_session::AdrSession;
pub use config::{
    random_seed, ModelChoice, SimConfig, SimParams, SyntheticChoice, TrajectorySource, MAX_SEED,
};
pub use drone::{run_drone, DroneTrack};
pub use error::SimError;
pub use link::{schedule_transmissions, LinkSetup, Transmission};
pub use report::{ModelResult, ModelSeries, RunConfig, Series, SimReport};
pub use sender::{
    new_sender, ErrorTriggered, Periodic, Sender, SenderKind, Sending, DEFAULT_BURST,
    DEFAULT_MAX_INTERVAL_S, DEFAULT_THRESHOLD_M,
};
pub use simulator::{Simulator, MAX_FILTER_STEPS};
pub use station::{
    new_tracker, track_station, Bounds, Imm, Prediction, StationModel, StationPredictor,
    StationSetup, StationTrack, Tracker,
};
pub use swarm::{
    aloha_collision_rate, run_swarm, DroneReport, SfPlan, SwarmConfig, SwarmParams, SwarmReport,
};
