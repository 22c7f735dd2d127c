//! `swarm`: many drones sharing the gateways: collisions, the network server, every drone's error.

use super::ApiError;
use crate::sim::{
    run_swarm, run_swarm_sharing, run_swarm_stoppable, Scenario, SharedDroneRuns, SwarmReport,
};

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

/// [`swarm_with_progress`], where `progress` also says whether to go on: `false` stops the swarm
/// where it is with [`SimError::Stopped`](crate::sim::SimError::Stopped)
/// ([`run_swarm_stoppable`]).
pub fn swarm_stoppable(
    p: &Scenario,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SwarmReport, ApiError> {
    let cfg = p.validate()?;
    Ok(run_swarm_stoppable(&cfg, progress)?)
}

/// [`swarm`], its drones' filter runs shared with every other swarm run on `shared`: the same
/// report, computed with less work when the swarms fly the same drones (`sweep --swarm`).
pub fn swarm_sharing(p: &Scenario, shared: &SharedDroneRuns) -> Result<SwarmReport, ApiError> {
    let cfg = p.validate()?;
    Ok(run_swarm_sharing(&cfg, Some(shared), &mut |_, _| true)?)
}
