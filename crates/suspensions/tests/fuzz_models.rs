//! Seeded mutation testing of the model files: the shipped examples and every shipped Project Chrono suspension file
//! (`tests/data/chrono/`), half the cases each, each mutated in one to three places (numbers scaled or replaced by
//! extremes, hardpoints swapped or moved, keys deleted, duplicated or added, types changed, arrays truncated,
//! connections changed, a control character put into a text), then read as the command reads a model and, when they
//! read, run through the whole K&C suite (or, in some cases, one analysis over a random `--range`), in corrected or
//! paper mode, the wheel held or free. A model the engine cannot accept must be refused with a message; one it accepts
//! must give a report with no panic, no non-finite number anywhere a user reads it, and no figure or cell left out
//! because a NaN was computed on the way; an analysis that fails costs only itself and must say why in words.
//!
//! The case counts fit the CI budget: 4000 read-only and 1600 full-suite cases take 2 s and 12 s in the
//! test profile on two shared cores (the cases are spread over every core). The long campaign is
//! `cargo xtask fuzz` (10⁵ full-suite cases, its report in `bench/results/fuzz.md`); by hand, set
//! `ELASTOKIN_FUZZ_CASES` (full-suite cases; the read-only cases are scaled with it) and
//! `ELASTOKIN_FUZZ_SEED`, preferably in release:
//!
//! ```sh
//! ELASTOKIN_FUZZ_CASES=5000 ELASTOKIN_FUZZ_SEED=7 cargo test --release -p elastokin-suspensions --test fuzz_models
//! ```
//!
//! `ELASTOKIN_FUZZ_CASE=N` runs case `N` alone (with the same seed), to reproduce a failure;
//! `ELASTOKIN_FUZZ_VERBOSE=1` prints every case's mutations, refusals and figures left out with their
//! reasons (to review the messages users get).
//!
//! Below the campaign: one regression test per bug it (or a user) found, named after the bug.

mod common;

use elastokin_solver::{Mode, MAX_STEPS};
use elastokin_suspensions::kc::{self, KcReport, Settings};
use elastokin_suspensions::SuspensionFile;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

/// The campaign's seed: every case is drawn from it and its index, so a failure is reproducible.
const SEED: u64 = 0x00E1_A570_F022;
/// Cases read only (most mutations of the file's structure are refused when read).
const PARSE_CASES: usize = 4000;
/// Cases run through the whole suite when they read.
const SUITE_CASES: usize = 1600;
/// The time over which a case counts as a hang (it loops, or allocates without bound): given by
/// `ELASTOKIN_FUZZ_SLOW_CASE_SECONDS`, which `cargo xtask fuzz` sets. `cargo test` times nothing: its
/// build and its shared cores make a time a guess (a true hang still stops the run).
fn slow_case() -> Option<Duration> {
    env_number("ELASTOKIN_FUZZ_SLOW_CASE_SECONDS").map(Duration::from_secs)
}

const EXAMPLES: [(&str, &str); 8] = [
    ("macpherson.json", include_str!("../../../examples/generic/macpherson.json")),
    ("double_wishbone.json", include_str!("../../../examples/generic/double_wishbone.json")),
    ("double_wishbone_axle.json", include_str!("../../../examples/double_wishbone_axle.json")),
    ("five_link.json", include_str!("../../../examples/five_link.json")),
    ("four_link_axle.json", include_str!("../../../examples/four_link_axle.json")),
    ("twist_beam.json", include_str!("../../../examples/twist_beam.json")),
    ("twist_beam_template.json", include_str!("../../../examples/twist_beam_template.json")),
    ("pushrod_rocker.json", include_str!("../../../examples/pushrod_rocker.json")),
];

/// A model a case starts from: its name and text.
type Source = (String, String);

/// What a case mutates: a shipped example (half the cases) or a shipped Project Chrono suspension file
/// (`tests/data/chrono/`, the other half), by name and text.
fn sources() -> (&'static [Source], &'static [Source]) {
    static CHRONO: std::sync::OnceLock<Vec<Source>> = std::sync::OnceLock::new();
    static SHIPPED: std::sync::OnceLock<Vec<Source>> = std::sync::OnceLock::new();
    let shipped = SHIPPED.get_or_init(|| EXAMPLES.iter().map(|(n, t)| (n.to_string(), t.to_string())).collect());
    let chrono = CHRONO.get_or_init(|| {
        common::chrono::every_file()
            .into_iter()
            .map(|n| {
                let text = elastokin_suspensions::import::chrono::without_comments(&common::chrono::fixture(&n));
                (format!("chrono/{n}"), text)
            })
            .collect()
    });
    (shipped, chrono)
}

/// Factors a number is scaled by.
const FACTORS: [f64; 9] = [0.0, -1.0, 1e-3, 0.5, 1.01, 2.0, 1e3, 1e6, 1e300];

fn env_number(name: &str) -> Option<u64> {
    std::env::var(name).ok().map(|v| v.trim().parse().unwrap_or_else(|_| panic!("{name}={v} is not a number")))
}

fn seed() -> u64 {
    env_number("ELASTOKIN_FUZZ_SEED").unwrap_or(SEED)
}

/// `(parse-only cases, full-suite cases)`.
fn case_counts() -> (usize, usize) {
    match env_number("ELASTOKIN_FUZZ_CASES") {
        Some(n) => ((n as usize) * (PARSE_CASES / SUITE_CASES), n as usize),
        None => (PARSE_CASES, SUITE_CASES),
    }
}

/// The generator of case `index` of stream `stream` (each test draws from its own stream).
fn case_rng(stream: u64, index: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed());
    rng.set_stream(stream);
    rng.set_word_pos(u128::from(index as u64) << 20);
    rng
}

/// JSON pointers of every value in `v` (depth first), with the values.
fn walk<'a>(v: &'a Value, at: String, out: &mut Vec<(String, &'a Value)>) {
    out.push((at.clone(), v));
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                walk(child, format!("{at}/{}", k.replace('~', "~0").replace('/', "~1")), out);
            }
        }
        Value::Array(items) => {
            for (k, child) in items.iter().enumerate() {
                walk(child, format!("{at}/{k}"), out);
            }
        }
        _ => {}
    }
}

fn pointers(v: &Value, keep: impl Fn(&str, &Value) -> bool) -> Vec<String> {
    let mut all = Vec::new();
    walk(v, String::new(), &mut all);
    all.into_iter().filter(|(p, v)| keep(p, v)).map(|(p, _)| p).collect()
}

fn pick<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> Option<&'a T> {
    (!items.is_empty()).then(|| &items[rng.random_range(0..items.len())])
}

fn number(x: f64) -> Value {
    // A non-finite result (1e308 × 1e300) has no JSON number: it becomes null, one more wrong type.
    serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
}

fn is_hardpoint(p: &str, v: &Value) -> bool {
    p.contains("/hardpoints/") && p.matches('/').count() == 4 && v.is_array()
}

fn is_connection(p: &str) -> bool {
    ["lower_arm_mounts", "upper_arm_mounts", "top_mount", "tie_rod"].iter().any(|c| p.ends_with(c))
}

/// Applies one mutation; returns what it did, or `None` when the model has nothing it applies to.
fn mutate_once(model: &mut Value, rng: &mut ChaCha8Rng, structural: bool) -> Option<String> {
    let numbers = pointers(model, |_, v| v.is_number());
    let hardpoints = pointers(model, is_hardpoint);
    let kind = if structural { rng.random_range(0..12) } else { rng.random_range(0..5) };
    match kind {
        0 => {
            let at = pick(rng, &numbers)?.clone();
            let factor = *pick(rng, &FACTORS)?;
            let v = model.pointer_mut(&at)?;
            let x = v.as_f64()? * factor;
            *v = number(x);
            Some(format!("{at} scaled by {factor:e}"))
        }
        1 => {
            let at = pick(rng, &numbers)?.clone();
            let replacement = match rng.random_range(0..8) {
                0 => json!(0.0),
                1 => json!(-0.0),
                2 => json!(1e-300),
                3 => json!(1e308),
                4 => json!(-1e308),
                5 => json!(u64::MAX),
                6 => json!(i64::MIN),
                _ => json!(-rng.random_range(1..1_000_000i64)),
            };
            let what = format!("{at} replaced by {replacement}");
            *model.pointer_mut(&at)? = replacement;
            Some(what)
        }
        2 => {
            // Two hardpoints swapped, or one moved onto another.
            let a = pick(rng, &hardpoints)?.clone();
            let b = pick(rng, &hardpoints)?.clone();
            let (va, vb) = (model.pointer(&a)?.clone(), model.pointer(&b)?.clone());
            if rng.random_bool(0.5) {
                *model.pointer_mut(&a)? = vb;
                *model.pointer_mut(&b)? = va;
                Some(format!("{a} and {b} swapped"))
            } else {
                *model.pointer_mut(&a)? = vb;
                Some(format!("{a} moved onto {b}"))
            }
        }
        3 => {
            // A hardpoint moved by a distance from a hair to absurd, in a random direction.
            let at = pick(rng, &hardpoints)?.clone();
            let distance = *pick(rng, &[1e-9, 1e-4, 0.01, 0.1, 1.0, 1e3, 1e6, 1e293])?;
            let point = model.pointer_mut(&at)?.as_array_mut()?;
            let mut moved = Vec::new();
            for c in point.iter_mut() {
                let x = c.as_f64()? + distance * rng.random_range(-1.0..1.0);
                moved.push(x);
                *c = number(x);
            }
            Some(format!("{at} moved {distance:e} m to {moved:?}"))
        }
        4 => {
            // A connection made ideal, or a bushing of scaled rates.
            let at = pick(rng, &["lower_arm_mounts", "upper_arm_mounts", "top_mount", "tie_rod"])?;
            let template = pointers(model, |p, _| p.matches('/').count() == 2 && p.starts_with("/suspension/"));
            let owner = pick(rng, &template)?.clone();
            let factor = *pick(rng, &[1e-9, 1e-3, 1.0, 1e3, 1e9])?;
            let connection = if rng.random_bool(0.3) {
                json!("ideal")
            } else {
                json!({ "bushing": { "radial": 5e6 * factor, "axial": 1e6 * factor, "torsion": 573.0 * factor,
                                     "conical": 5730.0 * factor } })
            };
            let what = format!("{owner}/{at} set to {connection}");
            model.pointer_mut(&owner)?.as_object_mut()?.insert(at.to_string(), connection);
            Some(what)
        }
        5 => {
            let keys = pointers(model, |p, _| !p.is_empty() && !p.ends_with(|c: char| c.is_ascii_digit()));
            let at = pick(rng, &keys)?.clone();
            let (parent, key) = at.rsplit_once('/')?;
            model.pointer_mut(parent)?.as_object_mut()?.remove(key)?;
            Some(format!("{at} deleted"))
        }
        6 => {
            // A key copied into another object.
            let keys = pointers(model, |p, _| !p.is_empty() && !p.ends_with(|c: char| c.is_ascii_digit()));
            let objects = pointers(model, |_, v| v.is_object());
            let at = pick(rng, &keys)?.clone();
            let into = pick(rng, &objects)?.clone();
            let (_, key) = at.rsplit_once('/')?;
            let value = model.pointer(&at)?.clone();
            model.pointer_mut(&into)?.as_object_mut()?.insert(key.to_string(), value);
            Some(format!("{at} copied into {into:?}"))
        }
        7 => {
            let at = pick(rng, &numbers)?.clone();
            let v = model.pointer_mut(&at)?;
            let x = v.clone();
            *v = match rng.random_range(0..3) {
                0 => json!(x.to_string()),
                1 => json!([x]),
                _ => Value::Null,
            };
            Some(format!("{at} changed to {v}"))
        }
        8 => {
            let objects = pointers(model, |_, v| v.is_object());
            let into = pick(rng, &objects)?.clone();
            model.pointer_mut(&into)?.as_object_mut()?.insert("stiffness".into(), json!(1.0));
            Some(format!("unknown key added in {into:?}"))
        }
        9 => {
            let arrays = pointers(model, |_, v| v.as_array().is_some_and(|a| !a.is_empty()));
            let at = pick(rng, &arrays)?.clone();
            let items = model.pointer_mut(&at)?.as_array_mut()?;
            let keep = rng.random_range(0..items.len());
            items.truncate(keep);
            Some(format!("{at} truncated to {keep} items"))
        }
        11 => {
            // A character no name is written with, put into a name or any other text of the file.
            let texts = pointers(model, |_, v| v.is_string());
            let at = pick(rng, &texts)?.clone();
            let c = *pick(rng, &['\u{1b}', '\0', '\u{7}', '\u{b}', '\u{7f}', '\u{85}', '\u{fffe}', '\u{2028}'])?;
            let v = model.pointer_mut(&at)?;
            let text = format!("{}{c}[31m", v.as_str()?);
            *v = json!(text);
            Some(format!("{at} given the character U+{:04X}", c as u32))
        }
        _ => {
            let connections = pointers(model, |p, _| is_connection(p));
            let at = pick(rng, &connections)?.clone();
            *model.pointer_mut(&at)? = json!(*pick(rng, &["bushing", "rigid", ""])?);
            Some(format!("{at} set to an unknown connection"))
        }
    }
}

/// A mutated example: its name, the mutations and the JSON text.
struct Case {
    example: &'static str,
    mutations: Vec<String>,
    text: String,
}

impl std::fmt::Display for Case {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{} with {}:\n{}", self.example, self.mutations.join("; "), self.text)
    }
}

fn mutated(rng: &mut ChaCha8Rng, structural: bool) -> Case {
    let (shipped, chrono) = sources();
    let pool = if rng.random_bool(0.5) { shipped } else { chrono };
    let (example, text) = pick(rng, pool).unwrap();
    let example = example.as_str();
    let mut model: Value = serde_json::from_str(text).unwrap();
    let mut mutations = Vec::new();
    let count = rng.random_range(1..=3);
    while mutations.len() < count {
        if let Some(m) = mutate_once(&mut model, rng, structural) {
            mutations.push(m);
        }
    }
    Case { example, mutations, text: serde_json::to_string_pretty(&model).unwrap() }
}

/// Whether `text` shows a non-finite number as Rust or JSON writers print it.
fn shows_non_finite(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| matches!(w, "NaN" | "inf" | "Infinity" | "infinity"))
}

/// What is wrong with a refusal message, if anything.
fn check_refusal(message: &str) -> Result<(), String> {
    if message.trim().is_empty() {
        return Err("an empty error message".into());
    }
    if shows_non_finite(message) {
        return Err(format!("an error message showing a non-finite number: {message}"));
    }
    Ok(())
}

/// Table columns whose cells are empty by definition in some rows.
const MAY_BE_EMPTY: [&str; 11] = [
    "ideal_outer_steer_deg",
    "ackermann_error_deg",
    "ackermann_percent",
    // No roll centre where the front-view lines through the patches are parallel.
    "roll_centre_lateral_m",
    "roll_centre_height_m",
    // No instant centre in a view where the upright does not turn.
    "front_view_instant_centre_y_m",
    "front_view_instant_centre_z_m",
    "front_view_swing_arm_length_m",
    "side_view_instant_centre_x_m",
    "side_view_instant_centre_z_m",
    "side_view_swing_arm_length_m",
];

/// A suite's report of one analysis alone, as [`check_report`] takes it.
fn one_analysis(file: &SuspensionFile, settings: Settings, report: kc::AnalysisReport) -> KcReport {
    KcReport {
        model: file.name.clone(),
        settings,
        analyses: vec![report],
        skipped: Vec::new(),
        failed: Vec::new(),
        model_check: None,
        warnings: Vec::new(),
    }
}

/// What is wrong with a report, if anything: every number a user reads must be finite.
fn check_report(report: &KcReport) -> Result<(), String> {
    let finite = |what: String, v: f64| if v.is_finite() { Ok(()) } else { Err(format!("{what} = {v}")) };
    for a in &report.analyses {
        let name = a.analysis.name();
        for f in &a.figures {
            if let Some(v) = f.value {
                finite(format!("{name} figure {}", f.key), v)?;
            }
            if let Some(e) = f.error {
                finite(format!("{name} figure {} error", f.key), e)?;
            }
            match (&f.value, f.reason.as_deref()) {
                (None, None) => return Err(format!("{name} figure {} has neither a value nor a reason", f.key)),
                (None, Some(r)) if r.trim().is_empty() => return Err(format!("{name} figure {} has no reason", f.key)),
                // The report's catch-all for a non-finite value: a NaN or infinity computed upstream, which
                // the analysis must prevent or explain in its own words.
                (None, Some(r)) if r.starts_with("not a finite number") => {
                    return Err(format!("{name} figure {} computed a non-finite value: {r}", f.key))
                }
                _ => {}
            }
        }
        for table in std::iter::once(&a.table).chain(&a.compliance) {
            for row in &table.rows {
                for (cell, column) in row.iter().zip(&table.columns) {
                    match cell {
                        kc::Cell::Number(v) => finite(format!("{name} table {} column {column}", table.name), *v)?,
                        // `Cell::from` empties a non-finite number: only these columns are empty by
                        // definition (no Ackermann figure where neither wheel steers).
                        kc::Cell::Empty if !MAY_BE_EMPTY.contains(&column.as_str()) => {
                            return Err(format!("{name} table {} column {column}: an empty cell", table.name))
                        }
                        _ => {}
                    }
                }
            }
        }
        for row in a.wheel_compliance_at_design.iter().flatten() {
            for &v in row {
                finite(format!("{name} wheel compliance at design"), v)?;
            }
        }
        let acc = &a.accuracy;
        finite(format!("{name} angle error"), acc.angle_error_deg)?;
        finite(format!("{name} length error"), acc.length_error_m)?;
        finite(format!("{name} force residual"), acc.force_residual)?;
        finite(format!("{name} constraint residual"), acc.constraint_residual)?;
        for (column, e) in &acc.columns {
            if let Some(e) = e {
                finite(format!("{name} error of column {column}"), *e)?;
            }
        }
        finite(format!("{name} range start"), a.range.0)?;
        finite(format!("{name} range end"), a.range.1)?;
        for line in a.headline() {
            if shows_non_finite(&line) {
                return Err(format!("{name} headline line shows a non-finite number: {line}"));
            }
        }
    }
    let json = serde_json::to_string(report).map_err(|e| format!("the report does not serialise: {e}"))?;
    if shows_non_finite(&json) {
        return Err("the serialised report shows a non-finite number".into());
    }
    Ok(())
}

/// Settings of a suite case: few steps, and sometimes paper mode, the wheel free, the compliance.
fn settings(rng: &mut ChaCha8Rng) -> Settings {
    let range = rng.random_bool(0.15).then(|| range(rng));
    // Mostly 4 steps (cheap); sometimes 1–3, which leave the design position between rows.
    let steps = if rng.random_bool(0.2) { rng.random_range(1..=3) } else { 4 };
    Settings {
        range,
        steps,
        mode: if rng.random_bool(0.25) { Mode::Paper } else { Mode::Corrected },
        height_held: rng.random_bool(0.75),
        compliance: rng.random_bool(0.1),
        ..Settings::default()
    }
}

/// A range in an analysis's own parameter for a run of one analysis, as `--range` gives it: ordinary,
/// reversed, empty, tiny or absurd.
fn range(rng: &mut ChaCha8Rng) -> (f64, f64) {
    let scale = *pick(rng, &[1e-300, 1e-6, 0.01, 1.0, 100.0, 1e4, 1e8, 1e300, f64::MAX]).unwrap();
    let (a, b) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
    match rng.random_range(0..4) {
        0 => (0.0, 0.0),
        1 => (a * scale, a * scale),
        2 => (-scale, scale),
        _ => (a * scale, b * scale),
    }
}

/// Runs one case: reads the text and, if `suite`, runs the suite on what reads. A panic is caught only to
/// report it with the case.
fn run_case(case: &Case, settings: Option<&Settings>) -> Result<&'static str, String> {
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // Read as the command reads a model: an elastokin model file or a Chrono suspension file.
        let file = match elastokin_suspensions::document::parse_model(&case.text, "model.json") {
            Ok((file, _)) => file,
            Err(e) => {
                let message = e.to_string();
                if std::env::var_os("ELASTOKIN_FUZZ_VERBOSE").is_some() {
                    eprintln!("UNREAD {message}");
                }
                check_refusal(&message)?;
                if message.contains("::") {
                    return Err(format!("an error message naming code: {message}"));
                }
                return Ok("refused when read");
            }
        };
        let Some(settings) = settings else { return Ok("read") };
        let verbose = std::env::var_os("ELASTOKIN_FUZZ_VERBOSE").is_some();
        if settings.range.is_some() {
            // A run of one analysis over a range given by the user.
            let analysis = kc::ALL[(settings.steps + case.text.len()) % kc::ALL.len()];
            return match kc::run(analysis, &file, settings) {
                Ok(report) => {
                    let suite = one_analysis(&file, *settings, report);
                    check_report(&suite).map(|()| "ran one analysis over a range")
                }
                Err(e) => {
                    if verbose {
                        eprintln!("REFUSED {e}");
                    }
                    check_refusal(&e.to_string()).map(|()| "refused by an analysis")
                }
            };
        }
        let report = kc::run_suite(&file, &[], settings, |_| {});
        if verbose {
            for a in &report.analyses {
                for f in a.figures.iter().filter(|f| f.value.is_none()) {
                    eprintln!("MISSING {} {}: {}", a.analysis.name(), f.key, f.reason.as_deref().unwrap_or(""));
                }
                let empty = a.table.rows.iter().flatten().filter(|c| **c == kc::Cell::Empty).count();
                if empty > 0 {
                    eprintln!("EMPTY {} {empty} cells", a.analysis.name());
                }
            }
            for f in &report.failed {
                eprintln!("REFUSED {}: {}", f.analysis.name(), f.reason);
            }
        }
        // A failed analysis costs only itself: the others' results stand and are checked as any.
        for f in &report.failed {
            check_refusal(&format!("{}: {}", f.analysis.name(), f.reason))?;
        }
        check_report(&report).map(|()| if report.failed.is_empty() { "ran" } else { "refused by an analysis" })
    }));
    match outcome {
        Ok(result) => result,
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("panicked: {message}"))
        }
    }
}

/// What one case came to: its label and mutations, how long it took, and its outcome or why it failed.
struct Ran {
    index: usize,
    label: String,
    source: &'static str,
    took: Duration,
    result: Result<&'static str, String>,
    case: String,
}

/// Draws and runs case `index` of `stream`.
fn run_index(stream: u64, index: usize, suite: bool) -> Ran {
    let mut rng = case_rng(stream, index);
    // Suite cases mostly change numbers and geometry, which still read; structural changes are refused.
    let structural = !suite || rng.random_bool(0.1);
    let mut case = mutated(&mut rng, structural);
    // Suite cases are drawn again (a few times) until one reads, so that most of them run the suite.
    for _ in 0..8 {
        if !suite || elastokin_suspensions::document::parse_model(&case.text, "model.json").is_ok() {
            break;
        }
        case = mutated(&mut rng, structural);
    }
    let settings = suite.then(|| settings(&mut rng));
    if std::env::var_os("ELASTOKIN_FUZZ_VERBOSE").is_some() {
        eprintln!("CASE {index}: {} with {}", case.example, case.mutations.join("; "));
    }
    let t = Instant::now();
    let result = run_case(&case, settings.as_ref());
    let took = t.elapsed();
    let label = format!("case {index} (seed {}, stream {stream}) {settings:?}", seed());
    let result = match result {
        Ok(_) if slow_case().is_some_and(|slow| took > slow) => Err(format!("took {took:.1?}")),
        other => other,
    };
    let case_text =
        if result.is_err() { case.to_string() } else { format!("{} with {}", case.example, case.mutations.join("; ")) };
    Ran { index, label, source: case.example, took, result, case: case_text }
}

/// Runs `count` cases of `stream` on every core, and fails with every failing case (seed, index, mutations,
/// JSON), the slowest case, and any case slower than [`slow_case`]. With `ELASTOKIN_FUZZ_REPORT=DIR` it
/// also writes what it found to `DIR/fuzz_stream<stream>.json` (what `cargo xtask fuzz` reports).
fn campaign(stream: u64, count: usize, suite: bool) {
    let only = env_number("ELASTOKIN_FUZZ_CASE").map(|n| n as usize);
    let indices: Vec<usize> = (0..count).filter(|i| only.is_none_or(|o| o == *i)).collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(indices.len().max(1));
    let start = Instant::now();
    // Cases are dealt round robin to the threads and put back in order: the report does not depend on
    // how many threads ran it.
    let mut ran: Vec<Ran> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|k| {
                let mine: Vec<usize> = indices.iter().copied().skip(k).step_by(threads).collect();
                scope.spawn(move || mine.into_iter().map(|i| run_index(stream, i, suite)).collect::<Vec<Ran>>())
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().expect("a fuzz worker panicked outside a case")).collect()
    });
    ran.sort_by_key(|r| r.index);
    let wall = start.elapsed();
    let mut outcomes = std::collections::BTreeMap::<&str, usize>::new();
    let mut sources = std::collections::BTreeMap::<&str, usize>::new();
    let mut failures = Vec::new();
    for r in &ran {
        *sources.entry(if r.source.starts_with("chrono/") { "chrono" } else { "examples" }).or_default() += 1;
        match &r.result {
            Ok(outcome) => *outcomes.entry(outcome).or_default() += 1,
            Err(why) => failures.push(format!("{}: {why}\n{}", r.label, r.case)),
        }
    }
    let slowest = ran.iter().max_by_key(|r| r.took);
    let slowest_line = slowest.map_or(String::new(), |r| format!("{:.2?}, {}: {}", r.took, r.label, r.case));
    let count_of =
        |what: &dyn Fn(&str) -> bool| ran.iter().filter(|r| r.result.as_ref().is_err_and(|w| what(w))).count();
    eprintln!("{} cases in {wall:.1?} on {threads} threads: {outcomes:?}; slowest {slowest_line}", ran.len());
    if let Some(dir) = std::env::var_os("ELASTOKIN_FUZZ_REPORT") {
        let report = json!({
            "stream": stream,
            "seed": seed(),
            "suite": suite,
            "cases": ran.len(),
            "threads": threads,
            "seconds": wall.as_secs_f64(),
            "sources": sources,
            "outcomes": outcomes,
            "panics": count_of(&|w| w.starts_with("panicked")),
            "hangs": count_of(&|w| w.starts_with("took")),
            "non_finite": count_of(&|w| w.contains("non-finite") || w.contains(" = NaN") || w.contains(" = inf") || w.contains(" = -inf")),
            "failures": failures,
            "slowest_seconds": slowest.map_or(0.0, |r| r.took.as_secs_f64()),
            "slowest": slowest_line,
        });
        let path = std::path::Path::new(&dir).join(format!("fuzz_stream{stream}.json"));
        std::fs::write(&path, serde_json::to_string_pretty(&report).unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    assert!(failures.is_empty(), "{} failing cases:\n\n{}", failures.len(), failures.join("\n\n"));
}

#[test]
fn mutated_models_are_read_or_refused_with_a_message() {
    campaign(1, case_counts().0, false);
}

#[test]
fn mutated_models_run_the_suite_without_panic_or_non_finite_output() {
    campaign(2, case_counts().1, true);
}

// Regression tests: one per bug, named after it.

/// The example `name` with the values at JSON pointers `edits` replaced.
fn example_with(name: &str, edits: &[(&str, Value)]) -> String {
    let text = EXAMPLES.iter().find(|(n, _)| *n == name).unwrap().1;
    let mut model: Value = serde_json::from_str(text).unwrap();
    for (at, value) in edits {
        *model.pointer_mut(at).unwrap_or_else(|| panic!("{name} has no {at}")) = value.clone();
    }
    serde_json::to_string_pretty(&model).unwrap()
}

/// The refusal of a model that must not read, checked as the campaign checks it.
fn refusal(text: &str) -> String {
    let message = SuspensionFile::from_json(text, "model.json").expect_err("the model must be refused").to_string();
    check_refusal(&message).unwrap();
    message
}

const MP_HARDPOINTS: &str = "/suspension/macpherson/hardpoints";

fn mp_point(name: &str) -> [f64; 3] {
    let model: Value = serde_json::from_str(EXAMPLES[0].1).unwrap();
    let p = &model.pointer(&format!("{MP_HARDPOINTS}/{name}")).unwrap();
    [0, 1, 2].map(|k| p[k].as_f64().unwrap())
}

#[test]
fn zero_spring_design_force_gives_no_nan_wheel_rate() {
    let text = example_with("macpherson.json", &[("/suspension/macpherson/spring/design_force", json!(0.0))]);
    let file = SuspensionFile::from_json(&text, "model.json").unwrap();
    let settings = Settings { steps: 4, ..Settings::default() };
    // The default range is 0.5–1.5 × the design wheel load, which the spring's design force carries: with
    // none, a range around nothing would have no width, so 0 to 3 kN is taken, and the wheel rate is there.
    let report = kc::run(kc::Analysis::VerticalForce, &file, &settings).unwrap();
    assert_eq!(report.range, (0.0, 3000.0));
    check_report(&one_analysis(&file, settings, report)).unwrap();
    // With a range the wheel rate is there.
    let ranged = Settings { range: Some((-1000.0, 1000.0)), ..settings };
    let report = kc::run(kc::Analysis::VerticalForce, &file, &ranged).unwrap();
    let rate = report.figure("wheel_rate").unwrap().value.unwrap();
    assert!(rate > 10e3 && rate < 100e3, "{rate} N/m");
}

#[test]
fn huge_wheelbase_is_refused_not_an_infinite_anti_dive() {
    let text = example_with("macpherson.json", &[("/vehicle/wheelbase", json!(1e308))]);
    let e = refusal(&text);
    assert!(e.contains("vehicle.wheelbase") && e.contains("is outside 0.5–20 m"), "{e}");
}

#[test]
fn top_mount_a_thousand_kilometres_away_is_refused() {
    let [x, y, z] = mp_point("top_mount");
    let text = example_with("macpherson.json", &[(&format!("{MP_HARDPOINTS}/top_mount"), json!([x, y + 1e6, z]))]);
    let e = refusal(&text);
    assert!(e.contains("top_mount") && e.contains("beyond ±1000 m"), "{e}");
}

#[test]
fn tie_rod_point_at_1e293_m_is_refused() {
    for end in ["tie_rod_inner", "tie_rod_outer"] {
        let [x, y, _] = mp_point(end);
        let text = example_with("macpherson.json", &[(&format!("{MP_HARDPOINTS}/{end}"), json!([x, y, 1e293]))]);
        let e = refusal(&text);
        assert!(e.contains(end) && e.contains("metres"), "{e}");
    }
}

#[test]
fn macpherson_tie_rod_along_the_steering_axis_is_refused() {
    let (lower, top) = (mp_point("lower_ball_joint"), mp_point("top_mount"));
    let along = |t: f64, offset: [f64; 3]| json!([0, 1, 2].map(|k| lower[k] + t * (top[k] - lower[k]) + offset[k]));
    // On the axis, and parallel to it 80 mm behind: a pull along either has no moment about the axis.
    for offset in [[0.0; 3], [-0.08, 0.0, 0.0]] {
        let text = example_with(
            "macpherson.json",
            &[
                (&format!("{MP_HARDPOINTS}/tie_rod_outer"), along(0.2, offset)),
                (&format!("{MP_HARDPOINTS}/tie_rod_inner"), along(0.5, offset)),
            ],
        );
        let e = refusal(&text);
        assert!(e.contains("tie_rod_outer") && e.contains("steering axis"), "{e}");
    }
}

#[test]
fn hardpoint_checks_accept_the_shipped_examples() {
    for (name, text) in EXAMPLES {
        SuspensionFile::from_json(text, name).unwrap();
    }
}

#[test]
fn loaded_radius_1e308_is_refused_not_an_infinite_path_tangent() {
    let text = example_with("double_wishbone.json", &[("/suspension/double_wishbone/loaded_radius", json!(1e308))]);
    let e = refusal(&text);
    assert!(e.contains("loaded_radius") && e.contains("is outside 0.05–2 m"), "{e}");
}

#[test]
fn a_twist_beams_arm_of_no_length_is_refused_not_a_nan_junction() {
    let at = "/suspension/twist_beam/hardpoints/arm_end";
    let e = refusal(&example_with("twist_beam_template.json", &[(at, json!([0.46, 0.6, 0.33]))]));
    assert!(e.contains("hardpoints.arm_end") && e.contains("0.0 mm long") && !e.contains("NaN"), "{e}");
}

#[test]
fn a_cross_members_second_moment_of_1e294_is_refused_not_a_nan_stiffness() {
    let at = "/suspension/twist_beam/cross_member/section/iy";
    let e = refusal(&example_with("twist_beam_template.json", &[(at, json!(1.28e294))]));
    assert!(e.contains("second moment Iy") && e.contains("beyond") && !e.contains("NaN"), "{e}");
}

#[test]
fn bushing_rate_1e308_is_refused_not_an_infinite_stiffness() {
    let at = "/suspension/macpherson/lower_arm_mounts/bushing/conical";
    let e = refusal(&example_with("macpherson.json", &[(at, json!(1e308))]));
    // Refused where the file is read, with the key, its line and the accepted range.
    assert!(e.contains("lower_arm_mounts.bushing.conical") && e.contains("outside the accepted range"), "{e}");
    let at = "/suspension/macpherson/spring/rate";
    let e = refusal(&example_with("macpherson.json", &[(at, json!(3e304))]));
    assert!(e.contains("spring.rate") && e.contains("outside the accepted range"), "{e}");
}

#[test]
fn tie_rod_bushing_of_a_thousandth_newton_per_metre_is_refused_not_an_infinite_steering_ratio() {
    let rates = json!({ "bushing": { "radial": 5e-3, "axial": 1e-3, "torsion": 5.7e-7, "conical": 5.7e-6 } });
    // The example's tie rod is ideal, by default: the key is added.
    let mut model: Value = serde_json::from_str(EXAMPLES[0].1).unwrap();
    model["suspension"]["macpherson"]["tie_rod"] = rates;
    let e = refusal(&model.to_string());
    assert!(e.contains("tie_rod.bushing.radial") && e.contains("N/m"), "{e}");
}

#[test]
fn wheel_centre_on_the_centre_line_is_refused_not_a_nan_ackermann() {
    let at = "/suspension/double_wishbone/hardpoints/wheel_centre";
    let e = refusal(&example_with("double_wishbone.json", &[(at, json!([-0.04, 0.0, -0.026]))]));
    assert!(e.contains("wheel_centre") && e.contains("left corner"), "{e}");
}

#[test]
fn bushings_a_thousandth_as_stiff_that_let_the_macpherson_settle_at_15_deg_are_named() {
    let mut model: Value = serde_json::from_str(EXAMPLES[0].1).unwrap();
    for mount in ["lower_arm_mounts", "top_mount"] {
        for rate in model["suspension"]["macpherson"][mount]["bushing"].as_object_mut().unwrap().values_mut() {
            *rate = json!(rate.as_f64().unwrap() * 1e-3);
        }
    }
    let file = SuspensionFile::from_json(&model.to_string(), "model.json").unwrap();
    let notices = elastokin_suspensions::check::bushing_deflection_at_design(&file);
    assert!(notices.iter().any(|n| n.message.contains("'top mount' deflects")), "{notices:?}");
    // The suite says so, with whatever fails on such a model.
    let settings = Settings { steps: 4, ..Settings::default() };
    let report = kc::run_suite(&file, &[], &settings, |_| {});
    assert!(report.all_warnings().any(|w| w.code == "bushing-deflection"));
    for f in &report.failed {
        assert!(f.reason.contains("'top mount' deflects"), "{}: {}", f.analysis.name(), f.reason);
    }
    // The examples' bushings hold the design position within a fraction of a millimetre.
    for (name, text) in EXAMPLES {
        let notices =
            elastokin_suspensions::check::bushing_deflection_at_design(&SuspensionFile::from_json(text, name).unwrap());
        assert!(notices.is_empty(), "{name}: {notices:?}");
    }
}

#[test]
fn spring_design_force_1e308_is_refused_not_an_infinite_stiffness() {
    let at = "/suspension/macpherson/spring/design_force";
    let e = refusal(&example_with("macpherson.json", &[(at, json!(1e308))]));
    assert!(e.contains("spring.design_force") && e.contains("beyond ±1e6 N"), "{e}");
}

#[test]
fn wheel_centre_at_y_1e_300_is_refused_not_a_nan_ackermann() {
    let at = "/suspension/macpherson/hardpoints/wheel_centre/1";
    let e = refusal(&example_with("macpherson.json", &[(at, json!(1e-300))]));
    assert!(e.contains("wheel_centre") && e.contains("left corner"), "{e}");
}

#[test]
fn empty_range_is_refused_not_a_nan_bump_steer() {
    let file = SuspensionFile::from_json(EXAMPLES[0].1, "macpherson.json").unwrap();
    for analysis in kc::ALL {
        let settings = Settings { range: Some((0.0, 0.0)), steps: 4, ..Settings::default() };
        let e = kc::run(analysis, &file, &settings).unwrap_err().to_string();
        check_refusal(&e).unwrap();
        // The static load walks no range at all.
        let says = if analysis == kc::Analysis::StaticLoad { "with no range to walk" } else { "two finite ends" };
        assert!(e.contains(says), "{e}");
    }
}

#[test]
fn range_of_1e_300_is_refused_not_an_infinite_roll_steer() {
    let file = SuspensionFile::from_json(EXAMPLES[0].1, "macpherson.json").unwrap();
    let settings = Settings { range: Some((-1e-300, 1e-300)), steps: 4, ..Settings::default() };
    let e = kc::run(kc::Analysis::Roll, &file, &settings).unwrap_err().to_string();
    check_refusal(&e).unwrap();
    assert!(e.contains("at least 1e-9 apart"), "{e}");
}

#[test]
fn ball_joints_on_one_point_are_refused_not_a_nan_scrub_radius() {
    let model: Value = serde_json::from_str(EXAMPLES[1].1).unwrap();
    let upper = model["suspension"]["double_wishbone"]["hardpoints"]["upper_ball_joint"].clone();
    let at = "/suspension/double_wishbone/hardpoints/lower_ball_joint";
    let e = refusal(&example_with("double_wishbone.json", &[(at, upper)]));
    assert!(e.contains("lower_ball_joint and upper_ball_joint") && e.contains("steering axis"), "{e}");
    // A level steering axis never meets the ground.
    let level = json!([-0.3, 0.85, 0.243]);
    let e = refusal(&example_with("double_wishbone.json", &[(at, level)]));
    assert!(e.contains("must rise"), "{e}");
}

#[test]
fn zero_steps_are_refused_in_words_not_a_load_path_dump() {
    let file = SuspensionFile::from_json(EXAMPLES[0].1, "macpherson.json").unwrap();
    let expected = [
        "a sweep needs at least 1 step, got 0".to_string(),
        format!("a sweep takes at most {MAX_STEPS} steps, got {}", MAX_STEPS + 1),
    ];
    for (steps, expected) in [0, MAX_STEPS + 1].into_iter().zip(expected) {
        let e = kc::run(kc::Analysis::ParallelTravel, &file, &Settings { steps, ..Settings::default() }).unwrap_err();
        // The library's one step limit, in the words every front end shows: no command flag, no type name.
        assert!(
            matches!(&e.cause, kc::Cause::Settings(m) if m.starts_with(&expected) && !m.contains("LoadPath") && !m.contains("--")),
            "{e}"
        );
    }
}

/// Three steps over a range symmetric about design put no row there; the figures at design are read off the
/// equilibrium there and its path, not the rows, so they are the four steps' to the bit.
#[test]
fn odd_steps_give_the_figures_at_design_that_even_steps_give() {
    let file = SuspensionFile::from_json(EXAMPLES[0].1, "macpherson.json").unwrap();
    let run = |steps| kc::run(kc::Analysis::ParallelTravel, &file, &Settings { steps, ..Settings::default() }).unwrap();
    let (odd, even) = (run(3), run(4));
    assert!(odd.table.rows.iter().all(|r| r[0].number().unwrap().abs() > 1e-3), "no row at design");
    for key in ["caster", "bump_steer", "wheel_rate"] {
        let (a, b) = (odd.figure(key).unwrap().value, even.figure(key).unwrap().value);
        assert!(a.is_some() && a == b, "{key}: {a:?} against {b:?}");
    }
}

#[test]
fn soft_tie_rod_bushings_toeing_both_wheels_17_deg_give_the_ackermann_reason_and_a_warning() {
    let mut model: Value = serde_json::from_str(EXAMPLES[0].1).unwrap();
    model["suspension"]["macpherson"]["tie_rod"] =
        json!({ "bushing": { "radial": 5000.0, "axial": 1000.0, "torsion": 0.573, "conical": 5.73 } });
    let file = SuspensionFile::from_json(&model.to_string(), "model.json").unwrap();
    let report = kc::run_suite(&file, &[], &Settings { steps: 4, ..Settings::default() }, |_| {}).complete().unwrap();
    let steering = report.analysis(kc::Analysis::Steering).unwrap();
    let why = steering.figure("ackermann").unwrap().reason.clone().unwrap();
    // The rack does steer (the figure said it steered neither wheel): both wheels sit toed in at rack centre.
    assert!(steering.figure("steer_per_rack_travel").unwrap().value.unwrap().abs() > 1e-3);
    assert!(why.contains("toe at rack centre outweighs"), "{why}");
    assert!(
        report.warnings.iter().any(|w| w.message.contains("'tie rod inner bushing' deflects")),
        "{:?}",
        report.warnings
    );
}

/// Found by the campaign with seed 23 (case 3065): a rack travel per turn of -0 passed, and the overall
/// steering ratio 360 / (c · dδ/dx) came out infinite. The optional vehicle values are held to their
/// ranges where the file is read, as the others are.
#[test]
fn rack_travel_per_revolution_of_minus_zero_is_refused_not_an_infinite_steering_ratio() {
    for (key, value) in [("rack_travel_per_revolution", json!(-0.0)), ("tyre_rate", json!(0.0))] {
        let e = refusal(&example_with("double_wishbone.json", &[(&format!("/vehicle/{key}"), value)]));
        assert!(e.contains(&format!("vehicle.{key}")) && e.contains("is outside"), "{e}");
    }
}

/// Fuzz case 195 (seed 0xE1A570F022, stream 2): the four-link axle with its upper links' chassis ends on the
/// lower links' axle ends rolled not at all as its wheels travelled opposite, and the roll steer, roll camber
/// and roll stiffness, per degree of that roll, were 0 / 0.
#[test]
fn an_axle_that_does_not_roll_gives_no_per_degree_of_roll_figure_not_a_nan_roll_steer() {
    let g = "/suspension/general/hardpoints";
    let model: Value = serde_json::from_str(EXAMPLES[4].1).unwrap();
    let lower_link_axle = model.pointer(&format!("{g}/lower_link_axle")).unwrap().clone();
    let text = example_with(
        "four_link_axle.json",
        &[
            (&format!("{g}/upper_link_chassis"), lower_link_axle),
            (&format!("{g}/lower_link_chassis/0"), json!(1e-300)),
            (&format!("{g}/spring_chassis"), json!([-0.08413918730219289, 0.45988175466563963, 0.6893378609942479])),
        ],
    );
    let file = SuspensionFile::from_json(&text, "model.json").unwrap();
    let settings = Settings { steps: 4, ..Settings::default() };
    let report = kc::run(kc::Analysis::Roll, &file, &settings).unwrap();
    let angle = report.table.columns.iter().position(|c| c == "roll_angle_deg").unwrap();
    let rolled: Vec<f64> = report.table.rows.iter().map(|r| r[angle].number().unwrap()).collect();
    // The roll angle does not change (measured: -0.2385° in every row, to the last bit).
    assert!(rolled.iter().all(|a| (a - rolled[0]).abs() < 1e-12), "{rolled:?}");
    for key in ["roll_steer", "roll_camber", "roll_stiffness"] {
        let f = report.figure(key).unwrap();
        assert!(f.value.is_none() && f.reason.as_deref().unwrap().contains("does not roll"), "{key}: {f:?}");
    }
    check_report(&one_analysis(&file, settings, report)).unwrap();
}

/// Fuzz case 57510 of the long campaign (`cargo xtask fuzz`, seed 0xE1A570F022, stream 2): the four-link
/// axle with a lower link of (nearly) no length locks the wheel's height, and the static load case refused
/// it as "unstable (wheel rate inf N/m)". It now says the joints alone hold the wheel, without a non-finite
/// number.
#[test]
fn a_locked_linkage_is_named_in_the_static_load_case_not_an_infinite_wheel_rate() {
    let g = "/suspension/general/hardpoints";
    let model: Value = serde_json::from_str(EXAMPLES[4].1).unwrap();
    let mut moved = model.pointer(&format!("{g}/lower_link_axle")).unwrap().clone();
    moved[2] = json!(moved[2].as_f64().unwrap() * 1.01);
    let text = example_with("four_link_axle.json", &[(&format!("{g}/lower_link_chassis"), moved)]);
    let file = SuspensionFile::from_json(&text, "model.json").unwrap();
    let settings = Settings { steps: 2, ..Settings::default() };
    let e = kc::run(kc::Analysis::StaticLoad, &file, &settings).unwrap_err().to_string();
    check_refusal(&e).unwrap();
    assert!(e.contains("the joints alone hold its height"), "{e}");
}

/// Fuzz case 1859 (seed 33, stream 2): the twist-beam template with its spring seat moved a kilometre and
/// its wheel centre onto it steers not at all under a lateral force, so the bushings' share of that steer
/// has no value, but its error estimate was written as 0/0, a NaN. It now has none.
#[test]
fn the_bushings_share_of_a_steer_that_is_zero_has_no_nan_error_estimate() {
    let h = "/suspension/twist_beam/hardpoints";
    let far = json!([417.6112427037673, 183.67176287895893, -706.281653053493]);
    let text = example_with(
        "twist_beam_template.json",
        &[(&format!("{h}/spring_seat"), far.clone()), (&format!("{h}/wheel_centre"), far)],
    );
    let file = SuspensionFile::from_json(&text, "model.json").unwrap();
    let settings = Settings { steps: 4, ..Settings::default() };
    let lateral = kc::Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral);
    let report = kc::run(lateral, &file, &settings).unwrap();
    let share = report.figure("bushing_share_of_steer").unwrap();
    assert!(share.value.is_none() && share.error.is_none(), "{share:?}");
    // Read off the path at design, the steer is rounding (-6 ± 859 deg/kN, measured), not zero to the bit as
    // the rows' differences read it.
    assert_eq!(share.reason.as_deref(), Some("the figure is zero within its error estimate"));
    check_report(&one_analysis(&file, settings, report)).unwrap();
}
