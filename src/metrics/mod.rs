//! Error statistics: summaries (mean and percentiles) and boxplots (SPEC §8; paper Figs. 3–6).

mod boxplot;
mod percentile;
mod summary;

pub use boxplot::Boxplot;
pub use percentile::percentile;
pub use summary::Summary;
