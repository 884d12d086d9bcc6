//! What `--strict` refuses, every command alike: a model its plausibility checks warn of (exit 2), and
//! results any analysis warned of (exit 1, nothing written).

use crate::output::Failure;
use elastokin::suspensions::check::ModelCheck;
use elastokin::suspensions::kc::Warning;
use elastokin::suspensions::SuspensionFile;
use std::path::Path;

/// Under `--strict`, a model its plausibility checks warn of (`check`) is refused before any time is spent
/// on it, every command alike (exit 2); a model the checks cannot build is left to the command to refuse.
pub fn refuse_implausible(path: &Path, check: Option<&ModelCheck>) -> Result<(), Failure> {
    let Some(check) = check.filter(|c| !c.warnings.is_empty()) else { return Ok(()) };
    let lines: Vec<String> = check.warnings.iter().map(|w| format!("warning [{}]: {}", w.code, w.message)).collect();
    Err(Failure::Input(format!("{}: refused under --strict:\n{}", path.display(), lines.join("\n"))))
}

/// [`refuse_implausible`] of the model in `file` at `path`, when `strict`.
pub fn strict_model(path: &Path, file: &SuspensionFile, strict: bool) -> Result<(), Failure> {
    if strict {
        refuse_implausible(path, elastokin::suspensions::check_model(file).ok().as_ref())?;
    }
    Ok(())
}

/// Under `--strict`, results any analysis warned of (an error estimate over the tolerance, a limit point)
/// are refused, as `--help` promises for every command: nothing is written.
pub fn refuse_warned<'a>(strict: bool, warnings: impl Iterator<Item = &'a Warning>) -> Result<(), Failure> {
    let codes: Vec<&str> = warnings.map(|w| w.code).collect();
    if strict && !codes.is_empty() {
        return Err(Failure::Run(format!("{} warning(s) under --strict: {}", codes.len(), codes.join(", "))));
    }
    Ok(())
}
