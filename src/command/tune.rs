//! `elastokin tune MODEL TARGETS`: the model's free numbers moved within their bounds to meet the targets.

use super::input::{open_model, read_targets_file};
use super::strict::refuse_warned;
use crate::output::{write_table, wrote, Failure, Progress, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::plot;
use elastokin::solver::Mode;
use elastokin::suspensions::design::fit::FitUncertainty;
use elastokin::suspensions::design::targets::{Reading, Targets};
use elastokin::suspensions::design::tune::{self, Tuned};
use elastokin::suspensions::design::Parameters;
use elastokin::suspensions::{design, kc};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct TuneArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    /// The targets file (JSON; see examples/targets/bump_steer.json)
    pub targets: PathBuf,
    /// Where tuned.json, tune.csv, tune_targets.csv and report.html go; the directory is replaced as a
    /// whole on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `tune`: the model's free numbers moved to meet the targets.
pub fn run(args: TuneArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    let read = open_model(&args.model, out, strict)?;
    let origin = args.model.display().to_string();
    let base = read.document(&args.model)?;
    let (targets_bytes, targets) = read_targets_file(&args.targets, &base, Reading::ToTune)?;
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    let parameters = Parameters::new(&base, &pointers).map_err(|e| Failure::Input(format!("{origin}: {e}")))?;
    let tuned = tune_printing(&parameters, &targets, &origin, out, quiet)?;
    // The analyses of the model as it was and as it is tuned.
    refuse_warned(strict, [&tuned.start, &tuned.end].into_iter().flat_map(|e| &e.reports).flat_map(|r| &r.warnings))?;
    let mut provenance = Provenance::new(&args.model, &read.bytes, kc::mode_word(Mode::Corrected), targets.steps);
    provenance.targets = Some((args.targets.display().to_string(), elastokin::provenance::sha256_hex(&targets_bytes)));
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let mut json = serde_json::to_string_pretty(&tuned.document).map_err(|e| Failure::Run(e.to_string()))?;
        json.push('\n');
        let html = elastokin::html::tune_html(&tuned, &targets, &read.file.name, &provenance.to_json(), plot::svg);
        Ok(vec![
            staging.write("tuned.json", json.as_bytes())?,
            staging.write("tune.csv", &write_table(&tuned.iteration_table(), &provenance))?,
            staging.write("tune_targets.csv", &write_table(&tuned.residual_table(&targets), &provenance))?,
            staging.write("tune_uncertainty.csv", &write_table(&tuned.uncertainty_table(&targets), &provenance))?,
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line("")?;
    out.line(format!("{}: {}", read.file.name, tuned.stopped))?;
    print_tuned(out, &tuned, &targets)?;
    out.line("")?;
    out.line(wrote(&written))?;
    let unmet = unmet(&tuned);
    if unmet.is_empty() {
        return Ok(());
    }
    Err(Failure::Run(format!(
        "{} of {} targets and packaging constraints not met (the tune's results are in {}):\n{}",
        unmet.len(),
        tuned.verdicts.len() + tuned.packaging.len(),
        args.out.display(),
        unmet.join("\n")
    )))
}

/// The tune of `parameters` (of the model file `origin`) to `targets`, each iteration after the first
/// printed as it ends.
fn tune_printing(
    parameters: &Parameters,
    targets: &Targets,
    origin: &str,
    out: &Stdout,
    quiet: bool,
) -> Result<Tuned, Failure> {
    let progress = Progress::new("iterations", tune::MAX_ITERATIONS, quiet);
    let tuned = tune::tune(parameters, targets, |i| {
        progress.end(None);
        if i.iteration > 0 {
            progress
                .suspend(|| {
                    out.line(format!(
                        "iteration {:>2}: objective {:<10} step {:<10} {}",
                        i.iteration,
                        kc::significant(i.objective, 4),
                        kc::significant(i.step, 3),
                        i.outcome
                    ))
                })
                .ok();
        }
    })
    .map_err(|e| match e {
        // The targets ask what the model's analyses do not give: bad input, as a bad TARGETS file is.
        tune::TuneError::Targets(why) => Failure::Input(format!("{origin}: {why}")),
        e @ (tune::TuneError::Model(_) | tune::TuneError::Parameters(_) | tune::TuneError::Analysis { .. }) => {
            Failure::Run(format!("{origin}: {e}"))
        }
    })?;
    progress.finish();
    Ok(tuned)
}

/// Each free number before and after with its standard uncertainty, what the fit cannot tell, whether
/// each target is met, whether each packaging constraint holds.
fn print_tuned(out: &Stdout, tuned: &Tuned, targets: &Targets) -> Result<(), Failure> {
    for (f, k) in targets.free.iter().zip(0..) {
        let uncertainty = match tuned.uncertainty.as_ref().map(|u| (u.standard[k], u.at_bound.contains(&k))) {
            Some((_, true)) => "held by a bound".to_string(),
            Some((Some(s), false)) => format!("± {}", design::parameter_value_words(&f.pointer, s)),
            Some((None, false)) | None => String::new(),
        };
        out.line(format!(
            "  {:<40} {:>14} -> {:<14} {uncertainty}",
            design::parameter_words(&f.pointer),
            design::parameter_value_words(&f.pointer, tuned.start.x[k]),
            design::parameter_value_words(&f.pointer, tuned.end.x[k])
        ))?;
    }
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    if let Some(u) = &tuned.uncertainty {
        let correlations = if u.residual_scale.is_some() { "; correlations in tune_uncertainty.csv" } else { "" };
        out.line(format!("  {}{correlations}", u.basis()))?;
        for unseen in &u.unseen {
            out.line(format!("  {}", FitUncertainty::not_unique(unseen, &pointers)))?;
        }
    }
    if let Some(o) = &tuned.objective {
        out.line(format!("  {}", o.said()))?;
    }
    for v in &tuned.verdicts {
        let state = if v.met { "met" } else { "NOT met" };
        out.line(format!("  {state}: {} ({})", v.target, v.judged))?;
    }
    for p in &tuned.packaging {
        out.line(if p.broken_by == 0.0 {
            format!("  holds: {}", p.constraint)
        } else {
            format!("  BROKEN: {} (by {} mm)", p.constraint, kc::significant(p.broken_by * 1e3, 3))
        })?;
    }
    Ok(())
}

/// The targets not met and the packaging constraints broken, a line each with why.
fn unmet(tuned: &Tuned) -> Vec<String> {
    let mut unmet: Vec<String> = tuned
        .verdicts
        .iter()
        .filter(|v| !v.met)
        .map(|v| format!("{}: {}", v.target, v.why.as_deref().unwrap_or("")))
        .collect();
    unmet.extend(tuned.packaging.iter().filter(|p| p.broken_by > 0.0).map(|p| {
        format!(
            "{}: broken by {} mm; free the numbers that move its points, or widen its range",
            p.constraint,
            kc::significant(p.broken_by * 1e3, 3)
        )
    }));
    unmet
}
