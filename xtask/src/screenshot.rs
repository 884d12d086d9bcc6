//! `cargo xtask screenshot`: the K&C report of `examples/macpherson.json` as a picture, for the README.
//!
//! Runs the K&C suite through the library (`elastokin::suspensions::kc::run_suite`), writes the HTML report
//! (`elastokin::html::report_html`) to `target/screenshot/report.html`, and has headless Chromium (Debian's
//! `chromium` package) take a 1200 × 3000 px screenshot of it into `docs/images/report.png`: the top of the
//! report, as a person opening the mailed file sees it.
//!
//! The plots in it are drawn by [`line_chart`] below, a small SVG writer for the screenshot only, until
//! the command's chart renderer is public in the library; then it is the one to pass.

use elastokin::suspensions::kc::{self, Chart, Scale, Settings};
use elastokin::suspensions::SuspensionFile;
use html_escape::encode_text as text;
use sha2::{Digest, Sha256};
use std::convert::Infallible;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant, SystemTime};

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

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask sits in the workspace").to_path_buf()
}

fn run() -> Result<PathBuf, String> {
    // Look for Chromium first: without it the run would be wasted.
    let chromium = find_chromium()?;
    let root = workspace_root();
    let model_path = root.join(MODEL);
    let bytes = std::fs::read(&model_path).map_err(|e| format!("{}: {e}", model_path.display()))?;
    let file = SuspensionFile::read(&model_path).map_err(|e| e.to_string())?;
    let settings = Settings::default();
    let report =
        kc::run_suite(&file, &[], &settings, |a| eprintln!("running {}", a.name())).map_err(|e| e.to_string())?;

    let sha256: String = Sha256::digest(&bytes).iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    });
    let provenance = serde_json::json!({
        "made_by": "cargo xtask screenshot",
        "model_file": MODEL,
        "model_sha256": sha256,
        "settings": settings,
        "date": humantime::format_rfc3339_seconds(SystemTime::now()).to_string(),
    });
    let html = elastokin::html::report_html(&report, &file, &provenance, |chart: &Chart| {
        Ok::<_, Infallible>(line_chart(chart))
    });

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

const W: f64 = 640.0;
const H: f64 = 400.0;
const TOP: f64 = 52.0;
const BOTTOM: f64 = 88.0;
const LEFT: f64 = 72.0;
const COLOURS: [&str; 6] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"];

/// One vertical axis's numbers: the plotted values (log10 on a log scale) of its finite points.
struct AxisData<'a> {
    label: &'a str,
    log: bool,
    series: Vec<(&'a str, Vec<(f64, f64)>)>,
}

fn plotted(scale: Scale, v: f64) -> Option<f64> {
    match scale {
        Scale::Linear => v.is_finite().then_some(v),
        Scale::Log => (v.is_finite() && v > 0.0).then(|| v.log10()),
    }
}

fn axis_data<'a>(axis: &'a kc::YAxis, x_scale: Scale) -> AxisData<'a> {
    AxisData {
        label: &axis.label,
        log: axis.scale == Scale::Log,
        series: axis
            .series
            .iter()
            .map(|s| {
                let points =
                    s.points.iter().filter_map(|&(x, y)| Some((plotted(x_scale, x)?, plotted(axis.scale, y)?)));
                (s.name.as_str(), points.collect())
            })
            .collect(),
    }
}

/// The range of `values`, widened when flat so that a constant curve sits in the middle of its axis.
fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return None;
    }
    let pad =
        if hi - lo > 1e-12 * hi.abs().max(lo.abs()).max(1e-300) { 0.04 * (hi - lo) } else { 0.5 * lo.abs().max(1.0) };
    Some((lo - pad, hi + pad))
}

/// Round tick positions inside `[lo, hi]` (steps of 1, 2 or 5 × 10ⁿ) and the decimals to print them with.
fn ticks(lo: f64, hi: f64) -> (Vec<f64>, usize) {
    let raw = (hi - lo) / 6.0;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step =
        [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * magnitude).find(|s| (hi - lo) / s <= 7.0).unwrap_or(10.0 * magnitude);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    ((first..=last).map(|i| i as f64 * step).collect(), decimals)
}

fn tick_label(v: f64, decimals: usize, log: bool) -> String {
    if log {
        format!("1e{}", v.round() as i64)
    } else {
        let s = format!("{v:.decimals$}");
        if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
            s.trim_start_matches('-').to_string()
        } else {
            s
        }
    }
}

/// The chart as an SVG line plot: the left axis's curves solid, the right axis's dashed, the design
/// position as a grey vertical line, the legend under the plot. Points with a non-finite coordinate (or
/// not positive, on a log axis) are left out.
pub fn line_chart(chart: &Chart) -> String {
    let left = axis_data(&chart.left, chart.x_scale);
    let right = chart.right.as_ref().map(|r| axis_data(r, chart.x_scale));
    let right_margin = if right.is_some() { 72.0 } else { 24.0 };
    let (x0, x1, y0, y1) = (LEFT, W - right_margin, H - BOTTOM, TOP);
    let all_x = left.series.iter().chain(right.iter().flat_map(|r| &r.series)).flat_map(|s| s.1.iter().map(|p| p.0));
    let design = chart.design_x.and_then(|x| plotted(chart.x_scale, x));
    let xr = range(all_x.chain(design)).unwrap_or((-1.0, 1.0));
    let sx = |x: f64| x0 + (x - xr.0) / (xr.1 - xr.0) * (x1 - x0);

    let mut svg = String::new();
    let _ = write!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {W} {H}\" width=\"{W}\" height=\"{H}\" \
         font-family=\"DejaVu Sans, sans-serif\" font-size=\"12\">\
         <rect width=\"{W}\" height=\"{H}\" fill=\"white\"/>\
         <text x=\"{:.1}\" y=\"20\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">{}</text>\
         <text x=\"{:.1}\" y=\"37\" text-anchor=\"middle\" fill=\"#57606a\">{}</text>",
        (x0 + x1) / 2.0,
        text(&chart.title),
        (x0 + x1) / 2.0,
        text(&chart.subtitle)
    );
    let (xt, xd) = ticks(xr.0, xr.1);
    for t in xt {
        let x = sx(t);
        let _ = write!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{y0}\" x2=\"{x:.1}\" y2=\"{y1}\" stroke=\"#eaeef2\"/>\
             <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            y0 + 16.0,
            tick_label(t, xd, chart.x_scale == Scale::Log)
        );
    }
    let _ = write!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
        (x0 + x1) / 2.0,
        y0 + 34.0,
        text(&chart.x_label)
    );

    let mut legend = Vec::new();
    let mut colour = 0;
    for (side, axis) in [(0, Some(&left)), (1, right.as_ref())] {
        let Some(axis) = axis else { continue };
        let yr = range(axis.series.iter().flat_map(|s| s.1.iter().map(|p| p.1))).unwrap_or((-1.0, 1.0));
        let sy = |y: f64| y0 - (y - yr.0) / (yr.1 - yr.0) * (y0 - y1);
        let (yt, yd) = ticks(yr.0, yr.1);
        let (edge, anchor, dx, label_x, rotate) =
            if side == 0 { (x0, "end", -6.0, 16.0, -90) } else { (x1, "start", 6.0, W - 14.0, 90) };
        for t in yt {
            let y = sy(t);
            if side == 0 {
                let _ = write!(svg, "<line x1=\"{x0}\" y1=\"{y:.1}\" x2=\"{x1}\" y2=\"{y:.1}\" stroke=\"#eaeef2\"/>");
            }
            let _ = write!(
                svg,
                "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"{anchor}\">{}</text>",
                edge + dx,
                y + 4.0,
                tick_label(t, yd, axis.log)
            );
        }
        let mid = (y0 + y1) / 2.0;
        let _ = write!(
            svg,
            "<text x=\"{label_x}\" y=\"{mid}\" text-anchor=\"middle\" transform=\"rotate({rotate} {label_x} {mid})\">{}</text>",
            text(axis.label)
        );
        for (name, points) in &axis.series {
            let c = COLOURS[colour % COLOURS.len()];
            colour += 1;
            let dash = if side == 1 { " stroke-dasharray=\"7 4\"" } else { "" };
            let path: Vec<String> = points.iter().map(|&(x, y)| format!("{:.1},{:.1}", sx(x), sy(y))).collect();
            let _ = write!(
                svg,
                "<polyline fill=\"none\" stroke=\"{c}\" stroke-width=\"2\"{dash} points=\"{}\"/>",
                path.join(" ")
            );
            legend.push((format!("{name}{}", if side == 1 { " (right axis)" } else { "" }), c, dash));
        }
    }
    let _ = write!(
        svg,
        "<rect x=\"{x0}\" y=\"{y1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" stroke=\"#57606a\"/>",
        x1 - x0,
        y0 - y1
    );
    if let Some(d) = design {
        let x = sx(d);
        let _ = write!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{y0}\" x2=\"{x:.1}\" y2=\"{y1}\" stroke=\"#8c959f\" stroke-dasharray=\"3 3\"/>\
             <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\" fill=\"#57606a\" font-size=\"11\">design</text>",
            y1 - 3.0
        );
    }
    // The legend under the axis label, entries side by side, wrapped to a new row at the plot's width
    // (each entry's width from its number of characters, at about 6.8 px a character at 12 px).
    let (mut x, mut y) = (x0, y0 + 54.0);
    for (name, c, dash) in &legend {
        let width = 36.0 + 6.8 * name.chars().count() as f64;
        if x > x0 && x + width > x1 {
            x = x0;
            y += 16.0;
        }
        let _ = write!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{c}\" stroke-width=\"2\"{dash}/>\
             <text x=\"{:.1}\" y=\"{y:.1}\">{}</text>",
            y - 4.0,
            x + 22.0,
            y - 4.0,
            x + 27.0,
            text(name)
        );
        x += width;
    }
    svg.push_str("</svg>");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside_the_range() {
        let (t, d) = ticks(-0.083, 0.083);
        assert_eq!(d, 2);
        assert!(t.iter().all(|&v| (-0.083..=0.083).contains(&v)));
        assert!(t.contains(&0.0) && t.len() >= 3);
    }

    #[test]
    fn chart_leaves_out_non_finite_points() {
        let chart = Chart {
            name: "c".into(),
            title: "toe & camber".into(),
            subtitle: "strut".into(),
            x_label: "travel [mm]".into(),
            x_scale: Scale::Linear,
            left: kc::YAxis {
                label: "angle [deg]".into(),
                scale: Scale::Linear,
                series: vec![kc::Series { name: "toe".into(), points: vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0)] }],
            },
            right: None,
            design_x: Some(0.0),
        };
        let svg = line_chart(&chart);
        assert!(svg.contains("points=\"") && !svg.contains("NaN"), "{svg}");
        assert!(svg.contains("toe &amp; camber"));
        assert_eq!(svg.matches("<polyline").count(), 1);
    }
}
