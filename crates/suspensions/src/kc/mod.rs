//! The K&C suite: which analyses a K&C rig runs on a suspension, and the typed, serialisable report each
//! produces (table, headline figures, plots, error estimate). Front ends (the `elastokin` command, the
//! HTML report, bindings) only render it.

pub mod chart;

pub use chart::{Chart, Scale, Series, YAxis};
