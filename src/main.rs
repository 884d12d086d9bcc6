//! The `elastokin` command: K&C analyses of a suspension model file.
//!
//! ```text
//! elastokin run MODEL [--analysis NAME] [--range FROM,TO] [--steps N] [--mode paper|corrected]
//!                     [--wheel held|free] [--through-limits [--arc-step VALUE]] [--out DIR]
//! elastokin check MODEL
//! elastokin batch MODEL VARIANTS [--shard I/N] [--out DIR]
//! elastokin merge [--out DIR] SHARD...
//! ```
//!
//! What the command depends on, and why: clap parses the arguments (help, `--version`, suggestions for
//! mistyped names, errors that name the argument); csv writes the tables (quoting done right); sha2 gives
//! each result the model file's SHA-256; indicatif draws progress bars on a terminal.

use clap::{Args, Parser, Subcommand, ValueEnum};
use elastokin::solver::{LoadPath, Mode, SolverOptions, StaticSolver};
use elastokin::suspensions::import::chrono::Imported;
use elastokin::suspensions::{Rig, Side, SuspensionFile};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod batch;
mod merge;
mod output;
use elastokin::plot;
use elastokin::suspensions::kc::{self, Analysis, Settings, SuiteEvent, Tolerance};
use output::{note, write_table, Failure, Part, Progress, Provenance, Staging, Stdout};

/// The most load steps a sweep may take (the suite's limit, which its advice on steps respects).
pub use elastokin::solver::MAX_STEPS;

const EXIT_STATUS: &str = "\
Exit status: 0 success; 1 a run that failed while solving or writing (the analyses that ran are written \
beside the failed one's reason; when none ran, or writing failed, previous results are left untouched); 2 bad \
arguments or input files.";

/// elastokin — quasi-static elastokinematics of suspensions.
///
/// MODEL is a JSON file (SI units, ISO 8855 axes, left corner); see examples/*.json.
#[derive(Debug, Parser)]
#[command(name = "elastokin", version, propagate_version = true, after_help = EXIT_STATUS, arg_required_else_help = true)]
pub struct Cli {
    /// Print nothing but errors: no progress, no headline figures (the exit status and the files tell)
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// Treat every warning (implausible model, error estimate over the tolerance) as an error: exit 2
    /// for the model's, 1 for a result's, and write no results
    #[arg(long, global = true)]
    pub strict: bool,
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the model's K&C tests: write CSV, SVG, report.html and summary.json, print headline figures
    #[command(after_help = EXIT_STATUS)]
    Run(RunArgs),
    /// Parse the model and report bodies, degrees of freedom, redundant or unrestrained parts
    #[command(after_help = EXIT_STATUS)]
    Check(CheckArgs),
    /// Run design variants in parallel: one table of bump steer, camber gain and wheel rate at design
    ///
    /// VARIANTS has one variant per line: an optional `name:`, then `/json/pointer=value` edits of the
    /// model separated by `;`. Blank lines and lines starting with `#` are skipped. Each variant walks
    /// parallel wheel travel ±20 mm in 8 steps, corrected mode.
    #[command(after_help = EXIT_STATUS)]
    Batch(BatchArgs),
    /// Sensitivities of every figure and every table cell of the K&C suite (or one analysis) to numbers
    /// of the model file, through the equilibrium, each with its error estimate
    ///
    /// Each parameter is a JSON pointer into the model file, as batch variants name them
    /// (/suspension/macpherson/hardpoints/tie_rod_inner/2, /suspension/macpherson/spring/rate); --hardpoints
    /// takes every coordinate of every hardpoint. Each derivative is a Richardson difference of the recorded
    /// equilibria moved one Newton iteration by the moved model, with its error estimate. Writes
    /// sensitivity.csv (analysis, figure × parameter: derivative, its error estimate and effect per mm or
    /// per %, or why there is none) and sensitivity_<table>.csv per analysis (every cell's derivative and
    /// its estimate), and prints each figure's parameters ranked by effect. Corrected mode.
    #[command(after_help = EXIT_STATUS)]
    Sensitivity(SensitivityArgs),
    /// Move the free numbers of a model within their bounds until its figures and curves meet targets
    ///
    /// TARGETS is JSON: "free" (each number's JSON pointer and [min, max]), "targets" (a headline figure
    /// "analysis/key" with its "value", a table column's "curve" "analysis/column" through [load parameter,
    /// value] "points", or a "measured" K&C rig CSV of an analysis, each with its "tolerance" and an
    /// optional "range"), optional "constraints" (a "distance" between two hardpoints within min and max,
    /// a hardpoint kept "outside_sphere" or "outside_box") and "steps". Bound-constrained Gauss-Newton with
    /// the sensitivities. Writes tuned.json (the model file with the numbers moved, every other key
    /// and the order of keys kept), tune.csv (each iteration), tune_targets.csv (each residual before and
    /// after) and report.html; exits 1 when a target is not met, saying why.
    #[command(after_help = EXIT_STATUS)]
    Tune(TuneArgs),
    /// Stack up tolerances: how far each figure spreads when the model's numbers are made within their
    /// tolerances
    ///
    /// TOLERANCES is JSON: "tolerances" (each number's JSON pointer and its ± band in the file's units, or
    /// "15%"), "hardpoints" (± for every hardpoint coordinate), "analyses" (default: the suite) and
    /// "steps". First order from the sensitivities: each figure's worst case and standard deviation
    /// (the numbers independent and uniform over their bands), its contributors ranked; --monte-carlo N
    /// checks it on N sampled models. Writes tolerance.csv, tolerance_contributions.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Tolerance(ToleranceArgs),
    /// Compare designs: two or more models' K&C suites (and measured K&C files) overlaid
    ///
    /// Each DESIGN is a model file (JSON) or a measured K&C file (CSV, its first column the load parameter
    /// and a comment line `# analysis: NAME`, as docs/kc-rig-data.md says). Every curve of every analysis
    /// the models share is overlaid, a colour and a legend entry per design; the figures side by side with
    /// their error estimates and each model's difference to the first; the geometry overlaid. Writes
    /// compare.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Compare(CompareArgs),
    /// The whole car from a front and a rear model: roll stiffness and its distribution, roll gradient,
    /// lateral load-transfer distribution, and the understeer budget (deg/g) term by term
    ///
    /// VEHICLE is JSON: "name", "front" and "rear" (model files, paths relative to VEHICLE), "car" (mass
    /// kg, cg_height m, wheelbase m, front_weight_share, steering_ratio) and "tyres" (cornering_stiffness
    /// and camber_stiffness N/deg per tyre, vertical_rate N/m, pneumatic_trail m), "rear_tyres" if they
    /// differ; docs/vehicle.md gives every formula. Writes vehicle.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Vehicle(VehicleArgs),
    /// Join the batch.csv files of `batch --shard I/N` runs into the batch.csv one `batch` writes
    ///
    /// The shards must be of one model and one variants file (the same SHA-256 in their first lines) and
    /// the same N, each of 1..N given once. The rows are those of a single `batch`, byte for byte; the
    /// first line says the table was merged from N shards.
    #[command(after_help = EXIT_STATUS)]
    Merge(MergeArgs),
    /// Print the model in the general form (named bodies, joints, bushings, springs and the corner
    /// description): a template expanded, ready to edit into any other suspension
    #[command(after_help = EXIT_STATUS)]
    Expand(CheckArgs),
    /// Read another tool's suspension file and print it as an elastokin model file (the general form);
    /// what was read, taken or left out goes to standard error, a line each
    #[command(after_help = EXIT_STATUS)]
    Import(ImportArgs),
}

#[derive(Debug, Args)]
pub struct ImportArgs {
    /// The format: `chrono`, a Project Chrono vehicle suspension file (data/vehicle/*/suspension/*.json)
    #[arg(value_enum)]
    pub format: ImportFormat,
    /// The file
    pub file: PathBuf,
    /// The loaded tyre radius, m (a Chrono suspension file has no tyre; default 0.3)
    #[arg(long, value_name = "M", value_parser = parse_loaded_radius, allow_negative_numbers = true)]
    pub loaded_radius: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ImportFormat {
    /// Project Chrono (projectchrono/chrono) suspension JSON
    Chrono,
}

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
}

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
}

#[derive(Debug, Args)]
pub struct BatchArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
    #[arg(help = format!("The variants file, one variant per line (format in --help; at most {})", batch::MAX_VARIANTS))]
    pub variants: PathBuf,
    /// Run only shard I of N (I from 1 to N, as SLURM_ARRAY_TASK_ID counts with --array=1-N): variant k
    /// (counting from 0) of V belongs to shard floor(k*N/V)+1, contiguous blocks differing in size by at
    /// most one (empty ones when N > V). Its batch.csv adds the column variant_number and says I/N in its
    /// first line; `elastokin merge` joins the shards
    #[arg(long, value_name = "I/N", value_parser = batch::Shard::parse)]
    pub shard: Option<batch::Shard>,
    /// Where batch.csv goes; the directory is replaced as a whole when the batch succeeds
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// Which analyses a command walks, over what range, in how many steps: `run`'s and `sensitivity`'s.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// One analysis instead of all of them (--help lists each one's load parameter, units and default range)
    #[arg(long, value_enum, value_name = "NAME")]
    pub analysis: Option<AnalysisName>,
    /// The load parameter's range, in the analysis's own units (needs --analysis)
    #[arg(long, value_name = "FROM,TO", value_parser = parse_range, allow_hyphen_values = true)]
    pub range: Option<(f64, f64)>,
    #[arg(
        long,
        value_name = "N",
        default_value_t = 32,
        value_parser = parse_steps,
        allow_negative_numbers = true,
        help = format!("Load steps per sweep, 1 to {MAX_STEPS}")
    )]
    pub steps: usize,
}

impl SweepArgs {
    /// The analyses asked for by name (none: the suite).
    fn which(&self) -> Vec<Analysis> {
        self.analysis.map(|a| vec![a.analysis()]).unwrap_or_default()
    }

    /// Refuses a range without an analysis to give it units, and settings an analysis cannot take, as bad
    /// input before anything runs.
    fn check(&self, settings: &Settings) -> Result<(), Failure> {
        if self.range.is_some() && self.analysis.is_none() {
            return Err(Failure::Input(
                "--range needs --analysis NAME: each analysis has its own load parameter and units".into(),
            ));
        }
        let which = self.which();
        for &a in if which.is_empty() { &kc::ALL[..] } else { &which[..] } {
            kc::check_settings(a, settings).map_err(|e| Failure::Input(e.to_string()))?;
        }
        Ok(())
    }
}

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
    /// Where tolerance.csv, tolerance_contributions.csv and report.html go; the directory is replaced as a
    /// whole on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

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

#[derive(Debug, Args)]
pub struct VehicleArgs {
    /// The vehicle file (JSON; see examples/vehicle/compact_car.json)
    pub vehicle: PathBuf,
    #[arg(
        long,
        value_name = "N",
        default_value_t = 32,
        value_parser = parse_steps,
        allow_negative_numbers = true,
        help = format!("Load steps of each axle's roll and parallel travel, 1 to {MAX_STEPS}")
    )]
    pub steps: usize,
    /// Where vehicle.csv and report.html go; the directory is replaced as a whole on success
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The shards: each a batch.csv that `batch --shard I/N` wrote, or the --out directory holding it
    #[arg(required = true, value_name = "SHARD")]
    pub shards: Vec<PathBuf>,
    /// Where the merged batch.csv goes; the directory is replaced as a whole when the merge succeeds
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// An analysis by its command-line name. Its help (what its load parameter is, and its default range) is
/// the library's declaration of it (`Analysis::parameter`, `Analysis::default_range`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AnalysisName(Analysis);

/// Every analysis, as the command lists them.
static ANALYSIS_NAMES: std::sync::LazyLock<Vec<AnalysisName>> =
    std::sync::LazyLock::new(|| kc::ALL.iter().map(|&a| AnalysisName(a)).collect());

impl ValueEnum for AnalysisName {
    fn value_variants<'a>() -> &'a [Self] {
        &ANALYSIS_NAMES
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let a = self.0;
        let help = match a.rig_words() {
            Some(rig) => format!("{}, {rig}; {}", a.parameter(), a.default_range()),
            None => format!("{}; {}", a.parameter(), a.default_range()),
        };
        Some(clap::builder::PossibleValue::new(self.0.name()).help(help))
    }
}

impl AnalysisName {
    /// The analysis of this name.
    fn analysis(self) -> Analysis {
        self.0
    }
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

fn parse_steps(text: &str) -> Result<usize, String> {
    let n: u64 = text.trim().parse().map_err(|_| format!("'{text}' is not a whole number of steps"))?;
    let n = usize::try_from(n).unwrap_or(usize::MAX);
    LoadPath::check_steps(n).map(|()| n)
}

fn parse_loaded_radius(text: &str) -> Result<f64, String> {
    use elastokin::suspensions::description::limits::LOADED_RADIUS;
    match text.trim().parse::<f64>() {
        Ok(v) if LOADED_RADIUS.contains(&v) => Ok(v),
        _ => Err(format!(
            "'{text}' is not a loaded tyre radius: give metres from {} to {} (a car's tyre is 0.25–0.40 m), e.g. \
             --loaded-radius 0.3",
            LOADED_RADIUS.start(),
            LOADED_RADIUS.end()
        )),
    }
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

fn parse_range(text: &str) -> Result<(f64, f64), String> {
    let (from, to) = text.split_once(',').ok_or("give FROM,TO, e.g. --range -0.02,0.02")?;
    let parse = |s: &str| match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{}' is not a finite number", s.trim())),
    };
    let (from, to) = (parse(from)?, parse(to)?);
    if from == to {
        return Err("FROM and TO must differ".into());
    }
    if !(to - from).is_finite() {
        return Err("FROM and TO are too far apart to step between".into());
    }
    Ok((from, to))
}

/// Reads an input file whole; errors name the file and what it is for.
fn read_input(path: &Path, what: &str) -> Result<(Vec<u8>, String), Failure> {
    elastokin::suspensions::file::read_input(path, what).map_err(Failure::Input)
}

/// A model read from a file: its bytes (for the provenance hash), the model parsed from them and, for
/// another tool's file, how it was read.
struct ModelInput {
    bytes: Vec<u8>,
    file: SuspensionFile,
    imported: Option<Imported>,
}

impl ModelInput {
    /// The line that says which format the file was read as (another tool's only), with the count of notes.
    fn format_line(&self) -> Option<String> {
        self.imported.as_ref().map(|i| {
            format!(
                "read as a Project Chrono {} suspension ({} notes: `elastokin import chrono FILE` lists them)",
                i.template,
                i.notes.len()
            )
        })
    }
}

/// The model file: an elastokin model file, or a Project Chrono suspension file (recognised by its
/// `"Type": "Suspension"` and `"Template"`).
fn read_model(path: &Path) -> Result<ModelInput, Failure> {
    let (bytes, text) = read_input(path, "MODEL")?;
    let (file, imported) = elastokin::suspensions::document::parse_model(&text, &path.display().to_string())
        .map_err(|e| Failure::Input(e.to_string()))?;
    Ok(ModelInput { bytes, file, imported })
}

/// Under `--strict`, a model its plausibility checks warn of (`check`) is refused before any time is spent
/// on it, every command alike (exit 2); a model the checks cannot build is left to the command to refuse.
fn refuse_implausible(path: &Path, check: Option<&elastokin::suspensions::check::ModelCheck>) -> Result<(), Failure> {
    let Some(check) = check.filter(|c| !c.warnings.is_empty()) else { return Ok(()) };
    let lines: Vec<String> = check.warnings.iter().map(|w| format!("warning [{}]: {}", w.code, w.message)).collect();
    Err(Failure::Input(format!("{}: refused under --strict:\n{}", path.display(), lines.join("\n"))))
}

/// Under `--strict`, results any analysis warned of (an error estimate over the tolerance, a limit point)
/// are refused, as `--help` promises for every command: nothing is written.
fn refuse_warned<'a>(strict: bool, warnings: impl Iterator<Item = &'a kc::Warning>) -> Result<(), Failure> {
    let codes: Vec<&str> = warnings.map(|w| w.code).collect();
    if strict && !codes.is_empty() {
        return Err(Failure::Run(format!("{} warning(s) under --strict: {}", codes.len(), codes.join(", "))));
    }
    Ok(())
}

/// [`refuse_implausible`] of the model in `file` at `path`, when `strict`.
fn strict_model(path: &Path, file: &SuspensionFile, strict: bool) -> Result<(), Failure> {
    if strict {
        refuse_implausible(path, elastokin::suspensions::check_model(file).ok().as_ref())?;
    }
    Ok(())
}

fn run(args: RunArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    if args.arc_step.is_some() && args.sweeps.analysis.is_none() {
        return Err(Failure::Input(
            "--arc-step needs --analysis NAME: each analysis has its own load parameter and units".into(),
        ));
    }
    let mode = match args.mode {
        ModeName::Corrected => Mode::Corrected,
        ModeName::Paper => Mode::Paper,
    };
    let settings = Settings {
        range: args.sweeps.range,
        steps: args.sweeps.steps,
        mode,
        height_held: args.wheel == WheelName::Held,
        load_point: match args.load_point {
            LoadPointName::ContactPatch => elastokin::suspensions::LoadPoint::ContactPatch,
            LoadPointName::WheelCentre => elastokin::suspensions::LoadPoint::WheelCentre,
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
    };
    args.sweeps.check(&settings)?;
    let read = read_model(&args.model)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    let ModelInput { bytes, file, .. } = read;
    // Checked once: `--strict` refuses an implausible model before spending any time on it, and the suite
    // reports the same check.
    let model_check = elastokin::suspensions::check_model(&file).ok();
    if strict {
        refuse_implausible(&args.model, model_check.as_ref())?;
    }
    let mut provenance = Provenance::new(&args.model, &bytes, kc::mode_word(mode), args.sweeps.steps);
    provenance.wheel = Some(if settings.height_held { "held" } else { "free" });
    provenance.load_point = Some(match settings.load_point {
        elastokin::suspensions::LoadPoint::ContactPatch => "contact_patch",
        elastokin::suspensions::LoadPoint::WheelCentre => "wheel_centre",
    });
    provenance.range = args.sweeps.range;
    provenance.tolerance = Some(settings.tolerance);
    let which = args.sweeps.which();
    // The sensitivities' parameters, refused before anything runs when the model has none.
    let hardpoints = match args.sensitivity {
        true => {
            Some(parameters_of(&args.model, &bytes, &[], "--sensitivity", "`elastokin sensitivity --param POINTER`")?)
        }
        false => None,
    };
    let staging = Staging::new(&args.out)?;
    let count = if which.is_empty() { kc::ALL.len() } else { which.len() };
    let progress = Progress::new("analyses", count, quiet);
    let result = (|| -> Result<(Vec<PathBuf>, Vec<kc::Failed>), Failure> {
        out.line(format!("{} — {} mode", file.name, kc::mode_word(mode)))?;
        // The terminal hears of each analysis as it ends; a closed pipe stops the printing, not the run.
        let mut printed: Result<(), Failure> = Ok(());
        let report = kc::run_suite_checked(&file, model_check, &which, &settings, |event| {
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
        // Nothing ran: there is nothing to report but the reasons, and the previous results stay.
        if report.analyses.is_empty() && !report.failed.is_empty() {
            return Err(Failure::Run(failed_lines(&report.failed)));
        }
        if !report.warnings.is_empty() {
            out.line("")?;
            for w in &report.warnings {
                out.line(format!("warning [{}]: {}", w.code, w.message))?;
            }
        }
        refuse_warned(strict, report.all_warnings())?;
        let mut written = Vec::new();
        // Each plot is drawn once: for its file and for the report's page.
        let mut svgs = std::collections::HashMap::new();
        for analysis in &report.analyses {
            let table = &analysis.table;
            written.push(staging.write(&format!("{}.csv", table.name), &write_table(table, &provenance))?);
            if let Some(c) = &analysis.compliance {
                written.push(staging.write(&format!("{}.csv", c.name), &write_table(c, &provenance))?);
            }
            for chart in &analysis.charts {
                let svg = plot::svg(chart).map_err(|e| Failure::Run(format!("plot '{}': {e}", chart.name)))?;
                let stamped = provenance.stamp_svg(&svg);
                written.push(staging.write(&format!("{}.svg", chart.name), stamped.as_bytes())?);
                svgs.insert(chart.name.as_str(), svg);
                if args.png {
                    let png = plot::png(chart).map_err(|e| Failure::Run(format!("plot '{}': {e}", chart.name)))?;
                    written.push(staging.write(&format!("{}.png", chart.name), &png)?);
                }
            }
        }
        let drawn =
            |chart: &kc::Chart| svgs.get(chart.name.as_str()).map_or_else(|| plot::svg(chart), |svg| Ok(svg.clone()));
        let sensitivities = match &hardpoints {
            Some(parameters) => {
                let suite = elastokin::suspensions::design::suite_sensitivity(parameters, &which, &settings)
                    .map_err(|e| Failure::Run(e.to_string()))?;
                written.extend(write_sensitivities(&staging, &suite, parameters, &provenance, settings.figures_only)?);
                Some(suite)
            }
            None => None,
        };
        let with = sensitivities.as_ref().zip(hardpoints.as_ref());
        let html = elastokin::html::report_html_with(&report, &file, &provenance.to_json(), drawn, with);
        written.push(staging.write("report.html", html.as_bytes())?);
        let mut summary = serde_json::to_value(&report).map_err(|e| Failure::Run(e.to_string()))?;
        summary["provenance"] = provenance.to_json();
        let text = serde_json::to_string_pretty(&summary).map_err(|e| Failure::Run(e.to_string()))?;
        written.push(staging.write("summary.json", text.as_bytes())?);
        Ok((written, report.failed))
    })();
    progress.finish();
    let (written, failed) = result.map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    out.line("")?;
    out.line(format!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))?;
    // The others' results are written whole; the run still failed.
    if failed.is_empty() {
        return Ok(());
    }
    Err(Failure::Run(format!(
        "{} of the analyses failed (the others' results are in {}):\n{}",
        failed.len(),
        args.out.display(),
        failed_lines(&failed)
    )))
}

/// The failed analyses, a line each: `name: reason`.
fn failed_lines(failed: &[kc::Failed]) -> String {
    failed.iter().map(|f| format!("{}: {}", f.analysis.name(), f.reason)).collect::<Vec<_>>().join("\n")
}

/// `import`: another tool's file as an elastokin model file on standard output, the notes on standard error.
fn import(args: ImportArgs, out: &Stdout) -> Result<(), Failure> {
    let ImportFormat::Chrono = args.format;
    let (_, text) = read_input(&args.file, "FILE")?;
    let origin = args.file.display().to_string();
    if !elastokin::suspensions::import::chrono::is_chrono(&text) {
        return Err(Failure::Input(format!(
            "{origin}: not a Project Chrono suspension file (a JSON object with \"Type\": \"Suspension\" and a \"Template\")"
        )));
    }
    let imported = elastokin::suspensions::document::import_chrono(&text, &origin, args.loaded_radius)
        .map_err(|e| Failure::Input(e.to_string()))?;
    note(format!("read as a Project Chrono {} suspension", imported.template));
    for n in &imported.notes {
        note(format!("note: {n}"));
    }
    out.line(imported.file.to_json())?;
    Ok(())
}

/// `expand`: the model file with its suspension in the general form, which builds the same model.
fn expand(args: CheckArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let file = read_model(&args.model)?.file;
    strict_model(&args.model, &file, strict)?;
    let general = SuspensionFile {
        suspension: elastokin::suspensions::Template::General(Box::new(file.suspension.expand())),
        ..file
    };
    out.line(general.to_json())?;
    Ok(())
}

fn check(args: CheckArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let model = args.model.display();
    let read = read_model(&args.model)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
        for n in read.imported.iter().flat_map(|i| &i.notes) {
            out.line(format!("note: {n}"))?;
        }
    }
    let file = read.file;
    let input = |e: &dyn std::fmt::Display| Failure::Input(format!("{model}: {e}"));
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| input(&e))?;
    let m = &corner.model;
    out.line(&file.name)?;
    // Before the solver: its refusal of a free part would hide the warnings that explain it.
    let plausibility = elastokin::suspensions::check_model(&file).map_err(|e| input(&e))?;
    for line in plausibility.report() {
        out.line(line)?;
    }
    out.line(format!("bodies: {}", m.bodies().iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", ")))?;
    out.line(format!("joints: {}, elements: {}", m.joints().len(), m.elements().len()))?;
    out.line(format!(
        "coordinates: {}, constraint rows: {} (with the wheel-travel driver)",
        m.dofs(),
        m.constraint_rows()
    ))?;
    let solver = StaticSolver::new(m, SolverOptions::default()).map_err(|e| input(&e))?;
    let d = solver.diagnostics();
    if d.redundant.is_empty() {
        out.line("redundant constraints: none")?;
    }
    for line in d.messages() {
        out.line(line)?;
    }
    out.line("every body is restrained")?;
    // The whole report first, then the refusal: `check` is where a user reads why.
    if strict && !plausibility.warnings.is_empty() {
        return Err(Failure::Input(format!(
            "{model}: {} warning(s) under --strict (above)",
            plausibility.warnings.len()
        )));
    }
    Ok(())
}

fn run_batch(args: BatchArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    let read = read_model(&args.model)?;
    strict_model(&args.model, &read.file, strict)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    let bytes = read.bytes;
    let origin = args.model.display().to_string();
    // The variants edit the file as written: a Chrono file's own keys (its comments removed).
    let base = batch::base_document(&String::from_utf8_lossy(&bytes), &origin).map_err(Failure::Input)?;
    let (variant_bytes, variant_text) = read_input(&args.variants, "VARIANTS")?;
    // Every wrong line of the file (a key the model lacks among them) is said before anything runs. The
    // models read here are the ones run.
    let (list, files) =
        batch::read_and_apply(&base, &variant_text, &args.variants.display().to_string()).map_err(Failure::Input)?;
    let mut provenance = Provenance::new(&args.model, &bytes, kc::mode_word(Mode::Corrected), batch::STEPS);
    provenance.range = Some((-batch::HALF_RANGE, batch::HALF_RANGE));
    provenance.variants = Some((args.variants.display().to_string(), output::sha256_hex(&variant_bytes)));
    // Every shard reads and checks all variants above, so a mistake anywhere in the file stops each shard
    // alike; each runs only its own block.
    let range = args.shard.map_or(0..list.len(), |s| s.range(list.len()));
    provenance.part = args.shard.map(|s| Part::Shard { index: s.index, count: s.count, variants: list.len() });
    let staging = Staging::new(&args.out)?;
    let progress = Progress::new("variants", range.len(), quiet);
    let results = batch::run_all(&list[range.clone()], &files[range.clone()], &progress);
    progress.finish();
    let result = (|| {
        out.line(format!("{:<28} {:>16} {:>16} {:>14}", "variant", "bump °/10 mm", "camber °/10 mm", "rate N/mm"))?;
        let mut rows = Vec::new();
        for ((k, v), r) in list.iter().enumerate().skip(range.start).zip(&results) {
            let name = kc::Cell::Text(v.name.clone());
            let mut row = match r {
                Ok(o) => {
                    out.line(format!(
                        "{:<28} {:>16.4} {:>16.4} {:>14.2}",
                        v.name,
                        o.bump_steer * 0.01,
                        o.camber_gain * 0.01,
                        o.wheel_rate * 1e-3
                    ))?;
                    let figures = o.figures().map(kc::Cell::from);
                    std::iter::once(name).chain(figures).chain([kc::Cell::Empty]).collect()
                }
                Err(e) => {
                    out.line(format!("{:<28} failed: {e}", v.name))?;
                    let empty = kc::Cell::Empty;
                    vec![name, empty.clone(), empty.clone(), empty, kc::Cell::Text(e.clone())]
                }
            };
            if args.shard.is_some() {
                row.push(kc::Cell::Text((k + 1).to_string()));
            }
            rows.push(row);
        }
        let table = kc::Table { name: "batch".into(), columns: batch::columns(args.shard.is_some()), rows };
        staging.write(&format!("{}.csv", table.name), &write_table(&table, &provenance))
    })();
    let path = result.map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    let failed = results.iter().filter(|r| r.is_err()).count();
    if failed > 0 && !quiet {
        note(format!("{failed} of {} variants failed (their error is in the error column)", results.len()));
    }
    out.line(format!("wrote {}", path.display()))
}

/// The parameters `params` of the model file `model` (its `bytes`), then every coordinate of every
/// hardpoint; a model without hardpoints is refused, naming the `flag` that asked for them and the
/// `other` way to name numbers.
fn parameters_of(
    model: &Path,
    bytes: &[u8],
    params: &[String],
    flag: &str,
    other: &str,
) -> Result<elastokin::suspensions::design::Parameters, Failure> {
    use elastokin::suspensions::design::{hardpoint_pointers, Parameters};
    let origin = model.display().to_string();
    let base = batch::base_document(&String::from_utf8_lossy(bytes), &origin).map_err(Failure::Input)?;
    let all = hardpoint_pointers(&base);
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
fn write_sensitivities(
    staging: &Staging,
    suite: &elastokin::suspensions::design::SuiteSensitivity,
    parameters: &elastokin::suspensions::design::Parameters,
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

/// `sensitivity`: every figure's and cell's derivatives with respect to numbers of the model file, for the
/// suite or one analysis.
fn sensitivity(args: SensitivityArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    use elastokin::suspensions::design::{self, sensitivity::effect_unit};
    let settings = Settings {
        range: args.sweeps.range,
        steps: args.sweeps.steps,
        figures_only: args.figures_only,
        ..Settings::default()
    };
    args.sweeps.check(&settings)?;
    let read = read_model(&args.model)?;
    strict_model(&args.model, &read.file, strict)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    let parameters = if args.hardpoints {
        parameters_of(&args.model, &read.bytes, &args.params, "--hardpoints", "--param POINTER")?
    } else if args.params.is_empty() {
        return Err(Failure::Input(
            "no parameters: give --param POINTER (a JSON pointer into the model file) or --hardpoints".into(),
        ));
    } else {
        let origin = args.model.display().to_string();
        let base = batch::base_document(&String::from_utf8_lossy(&read.bytes), &origin).map_err(Failure::Input)?;
        design::Parameters::new(&base, &args.params).map_err(|e| Failure::Input(format!("{origin}: {e}")))?
    };
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
    let mut provenance = Provenance::new(&args.model, &read.bytes, kc::mode_word(Mode::Corrected), args.sweeps.steps);
    provenance.range = args.sweeps.range;
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let mut written = write_sensitivities(&staging, &suite, &parameters, &provenance, args.figures_only)?;
        let html = elastokin::html::sensitivity_html(&suite, &parameters, &read.file.name, &provenance.to_json());
        written.push(staging.write("report.html", html.as_bytes())?);
        Ok(written)
    })()
    .map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    out.line(format!(
        "{} — {} parameters, {} steps per sweep, corrected mode",
        read.file.name,
        parameters.len(),
        args.sweeps.steps
    ))?;
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
            for (k, e) in a.largest_effects(j, &parameters, 3) {
                let pointer = &parameters.pointers[k];
                let per = effect_unit(pointer);
                let e = kc::significant(e * written.factor, 3);
                out.line(format!("      {:<52} {:>12} {unit}per {per}", pointer, e))?;
            }
            let missing = (0..parameters.len()).filter_map(|k| a.figures[k][j].err().map(|e| (k, e))).next();
            if let Some((k, why)) = missing {
                out.line(format!("      {:<52} {}", parameters.pointers[k], why.reason()))?;
            }
        }
    }
    for s in &suite.skipped {
        out.line(format!("\n{}: skipped — {}", s.analysis.name(), s.reason))?;
    }
    out.line("")?;
    out.line(format!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))?;
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

/// `tune`: the model's free numbers moved to meet the targets.
fn tune(args: TuneArgs, out: &Stdout, quiet: bool, strict: bool) -> Result<(), Failure> {
    use elastokin::suspensions::design::{targets::read_targets, tune, Parameters};
    let read = read_model(&args.model)?;
    strict_model(&args.model, &read.file, strict)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    let origin = args.model.display().to_string();
    let base = batch::base_document(&String::from_utf8_lossy(&read.bytes), &origin).map_err(Failure::Input)?;
    let (targets_bytes, targets_text) = read_input(&args.targets, "TARGETS")?;
    // A measured file is named relative to the targets file.
    let beside = args.targets.parent().map(Path::to_path_buf).unwrap_or_default();
    let read_file = |name: &str| {
        std::fs::read_to_string(beside.join(name))
            .map_err(|e| format!("cannot read {}: {e}", beside.join(name).display()))
    };
    let targets = read_targets(&targets_text, &args.targets.display().to_string(), &base, read_file)
        .map_err(|e| Failure::Input(e.to_string()))?;
    let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
    let parameters = Parameters::new(&base, &pointers).map_err(|e| Failure::Input(format!("{origin}: {e}")))?;
    let progress = Progress::new("iterations", tune::MAX_ITERATIONS, quiet);
    let tuned = tune::tune(&parameters, &targets, |i| {
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
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    out.line("")?;
    out.line(format!("{}: {}", read.file.name, tuned.stopped))?;
    for (f, k) in targets.free.iter().zip(0..) {
        out.line(format!(
            "  {:<56} {:>12} -> {:<12}",
            f.pointer,
            kc::significant(tuned.start.x[k], 6),
            kc::significant(tuned.end.x[k], 6)
        ))?;
    }
    for v in &tuned.verdicts {
        let state = if v.met { "met" } else { "NOT met" };
        out.line(format!("  {state}: {} (largest miss {} of its tolerance)", v.target, kc::significant(v.worst, 3)))?;
    }
    for p in &tuned.packaging {
        out.line(if p.broken_by == 0.0 {
            format!("  holds: {}", p.constraint)
        } else {
            format!("  BROKEN: {} (by {} mm)", p.constraint, kc::significant(p.broken_by * 1e3, 3))
        })?;
    }
    out.line("")?;
    out.line(format!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))?;
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

/// `tolerance`: the figures' spread under the model's tolerances.
fn compare(args: CompareArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    use elastokin::suspensions::compare::{compare, Design};
    use elastokin::suspensions::design::targets::read_measured;
    let settings = Settings { range: args.sweeps.range, steps: args.sweeps.steps, motion: true, ..Settings::default() };
    args.sweeps.check(&settings)?;
    let mut designs = Vec::new();
    let mut files = Vec::new();
    for path in &args.designs {
        let measured = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv"));
        let (bytes, design) = if measured {
            let (bytes, text) = read_input(path, "DESIGN")?;
            let origin = path.display().to_string();
            let measured = read_measured(&text, &origin).map_err(|e| Failure::Input(e.to_string()))?;
            let name = path.file_name().map_or(origin.clone(), |n| n.to_string_lossy().into_owned());
            (bytes, Design::Measured { name, measured })
        } else {
            let read = read_model(path)?;
            strict_model(path, &read.file, strict)?;
            if let Some(line) = read.format_line() {
                out.line(line)?;
            }
            let report = kc::run_suite(&read.file, &args.sweeps.which(), &settings, |_| {});
            refuse_warned(strict, report.all_warnings())?;
            let design = Design::model(&read.file, report);
            (read.bytes, design)
        };
        files.push((path.display().to_string(), elastokin::provenance::sha256_hex(&bytes)));
        designs.push(design);
    }
    let comparison = compare(&designs).map_err(Failure::Input)?;
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
            staging.write("compare.csv", &write_table(&comparison.figures, &provenance))?,
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    out.line(format!("compared {}", comparison.names.join(", ")))?;
    out.line(format!(
        "wrote {} ({} figures, {} curves overlaid)",
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
        comparison.figures.rows.len(),
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

fn vehicle(args: VehicleArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    use elastokin::suspensions::full_vehicle::{check_axles, run_vehicle, VehicleFile};
    let (bytes, text) = read_input(&args.vehicle, "VEHICLE")?;
    let origin = args.vehicle.display().to_string();
    let file = VehicleFile::from_json(&text, &origin).map_err(Failure::Input)?;
    let dir = args.vehicle.parent().unwrap_or(Path::new("."));
    let (front_path, rear_path) = (dir.join(&file.front), dir.join(&file.rear));
    let (front, rear) = (read_model(&front_path)?, read_model(&rear_path)?);
    strict_model(&front_path, &front.file, strict)?;
    strict_model(&rear_path, &rear.file, strict)?;
    check_axles(&file, &front.file, &rear.file).map_err(|e| Failure::Input(format!("{origin}: {e}")))?;
    let settings = Settings { steps: args.steps, ..Settings::default() };
    let report =
        run_vehicle(&file, &front.file, &rear.file, &settings).map_err(|e| Failure::Run(format!("{origin}: {e}")))?;
    if strict && !report.warnings.is_empty() {
        let n = report.warnings.len();
        return Err(Failure::Run(format!("{origin}: {n} warning(s) under --strict:\n{}", report.warnings.join("\n"))));
    }
    let mut provenance = Provenance::new(&args.vehicle, &bytes, kc::mode_word(settings.mode), settings.steps);
    provenance.tolerance = Some(settings.tolerance);
    provenance.other_files = vec![
        (front_path.display().to_string(), elastokin::provenance::sha256_hex(&front.bytes)),
        (rear_path.display().to_string(), elastokin::provenance::sha256_hex(&rear.bytes)),
    ];
    let staging = Staging::new(&args.out)?;
    let written = (|| -> Result<Vec<PathBuf>, Failure> {
        let html = elastokin::html::vehicle_html(&report, &provenance.to_json());
        Ok(vec![
            staging.write("vehicle.csv", &write_table(&report.table(), &provenance))?,
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    let b = &report.budget;
    out.line(format!("{} — front {}, rear {}", report.name, front.file.name, rear.file.name))?;
    out.line(format!(
        "  understeer gradient {} deg/g ({} deg/g at the steering wheel), roll gradient {} deg/g",
        kc::significant(b.understeer_gradient, 4),
        kc::significant(b.steering_wheel_gradient, 4),
        kc::significant(b.roll_gradient, 4)
    ))?;
    out.line(format!(
        "  roll stiffness front share {:.1} %, lateral load transfer front share {:.1} %",
        100.0 * b.roll_stiffness_front_share,
        100.0 * b.load_transfer_front_share
    ))?;
    for c in &b.contributions {
        out.line(format!("    {:<36} {:<5} {:>9} deg/g", c.effect, c.axle.name(), kc::significant(c.value, 3)))?;
    }
    for w in &report.warnings {
        out.line(format!("  warning: {w}"))?;
    }
    out.line(format!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))
}

fn tolerance(args: ToleranceArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    use elastokin::suspensions::design::tolerance::{read_tolerances, stack_up};
    let read = read_model(&args.model)?;
    strict_model(&args.model, &read.file, strict)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    let origin = args.model.display().to_string();
    let base = batch::base_document(&String::from_utf8_lossy(&read.bytes), &origin).map_err(Failure::Input)?;
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
        Ok(vec![
            staging.write("tolerance.csv", &write_table(&stack.table(), &provenance))?,
            staging.write("tolerance_contributions.csv", &write_table(&stack.contribution_table(), &provenance))?,
            staging.write("report.html", html.as_bytes())?,
        ])
    })()
    .map_err(|e| Failure::Run(format!("{}\n{}", e.message(), staging.untouched())))?;
    staging.commit()?;
    out.line(format!("{} — {} numbers within their tolerances", read.file.name, stack.bands.len()))?;
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
        for (p, c) in s.contributions.iter().take(3) {
            out.line(format!("      {:<56} {:>12} {}", stack.parameters.pointers[*p], shown(*c, 3), unit.symbol))?;
        }
    }
    out.line("")?;
    for w in &stack.warnings {
        out.line(format!("warning [{}]: {}", w.code, w.message))?;
    }
    out.line(format!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")))?;
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

fn main() -> ExitCode {
    // Usage errors exit with status 2, help and --version with 0; clap prints them.
    let cli = Cli::parse();
    output::on_interrupt_remove_staging();
    let out = Stdout::new(cli.quiet);
    let result = match cli.command {
        Command::Run(args) => run(args, &out, cli.quiet, cli.strict),
        Command::Check(args) => check(args, &out, cli.strict),
        Command::Batch(args) => run_batch(args, &out, cli.quiet, cli.strict),
        Command::Sensitivity(args) => sensitivity(args, &out, cli.strict),
        Command::Tune(args) => tune(args, &out, cli.quiet, cli.strict),
        Command::Tolerance(args) => tolerance(args, &out, cli.strict),
        Command::Compare(args) => compare(args, &out, cli.strict),
        Command::Vehicle(args) => vehicle(args, &out, cli.strict),
        Command::Merge(args) => merge::merge(args, &out),
        Command::Expand(args) => expand(args, &out, cli.strict),
        Command::Import(args) => import(args, &out),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            note(format!("error: {}", failure.message()));
            ExitCode::from(failure.exit_status())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_analysis_has_its_command_line_name() {
        let names: Vec<AnalysisName> = AnalysisName::value_variants().to_vec();
        assert_eq!(names.len(), kc::ALL.len());
        for (name, analysis) in names.into_iter().zip(kc::ALL) {
            assert_eq!(name.analysis(), analysis);
        }
    }

    #[test]
    fn the_argument_definitions_are_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
