//! `cargo xtask fuzz`: the long fuzz campaign. It runs the campaign of
//! `crates/suspensions/tests/fuzz_models.rs` (every shipped example and Project Chrono file, mutated and
//! read, then run through the K&C suite) with many more cases than the test suite's, in release, and
//! writes what it found to `bench/results/fuzz.md` and `bench/results/fuzz.json`: cases, outcomes,
//! panics, hangs (a case over [`SLOW_CASE_SECONDS`]), non-finite numbers, the slowest case, and every failing case whole.
//!
//! ```sh
//! cargo xtask fuzz                     # 10⁵ full-suite cases (and 2·10⁵ read-only ones), seed 0xE1A570F022
//! cargo xtask fuzz --cases 5000 --seed 7
//! ```

use crate::{cargo, workspace_root};
use serde_json::{json, Value};
use std::process::{Command, ExitCode};

/// Full-suite cases of a campaign unless `--cases` says otherwise.
const DEFAULT_CASES: u64 = 100_000;

/// A case slower than this hangs or allocates without bound (the campaign runs in release; its slowest
/// shipped case takes under 3 s).
const SLOW_CASE_SECONDS: u64 = 5;

pub fn main(args: &[String]) -> ExitCode {
    match run(args) {
        Ok(clean) => {
            if clean {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("xtask fuzz: {e}");
            ExitCode::from(2)
        }
    }
}

fn number(args: &[String], i: usize, flag: &str) -> Result<u64, String> {
    let v = args.get(i + 1).ok_or_else(|| format!("{flag} needs a number"))?;
    v.parse().map_err(|_| format!("{flag} needs a whole number, got '{v}'"))
}

/// Runs the campaign; `Ok(true)` when it found nothing.
fn run(args: &[String]) -> Result<bool, String> {
    let (mut cases, mut seed) = (DEFAULT_CASES, None);
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--cases" => cases = number(args, i, "--cases")?,
            "--seed" => seed = Some(number(args, i, "--seed")?),
            "-h" | "--help" => {
                println!("usage: cargo xtask fuzz [--cases N (full-suite cases, default {DEFAULT_CASES})] [--seed S]");
                return Ok(true);
            }
            other => return Err(format!("unknown argument '{other}' (try --help)")),
        }
        i += 2;
    }
    if cases == 0 {
        return Err("--cases must be at least 1".into());
    }
    let root = workspace_root();
    let scratch = root.join("target/fuzz-report");
    std::fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    for stream in [1, 2] {
        let _ = std::fs::remove_file(scratch.join(format!("fuzz_stream{stream}.json")));
    }
    let mut cmd = Command::new(cargo());
    cmd.current_dir(&root)
        .args(["test", "--release", "-p", "elastokin-suspensions", "--test", "fuzz_models", "mutated_models"])
        .args(["--", "--test-threads=1", "--nocapture"])
        .env("ELASTOKIN_FUZZ_CASES", cases.to_string())
        .env("ELASTOKIN_FUZZ_REPORT", &scratch)
        .env("ELASTOKIN_FUZZ_SLOW_CASE_SECONDS", SLOW_CASE_SECONDS.to_string());
    if let Some(seed) = seed {
        cmd.env("ELASTOKIN_FUZZ_SEED", seed.to_string());
    }
    let status = cmd.status().map_err(|e| format!("could not start cargo test: {e}"))?;
    let mut streams = Vec::new();
    for stream in [1, 2] {
        let path = scratch.join(format!("fuzz_stream{stream}.json"));
        let text = std::fs::read_to_string(&path).map_err(|e| {
            format!("{}: {e} (the campaign did not finish; cargo test exited with {status})", path.display())
        })?;
        streams.push(serde_json::from_str::<Value>(&text).map_err(|e| format!("{}: {e}", path.display()))?);
    }
    let provenance = crate::bench::track::Provenance::current(false);
    let total = |key: &str| streams.iter().map(|s| s[key].as_u64().unwrap_or(0)).sum::<u64>();
    let failures = streams.iter().map(|s| s["failures"].as_array().map_or(0, Vec::len)).sum::<usize>();
    // The campaigns' own time, without the build.
    let seconds: f64 = streams.iter().map(|s| s["seconds"].as_f64().unwrap_or(0.0)).sum();
    let report = json!({
        "commit": provenance.commit,
        "dirty": provenance.dirty,
        "unix_time": provenance.unix_time,
        "threads": provenance.threads,
        "seconds": seconds,
        "cases": total("cases"),
        "panics": total("panics"),
        "hangs": total("hangs"),
        "non_finite": total("non_finite"),
        "failures": failures,
        "streams": streams,
    });
    let results = root.join("bench/results");
    let write = |name: &str, text: String| {
        let path = results.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
    };
    write("fuzz.json", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?)?;
    write("fuzz.md", markdown(&report))?;
    println!("{}", markdown(&report));
    Ok(failures == 0 && status.success())
}

/// The report as a page.
fn markdown(r: &Value) -> String {
    let mut out = String::new();
    let dirty = if r["dirty"].as_bool() == Some(true) { " (with uncommitted changes)" } else { "" };
    out.push_str("# Fuzz campaign\n\n");
    out.push_str(&format!(
        "`cargo xtask fuzz` at commit `{}`{dirty}: {} cases in {:.0} s on {} threads, every shipped example and \
         Project Chrono file mutated (`crates/suspensions/tests/fuzz_models.rs`).\n\n",
        r["commit"].as_str().unwrap_or("?"),
        r["cases"],
        r["seconds"].as_f64().unwrap_or(0.0),
        r["threads"]
    ));
    out.push_str(&format!(
        "**{} panics, {} hangs (a case over 5 s), {} non-finite numbers, {} failing cases in all.**\n\n",
        r["panics"], r["hangs"], r["non_finite"], r["failures"]
    ));
    out.push_str("| campaign | seed | cases | from examples | from Chrono files | outcomes | slowest case |\n");
    out.push_str("|---|---|---|---|---|---|---|\n");
    for s in r["streams"].as_array().into_iter().flatten() {
        let outcomes: Vec<String> =
            s["outcomes"].as_object().into_iter().flatten().map(|(k, v)| format!("{k}: {v}")).collect();
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {:.3} s |\n",
            if s["suite"].as_bool() == Some(true) { "read, then the K&C suite" } else { "read only" },
            s["seed"],
            s["cases"],
            s["sources"]["examples"].as_u64().unwrap_or(0),
            s["sources"]["chrono"].as_u64().unwrap_or(0),
            outcomes.join(", "),
            s["slowest_seconds"].as_f64().unwrap_or(0.0),
        ));
    }
    for s in r["streams"].as_array().into_iter().flatten() {
        out.push_str(&format!("\nSlowest case of stream {}: {}\n", s["stream"], s["slowest"].as_str().unwrap_or("")));
        for f in s["failures"].as_array().into_iter().flatten() {
            out.push_str(&format!("\n```text\n{}\n```\n", f.as_str().unwrap_or("")));
        }
    }
    out
}
