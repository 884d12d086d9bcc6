//! How long a bench run measures: the settings every section reads.

use super::stats::Budget;

/// How long the measurements take.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// `--quick`: fewer repetitions, fewer and smaller sizes.
    pub quick: bool,
}

impl Settings {
    /// Repetitions of one timed measurement.
    pub fn budget(&self) -> Budget {
        if self.quick {
            Budget { seconds: 0.08, min_reps: 3, max_reps: 25 }
        } else {
            Budget { seconds: 0.5, min_reps: 7, max_reps: 301 }
        }
    }

    /// Repetitions for the scaling scene of `n` bodies (the largest take seconds each).
    pub fn budget_large(&self, n: usize) -> Budget {
        if n >= 2000 {
            Budget { seconds: 0.0, min_reps: 3, max_reps: 3 }
        } else {
            self.budget()
        }
    }

    /// Repetitions of a whole batch.
    pub fn batch_budget(&self) -> Budget {
        let reps = if self.quick { 3 } else { 5 };
        Budget { seconds: 0.0, min_reps: reps, max_reps: reps }
    }
}
