//! `elastokin compare DESIGN DESIGN...`: models' K&C suites and measured K&C files side by side, every
//! curve overlaid.

use super::input::{open_model, read_input};
use super::strict::refuse_warned;
use super::sweeps::SweepArgs;
use crate::output::{write_table, wrote, Failure, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::plot;
use elastokin::suspensions::compare::{compare, Design};
use elastokin::suspensions::design::targets::read_measured;
use elastokin::suspensions::kc::{self, Settings};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The designs: model files (JSON) or measured K&C files (CSV); two at least
    #[arg(required = true, num_args = 2.., value_name = "DESIGN")]
    pub designs: Vec<PathBuf>,
    #[command(flatten)]
    pub sweeps: SweepArgs,
    /// Where compare.csv and report.html go; the directory is replaced as a whole on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `compare`: the designs' figures and curves side by side, written as one table and one page.
pub fn run(args: CompareArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let settings =
        Settings { range: args.sweeps.range, steps: args.sweeps.load.steps, motion: true, ..Settings::default() };
    args.sweeps.check(&settings)?;
    let mut designs = Vec::new();
    let mut files = Vec::new();
    for path in &args.designs {
        let (bytes, design) = read_design(path, &args.sweeps, &settings, out, strict)?;
        files.push((path.display().to_string(), elastokin::provenance::sha256_hex(&bytes)));
        designs.push(design);
    }
    // Designs of one name (a tuned model keeps its parent's) are told apart by their files.
    let names: Vec<String> = designs.iter().map(|d| d.name().to_string()).collect();
    for ((design, name), path) in designs.iter_mut().zip(&names).zip(&args.designs) {
        if names.iter().filter(|n| *n == name).count() > 1 {
            design.rename(format!("{}: {name}", path.display()));
        }
    }
    let comparison = compare(&designs).map_err(|e| Failure::Input(e.to_string()))?;
    let mut provenance = Provenance::new(&args.designs[0], &[], kc::mode_word(settings.mode), settings.steps);
    provenance.model_sha256 = files[0].1.clone();
    provenance.other_files = files[1..].to_vec();
    provenance.tolerance = Some(settings.tolerance);
    provenance.range = settings.range;
    let models = comparison.models(&designs);
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let html = elastokin::html::compare_html(&comparison, &models, &provenance.to_json(), plot::svg);
        Ok(vec![
            staging.write("compare.csv", &write_table(&comparison.table(), &provenance))?,
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line(format!("compared {}", comparison.names.join(", ")))?;
    out.line(format!(
        "{} ({} figures, {} curves overlaid)",
        wrote(&written),
        comparison.figures.len(),
        comparison.charts.len()
    ))?;
    let failed: Vec<String> = models
        .iter()
        .flat_map(|(name, r)| r.failed.iter().map(move |f| format!("{name}: {}: {}", f.analysis.name(), f.reason)))
        .collect();
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Failure::Run(format!(
            "{} analyses failed (the rest is compared in {}):\n{}",
            failed.len(),
            args.out.display(),
            failed.join("\n")
        )))
    }
}

/// One design with its file's bytes (for the provenance hash): a measured K&C file (`.csv`) read, or a
/// model file read and its suite run.
fn read_design(
    path: &Path,
    sweeps: &SweepArgs,
    settings: &Settings,
    out: &Stdout,
    strict: bool,
) -> Result<(Vec<u8>, Design), Failure> {
    let measured = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    if measured {
        let (bytes, text) = read_input(path, "DESIGN")?;
        let origin = path.display().to_string();
        let measured = read_measured(&text, &origin).map_err(|e| Failure::Input(e.to_string()))?;
        let name = path.file_name().map_or(origin.clone(), |n| n.to_string_lossy().into_owned());
        return Ok((bytes, Design::Measured { name, measured }));
    }
    let read = open_model(path, out, strict)?;
    let report = kc::run_suite(&read.file, &sweeps.which(), settings, |_| {});
    refuse_warned(strict, report.all_warnings())?;
    let design = Design::model(&read.file, report);
    Ok((read.bytes, design))
}
