//! `elastokin batch MODEL VARIANTS`: design variants of one model, run in parallel.
//!
//! A variants file has one variant per line: an optional `name:` and then `pointer=value` edits separated
//! by `;`, where `pointer` is a JSON pointer into the model file and `value` is JSON. Blank lines and lines
//! starting with `#` are skipped.
//!
//! ```text
//! # raise the inner tie-rod point by 10 mm
//! tie rod up: /suspension/macpherson/hardpoints/tie_rod_inner/2=-0.049
//! soft spring: /suspension/macpherson/spring/rate=20000
//! ```
//!
//! `--shard I/N` runs one of N contiguous, nearly equal blocks of the variants ([`Shard`]), so that a job
//! array can spread one batch over machines; `elastokin merge` (src/merge.rs) joins the shards' tables.

use crate::output::Progress;
use elastokin::solver::Mode;
use elastokin::suspensions::analysis::{parallel_wheel_travel, slope_at, TravelRow};
use elastokin::suspensions::{Rig, Side, SuspensionFile};
use rayon::prelude::*;

/// Each variant walks parallel wheel travel ±`HALF_RANGE` (m)…
pub const HALF_RANGE: f64 = 0.02;
/// …in `STEPS` steps (even, so design is a step).
pub const STEPS: usize = 8;
/// The most variants a file may hold: each is a sweep of its own, and all results are kept until the
/// table is written.
pub const MAX_VARIANTS: usize = 10_000;

/// The columns of `batch.csv`.
pub const COLUMNS: [&str; 5] =
    ["variant", "bump_steer_deg_per_m", "camber_gain_deg_per_m", "wheel_rate_n_per_m", "error"];

/// The column a shard's `batch.csv` adds: the variant's place in the whole variants file, counting from 1,
/// so that the merge can check that the shards cover every variant once and in order.
pub const NUMBER_COLUMN: &str = "variant_number";

/// Shard `index` of `count` (1-based, as a job array numbers its tasks).
///
/// The split is contiguous and nearly equal: variant k (counting from 0) of V belongs to shard
/// ⌊k·N/V⌋ + 1, so shard I holds variants ⌈(I−1)·V/N⌉ up to, not including, ⌈I·V/N⌉; shard sizes differ
/// by at most one, and with more shards than variants some shards are empty.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// I, from 1 to `count`.
    pub index: usize,
    /// N, at least 1.
    pub count: usize,
}

impl Shard {
    /// Reads `I/N` with 1 ≤ I ≤ N.
    pub fn parse(text: &str) -> Result<Shard, String> {
        let form = "give the shard as I/N with 1 ≤ I ≤ N, e.g. --shard 3/16 for the third of 16 \
                    (I counts from 1, as SLURM_ARRAY_TASK_ID does with --array=1-16)";
        let (i, n) = text.split_once('/').ok_or_else(|| format!("'{text}' is not I/N: {form}"))?;
        let whole = |s: &str| s.trim().parse::<usize>().ok();
        match (whole(i), whole(n)) {
            (Some(index), Some(count)) if 1 <= index && index <= count => Ok(Shard { index, count }),
            (Some(_), Some(0)) => Err(format!("'{text}': N must be at least 1; {form}")),
            (Some(_), Some(_)) => Err(format!("'{text}': I must be from 1 to N; {form}")),
            _ => Err(format!("'{text}' is not two whole numbers I/N: {form}")),
        }
    }

    /// The variants (0-based positions) of this shard among `total`.
    pub fn range(self, total: usize) -> std::ops::Range<usize> {
        // u128: I·V cannot overflow however large a shard count is given.
        let start = |i: usize| ((i as u128 * total as u128).div_ceil(self.count as u128)) as usize;
        start(self.index - 1)..start(self.index)
    }
}

/// One parsed variant: its name and its edits.
pub struct Variant {
    /// Name (the line's label, or `line N`).
    pub name: String,
    /// `(JSON pointer, value)` edits.
    pub edits: Vec<(String, serde_json::Value)>,
}

/// Parses a variants file; errors name the line.
pub fn parse_variants(text: &str, origin: &str) -> Result<Vec<Variant>, String> {
    let mut out = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (name, body) = match line.split_once(':') {
            Some((n, b)) if !n.trim_start().starts_with('/') => (n.trim().to_string(), b),
            _ => (format!("line {}", k + 1), line),
        };
        let mut edits = Vec::new();
        for edit in body.split(';').map(str::trim).filter(|e| !e.is_empty()) {
            let (pointer, value) =
                edit.split_once('=').ok_or_else(|| format!("{origin}:{}: '{edit}' is not pointer=value", k + 1))?;
            let value: serde_json::Value = serde_json::from_str(value.trim())
                .map_err(|e| format!("{origin}:{}: value of '{}' is not JSON: {e}", k + 1, pointer.trim()))?;
            edits.push((pointer.trim().to_string(), value));
        }
        if edits.is_empty() {
            return Err(format!("{origin}:{}: no edits in '{line}'", k + 1));
        }
        if out.len() == MAX_VARIANTS {
            return Err(format!(
                "{origin}:{}: more than {MAX_VARIANTS} variants; split the file and run a batch for each part",
                k + 1
            ));
        }
        out.push(Variant { name, edits });
    }
    if out.is_empty() {
        return Err(format!("{origin}: no variants (one per line: name: /json/pointer=value; …)"));
    }
    Ok(out)
}

/// The base model with a variant's edits applied; an edit to a pointer the model lacks is an error. A
/// Project Chrono suspension file (the pointers then name its own keys: `/Spring/Spring Coefficient`) is read
/// after the edits, as `run` reads it.
pub fn apply(base: &serde_json::Value, v: &Variant) -> Result<SuspensionFile, String> {
    let mut doc = base.clone();
    for (pointer, value) in &v.edits {
        let slot =
            doc.pointer_mut(pointer).ok_or_else(|| format!("variant '{}': the model has no '{pointer}'", v.name))?;
        *slot = value.clone();
    }
    let text = serde_json::to_string(&doc).map_err(|e| e.to_string())?;
    let origin = format!("variant '{}'", v.name);
    if elastokin::suspensions::chrono::is_chrono(&text) {
        return elastokin::suspensions::chrono::import(&text, &origin, None).map(|i| i.file).map_err(|e| e.to_string());
    }
    SuspensionFile::from_json(&text, &origin).map_err(|e| e.to_string())
}

/// Headline figures of one variant.
pub struct Outcome {
    /// Bump steer at design, deg per metre of travel.
    pub bump_steer: f64,
    /// Camber gain at design, deg per metre.
    pub camber_gain: f64,
    /// Wheel rate at design, N/m.
    pub wheel_rate: f64,
}

/// Runs one variant: parallel travel ±`half_range` in `steps` (even) steps.
pub fn evaluate(file: &SuspensionFile, half_range: f64, steps: usize) -> Result<Outcome, String> {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
    let rows =
        parallel_wheel_travel(&corner, -half_range, half_range, steps, Mode::Corrected).map_err(|e| e.to_string())?;
    let slope = |y: &dyn Fn(&TravelRow) -> f64| {
        slope_at(&rows, 0.0, |r| r.travel, y).ok_or("too few steps for a slope at design")
    };
    Ok(Outcome {
        bump_steer: slope(&|r| r.attitude.toe.to_degrees())?,
        camber_gain: slope(&|r| r.attitude.camber.to_degrees())?,
        wheel_rate: slope(&|r| r.wheel_load)?,
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_split_the_variants_contiguously_and_nearly_equally() {
        for total in [1, 2, 5, 6, 7, 16, 100] {
            for count in [1, 2, 3, 4, 7, 8, 16, 150] {
                let ranges: Vec<_> = (1..=count).map(|index| Shard { index, count }.range(total)).collect();
                // Back to back from 0 to V: every variant in exactly one shard.
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[count - 1].end, total);
                for pair in ranges.windows(2) {
                    assert_eq!(pair[0].end, pair[1].start);
                }
                let sizes: Vec<usize> = ranges.iter().map(|r| r.len()).collect();
                assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 1, "{total}/{count}: {sizes:?}");
                // The documented rule: variant k is in shard ⌊k·N/V⌋ + 1.
                for (i, r) in ranges.iter().enumerate() {
                    for k in r.clone() {
                        assert_eq!(k * count / total, i, "variant {k} of {total} in {count} shards");
                    }
                }
            }
        }
    }

    #[test]
    fn a_shard_is_i_of_n_with_i_from_1_to_n() {
        assert_eq!(Shard::parse("1/3"), Ok(Shard { index: 1, count: 3 }));
        assert_eq!(Shard::parse("16/16"), Ok(Shard { index: 16, count: 16 }));
        for bad in ["0/3", "4/3", "1/0", "abc", "1/", "/3", "-1/3", "1.5/3", "1/3/4"] {
            let e = Shard::parse(bad).unwrap_err();
            assert!(e.contains("I/N with 1 ≤ I ≤ N") && e.contains(bad), "{bad}: {e}");
        }
    }
}
