//! The end-to-end tracking simulation (paper §IV; `docs/reference.md`), read as its pipeline:
//! drone (sensors, UKF: [`run_drone`], [`DroneFilter`]) → sender (when to send: [`sender`]) → duty-cycle rule
//! ([`DutyCycle`](crate::lora::DutyCycle)) → link (path loss and shadowing per drone–gateway
//! link: `link`) → gateways and network server (reception, first copy, ADR: [`network`]) →
//! station (predictor: [`station`]) → metrics.
//!
//! One settings type ([`Scenario`]) and one event loop ([`run_episode`]) serve both entry
//! points: [`Simulator`] (`simulate`: one drone, each flight an episode, drone runs cached so
//! that a link change never re-runs a drone filter) and [`run_swarm`] (`swarm`: many drones).

mod cache_budget;
mod caveats;
mod clock;
mod delivery_spread;
mod drone;
mod error;
mod flier;
mod link;
pub mod network;
mod packet;
mod pooled;
mod radio;
mod report;
pub mod scenario;
pub mod schedule;
pub mod sender;
mod simulator;
pub mod station;
mod station_run;
mod streams;
pub mod swarm;
mod versus_lowest;

pub use cache_budget::MAX_CACHE_BYTES;
pub use caveats::{Caveats, Saturation, FEW_PACKETS, SILENCE_LOSS};
pub use clock::{Clock, Timing};
pub use delivery_spread::{DeliverySpread, DELIVERY_SPREAD};
pub use drone::{run_drone, run_drones, DroneFilter, DroneTrack, Estimates, Sensing};
pub use error::{LongRun, SimError};
pub use flier::{Aboard, Air, Flier};
pub use link::{Link, Reception};
pub use network::{fly_alone, run_episode, CrowdLoad, GatewayReport, Network, NetworkSetup};
pub use packet::Transmission;
pub use radio::{DroneRadio, Frame, RateTable};
pub use report::{
    Boxplots, DataRateUse, Delivery, Energy, FrameTiming, ModelResult, ModelSeries, RunConfig,
    Series, SimReport, SENT_EVERY_NOTED,
};
pub use scenario::{
    parse_seed, random_seed, AccessSettings, ChannelSettings, CliCommand, DroneSettings,
    FlightSettings, GatewaySite, ModelChoice, NetworkSettings, RadioSettings, RunSettings,
    Scenario, SfPlan, StationSettings, SwarmSettings, SyntheticChoice, TrajectorySource, Validated,
    MAX_SEED,
};
pub use schedule::{aloha_collision_rate, Schedule, Slot};
pub use sender::{
    ChannelLoad, ChannelSense, ErrorTriggered, LeanPayload, PayloadChoice, Periodic, Sender,
    SenderKind, Sending, DEFAULT_BURST, DEFAULT_MAX_INTERVAL_S, DEFAULT_THRESHOLD_M,
    LEAN_SIGNIFICANCE,
};
pub use simulator::Simulator;
pub use station::{
    new_tracker, split_stations, station_work, track_station, Bounds, Calibration, HeadingNoise,
    HedgeChoice, Imm, ManoeuvreEvidence, MissionPlan, MissionStation, PlanPace, Prediction,
    Scoring, StationModel, StationPredictor, StationSetup, StationTrack, Tracker, Upcoming,
    CALIBRATION_GAIN, HOLD_RADIUS, HOLD_SPEED, MANOEUVRE_SPREAD, OFFSET_TIME, PACE_SIGMA,
    PACE_TIME, PLANE_V_MAX,
};
pub use streams::DroneStreams;
pub use swarm::{
    run_swarm, run_swarm_sharing, run_swarm_stoppable, DroneReport, LargestSwarm, SfLimit,
    SharedDroneRuns, SwarmEcho, SwarmReport, SwarmSaturation,
};
pub use versus_lowest::{versus_lowest, Contender, VersusLowest};
