//! `elastokin batch MODEL VARIANTS`: design variants of one model, run in parallel. The variants file's
//! syntax, the edits and the figures of each variant are the library's ([`elastokin::suspensions::study::batch`]);
//! this is the command's part: every variant on the rayon pool, with a progress bar.
//!
//! `--shard I/N` runs one of N contiguous, nearly equal blocks of the variants ([`Shard`]), so that a job
//! array can spread one batch over machines; `elastokin merge` (src/merge.rs) joins the shards' tables.

use crate::output::Progress;
pub use elastokin::suspensions::study::batch::*;
pub use elastokin::suspensions::study::shard::Shard;
use elastokin::suspensions::SuspensionFile;
use rayon::prelude::*;

/// The column a shard's `batch.csv` adds: the variant's place in the whole variants file, counting from 1,
/// so that the merge can check that the shards cover every variant once and in order.
pub const NUMBER_COLUMN: &str = "variant_number";

/// The header of `batch.csv`: `variant`, the library's [`FIGURES`], `error`, and [`NUMBER_COLUMN`] after them
/// in a shard's.
pub fn columns(shard: bool) -> Vec<String> {
    let number = shard.then_some(NUMBER_COLUMN);
    std::iter::once("variant").chain(FIGURES).chain(["error"]).chain(number).map(String::from).collect()
}

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
