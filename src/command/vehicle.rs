//! `elastokin vehicle VEHICLE`: the whole car from a front and a rear model, its understeer budget term by
//! term.

use super::input::{read_input, read_model};
use super::strict::strict_model;
use super::sweeps::{parse_steps, MAX_STEPS};
use crate::output::{write_table, wrote, Failure, Provenance, Staging, Stdout};
use clap::Args;
use elastokin::suspensions::full_vehicle::{check_axles, run_vehicle, VehicleFile, VehicleReport};
use elastokin::suspensions::kc::{self, Settings};
use std::path::{Path, PathBuf};

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

/// `vehicle`: the car's figures and budget from its two axles, written as a table and a page.
pub fn run(args: VehicleArgs, out: &Stdout, strict: bool) -> Result<(), Failure> {
    let (bytes, text) = read_input(&args.vehicle, "VEHICLE")?;
    let origin = args.vehicle.display().to_string();
    let file = VehicleFile::from_json(&text, &origin).map_err(|e| Failure::Input(e.to_string()))?;
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
    .map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line(format!("{} — front {}, rear {}", report.name, front.file.name, rear.file.name))?;
    print_budget(out, &report)?;
    out.line(wrote(&written))
}

/// The gradients, the front shares and the understeer budget term by term, then the warnings.
fn print_budget(out: &Stdout, report: &VehicleReport) -> Result<(), Failure> {
    let b = &report.budget;
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
    // A term zero by the model's form (the compliance steer of ideal links) is rounding beside the others.
    let scale = b.contributions.iter().fold(0.0f64, |m, c| m.max(c.value.abs()));
    for c in &b.contributions {
        let value = kc::significant_among(c.value, 3, scale);
        out.line(format!("    {:<36} {:<5} {value:>9} deg/g", c.effect, c.axle.name()))?;
    }
    for w in &report.warnings {
        out.line(format!("  warning: {w}"))?;
    }
    Ok(())
}
