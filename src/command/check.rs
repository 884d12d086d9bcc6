//! `elastokin check MODEL`: the model parsed and built, its plausibility checks, bodies, degrees of freedom
//! and redundant or unrestrained parts reported.

use super::input::read_model;
use crate::output::{Failure, Stdout};
use clap::Args;
use elastokin::solver::{SolverOptions, StaticSolver};
use elastokin::suspensions::{Rig, Side};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The model file (JSON; see examples/*.json)
    pub model: PathBuf,
}

/// `check`: the report of the model, then, under `--strict`, the refusal of a model its checks warn of.
pub fn run(args: CheckArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
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
