//! The operations loratrack offers, with their input and output shapes (reference §9).
//!
//! The CLI and the WebAssembly bindings are thin skins over these functions: both deserialize
//! the same parameter structs (JS objects use the CLI's long option names in camelCase) and
//! serialize the same reports, so `loratrack airtime --json` and `timeOnAir({...})` cannot drift
//! apart.

mod airtime;
mod distances;
mod error;
mod link_budget;
mod misread;
mod mission;
mod payload;
mod predict;
mod senders;
mod simulate;
mod swarm;

pub use airtime::{airtime, AirtimeParams, AirtimeReport};
pub use distances::{
    sweep_distances, DistanceRun, DistanceSweepReport, VersusBestFixed, ADR_DISTANCES,
};
pub use error::{clean_message, ApiError, MAX_ECHO_CHARS};
pub use link_budget::{link_budget, LinkBudgetParams, LinkBudgetReport, SfBudget};
pub use misread::{explain_serde_error, misread_setting};
pub use mission::{
    sweep_mission, HoldRun, MissionRun, MissionSweepReport, INSPECTION_SEED, MISSION_DISTANCES,
    MISSION_MODELS, MISSION_RATES,
};
pub use payload::{decode, encode, DecodeParams, DecodeReport, EncodeParams, EncodeReport};
pub use predict::{predict, validate_state, PredictParams, PredictReport, MAX_STEPS};
pub use senders::{
    sweep_senders, sweep_senders_at, SenderPoint, SenderSweepReport, HEARTBEAT_INTERVALS,
    SENDER_SETTINGS, SENDER_THRESHOLDS,
};
pub use simulate::{
    p75, simulate, simulate_stoppable, simulate_with_progress, sweep_paper, SweepReport, SweepRun,
    PAPER_DISTANCES, PAPER_SFS,
};
pub use swarm::{swarm, swarm_sharing, swarm_stoppable, swarm_with_progress};
