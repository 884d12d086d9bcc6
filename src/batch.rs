//! `elastokin batch MODEL VARIANTS`: design variants of one model, run in parallel. The variants file's
//! syntax, the edits and the figures of each variant are the library's ([`elastokin::suspensions::batch`]);
//! this is the command's part: every variant on the rayon pool, with a progress bar.

use crate::output::Progress;
pub use elastokin::suspensions::batch::*;
use elastokin::suspensions::SuspensionFile;
use rayon::prelude::*;

/// Runs every variant, `files[k]` being `variants[k]` applied, on the rayon pool, counting each one done on
/// `progress`.
pub fn run_all(variants: &[Variant], files: &[SuspensionFile], progress: &Progress) -> Vec<Result<Outcome, String>> {
    variants
        .par_iter()
        .zip(files)
        .map(|(v, file)| {
            let r = evaluate(file, HALF_RANGE, STEPS);
            progress.end(Some(&v.name));
            r
        })
        .collect()
}
