//! `cargo xtask screenshot`: the K&C report of `examples/macpherson.json` and its views as pictures, for
//! the README and `docs/commands.md`.
//!
//! Writes the report as `elastokin run` writes it (`browser::report_page`: the suite through the library,
//! the plots by `elastokin::plot::svg`, the geometry views, the provenance) to
//! `target/screenshot/report.html`, and has headless Chromium (Debian's `chromium` package) take
//! - `docs/images/report.png`: the top of the report, 1200 × 3000 px, as a person opening the mailed
//!   file sees it;
//! - `docs/images/view-front.png`, `view-side.png`, `view-plan.png`: each projection of the geometry, and
//!   `docs/images/view-3d.png`: the 3D view as it first shows — each a page of that part of the report
//!   alone (the report's own head and markup, its script for the 3D view), so the picture is what the
//!   browser draws there;
//! - `docs/images/compare.png`: the top of the comparison of `examples/macpherson.json` with the generic
//!   MacPherson it was tuned from, as `elastokin compare` writes it, and `docs/images/vehicle.png`: the top
//!   of the page `elastokin vehicle examples/vehicle/compact_car.json` writes;
//! - `docs/images/live.png`: the page of `elastokin live examples/macpherson.json --targets
//!   examples/targets/macpherson.json`, 1280 × 2150 px from its views down, served by the library's server
//!   in this process (on a copy of the model, which no save could write) and driven through Chromium's
//!   DevTools protocol (`elastokin_chromium`): a hardpoint typed, every chart redrawn over the design
//!   before, the point selected with its arrows.

use crate::browser::{part_of_page, report_page, screenshot};

use elastokin::live::{FrameAncestors, LiveServer, Served};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The model shown, relative to the workspace root.
const MODEL: &str = "examples/macpherson.json";
/// The report's picture, relative to the workspace root (committed; the README shows it).
const PICTURE: &str = "docs/images/report.png";
/// Chromium's window: the width of a laptop screen, tall enough for the summary and the first analyses.
const WINDOW: (u32, u32) = (1200, 3000);
/// The live page's picture, relative to the workspace root (committed; the README shows it).
const LIVE_PICTURE: &str = "docs/images/live.png";
/// The TARGETS file the live page judges every design against.
const LIVE_TARGETS: &str = "examples/targets/macpherson.json";
/// The live page's picture: a laptop screen's width, and tall enough for the views and the first charts.
const LIVE_WINDOW: (u32, u32) = (1280, 2150);
/// A view's picture: the figure it is (its id, and the text that ends it), the picture, the window.
struct View {
    id: &'static str,
    close: &'static str,
    picture: &'static str,
    window: (u32, u32),
}

/// The views, each a figure of the report: the projections end with their figure, the 3D view with its
/// script.
const VIEWS: [View; 4] = [
    View { id: "view-front", close: "</figure>", picture: "docs/images/view-front.png", window: (460, 780) },
    View { id: "view-side", close: "</figure>", picture: "docs/images/view-side.png", window: (460, 780) },
    View { id: "view-plan", close: "</figure>", picture: "docs/images/view-plan.png", window: (460, 780) },
    View { id: "view-3d", close: "//]]></script>", picture: "docs/images/view-3d.png", window: (980, 700) },
];

pub fn main(args: &[String]) -> ExitCode {
    if !args.is_empty() {
        eprintln!(
            "usage: cargo xtask screenshot   (writes target/screenshot/report.html, {PICTURE}, the views' pictures and {LIVE_PICTURE})"
        );
        return ExitCode::from(2);
    }
    match run() {
        Ok(pictures) => {
            for p in pictures {
                println!("wrote {}", p.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("xtask screenshot: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<Vec<PathBuf>, String> {
    // Look for Chromium first: without it the run would be wasted.
    let chromium = elastokin_chromium::find()?;
    let root = crate::workspace_root();
    eprintln!("running the K&C suite on {MODEL}");
    let html = report_page(&root, MODEL)?;
    let dir = root.join("target/screenshot");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let page = dir.join("report.html");
    std::fs::write(&page, &html).map_err(|e| format!("{}: {e}", page.display()))?;
    eprintln!("wrote {}", page.display());
    let profile = dir.join("chromium-profile");
    let picture = root.join(PICTURE);
    if let Some(parent) = picture.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    screenshot(&chromium, &page, "", &picture, WINDOW, &profile)?;
    let mut pictures = vec![picture];
    for view in VIEWS {
        let part = part_of_page(&html, "<figure", view.id, view.close)
            .ok_or_else(|| format!("the report has no {}", view.id))?;
        let part_page = dir.join(format!("{}.html", view.id));
        std::fs::write(&part_page, part).map_err(|e| format!("{}: {e}", part_page.display()))?;
        let picture = root.join(view.picture);
        screenshot(&chromium, &part_page, "", &picture, view.window, &profile)?;
        pictures.push(picture);
    }
    for (name, page, picture) in [
        ("compare", compare_page(&root)?, "docs/images/compare.png"),
        ("vehicle", vehicle_page(&root)?, "docs/images/vehicle.png"),
    ] {
        let path = dir.join(format!("{name}.html"));
        std::fs::write(&path, page).map_err(|e| format!("{}: {e}", path.display()))?;
        let picture = root.join(picture);
        screenshot(&chromium, &path, "", &picture, (1200, 1500), &profile)?;
        pictures.push(picture);
    }
    let picture = root.join(LIVE_PICTURE);
    live_picture(&root, &chromium, &dir.join("live"), &picture)?;
    pictures.push(picture);
    Ok(pictures)
}

/// The live page of a copy of [`MODEL`] in `dir`, judged against [`LIVE_TARGETS`], served by the library's
/// server and driven in headless Chromium as a user does: the tie rod's inner point typed 2 mm lower (every
/// chart then shows the design before in grey) and selected (arrows at it show the way that raises bump
/// steer); saved as `picture` once the page says it drew all of that with no error.
fn live_picture(root: &Path, chromium: &Path, dir: &Path, picture: &Path) -> Result<(), String> {
    use elastokin::suspensions::design::targets::{read_targets_as, Reading};
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let copy = dir.join("macpherson.json");
    std::fs::copy(root.join(MODEL), &copy).map_err(|e| format!("{}: {e}", copy.display()))?;
    eprintln!("serving {MODEL} live");
    let mut served = Served::open(&copy, &[], 32).map_err(|e| e.to_string())?;
    let targets = root.join(LIVE_TARGETS);
    let text = std::fs::read_to_string(&targets).map_err(|e| format!("{}: {e}", targets.display()))?;
    let beside = targets.parent().unwrap_or(root).to_path_buf();
    let read_file = |name: &str| std::fs::read_to_string(beside.join(name)).map_err(|e| format!("{name}: {e}"));
    let document = served.design.document().map_err(|e| e.to_string())?;
    let judged =
        read_targets_as(Reading::ToJudge, &text, LIVE_TARGETS, &document, read_file).map_err(|e| e.to_string())?;
    served.design = served.design.judged_against(judged);
    let any = std::net::SocketAddr::from(([127, 0, 0, 1], 0));
    let mut server = LiveServer::start(served, any, FrameAncestors::none()).map_err(|e| e.to_string())?;
    let mut browser = elastokin_chromium::Browser::start(chromium, dir.join("chromium-profile"))?;
    let page = browser.open(server.address())?;
    // A window as tall as the page down to the picture's end: the page draws only the charts in its window.
    browser.window(&page, (LIVE_WINDOW.0, 4500))?;
    // The page's report once every chart is drawn with no error and `ready` holds of it.
    let shown = |browser: &mut elastokin_chromium::Browser, ready: &dyn Fn(&serde_json::Value) -> bool| {
        let drawn = |state: &serde_json::Value| {
            let charts = state["charts"].as_u64().is_some_and(|c| c > 0 && state["drawn"] == c);
            charts && state["errors"] == serde_json::json!([]) && ready(state)
        };
        browser.output_when(&page, "live-state", drawn, std::time::Duration::from_secs(60))
    };
    shown(&mut browser, &|s| s["version"] == 1)?;
    let point = "/suspension/macpherson/hardpoints/tie_rod_inner";
    let typed = format!(
        "(() => {{ const input = document.querySelector('input[data-pointer=\"{point}/2\"]'); input.value = '-39.4'; \
         input.dispatchEvent(new Event('change')); return true; }})()"
    );
    browser.evaluate(&page, &typed)?;
    shown(&mut browser, &|s| s["version"] == 2 && s["ghosts"].as_u64().unwrap_or(0) > 0)?;
    browser.evaluate(&page, &format!("document.querySelector('tr[data-point=\"{point}\"] button').click(); true"))?;
    shown(&mut browser, &|s| s["arrows"].as_u64().unwrap_or(0) > 0)?;
    let said: Vec<&String> = browser.console.iter().filter(|(s, _)| *s == page).map(|(_, l)| l).collect();
    if !said.is_empty() {
        return Err(format!("the live page's console says {said:#?}"));
    }
    // From the views down: the point's arrows, the 3D view and the first charts over the design before.
    let top =
        browser.evaluate(&page, "document.getElementById('geometry').getBoundingClientRect().top + window.scrollY")?;
    let bytes = browser.picture(&page, (top.as_f64().unwrap_or(0.0) - 12.0).max(0.0), LIVE_WINDOW)?;
    std::fs::write(picture, bytes).map_err(|e| format!("{}: {e}", picture.display()))?;
    drop(browser);
    server.stop();
    Ok(())
}

/// The model of the workspace's file `path`, read as the command reads it.
fn model(root: &std::path::Path, path: &str) -> Result<elastokin::suspensions::SuspensionFile, String> {
    elastokin::suspensions::SuspensionFile::read(&root.join(path)).map_err(|e| e.to_string())
}

/// The page `elastokin compare examples/macpherson.json examples/generic/macpherson.json` writes.
fn compare_page(root: &std::path::Path) -> Result<String, String> {
    use elastokin::suspensions::compare::{compare, Design};
    use elastokin::suspensions::kc;
    let settings = kc::Settings { motion: true, ..kc::Settings::default() };
    let designs: Vec<Design> = ["examples/macpherson.json", "examples/generic/macpherson.json"]
        .iter()
        .map(|p| model(root, p).map(|f| Design::model(&f, kc::run_suite(&f, &[], &settings, |_| {}))))
        .collect::<Result<_, _>>()?;
    let comparison = compare(&designs).map_err(|e| e.to_string())?;
    let models = comparison.models(&designs);
    Ok(elastokin::html::compare_html(&comparison, &models, &serde_json::json!({}), elastokin::plot::svg))
}

/// The page `elastokin vehicle examples/vehicle/compact_car.json` writes.
fn vehicle_page(root: &std::path::Path) -> Result<String, String> {
    use elastokin::suspensions::full_vehicle::{run_vehicle, VehicleFile};
    let path = root.join("examples/vehicle/compact_car.json");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let file = VehicleFile::from_json(&text, "examples/vehicle/compact_car.json").map_err(|e| e.to_string())?;
    let (front, rear) = (
        model(root, &format!("examples/vehicle/{}", file.front))?,
        model(root, &format!("examples/vehicle/{}", file.rear))?,
    );
    let report = run_vehicle(&file, &front, &rear, &elastokin::suspensions::kc::Settings::default())
        .map_err(|e| e.to_string())?;
    Ok(elastokin::html::vehicle_html(&report, &serde_json::json!({})))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The live page's picture, taken into a scratch directory as `cargo xtask screenshot` takes it: the
    /// page drew every chart of the design first (else no picture), the picture is the window's size, and
    /// the server has stopped, its port free.
    ///
    /// Needs Debian's chromium, as the browser tests do: without it the test says so and passes on a
    /// developer's machine, and fails under CI (`CI` set).
    #[test]
    fn the_live_picture_is_taken_once_the_page_has_drawn_its_design() {
        let chromium = match elastokin_chromium::find() {
            Ok(c) => c,
            Err(e) if std::env::var_os("CI").is_none() => return eprintln!("skipped: {e}"),
            Err(e) => panic!("{e}"),
        };
        let root = crate::workspace_root();
        let dir = root.join("target/screenshot-test");
        let picture = dir.join("live.png");
        live_picture(&root, &chromium, &dir.join("live"), &picture).unwrap();
        let bytes = std::fs::read(&picture).unwrap();
        // A PNG's IHDR: its width and height, big-endian, at bytes 16 to 24.
        assert_eq!(&bytes[1..4], b"PNG");
        let size = |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        assert_eq!((size(16), size(20)), LIVE_WINDOW);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
