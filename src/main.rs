//! The `elastokin` command: K&C analyses of a suspension model file.
//!
//! ```text
//! elastokin run MODEL [--analysis parallel-travel] [--range FROM,TO] [--steps N] [--mode paper|corrected] [--out DIR]
//! elastokin check MODEL
//! ```

use elastokin::solver::{Mode, SolverOptions, StaticSolver};
use elastokin::suspensions::analysis::{parallel_wheel_travel, slope_at_design, TravelRow};
use elastokin::suspensions::{Rig, Side, SuspensionFile};
use std::path::PathBuf;

mod batch;
mod plot;
use std::process::ExitCode;

const HELP: &str = "\
elastokin — quasi-static elastokinematics of suspensions

USAGE:
    elastokin run MODEL [OPTIONS]     run the model's K&C analysis, write CSV, print headline figures
    elastokin check MODEL             parse, report bodies, degrees of freedom, redundant or unrestrained parts
    elastokin batch MODEL VARIANTS [--out DIR]
                                      run design variants in parallel (one per line: name: /json/pointer=value; …),
                                      one table of bump steer, camber gain and wheel rate at design
    elastokin help                    this text

RUN OPTIONS:
    --analysis NAME    parallel-travel (default)
    --range FROM,TO    wheel travel in metres, bump positive (default -0.08,0.08)
    --steps N          load steps (default 32)
    --mode MODE        corrected (default) or paper
    --out DIR          where CSV files go (default out/)

MODEL is a JSON file (SI units, ISO 8855 axes, left corner); see examples/*.json.";

struct RunOptions {
    model: PathBuf,
    range: (f64, f64),
    steps: usize,
    mode: Mode,
    out: PathBuf,
}

fn parse_run(args: &[String]) -> Result<RunOptions, String> {
    let mut it = args.iter();
    let model = it.next().ok_or("run needs a MODEL file: elastokin run examples/macpherson.json")?;
    let mut opts =
        RunOptions { model: model.into(), range: (-0.08, 0.08), steps: 32, mode: Mode::Corrected, out: "out".into() };
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--analysis" => {
                let v = value()?;
                if v != "parallel-travel" {
                    return Err(format!("unknown analysis '{v}': available is parallel-travel"));
                }
            }
            "--range" => {
                let v = value()?;
                let parts: Vec<&str> = v.split(',').collect();
                let parse = |s: &str| s.trim().parse::<f64>().map_err(|_| format!("--range: '{s}' is not a number"));
                if parts.len() != 2 {
                    return Err(format!("--range takes FROM,TO in metres, got '{v}'"));
                }
                opts.range = (parse(parts[0])?, parse(parts[1])?);
                if !(opts.range.0.is_finite() && opts.range.1.is_finite()) || opts.range.0 == opts.range.1 {
                    return Err(format!("--range needs two different finite values, got '{v}'"));
                }
            }
            "--steps" => {
                let v = value()?;
                opts.steps = v
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or_else(|| format!("--steps: '{v}' is not a positive integer"))?;
            }
            "--mode" => {
                opts.mode = match value()?.as_str() {
                    "corrected" => Mode::Corrected,
                    "paper" => Mode::Paper,
                    other => return Err(format!("--mode: '{other}' is neither paper nor corrected")),
                }
            }
            "--out" => opts.out = value()?.into(),
            other => return Err(format!("unknown option '{other}' (see elastokin help)")),
        }
    }
    Ok(opts)
}

fn run(opts: RunOptions) -> Result<(), String> {
    let file = SuspensionFile::read(&opts.model).map_err(|e| e.to_string())?;
    let corner =
        file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| format!("{}: {e}", opts.model.display()))?;
    let rows =
        parallel_wheel_travel(&corner, opts.range.0, opts.range.1, opts.steps, opts.mode).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&opts.out).map_err(|e| format!("{}: {e}", opts.out.display()))?;
    let csv_path = opts.out.join("parallel_travel.csv");
    let mut csv = String::from(
        "travel_m,toe_deg,camber_deg,wheel_centre_x_m,wheel_centre_y_m,wheel_centre_z_m,caster_deg,kingpin_inclination_deg,scrub_radius_m,mechanical_trail_m\n",
    );
    for r in &rows {
        let w = r.attitude.wheel_centre;
        let g = r.steering;
        csv += &format!(
            "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n",
            r.travel,
            r.attitude.toe.to_degrees(),
            r.attitude.camber.to_degrees(),
            w.x,
            w.y,
            w.z,
            g.caster.to_degrees(),
            g.kingpin_inclination.to_degrees(),
            g.scrub_radius,
            g.mechanical_trail
        );
    }
    std::fs::write(&csv_path, csv).map_err(|e| format!("{}: {e}", csv_path.display()))?;
    let svg_path = opts.out.join("parallel_travel_toe_camber.svg");
    let curve = |f: &dyn Fn(&TravelRow) -> f64| rows.iter().map(|r| (r.travel * 1e3, f(r).to_degrees())).collect();
    let svg = plot::line_plot(
        &format!("{}: toe and camber in parallel wheel travel", file.name.split(" (").next().unwrap_or(&file.name)),
        "wheel travel [mm], bump +",
        "angle [deg]",
        &[
            plot::Series { name: "toe (in +)", points: curve(&|r| r.attitude.toe) },
            plot::Series { name: "camber (top out +)", points: curve(&|r| r.attitude.camber) },
        ],
    );
    std::fs::write(&svg_path, svg).map_err(|e| format!("{}: {e}", svg_path.display()))?;
    println!(
        "{} — parallel wheel travel {:+.0}..{:+.0} mm, {} steps",
        file.name,
        opts.range.0 * 1e3,
        opts.range.1 * 1e3,
        opts.steps
    );
    println!("{:>10} {:>10} {:>12} {:>12}", "travel mm", "toe °", "camber °", "track Δ mm");
    let y0 = corner.wheel.wheel_centre.y;
    let stride = (rows.len() / 8).max(1);
    for r in rows.iter().step_by(stride) {
        println!(
            "{:>10.1} {:>10.4} {:>12.4} {:>12.2}",
            r.travel * 1e3,
            r.attitude.toe.to_degrees(),
            r.attitude.camber.to_degrees(),
            (r.attitude.wheel_centre.y - y0) * 1e3
        );
    }
    let mut summary = serde_json::json!({
        "model": file.name,
        "analysis": "parallel wheel travel",
        "mode": format!("{:?}", opts.mode).to_lowercase(),
        "range_m": [opts.range.0, opts.range.1],
        "steps": opts.steps,
    });
    let bump = slope_at_design(&rows, |r| r.attitude.toe.to_degrees());
    let gain = slope_at_design(&rows, |r| r.attitude.camber.to_degrees());
    if let (Some(bump), Some(gain)) = (bump, gain) {
        println!("bump steer at design: {:+.4} °/10 mm toe; camber gain {:+.4} °/10 mm", bump * 0.01, gain * 0.01);
        summary["bump_steer_deg_per_m"] = bump.into();
        summary["camber_gain_deg_per_m"] = gain.into();
    }
    let rate = slope_at_design(&rows, |r| r.wheel_load);
    let ratio = slope_at_design(&rows, |r| r.spring_deflection);
    if let (Some(rate), Some(ratio)) = (rate, ratio) {
        println!("wheel rate at design: {:.2} N/mm; spring motion ratio {:.3}", rate * 1e-3, ratio.abs());
        summary["wheel_rate_n_per_m"] = rate.into();
        summary["spring_motion_ratio"] = ratio.abs().into();
    }
    if let Some(design) = rows.iter().min_by(|a, b| a.travel.abs().total_cmp(&b.travel.abs())) {
        let g = design.steering;
        summary["steering_axis_at_design"] = serde_json::json!({
            "caster_deg": g.caster.to_degrees(),
            "kingpin_inclination_deg": g.kingpin_inclination.to_degrees(),
            "scrub_radius_m": g.scrub_radius,
            "mechanical_trail_m": g.mechanical_trail,
            "kingpin_offset_m": g.kingpin_offset,
        });
        println!(
            "steering axis at {:+.1} mm: caster {:.2}°, kingpin inclination {:.2}°, scrub radius {:.1} mm, trail {:.1} mm, kingpin offset {:.1} mm",
            design.travel * 1e3,
            g.caster.to_degrees(),
            g.kingpin_inclination.to_degrees(),
            g.scrub_radius * 1e3,
            g.mechanical_trail * 1e3,
            g.kingpin_offset * 1e3
        );
    }
    if opts.range.0 <= 0.0 && opts.range.1 >= 0.0 {
        let pc = elastokin::suspensions::analysis::patch_compliance(&corner, 0.0).map_err(|e| e.to_string())?;
        let per_kn = |rad_per_n: f64| rad_per_n.to_degrees() * 1e3;
        summary["compliance_at_design"] = serde_json::json!({
            "lateral_steer_deg_per_kn": per_kn(pc.lateral_steer),
            "lateral_camber_deg_per_kn": per_kn(pc.lateral_camber),
            "braking_steer_deg_per_kn": per_kn(pc.braking_steer),
            "aligning_torque_steer_deg_per_knm": pc.aligning_torque_steer.to_degrees() * 1e3,
            "lateral_stiffness_n_per_m": pc.lateral_stiffness,
            "longitudinal_stiffness_n_per_m": pc.longitudinal_stiffness,
        });
        println!(
            "compliance at design (wheel-centre height held): lateral steer {:+.4} °/kN, lateral camber {:+.4} °/kN, \
             braking steer {:+.4} °/kN, aligning-torque steer {:+.4} °/(100 N·m), lateral stiffness {:.0} N/mm",
            per_kn(pc.lateral_steer),
            per_kn(pc.lateral_camber),
            per_kn(pc.braking_steer),
            pc.aligning_torque_steer.to_degrees() * 100.0,
            pc.lateral_stiffness * 1e-3
        );
    }
    let json_path = opts.out.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    std::fs::write(&json_path, text).map_err(|e| format!("{}: {e}", json_path.display()))?;
    println!("wrote {}, {}, {}", csv_path.display(), svg_path.display(), json_path.display());
    Ok(())
}

fn check(model: &str) -> Result<(), String> {
    let file = SuspensionFile::read(model.as_ref()).map_err(|e| e.to_string())?;
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| format!("{model}: {e}"))?;
    let m = &corner.model;
    println!("{}", file.name);
    println!("bodies: {}", m.bodies().iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", "));
    println!("joints: {}, elements: {}", m.joints().len(), m.elements().len());
    println!("coordinates: {}, constraint rows: {} (with the wheel-travel driver)", m.dofs(), m.constraint_rows());
    let solver = StaticSolver::new(m, SolverOptions::default()).map_err(|e| format!("{model}: {e}"))?;
    let d = solver.diagnostics();
    if d.redundant.is_empty() {
        println!("redundant constraints: none");
    }
    for line in d.messages() {
        println!("{line}");
    }
    println!("every body is restrained");
    Ok(())
}

fn run_batch(args: &[String]) -> Result<(), String> {
    let (model, variants) = match args {
        [m, v, ..] => (m, v),
        _ => {
            return Err(
                "batch needs MODEL and VARIANTS files: elastokin batch examples/macpherson.json variants.txt".into()
            )
        }
    };
    let out: PathBuf = match args.get(2..) {
        Some([flag, dir]) if flag == "--out" => dir.into(),
        Some([]) | None => "out".into(),
        Some(other) => return Err(format!("unexpected arguments {other:?} (batch MODEL VARIANTS [--out DIR])")),
    };
    let base_text = std::fs::read_to_string(model).map_err(|e| format!("{model}: {e}"))?;
    SuspensionFile::from_json(&base_text, model).map_err(|e| e.to_string())?;
    let base: serde_json::Value = serde_json::from_str(&base_text).map_err(|e| format!("{model}: {e}"))?;
    let text = std::fs::read_to_string(variants).map_err(|e| format!("{variants}: {e}"))?;
    let list = batch::parse_variants(&text, variants)?;
    // A variant that names a key the model lacks is a mistake in the file: say so before running anything.
    for v in &list {
        batch::apply(&base, v)?;
    }
    let results = batch::run_all(&base, &list);
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut csv = String::from("variant,bump_steer_deg_per_m,camber_gain_deg_per_m,wheel_rate_n_per_m,error\n");
    println!("{:<28} {:>16} {:>16} {:>14}", "variant", "bump °/10 mm", "camber °/10 mm", "rate N/mm");
    for (v, r) in list.iter().zip(&results) {
        match r {
            Ok(o) => {
                println!(
                    "{:<28} {:>16.4} {:>16.4} {:>14.2}",
                    v.name,
                    o.bump_steer * 0.01,
                    o.camber_gain * 0.01,
                    o.wheel_rate * 1e-3
                );
                csv +=
                    &format!("\"{}\",{},{},{},\n", v.name.replace('"', "'"), o.bump_steer, o.camber_gain, o.wheel_rate);
            }
            Err(e) => {
                println!("{:<28} failed: {e}", v.name);
                csv += &format!("\"{}\",,,,\"{}\"\n", v.name.replace('"', "'"), e.replace('"', "'"));
            }
        }
    }
    let path = out.join("batch.csv");
    std::fs::write(&path, csv).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("run") => parse_run(&args[1..]).and_then(run),
        Some("check") => match args.get(1) {
            Some(model) => check(model),
            None => Err("check needs a MODEL file: elastokin check examples/macpherson.json".into()),
        },
        Some("batch") => run_batch(&args[1..]),
        Some("help" | "--help" | "-h") | None => {
            println!("{HELP}");
            Ok(())
        }
        Some(other) => Err(format!("unknown command '{other}' (see elastokin help)")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
