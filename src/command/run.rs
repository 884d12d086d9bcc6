//! `elastokin run MODEL`: the model's K&C suite (or one analysis), its headline figures printed as each
//! analysis ends, and its tables, plots, report page and summary written.

use super::input::{read_model, read_targets_file};
use super::sensitivity::{hardpoint_parameters, write_sensitivities};
use super::strict::{refuse_implausible, refuse_warned};
use super::sweeps::SweepArgs;
use crate::output::{failed_lines, write_table, wrote, Failure, Progress, Provenance, Staging, Stdout};
use clap::{Args, ValueEnum};
use elastokin::plot;
use elastokin::solver::Mode;
use elastokin::suspensions::check::ModelCheck;
use elastokin::suspensions::design;
use elastokin::suspensions::design::judge::{ConstraintCheck, TargetPoint};
use elastokin::suspensions::design::targets::Reading;
use elastokin::suspensions::kc::{self, Analysis, Chart, KcReport, Settings, SuiteEvent, Tolerance};
use elastokin::suspensions::{LoadPoint, SuspensionFile};
use std::collections::HashMap;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct RunArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    #[command(flatten)]
    pub sweeps: SweepArgs,
    /// Corrected: Newton iterations to the exact equilibrium at every step; paper: the paper's linear steps
    #[arg(long, value_enum, default_value_t = ModeName::Corrected)]
    pub mode: ModeName,
    /// Road loads with the wheel-centre height held by the rig, or the wheel free on its spring (road
    /// loads carry vehicle.corner_load, or the design wheel load when the file has no vehicle section)
    #[arg(long, value_enum, default_value_t = WheelName::Held)]
    pub wheel: WheelName,
    /// Where the vertical, lateral and braking forces act: the contact patch, as the tyre loads the wheel,
    /// or the wheel centre, as a rig loading the hub does (traction acts at the wheel centre either way)
    #[arg(long, value_enum, default_value_t = LoadPointName::ContactPatch)]
    pub load_point: LoadPointName,
    /// The units of bump steer and camber gain (deg/m, deg/10 mm or arc minutes per mm) and of the
    /// aligning-torque compliances (deg/kN·m, or deg/100 N·m with either rig unit); summary.json's figure
    /// units and its settings say which
    #[arg(long, value_enum, default_value_t = UnitsName::DegPerM)]
    pub units: UnitsName,
    /// Where the files go; the directory is replaced as a whole when the run succeeds
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Largest estimated error accepted without a warning: angles in degrees, lengths in mm, headline
    /// figures in per cent of their value
    #[arg(long, value_name = "ANGLE,LENGTH,PERCENT", default_value = "0.001,0.001,0.5", value_parser = parse_tolerance)]
    pub tolerance: Tolerance,
    /// Also write the 6x6 wheel compliance at every step (<analysis>_compliance.csv) of parallel travel,
    /// roll, the vertical force and the road loads
    #[arg(long)]
    pub compliance: bool,
    /// Also write every plot as PNG beside its SVG
    #[arg(long)]
    pub png: bool,
    /// At a limit point (a load the suspension cannot carry, a travel its linkage cannot reach), follow the
    /// path on through it by arc length and plot all of it; without it the sweep stops there. Either way a
    /// warning (limit-point) names the load
    #[arg(long)]
    pub through_limits: bool,
    /// Also the sensitivities of every figure and cell to every hardpoint coordinate (of the
    /// corrected path, whatever --mode): sensitivity.csv and sensitivity_<table>.csv, and a section of
    /// report.html with each figure's largest effects (as `sensitivity --hardpoints` gives them)
    #[arg(long)]
    pub sensitivity: bool,
    /// The arc-length step of --through-limits, in the analysis's own units like --range (m, N or N m):
    /// the change of travel or load of the first arc-length step, from the last load step before the
    /// limit point; later steps change the load less where the suspension gives way. Default: one load
    /// step, (TO - FROM) / STEPS (needs --analysis)
    #[arg(long, value_name = "VALUE", requires = "through_limits", value_parser = parse_arc_step, allow_negative_numbers = true)]
    pub arc_step: Option<f64>,
    /// A TARGETS file (as `tune` reads, `free` optional) to judge the run against: its figure and curve
    /// targets and packaging constraints met or not, in the report's summary and targets.csv; the run
    /// exits 1 when one is not met
    #[arg(long, value_name = "FILE")]
    pub targets: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModeName {
    Corrected,
    Paper,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum UnitsName {
    /// deg/m and deg/kN·m
    #[value(name = "deg-per-m")]
    DegPerM,
    /// deg/10 mm and deg/100 N·m, as K&C rigs print them
    #[value(name = "deg-per-10mm")]
    DegPer10Mm,
    /// arc minutes per mm and deg/100 N·m
    #[value(name = "arcmin-per-mm")]
    ArcminPerMm,
}

impl UnitsName {
    fn units(self) -> kc::Units {
        match self {
            UnitsName::DegPerM => kc::Units::DegPerM,
            UnitsName::DegPer10Mm => kc::Units::DegPer10Mm,
            UnitsName::ArcminPerMm => kc::Units::ArcminPerMm,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LoadPointName {
    /// At the contact patch.
    ContactPatch,
    /// At the wheel centre.
    WheelCentre,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum WheelName {
    Held,
    Free,
}

fn parse_arc_step(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "'{text}' is not a positive number: give the arc-length step in the analysis's own units (m for \
             travel, N for a force, N m for the aligning torque), e.g. --arc-step 50"
        )),
    }
}

fn parse_tolerance(text: &str) -> Result<Tolerance, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [angle, length, percent] = parts[..] else {
        return Err("give ANGLE,LENGTH,PERCENT (degrees, mm, per cent), e.g. --tolerance 0.001,0.001,0.5".into());
    };
    let parse = |s: &str, what: &str| match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("{what} '{s}' is not a positive number")),
    };
    Ok(Tolerance {
        angle_deg: parse(angle, "ANGLE")?,
        length_m: parse(length, "LENGTH")? * 1e-3,
        relative: parse(percent, "PERCENT")? * 1e-2,
    })
}

/// `run`: the suite (or one analysis) of the model, its results written whole into `--out`, or nothing
/// written when nothing ran; the analyses that failed make it fail after the others' results are written.
pub fn run(args: RunArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    if args.arc_step.is_some() && args.sweeps.analysis.is_none() {
        return Err(Failure::Input(
            "--arc-step needs --analysis NAME: each analysis has its own load parameter and units".into(),
        ));
    }
    let settings = settings(&args);
    args.sweeps.check(&settings)?;
    let read = read_model(&args.model)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    // Checked once: `--strict` refuses an implausible model before spending any time on it, and the suite
    // reports the same check.
    let model_check = elastokin::suspensions::check_model(&read.file).ok();
    if strict {
        refuse_implausible(&args.model, model_check.as_ref())?;
    }
    // A TARGETS file is read before anything runs, so that a mistake in it costs no solving.
    // With the model's document, which the packaging constraints are judged on.
    let targets = match &args.targets {
        Some(path) => {
            let document = read.document(&args.model)?;
            let (bytes, targets) = read_targets_file(path, &document, Reading::ToJudge)?;
            Some((bytes, targets, document))
        }
        None => None,
    };
    let mut provenance = provenance(&args, &read.bytes, &settings);
    if let (Some(path), Some((bytes, _, _))) = (&args.targets, &targets) {
        provenance.targets = Some((path.display().to_string(), elastokin::provenance::sha256_hex(bytes)));
    }
    let which = args.sweeps.which();
    // The sensitivities' parameters, refused before anything runs when the model has none.
    let hardpoints = match args.sensitivity {
        true => Some(hardpoint_parameters(
            &args.model,
            &read,
            &[],
            "--sensitivity",
            "`elastokin sensitivity --param POINTER`",
        )?),
        false => None,
    };
    let staging = Staging::new(&args.out)?;
    let count = if which.is_empty() { kc::ALL.len() } else { which.len() };
    let progress = Progress::new("analyses", count, quiet);
    let result = (|| -> Result<Ran, Failure> {
        out.line(format!("{} — {} mode", read.file.name, kc::mode_word(settings.mode)))?;
        // The model's own warnings first (millimetres, a spring rate in N/mm): they say what the figures
        // below are worth; the run's, found while solving, after the figures.
        let model_warnings = model_check.as_ref().map(|c| c.warnings.clone()).unwrap_or_default();
        for w in &model_warnings {
            out.line(format!("warning [{}]: {}", w.code, w.message))?;
        }
        let report = solve(&read.file, model_check, &which, &settings, out, &progress)?;
        // Nothing ran: there is nothing to report but the reasons, and the previous results stay.
        if report.analyses.is_empty() && !report.failed.is_empty() {
            return Err(Failure::Run(failed_lines(&report.failed)));
        }
        let found: Vec<_> = report.warnings.iter().filter(|w| !model_warnings.contains(w)).collect();
        if !found.is_empty() {
            out.line("")?;
            for w in found {
                out.line(format!("warning [{}]: {}", w.code, w.message))?;
            }
        }
        refuse_warned(strict, report.all_warnings())?;
        let (mut written, svgs) = write_analyses(&staging, &report, &provenance, args.png)?;
        let sensitivities = match &hardpoints {
            Some(parameters) => {
                let suite = design::suite_sensitivity(parameters, &which, &settings)
                    .map_err(|e| Failure::Run(e.to_string()))?;
                written.extend(write_sensitivities(&staging, &suite, parameters, &provenance, settings.figures_only)?);
                Some(suite)
            }
            None => None,
        };
        let judged = targets.as_ref().map(|(_, t, document)| design::judge::judge(&report, document, t));
        let unmet = match &judged {
            Some((points, constraints)) => {
                let table = design::judge::judged_table(points, constraints);
                written.push(staging.write("targets.csv", &write_table(&table, &provenance))?);
                print_judged(out, points, constraints)?
            }
            None => Vec::new(),
        };
        let extras = elastokin::html::Extras {
            sensitivities: sensitivities.as_ref().zip(hardpoints.as_ref()),
            judged: judged.as_ref().map(|(points, constraints)| elastokin::html::Judged { points, constraints }),
        };
        written.extend(write_report(&staging, &report, &read.file, &provenance, &svgs, extras)?);
        Ok(Ran { written, failed: report.failed, unmet })
    })();
    progress.finish();
    let Ran { written, failed, unmet } = result.map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line("")?;
    out.line(wrote(&written))?;
    // The others' results are written whole; the run still failed.
    if !failed.is_empty() {
        return Err(Failure::Run(format!(
            "{} of the analyses failed (the others' results are in {}):\n{}",
            failed.len(),
            args.out.display(),
            failed_lines(&failed)
        )));
    }
    if !unmet.is_empty() {
        return Err(Failure::Run(format!(
            "{} target points and packaging constraints not met (the results are in {}):\n{}",
            unmet.len(),
            args.out.display(),
            unmet.join("\n")
        )));
    }
    Ok(())
}

/// What a run wrote, the analyses that failed, and the targets it did not meet (each as printed).
struct Ran {
    written: Vec<PathBuf>,
    failed: Vec<kc::Failed>,
    unmet: Vec<String>,
}

/// Prints each target point and packaging constraint judged, met or not, as `tune` prints its verdicts;
/// gives the lines of those not met.
fn print_judged(out: &Stdout, points: &[TargetPoint], constraints: &[ConstraintCheck]) -> Result<Vec<String>, Failure> {
    out.line("")?;
    out.line("targets:")?;
    let mut unmet = Vec::new();
    for target in design::judge::by_target(points) {
        // A target judged whole is one line, its measure in words.
        if let Some(words) = design::judge::judged_whole(target) {
            let met = target[0].met();
            let line = format!("{} {}: {words}", if met { "met:" } else { "NOT met:" }, target[0].target.label);
            if !met {
                unmet.push(line.clone());
            }
            out.line(format!("  {line}"))?;
            continue;
        }
        for p in target {
            let at = p.at.map_or(String::new(), |at| format!(" at {}", kc::plain(at)));
            let line = match &p.reached {
                Ok(r) => format!(
                    "{} {}{at}: {} for {} ± {}",
                    if p.met() { "met:" } else { "NOT met:" },
                    p.target.label,
                    kc::significant(*r, 4),
                    kc::significant(p.aim, 4),
                    kc::significant(p.target.tolerance, 2)
                ),
                Err(why) => format!("NOT judged: {}{at}: {why}", p.target.label),
            };
            if !p.met() {
                unmet.push(line.clone());
            }
            out.line(format!("  {line}"))?;
        }
    }
    for c in constraints {
        let mm = |v: f64| if v.is_finite() { format!("{} mm", kc::significant(v * 1e3, 4)) } else { "∞".into() };
        let line = match &c.reached {
            Ok((v, min, max)) => format!(
                "{} {}: {} within {} to {}",
                if c.met() { "met:" } else { "NOT met:" },
                c.constraint.said(),
                mm(*v),
                mm(*min),
                mm(*max)
            ),
            Err(why) => format!("NOT judged: {}: {why}", c.constraint.said()),
        };
        if !c.met() {
            unmet.push(line.clone());
        }
        out.line(format!("  {line}"))?;
    }
    Ok(unmet)
}

/// The suite's settings as the arguments give them.
fn settings(args: &RunArgs) -> Settings {
    Settings {
        range: args.sweeps.range,
        steps: args.sweeps.load.steps,
        mode: match args.mode {
            ModeName::Corrected => Mode::Corrected,
            ModeName::Paper => Mode::Paper,
        },
        height_held: args.wheel == WheelName::Held,
        load_point: match args.load_point {
            LoadPointName::ContactPatch => LoadPoint::ContactPatch,
            LoadPointName::WheelCentre => LoadPoint::WheelCentre,
        },
        compliance: args.compliance,
        tolerance: args.tolerance,
        through_limits: args.through_limits,
        arc_step: args.arc_step,
        error_estimate: true,
        // The report draws the model moving through each analysis.
        motion: true,
        figures_only: false,
        units: args.units.units(),
    }
}

/// How the run is made, for every file it writes: the model file (its `bytes` hashed) and the settings.
fn provenance(args: &RunArgs, bytes: &[u8], settings: &Settings) -> Provenance {
    let mut provenance = Provenance::new(&args.model, bytes, kc::mode_word(settings.mode), args.sweeps.load.steps);
    provenance.wheel = Some(if settings.height_held { "held" } else { "free" });
    provenance.load_point = Some(match settings.load_point {
        LoadPoint::ContactPatch => "contact_patch",
        LoadPoint::WheelCentre => "wheel_centre",
    });
    provenance.range = args.sweeps.range;
    provenance.tolerance = Some(settings.tolerance);
    provenance
}

/// The suite run on `file`, the terminal hearing of each analysis as it ends (its headline figures, or
/// why it was skipped or failed); a closed pipe stops the printing, not the run.
fn solve(
    file: &SuspensionFile,
    model_check: Option<ModelCheck>,
    which: &[Analysis],
    settings: &Settings,
    out: &Stdout,
    progress: &Progress,
) -> Result<KcReport, Failure> {
    let mut printed: Result<(), Failure> = Ok(());
    let report = kc::run_suite_checked(file, model_check, which, settings, |event| {
        let said = match event {
            SuiteEvent::Starting(a) => {
                progress.begin(a.name());
                Ok(())
            }
            SuiteEvent::Done(report) => {
                progress.end(None);
                progress.suspend(|| -> Result<(), Failure> {
                    out.line("")?;
                    report.headline().iter().try_for_each(|line| out.line(line))
                })
            }
            SuiteEvent::Skipped(s) => {
                progress.end(None);
                progress.suspend(|| out.line(format!("\n{}: skipped — {}", s.analysis.name(), s.reason)))
            }
            SuiteEvent::Failed(f) => {
                progress.end(None);
                progress.suspend(|| out.line(format!("\n{}: failed — {}", f.analysis.name(), f.reason)))
            }
        };
        if printed.is_ok() {
            printed = said;
        }
    });
    printed?;
    Ok(report)
}

/// Each analysis's table (and compliance table) as CSV and each of its plots as SVG (and PNG when `png`),
/// staged; with the plots drawn, by chart name, for the report's page: each plot is drawn once.
fn write_analyses<'a>(
    staging: &Staging,
    report: &'a KcReport,
    provenance: &Provenance,
    png: bool,
) -> Result<(Vec<PathBuf>, HashMap<&'a str, String>), Failure> {
    let mut written = Vec::new();
    let mut svgs = HashMap::new();
    for analysis in &report.analyses {
        let table = &analysis.table;
        written.push(staging.write(&format!("{}.csv", table.name), &write_table(table, provenance))?);
        if let Some(c) = &analysis.compliance {
            written.push(staging.write(&format!("{}.csv", c.name), &write_table(c, provenance))?);
        }
        for chart in &analysis.charts {
            let svg = plot::svg(chart).map_err(|e| Failure::Run(format!("plot '{}': {e}", chart.name)))?;
            let stamped = provenance.stamp_svg(&svg);
            written.push(staging.write(&format!("{}.svg", chart.name), stamped.as_bytes())?);
            svgs.insert(chart.name.as_str(), svg);
            if png {
                let png = plot::png(chart).map_err(|e| Failure::Run(format!("plot '{}': {e}", chart.name)))?;
                written.push(staging.write(&format!("{}.png", chart.name), &png)?);
            }
        }
    }
    Ok((written, svgs))
}

/// `report.html` (its plots those drawn for the files, `svgs`, and the sensitivities' section when run)
/// and `summary.json`, staged.
fn write_report(
    staging: &Staging,
    report: &KcReport,
    file: &SuspensionFile,
    provenance: &Provenance,
    svgs: &HashMap<&str, String>,
    extras: elastokin::html::Extras,
) -> Result<Vec<PathBuf>, Failure> {
    let drawn = |chart: &Chart| svgs.get(chart.name.as_str()).map_or_else(|| plot::svg(chart), |svg| Ok(svg.clone()));
    let html = elastokin::html::report_html_with(report, file, &provenance.to_json(), drawn, extras);
    let page = staging.write("report.html", html.as_bytes())?;
    let mut summary = serde_json::to_value(report).map_err(|e| Failure::Run(e.to_string()))?;
    summary["provenance"] = provenance.to_json();
    let text = serde_json::to_string_pretty(&summary).map_err(|e| Failure::Run(e.to_string()))?;
    Ok(vec![page, staging.write("summary.json", text.as_bytes())?])
}
