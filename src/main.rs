//! The `elastokin` command: K&C analyses of a suspension model file.
//!
//! ```text
//! elastokin run MODEL [--analysis NAME] [--range FROM,TO] [--steps N] [--mode paper|corrected]
//!                     [--wheel held|free] [--through-limits [--arc-step VALUE]] [--out DIR]
//! elastokin check MODEL
//! elastokin batch MODEL VARIANTS [--shard I/N] [--out DIR]
//! elastokin merge [--out DIR] SHARD...
//! elastokin live MODEL [--analysis NAME]... [--targets FILE] [--bind ADDR] [--port N] [--no-open]
//! ```
//!
//! Each subcommand is a module of [`command`], holding its arguments and its `run`; this file parses the
//! command line, hands the subcommand its arguments and says a failure once, with its exit status.
//!
//! What the command depends on, and why: clap parses the arguments (help, `--version`, suggestions for
//! mistyped names, errors that name the argument); csv writes the tables (quoting done right); sha2 gives
//! each result the model file's SHA-256; indicatif draws progress bars on a terminal; ctrlc hears Ctrl-C
//! (a run's staging removed, `live`'s server stopped: the library's `elastokin::live::LiveServer`, on
//! tiny_http).

use clap::{Parser, Subcommand};
use command::{batch, check, compare, expand, import, live, merge, run, sensitivity, tolerance, tune, vehicle};
use output::{note, Stdout};
use std::process::ExitCode;

mod command;
mod output;

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
    Run(run::RunArgs),
    /// Parse the model and report bodies, degrees of freedom, redundant or unrestrained parts
    #[command(after_help = EXIT_STATUS)]
    Check(check::CheckArgs),
    /// Run design variants in parallel: one table of bump steer, camber gain and wheel rate at design
    ///
    /// VARIANTS has one variant per line: an optional `name:`, then `/json/pointer=value` edits of the
    /// model separated by `;`. Blank lines and lines starting with `#` are skipped. Each variant walks
    /// parallel wheel travel ±20 mm in 8 steps, corrected mode.
    #[command(after_help = EXIT_STATUS)]
    Batch(batch::BatchArgs),
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
    Sensitivity(sensitivity::SensitivityArgs),
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
    Tune(tune::TuneArgs),
    /// Stack up tolerances: how far each figure spreads when the model's numbers are made within their
    /// tolerances
    ///
    /// TOLERANCES is JSON: "tolerances" (each number's JSON pointer and its ± band in the file's units, or
    /// "15%"), "hardpoints" (± for every hardpoint coordinate), "analyses" (default: the suite) and
    /// "steps". First order from the sensitivities: each figure's worst case and standard deviation
    /// (the numbers independent and uniform over their bands), its contributors ranked; --monte-carlo N
    /// checks it on N sampled models. Writes tolerance.csv, tolerance_contributions.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Tolerance(tolerance::ToleranceArgs),
    /// Compare designs: two or more models' K&C suites (and measured K&C files) overlaid
    ///
    /// Each DESIGN is a model file (JSON) or a measured K&C file (CSV, its first column the load parameter
    /// and a comment line `# analysis: NAME`, as docs/kc-rig-data.md says). Every curve of every analysis
    /// the models share is overlaid, a colour and a legend entry per design; the figures side by side with
    /// their error estimates and each model's difference to the first; the geometry overlaid. Writes
    /// compare.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Compare(compare::CompareArgs),
    /// The whole car from a front and a rear model: roll stiffness and its distribution, roll gradient,
    /// lateral load-transfer distribution, and the understeer budget (deg/g) term by term
    ///
    /// VEHICLE is JSON: "name", "front" and "rear" (model files, paths relative to VEHICLE), "car" (mass
    /// kg, cg_height m, wheelbase m, front_weight_share, steering_ratio) and "tyres" (cornering_stiffness
    /// and camber_stiffness N/deg per tyre, vertical_rate N/m, pneumatic_trail m), "rear_tyres" if they
    /// differ; docs/vehicle.md gives every formula. Writes vehicle.csv and report.html.
    #[command(after_help = EXIT_STATUS)]
    Vehicle(vehicle::VehicleArgs),
    /// Serve the model on this machine: move its numbers from a browser and watch its figures answer
    ///
    /// Prints the page's address, with a random token that every request must carry; a browser opens it
    /// unless --no-open. Listens on 127.0.0.1 alone unless --bind says otherwise. Requests from another page
    /// or for another host are refused. Each edit (a number of the model file by its JSON pointer, in the
    /// file's SI units) runs the analyses again; an edit that does not solve is refused with the reason and
    /// the design kept. Undo and redo; a save writes MODEL itself, only the moved numbers rewritten, every
    /// other byte as it was. Ctrl-C stops the server.
    #[command(after_help = EXIT_STATUS)]
    Live(live::LiveArgs),
    /// Join the batch.csv files of `batch --shard I/N` runs into the batch.csv one `batch` writes
    ///
    /// The shards must be of one model and one variants file (the same SHA-256 in their first lines) and
    /// the same N, each of 1..N given once. The rows are those of a single `batch`, byte for byte; the
    /// first line says the table was merged from N shards.
    #[command(after_help = EXIT_STATUS)]
    Merge(merge::MergeArgs),
    /// Print the model in the general form (named bodies, joints, bushings, springs and the corner
    /// description): a template expanded, ready to edit into any other suspension
    #[command(after_help = EXIT_STATUS)]
    Expand(check::CheckArgs),
    /// Read another tool's suspension file and print it as an elastokin model file (the general form);
    /// what was read, taken or left out goes to standard error, a line each
    #[command(after_help = EXIT_STATUS)]
    Import(import::ImportArgs),
}

fn main() -> ExitCode {
    // Usage errors exit with status 2, help and --version with 0; clap prints them.
    let cli = Cli::parse();
    output::on_interrupt_remove_staging();
    let out = Stdout::new(cli.quiet);
    let result = match cli.command {
        Command::Run(args) => run::run(args, &out, cli.quiet, cli.strict),
        Command::Check(args) => check::run(args, &out, cli.strict),
        Command::Batch(args) => batch::run(args, &out, cli.quiet, cli.strict),
        Command::Sensitivity(args) => sensitivity::run(args, &out, cli.strict),
        Command::Tune(args) => tune::run(args, &out, cli.quiet, cli.strict),
        Command::Tolerance(args) => tolerance::run(args, &out, cli.strict),
        Command::Compare(args) => compare::run(args, &out, cli.strict),
        Command::Vehicle(args) => vehicle::run(args, &out, cli.strict),
        Command::Live(args) => live::run(args, &out),
        Command::Merge(args) => merge::run(args, &out),
        Command::Expand(args) => expand::run(args, &out, cli.strict),
        Command::Import(args) => import::run(args, &out),
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
    fn the_argument_definitions_are_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
