//! `elastokin import chrono FILE`: another tool's suspension file as an elastokin model file.

use super::input::read_input;
use crate::output::{note, Failure, Stdout};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

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

/// `import`: another tool's file as an elastokin model file on standard output, the notes on standard error.
pub fn run(args: ImportArgs, out: &Stdout) -> Result<(), Failure> {
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
