//! `swarm`: many drones sharing the gateways: collisions, the network server, every drone's error.

use super::ApiError;
use crate::sim::{run_swarm, run_swarm_sharing, Scenario, SharedDroneRuns, SwarmReport};

/// Runs a swarm.
pub fn swarm(p: &Scenario) -> Result<SwarmReport, ApiError> {
    swarm_with_progress(p, &mut |_, _| {})
}

/// [`swarm`], reporting `progress(done, total)` as drones complete.
pub fn swarm_with_progress(
    p: &Scenario,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SwarmReport, ApiError> {
    let cfg = p.validate()?;
    Ok(run_swarm(&cfg, progress)?)
}

/// [`swarm`], its drones' filter runs shared with every other swarm run on `shared`: the same
/// report, computed with less work when the swarms fly the same drones (`sweep --swarm`).
pub fn swarm_sharing(p: &Scenario, shared: &SharedDroneRuns) -> Result<SwarmReport, ApiError> {
    let cfg = p.validate()?;
    Ok(run_swarm_sharing(&cfg, Some(shared), &mut |_, _| {})?)
}
