//! `elastokin tolerance MODEL TOLERANCES`: each figure's spread when the model's numbers are made within
//! their tolerances.

use super::input::{open_model, read_input};
use super::strict::refuse_warned;
use crate::output::{failed_lines, write_table, wrote, Failure, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::solver::Mode;
use elastokin::suspensions::design::tolerance::{read_tolerances, stack_up, StackUp};
use elastokin::suspensions::{design, kc};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ToleranceArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    /// The tolerances file (JSON; see examples/targets/tolerances.json)
    pub tolerances: PathBuf,
    /// Also sample N models within the tolerances and run each: the spread they give beside the first
    /// order's
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub monte_carlo: Option<u32>,
    /// The seed of the Monte Carlo's samples (the same seed, the same samples)
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Where tolerance.csv, tolerance_contributions.csv, tolerance_adjustments.csv (with adjustments),
    /// tolerance_samples.csv (with --monte-carlo) and report.html go; the directory is replaced as a whole
    /// on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `tolerance`: the figures' spread under the model's tolerances.
pub fn run(args: ToleranceArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let read = open_model(&args.model, out, strict)?;
    let origin = args.model.display().to_string();
    let base = read.document(&args.model)?;
    let (bytes, text) = read_input(&args.tolerances, "TOLERANCES")?;
    let tolerances = read_tolerances(&text, &args.tolerances.display().to_string(), &base)
        .map_err(|e| Failure::Input(e.to_string()))?;
    let mut stack = stack_up(&base, &tolerances).map_err(|e| Failure::Run(format!("{origin}: {e}")))?;
    refuse_warned(strict, stack.warnings.iter())?;
    if stack.spreads.is_empty() && !stack.failed.is_empty() {
        return Err(Failure::Run(format!(
            "no spreads: {}\n(nothing was written; {} is untouched)",
            failed_lines(&stack.failed),
            args.out.display()
        )));
    }
    if let Some(n) = args.monte_carlo {
        stack.monte_carlo(n as usize, args.seed);
    }
    let mut provenance = Provenance::new(&args.model, &read.bytes, kc::mode_word(Mode::Corrected), tolerances.steps);
    provenance.targets = Some((args.tolerances.display().to_string(), elastokin::provenance::sha256_hex(&bytes)));
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let html = elastokin::html::tolerance_html(&stack, &read.file.name, &provenance.to_json());
        let mut written = vec![
            staging.write("tolerance.csv", &write_table(&stack.table(), &provenance))?,
            staging.write("tolerance_contributions.csv", &write_table(&stack.contribution_table(), &provenance))?,
        ];
        for table in [stack.adjustment_table(), stack.sample_table()].into_iter().flatten() {
            written.push(staging.write(&format!("{}.csv", table.name), &write_table(&table, &provenance))?);
        }
        written.push(staging.write("report.html", html.as_bytes())?);
        Ok(written)
    })()
    .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line(format!("{} — {} sources within their tolerances", read.file.name, stack.sources.len()))?;
    print_spreads(out, &stack)?;
    out.line("")?;
    for w in &stack.warnings {
        out.line(format!("warning [{}]: {}", w.code, w.message))?;
    }
    out.line(wrote(&written))?;
    let failed = stack.failed.len() + stack.failed_samples.len();
    if failed == 0 {
        return Ok(());
    }
    let lines = [failed_lines(&stack.failed), stack.failed_samples.join("\n")];
    Err(Failure::Run(format!(
        "{failed} analyses or samples failed (the others' results are in {}):\n{}",
        args.out.display(),
        lines.iter().filter(|l| !l.is_empty()).cloned().collect::<Vec<_>>().join("\n")
    )))
}

/// Each figure's value, worst case and σ (and the sampled σ), the share of cars outside its limit, with its
/// three largest contributors; each adjuster's range.
fn print_spreads(out: &Stdout, stack: &StackUp) -> Result<(), Failure> {
    for s in &stack.spreads {
        let unit = s.unit.shown();
        let shown = |v: f64, digits: usize| kc::significant(v * unit.factor, digits);
        let sampled = s.sampled.map_or(String::new(), |m| format!(", sampled σ {}", shown(m.sigma, 3)));
        out.line(format!(
            "  {:<44} {:>12} ±{} worst, σ {}{sampled} {}",
            format!("{} {}", s.analysis.name(), s.figure),
            shown(s.value, 5),
            shown(s.worst_case, 3),
            shown(s.sigma, 3),
            unit.symbol
        ))?;
        if let Some(share) = s.outside {
            out.line(format!("      {}", elastokin::html::outside_words(share, s.sampled.and_then(|m| m.outside))))?;
        }
        for c in s.contributions.iter().take(3) {
            let name = stack.source_words(c.source);
            out.line(format!("      {name:<40} {:>12} {}", shown(c.worst, 3), unit.symbol))?;
        }
    }
    for a in &stack.adjusters {
        let pointer = &stack.parameters.pointers[a.adjustment.by];
        let sampled = a.sampled.map_or(String::new(), |m| format!(", sampled σ {}", kc::significant(m.sigma, 3)));
        out.line(format!(
            "  {} {} set at alignment by {}: ±{} worst, σ {}{sampled}",
            a.adjustment.analysis.name(),
            a.adjustment.figure,
            design::parameter_words(pointer),
            kc::significant(a.worst_case, 3),
            kc::significant(a.sigma, 3),
        ))?;
    }
    Ok(())
}
