//! Project automation, run as `cargo xtask <task>` (alias in `.cargo/config.toml`, release build).
//!
//! Tasks:
//! - `ci`: format check and tests — what `.ci/run` starts with.
//! - `bench`: the benchmark instrument (error against run time, step cost, scaling, stiff cases, batch
//!   throughput, Exudyn side by side), tracked over commits; see `bench/mod.rs` and `docs/benchmarks.md`.
//!
//! It depends on the facade package `elastokin` for `elastokin::plot`, so the benchmark's plots are drawn
//! by the same renderer as the command's.
//! - `fuzz`: the long fuzz campaign over every shipped model and Chrono file, its report written to
//!   `bench/results/fuzz.md`; see `fuzz.rs`.
//! - `screenshot`: the HTML K&C report of `examples/macpherson.json`, and pictures of it, of its
//!   geometry views and of its live page (`elastokin live`'s, from the library's server) taken by headless
//!   Chromium for the README and `docs/commands.md`; see `screenshot.rs` (and `browser.rs`, the
//!   Chromium it runs, also loading every example's report in the browser test). It uses the `elastokin`
//!   facade (the suite, the plots, the HTML report, the provenance and the live server), as the command
//!   does.

use std::process::{Command, ExitCode};

mod bench;
mod browser;
mod fuzz;
mod screenshot;
#[cfg(test)]
mod tidy;

/// Every allocation is counted, so the benchmark can report peak memory of a measured section.
#[global_allocator]
static ALLOCATOR: bench::alloc::Counting = bench::alloc::Counting;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("ci") => run_ci(),
        Some("bench") => bench::main(&args[1..]),
        Some("screenshot") => screenshot::main(&args[1..]),
        Some("fuzz") => fuzz::main(&args[1..]),
        _ => {
            eprintln!(
                "usage: cargo xtask <ci|bench|screenshot|fuzz>   (cargo xtask bench --help for the benchmark's options)"
            );
            ExitCode::from(2)
        }
    }
}

/// The workspace root (where `examples/`, `bench/` and `tests/` are): the parent of this crate's directory.
pub(crate) fn workspace_root() -> std::path::PathBuf {
    let xtask = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    xtask.parent().expect("xtask sits in the workspace").to_path_buf()
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
