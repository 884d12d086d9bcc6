//! The `elastokin` command: K&C analyses of a suspension model file.
//!
//! ```text
//! elastokin run MODEL [--analysis NAME] [--range FROM,TO] [--steps N] [--mode paper|corrected] [--out DIR]
//! elastokin check MODEL
//! elastokin batch MODEL VARIANTS [--out DIR]
//! ```

use elastokin::solver::{Mode, SolverOptions, StaticSolver};
use elastokin::suspensions::{Rig, Side, SuspensionFile};
use std::path::PathBuf;

mod analyses;
mod batch;
use analyses::{Analysis, Settings};
use std::process::ExitCode;

const HELP: &str = "\
elastokin — quasi-static elastokinematics of suspensions

USAGE:
    elastokin run MODEL [OPTIONS]     run the model's K&C tests, write CSV, SVG and summary.json, print headline figures
    elastokin check MODEL             parse, report bodies, degrees of freedom, redundant or unrestrained parts
    elastokin batch MODEL VARIANTS [--out DIR]
                                      run design variants in parallel (one per line: name: /json/pointer=value; …),
                                      one table of bump steer, camber gain and wheel rate at design
    elastokin help                    this text

RUN OPTIONS:
    --analysis NAME    one analysis instead of all of them (its load parameter in brackets):
                       parallel-travel  [wheel travel, m, bump +; default -0.08,0.08]
                       roll             [left wheel travel, m, right opposite, full axle; default -0.05,0.05]
                       steering         [rack travel, m, towards +y, full axle, heights held; default -0.04,0.04]
                       vertical-force   [force at the contact patch, N, up +, wheel free;
                                         default 0.5..1.5 x the design wheel load]
                       lateral-force    [force at the contact patch, N, inboard +; default -3000,3000]
                       braking-force    [force at the contact patch, N, rearward +; default 0,3000]
                       traction-force   [force at the wheel centre, N, forward +; default 0,3000]
                       aligning-torque  [torque about +z, N m; default -200,200]
                       static-load      [the model's vehicle.corner_load at once, from the design position]
                       (road loads carry vehicle.corner_load, or the design wheel load when the file has no
                       vehicle section; with --wheel held the rig holds the wheel-centre height)
    --range FROM,TO    the load parameter's range (needs --analysis: each has its own units)
    --steps N          load steps (default 32)
    --mode MODE        corrected (default) or paper
    --wheel HOLD       road loads with the wheel-centre height held (default) or free
    --out DIR          where the files go (default out/)

MODEL is a JSON file (SI units, ISO 8855 axes, left corner); see examples/*.json.";

struct RunOptions {
    model: PathBuf,
    analysis: Option<Analysis>,
    settings: Settings,
    out: PathBuf,
}

fn parse_run(args: &[String]) -> Result<RunOptions, String> {
    let mut it = args.iter();
    let model = it.next().ok_or("run needs a MODEL file: elastokin run examples/macpherson.json")?;
    let mut opts = RunOptions {
        model: model.into(),
        analysis: None,
        settings: Settings { range: None, steps: 32, mode: Mode::Corrected, height_held: true },
        out: "out".into(),
    };
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--analysis" => {
                let v = value()?;
                let names: Vec<&str> = analyses::ALL.iter().map(|a| a.name()).collect();
                opts.analysis = Some(
                    Analysis::from_name(v)
                        .ok_or_else(|| format!("unknown analysis '{v}': available are {}", names.join(", ")))?,
                );
            }
            "--range" => {
                let v = value()?;
                let parts: Vec<&str> = v.split(',').collect();
                let parse = |s: &str| s.trim().parse::<f64>().map_err(|_| format!("--range: '{s}' is not a number"));
                if parts.len() != 2 {
                    return Err(format!("--range takes FROM,TO, got '{v}'"));
                }
                let range = (parse(parts[0])?, parse(parts[1])?);
                if !(range.0.is_finite() && range.1.is_finite()) || range.0 == range.1 {
                    return Err(format!("--range needs two different finite values, got '{v}'"));
                }
                opts.settings.range = Some(range);
            }
            "--steps" => {
                let v = value()?;
                opts.settings.steps = v
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or_else(|| format!("--steps: '{v}' is not a positive integer"))?;
            }
            "--mode" => {
                opts.settings.mode = match value()?.as_str() {
                    "corrected" => Mode::Corrected,
                    "paper" => Mode::Paper,
                    other => return Err(format!("--mode: '{other}' is neither paper nor corrected")),
                }
            }
            "--wheel" => {
                opts.settings.height_held = match value()?.as_str() {
                    "held" => true,
                    "free" => false,
                    other => return Err(format!("--wheel: '{other}' is neither held nor free")),
                }
            }
            "--out" => opts.out = value()?.into(),
            other => return Err(format!("unknown option '{other}' (see elastokin help)")),
        }
    }
    if opts.settings.range.is_some() && opts.analysis.is_none() {
        return Err("--range needs --analysis NAME: each analysis has its own load parameter and units".into());
    }
    Ok(opts)
}

fn run(opts: RunOptions) -> Result<(), String> {
    let file = SuspensionFile::read(&opts.model).map_err(|e| e.to_string())?;
    let chosen: Vec<Analysis> = match opts.analysis {
        Some(a) => vec![a],
        None => analyses::ALL.to_vec(),
    };
    std::fs::create_dir_all(&opts.out).map_err(|e| format!("{}: {e}", opts.out.display()))?;
    let write = |name: &str, text: &str| {
        let path = opts.out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display())).map(|()| path)
    };
    println!("{} — {} mode", file.name, format!("{:?}", opts.settings.mode).to_lowercase());
    let mut summaries = serde_json::Map::new();
    let mut written = Vec::new();
    for analysis in chosen {
        if analysis == Analysis::StaticLoad && file.vehicle.is_none() && opts.analysis.is_none() {
            let why = "the model file has no \"vehicle\" section with the corner_load to carry";
            println!("\nstatic load: skipped — {why}");
            summaries.insert(analysis.name().into(), serde_json::json!({ "skipped": why }));
            continue;
        }
        let report = analyses::run(analysis, &file, opts.settings)?;
        println!();
        for line in &report.headline {
            println!("{line}");
        }
        written.push(write(&report.table.file, &report.table.csv())?);
        for (name, svg) in &report.plots {
            written.push(write(name, svg)?);
        }
        let mut entry = report.summary;
        entry["parameter"] = analysis.parameter().into();
        summaries.insert(analysis.name().into(), entry);
    }
    let summary = serde_json::json!({
        "model": file.name,
        "mode": format!("{:?}", opts.settings.mode).to_lowercase(),
        "analyses": summaries,
    });
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    written.push(write("summary.json", &text)?);
    println!();
    println!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
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
    // `--help` anywhere (`elastokin run --help`) asks for the help text, not for a model named --help.
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{HELP}");
        return ExitCode::SUCCESS;
    }
    let result = match args.first().map(String::as_str) {
        Some("run") => parse_run(&args[1..]).and_then(run),
        Some("check") => match args.get(1) {
            Some(model) => check(model),
            None => Err("check needs a MODEL file: elastokin check examples/macpherson.json".into()),
        },
        Some("batch") => run_batch(&args[1..]),
        Some("help") | None => {
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
