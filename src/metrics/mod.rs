//! Error statistics: summaries (mean and percentiles), boxplots (reference §9; paper Figs. 3–6) and the
//! consistency of the station's uncertainty (95 % coverage), and how sure each statistic is
//! (bootstrap intervals over runs, and of the ratio of two stations' p75 on the same runs), and the error over the whole flight time, untracked time
//! included (and how sure a ratio of two of its p75s is, drawing whole seeds).

mod bootstrap;
mod boxplot;
mod coverage;
mod error_length;
mod paired;
mod percentile;
mod sort;
mod summary;
mod whole_flight;
mod whole_flight_draws;

pub(crate) use bootstrap::bootstrap_sorted;
pub use bootstrap::{bootstrap, Intervals, RESAMPLES};
pub use boxplot::Boxplot;
pub use coverage::{bound_95, inside_95, nees, Consistency, CHI2_3DOF_95};
pub use error_length::length_95;
pub(crate) use paired::station_draws;
pub use paired::{mean_ratio_interval, Draws};
pub use percentile::percentile;
pub use sort::sort_total;
pub use summary::Summary;
pub use whole_flight::{WholeFlightError, TRACKED_IN_FULL_PERCENT};
pub use whole_flight_draws::{SeedSpan, WholeFlightDraws};
