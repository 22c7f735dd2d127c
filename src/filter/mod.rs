//! The Unscented Kalman Filter that runs on the drone and at the station (reference §4; paper §III-C,
//! van der Merwe 2004).

mod cholesky;
mod noise;
mod sigma_points;
mod steady_state;
mod ukf;

pub use cholesky::cholesky_lower;
pub(crate) use cholesky::forward_substitute;
pub use noise::{measurement_noise, process_noise, PAPER_Q, PAPER_R_DIAGONAL};
pub use sigma_points::{SigmaParams, SigmaPoints, SigmaWeights, UNWRAPPED_SPREAD};
pub use steady_state::steady_state_covariance;
pub use ukf::Ukf;
