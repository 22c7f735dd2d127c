//! `swarm`: many drones, one gateway, collisions.

use super::ApiError;
use crate::sim::{run_swarm, SwarmParams, SwarmReport};

/// Runs a swarm.
pub fn swarm(p: &SwarmParams) -> Result<SwarmReport, ApiError> {
    swarm_with_progress(p, &mut |_, _| {})
}

/// [`swarm`], reporting `progress(done, total)` as drones complete.
pub fn swarm_with_progress(
    p: &SwarmParams,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SwarmReport, ApiError> {
    let cfg = p.validate()?;
    Ok(run_swarm(&cfg, progress)?)
}
