//! `elastokin sensitivity MODEL`: every figure's and cell's derivatives with respect to numbers of the model
//! file, for the suite or one analysis; and the parameters and files `run --sensitivity` shares with it.

use super::input::{open_model, ModelInput};
use super::strict::refuse_warned;
use super::sweeps::SweepArgs;
use crate::output::{failed_lines, write_table, wrote, Failure, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::solver::Mode;
use elastokin::suspensions::design::{self, sensitivity::effect_unit, Parameters, SuiteSensitivity};
use elastokin::suspensions::kc::{self, Settings};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct SensitivityArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    /// A number of the model file by its JSON pointer; give it once per parameter
    #[arg(long = "param", value_name = "POINTER")]
    pub params: Vec<String>,
    /// Every coordinate of every hardpoint (a Chrono file's Location points), after those given by --param
    #[arg(long)]
    pub hardpoints: bool,
    /// The derivatives of the figures alone: the rows read only as far as the figures read them (no force
    /// in every joint and element of the load sweeps, the roll centre at design only) and moved only where
    /// the figures read them; no sensitivity_<table>.csv (the same figures and derivatives, in about
    /// two fifths of the time)
    #[arg(long)]
    pub figures_only: bool,
    #[command(flatten)]
    pub sweeps: SweepArgs,
    /// Where sensitivity.csv, each analysis's sensitivity_<table>.csv and report.html go; the directory is
    /// replaced as a whole on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// `sensitivity`: every figure's and cell's derivatives with respect to numbers of the model file, for the
/// suite or one analysis.
pub fn run(args: SensitivityArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let settings = Settings {
        range: args.sweeps.range,
        steps: args.sweeps.load.steps,
        figures_only: args.figures_only,
        ..Settings::default()
    };
    args.sweeps.check(&settings)?;
    let read = open_model(&args.model, out, strict)?;
    let parameters = parameters(&args, &read)?;
    let which = args.sweeps.which();
    let suite = design::suite_sensitivity(&parameters, &which, &settings).map_err(|e| Failure::Run(e.to_string()))?;
    refuse_warned(strict, suite.analyses.iter().flat_map(|a| &a.report.warnings))?;
    if suite.analyses.is_empty() && !suite.failed.is_empty() {
        return Err(Failure::Run(format!(
            "no sensitivities: {}\n(nothing was written; {} is untouched)",
            failed_lines(&suite.failed),
            args.out.display()
        )));
    }
    let mut provenance =
        Provenance::new(&args.model, &read.bytes, kc::mode_word(Mode::Corrected), args.sweeps.load.steps);
    provenance.range = args.sweeps.range;
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let mut written = write_sensitivities(&staging, &suite, &parameters, &provenance, args.figures_only)?;
        let html = elastokin::html::sensitivity_html(&suite, &parameters, &read.file.name, &provenance.to_json());
        written.push(staging.write("report.html", html.as_bytes())?);
        Ok(written)
    })()
    .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line(format!(
        "{} — {} parameters, {} steps per sweep, corrected mode",
        read.file.name,
        parameters.len(),
        args.sweeps.load.steps
    ))?;
    print_effects(out, &suite, &parameters)?;
    out.line("")?;
    out.line(wrote(&written))?;
    if suite.failed.is_empty() {
        return Ok(());
    }
    Err(Failure::Run(format!(
        "{} of the analyses' sensitivities failed (the others' are in {}):\n{}",
        suite.failed.len(),
        args.out.display(),
        failed_lines(&suite.failed)
    )))
}

/// The parameters asked for: those given by `--param`, then with `--hardpoints` every hardpoint
/// coordinate; none is refused.
fn parameters(args: &SensitivityArgs, read: &ModelInput) -> Result<Parameters, Failure> {
    if args.hardpoints {
        hardpoint_parameters(&args.model, read, &args.params, "--hardpoints", "--param POINTER")
    } else if args.params.is_empty() {
        Err(Failure::Input(
            "no parameters: give --param POINTER (a JSON pointer into the model file) or --hardpoints".into(),
        ))
    } else {
        let base = read.document(&args.model)?;
        Parameters::new(&base, &args.params).map_err(|e| Failure::Input(format!("{}: {e}", args.model.display())))
    }
}

/// Per analysis, each figure with a value and the three parameters with the largest effects on it (per mm
/// or per %), or the first parameter it has no derivative to and why; then the analyses skipped.
fn print_effects(out: &Stdout, suite: &SuiteSensitivity, parameters: &Parameters) -> Result<(), Failure> {
    for a in &suite.analyses {
        out.line("")?;
        out.line(&a.report.description)?;
        for (j, figure) in a.report.figures.iter().enumerate() {
            if figure.value.is_none() {
                continue;
            }
            out.line(figure.line(a.report.units))?;
            // A figure without a unit (a ratio) changes by so much per mm or per %.
            let written = figure.written(a.report.units);
            let unit = if written.unit == "-" { String::new() } else { format!("{} ", written.unit) };
            for (k, e) in a.largest_effects(j, parameters, 3) {
                let pointer = &parameters.pointers[k];
                let per = effect_unit(pointer);
                let e = kc::significant(e * written.factor, 3);
                out.line(format!("      {:<40} {:>12} {unit}per {per}", design::parameter_words(pointer), e))?;
            }
            let missing = (0..parameters.len()).filter_map(|k| a.figures[k][j].err().map(|e| (k, e))).next();
            if let Some((k, why)) = missing {
                out.line(format!("      {:<40} {}", design::parameter_words(&parameters.pointers[k]), why.reason()))?;
            }
        }
    }
    for s in &suite.skipped {
        out.line(format!("\n{}: skipped — {}", s.analysis.name(), s.reason))?;
    }
    Ok(())
}

/// The parameters `params` of the model file `model` (read as `read`), then every coordinate of every
/// hardpoint; a model without hardpoints is refused, naming the `flag` that asked for them and the
/// `other` way to name numbers.
pub fn hardpoint_parameters(
    model: &Path,
    read: &ModelInput,
    params: &[String],
    flag: &str,
    other: &str,
) -> Result<Parameters, Failure> {
    let origin = model.display().to_string();
    let base = read.document(model)?;
    let all = design::hardpoint_pointers(&base);
    if all.is_empty() {
        return Err(Failure::Input(format!(
            "{origin}: {flag} found no hardpoints (a template's or the general form's suspension.<form>.hardpoints, \
             a Chrono file's Location points); name the numbers with {other}"
        )));
    }
    let mut pointers = params.to_vec();
    pointers.extend(all.into_iter().filter(|p| !params.contains(p)));
    Parameters::new(&base, &pointers).map_err(|e| Failure::Input(format!("{origin}: {e}")))
}

/// `sensitivity.csv` and each analysis's `sensitivity_<table>.csv`, staged.
pub fn write_sensitivities(
    staging: &Staging,
    suite: &SuiteSensitivity,
    parameters: &Parameters,
    provenance: &Provenance,
    figures_only: bool,
) -> Result<Vec<PathBuf>, Failure> {
    let mut written =
        vec![staging.write("sensitivity.csv", &write_table(&suite.figure_table(parameters), provenance))?];
    // Read for the figures alone, the tables have no derivatives.
    for a in suite.analyses.iter().filter(|_| !figures_only) {
        let rows = a.row_table(parameters);
        written.push(staging.write(&format!("{}.csv", rows.name), &write_table(&rows, provenance))?);
    }
    Ok(written)
}
