//! `elastokin batch MODEL VARIANTS`: design variants of one model, run in parallel. The variants file's
//! syntax, the edits and the figures of each variant are the library's ([`elastokin::suspensions::study::batch`]);
//! this is the command's part: every variant on the rayon pool, with a progress bar, and its table.
//!
//! `--shard I/N` runs one of N contiguous, nearly equal blocks of the variants ([`Shard`]), so that a job
//! array can spread one batch over machines; `elastokin merge` (src/command/merge.rs) joins the shards' tables.

use super::input::{open_model, read_input};
use crate::output::{note, sha256_hex, write_table, Failure, Part, Progress, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::solver::Mode;
use elastokin::suspensions::kc::{self, Cell, Table};
pub use elastokin::suspensions::study::batch::*;
pub use elastokin::suspensions::study::shard::Shard;
use elastokin::suspensions::SuspensionFile;
use rayon::prelude::*;
use std::ops::Range;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct BatchArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    #[arg(help = format!("The variants file, one variant per line (format in --help; at most {})", MAX_VARIANTS))]
    pub variants: PathBuf,
    /// Run only shard I of N (I from 1 to N, as SLURM_ARRAY_TASK_ID counts with --array=1-N): variant k
    /// (counting from 0) of V belongs to shard floor(k*N/V)+1, contiguous blocks differing in size by at
    /// most one (empty ones when N > V). Its batch.csv adds the column variant_number and says I/N in its
    /// first line; `elastokin merge` joins the shards
    #[arg(long, value_name = "I/N", value_parser = Shard::parse)]
    pub shard: Option<Shard>,
    /// Also run these analyses of the K&C suite on every variant (comma-separated names; `all` for the whole
    /// suite), each over its default range in 8 steps, and write every figure they report in
    /// batch_figures.csv (one column per figure, `analysis/figure (unit)`); not with --shard
    #[arg(long, value_name = "A,B", value_delimiter = ',', conflicts_with = "shard")]
    pub analyses: Option<Vec<SuiteChoice>>,
    /// Where batch.csv goes; the directory is replaced as a whole when the batch succeeds
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// The column a shard's `batch.csv` adds: the variant's place in the whole variants file, counting from 1,
/// so that the merge can check that the shards cover every variant once and in order.
pub const NUMBER_COLUMN: &str = "variant_number";

/// The header of `batch.csv`: `variant`, the library's [`FIGURES`], `error`, and [`NUMBER_COLUMN`] after them
/// in a shard's.
pub fn columns(shard: bool) -> Vec<String> {
    let number = shard.then_some(NUMBER_COLUMN);
    std::iter::once("variant").chain(FIGURES).chain(["error"]).chain(number).map(String::from).collect()
}

/// Runs `judge` on every variant, `files[k]` being `variants[k]` applied, on the rayon pool, counting each
/// one done on `progress`.
pub fn run_all<T: Send>(
    variants: &[Variant],
    files: &[SuspensionFile],
    progress: &Progress,
    judge: impl Fn(&SuspensionFile) -> T + Sync,
) -> Vec<T> {
    variants
        .par_iter()
        .zip(files)
        .map(|(v, file)| {
            let r = judge(file);
            progress.end(Some(&v.name));
            r
        })
        .collect()
}

/// `batch`: every variant (of the shard) run, a line each printed, and `batch.csv` written.
pub fn run(args: BatchArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    let read = open_model(&args.model, out, strict)?;
    // The variants edit the file as written: a Chrono file's own keys (its comments removed).
    let base = read.document(&args.model)?;
    let (variant_bytes, variant_text) = read_input(&args.variants, "VARIANTS")?;
    // Every wrong line of the file (a key the model lacks among them) is said before anything runs. The
    // models read here are the ones run.
    let (list, files) = read_and_apply(&base, &variant_text, &args.variants.display().to_string())
        .map_err(|e| Failure::Input(e.to_string()))?;
    let mut provenance = Provenance::new(&args.model, &read.bytes, kc::mode_word(Mode::Corrected), STEPS);
    provenance.range = Some((-HALF_RANGE, HALF_RANGE));
    provenance.variants = Some((args.variants.display().to_string(), sha256_hex(&variant_bytes)));
    // Every shard reads and checks all variants above, so a mistake anywhere in the file stops each shard
    // alike; each runs only its own block.
    let range = args.shard.map_or(0..list.len(), |s| s.range(list.len()));
    provenance.part = args.shard.map(|s| Part::Shard { index: s.index, count: s.count, variants: list.len() });
    let staging = Staging::new(&args.out)?;
    let progress = Progress::new("variants", range.len(), quiet);
    let results =
        run_all(&list[range.clone()], &files[range.clone()], &progress, |file| evaluate(file, HALF_RANGE, STEPS));
    progress.finish();
    let table = variants_table(out, &list, range.clone(), &results, args.shard.is_some());
    let suite = args.analyses.map(|choices| {
        let analyses = SuiteChoice::analyses(&choices);
        let progress = Progress::new("variants through the suite", range.len(), quiet);
        let r = run_all(&list[range.clone()], &files[range.clone()], &progress, |file| {
            evaluate_suite(file, &analyses, STEPS)
        });
        progress.finish();
        r
    });
    let paths = table
        .and_then(|table| {
            let mut paths = vec![staging.write(&format!("{}.csv", table.name), &write_table(&table, &provenance))?];
            if let Some(results) = &suite {
                let table = suite_table(&list[range.clone()], results);
                paths.push(staging.write(&format!("{}.csv", table.name), &write_table(&table, &provenance))?);
            }
            Ok(paths)
        })
        .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    let failed = results.iter().filter(|r| r.is_err()).count();
    if failed > 0 && !quiet {
        note(format!("{failed} of {} variants failed (their error is in the error column)", results.len()));
    }
    let suite_failed = suite.iter().flatten().filter(|r| r.is_err()).count();
    if suite_failed > 0 && !quiet {
        note(format!("{suite_failed} variants failed in the suite (their error is in batch_figures.csv)"));
    }
    out.line(crate::output::wrote(&paths))
}

/// An analysis of `--analyses`, or the whole suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SuiteChoice {
    /// One analysis.
    One(super::sweeps::AnalysisName),
    /// Every analysis the suite runs on the model.
    All,
}

impl clap::ValueEnum for SuiteChoice {
    fn value_variants<'a>() -> &'a [Self] {
        static CHOICES: std::sync::LazyLock<Vec<SuiteChoice>> = std::sync::LazyLock::new(|| {
            let names = super::sweeps::AnalysisName::value_variants().iter().map(|&a| SuiteChoice::One(a));
            names.chain([SuiteChoice::All]).collect()
        });
        &CHOICES
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        match self {
            SuiteChoice::One(a) => a.to_possible_value(),
            SuiteChoice::All => Some(clap::builder::PossibleValue::new("all").help("every analysis of the suite")),
        }
    }
}

impl SuiteChoice {
    /// The analyses chosen (none: every one the suite runs on the model).
    fn analyses(choices: &[SuiteChoice]) -> Vec<kc::Analysis> {
        if choices.contains(&SuiteChoice::All) {
            return Vec::new();
        }
        choices.iter().filter_map(|c| if let SuiteChoice::One(a) = c { Some(a.analysis()) } else { None }).collect()
    }
}

/// `batch_figures.csv`: per variant, every figure of the suite's analyses in its written unit (empty where
/// the variant has none), and why it failed.
fn suite_table(list: &[Variant], results: &[Result<Vec<(kc::Analysis, kc::Figure)>, VariantFailed>]) -> Table {
    let figures = suite_columns(results);
    let mut columns = vec!["variant".to_string()];
    columns.extend(figures.iter().map(|(a, key, unit)| kc::figure_column(*a, key, *unit)));
    columns.push("error".into());
    let rows = list
        .iter()
        .zip(results)
        .map(|(v, r)| {
            let mut row = vec![Cell::Text(v.name.clone())];
            match r {
                Ok(reported) => {
                    row.extend(figures.iter().map(|(a, key, unit)| {
                        let f = reported.iter().find(|(b, f)| b == a && f.key == *key);
                        Cell::from(f.and_then(|(_, f)| f.value).map(|x| x * unit.shown().factor))
                    }));
                    row.push(Cell::Empty);
                }
                Err(e) => {
                    row.extend(figures.iter().map(|_| Cell::Empty));
                    row.push(Cell::Text(e.to_string()));
                }
            }
            row
        })
        .collect();
    Table { name: "batch_figures".into(), columns, rows }
}

/// The table of the variants `list[range]`, whose `results` are printed a line each as it is made; a
/// shard's rows numbered in the whole list.
fn variants_table(
    out: &Stdout,
    list: &[Variant],
    range: Range<usize>,
    results: &[Result<Outcome, VariantFailed>],
    shard: bool,
) -> Result<Table, Failure> {
    // In run's units: deg/m, N/mm.
    out.line(format!("{:<28} {:>16} {:>16} {:>14}", "variant", "bump deg/m", "camber deg/m", "rate N/mm"))?;
    let mut rows = Vec::new();
    for ((k, v), r) in list.iter().enumerate().skip(range.start).zip(results) {
        let name = Cell::Text(v.name.clone());
        let mut row = match r {
            Ok(o) => {
                out.line(format!(
                    "{:<28} {:>16.3} {:>16.3} {:>14.2}",
                    v.name,
                    o.bump_steer,
                    o.camber_gain,
                    o.wheel_rate * 1e-3
                ))?;
                let figures = o.figures().map(Cell::from);
                std::iter::once(name).chain(figures).chain([Cell::Empty]).collect()
            }
            Err(e) => {
                out.line(format!("{:<28} failed: {e}", v.name))?;
                let empty = Cell::Empty;
                vec![name, empty.clone(), empty.clone(), empty, Cell::Text(e.to_string())]
            }
        };
        if shard {
            row.push(Cell::Text((k + 1).to_string()));
        }
        rows.push(row);
    }
    Ok(Table { name: "batch".into(), columns: columns(shard), rows })
}
