//! `cargo xtask screenshot`: the K&C report of `examples/macpherson.json` as a picture, for the README.
//!
//! Runs the K&C suite through the library (`elastokin::suspensions::kc::run_suite`), writes the HTML report
//! (`elastokin::html::report_html`) to `target/screenshot/report.html`, and has headless Chromium (Debian's
//! `chromium` package) take a 1200 × 3000 px screenshot of it into `docs/images/report.png`: the top of the
//! report, as a person opening the mailed file sees it.
//! The page is the one `elastokin run` writes: the same suite, the same plots (`elastokin::plot::svg`),
//! the same provenance.

use elastokin::provenance::Provenance;
use elastokin::suspensions::kc::{self, Settings, SuiteEvent};
use elastokin::suspensions::SuspensionFile;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant};

/// The model shown, relative to the workspace root.
const MODEL: &str = "examples/macpherson.json";
/// The picture, relative to the workspace root (committed; the README shows it).
const PICTURE: &str = "docs/images/report.png";
/// Chromium's window: the width of a laptop screen, tall enough for the summary and the first analyses.
const WINDOW: (u32, u32) = (1200, 3000);
/// A screenshot that takes longer than this has hung (a first start of Chromium takes a few seconds).
const CHROMIUM_TIME_LIMIT: Duration = Duration::from_secs(120);

pub fn main(args: &[String]) -> ExitCode {
    if !args.is_empty() {
        eprintln!("usage: cargo xtask screenshot   (writes target/screenshot/report.html and {PICTURE})");
        return ExitCode::from(2);
    }
    match run() {
        Ok(picture) => {
            println!("wrote {}", picture.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("xtask screenshot: {e}");
            ExitCode::FAILURE
        }
    }
}

use crate::workspace_root;

fn run() -> Result<PathBuf, String> {
    // Look for Chromium first: without it the run would be wasted.
    let chromium = find_chromium()?;
    let root = workspace_root();
    let model_path = root.join(MODEL);
    // Read once: the bytes hashed for the provenance are the ones parsed.
    let text = std::fs::read_to_string(&model_path).map_err(|e| format!("{}: {e}", model_path.display()))?;
    let file = SuspensionFile::from_json(&text, &model_path.display().to_string()).map_err(|e| e.to_string())?;
    let settings = Settings::default();
    let report = kc::run_suite(&file, &[], &settings, |event| {
        if let SuiteEvent::Starting(a) = event {
            eprintln!("running {}", a.name());
        }
    })
    .complete()
    .map_err(|e| e.to_string())?;
    let mut provenance =
        Provenance::new(Path::new(MODEL), text.as_bytes(), kc::mode_word(settings.mode), settings.steps);
    provenance.tolerance = Some(settings.tolerance);
    let html = elastokin::html::report_html(&report, &file, &provenance.to_json(), elastokin::plot::svg);

    let dir = root.join("target/screenshot");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let page = dir.join("report.html");
    std::fs::write(&page, html).map_err(|e| format!("{}: {e}", page.display()))?;
    eprintln!("wrote {}", page.display());

    let picture = root.join(PICTURE);
    if let Some(parent) = picture.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    screenshot(&chromium, &page, &picture, &dir.join("chromium-profile"))?;
    Ok(picture)
}

fn find_chromium() -> Result<PathBuf, String> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .map(|dir| dir.join("chromium"))
        .find(|p| p.is_file())
        .ok_or_else(|| "chromium is not on PATH: install Debian's chromium package: apt-get install chromium".into())
}

/// Has headless Chromium load `page` and save the window as `picture`. Its profile is made fresh in
/// `profile` and removed after, so no earlier state (cache, settings) changes the picture; everything
/// that would reach the network is off, since the page needs nothing outside itself.
fn screenshot(chromium: &Path, page: &Path, picture: &Path, profile: &Path) -> Result<(), String> {
    let _ = std::fs::remove_dir_all(profile);
    std::fs::create_dir_all(profile).map_err(|e| format!("{}: {e}", profile.display()))?;
    let _ = std::fs::remove_file(picture);
    let page = page.canonicalize().map_err(|e| format!("{}: {e}", page.display()))?;
    let mut cmd = Command::new(chromium);
    cmd.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
    ])
    .arg(format!("--user-data-dir={}", profile.display()))
    .arg(format!("--screenshot={}", picture.display()))
    .arg(format!("--window-size={},{}", WINDOW.0, WINDOW.1))
    .arg(format!("file://{}", page.display()))
    .stdout(Stdio::null())
    .stderr(Stdio::piped());
    let mut child = cmd.spawn().map_err(|e| format!("could not start {}: {e}", chromium.display()))?;
    let started = Instant::now();
    let status = loop {
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(status) => break status,
            None if started.elapsed() > CHROMIUM_TIME_LIMIT => {
                let _ = child.kill();
                let _ = child.wait();
                let _ = std::fs::remove_dir_all(profile);
                return Err(format!("chromium took longer than {} s; stopped", CHROMIUM_TIME_LIMIT.as_secs()));
            }
            None => std::thread::sleep(Duration::from_millis(100)),
        }
    };
    let stderr = child.stderr.take().map(std::io::read_to_string).transpose().ok().flatten().unwrap_or_default();
    let _ = std::fs::remove_dir_all(profile);
    if !status.success() || !picture.is_file() {
        return Err(format!("chromium failed ({status}), no {}:\n{stderr}", picture.display()));
    }
    Ok(())
}
