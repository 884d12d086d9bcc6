//! Seeded mutation testing of the design files: the shipped TARGETS files and TOLERANCES file, each
//! mutated in one or two places (numbers replaced by extremes or scaled, or written as text — "inf", "NaN",
//! "1e999", "0x10" —, values replaced by other types, keys and array items deleted, figure names changed, a
//! control character put into a text or a key) or with a key given twice, then read against their model as
//! the commands
//! read them. A file that cannot be meant must be refused with a message in words; one that reads is, in
//! some cases, evaluated or tuned (TARGETS) or stacked up with a few samples (TOLERANCES), which must end
//! in a result with no non-finite number or in a message, never in a panic. Bounds of 1e308 (a panic in the
//! tune's step) and an aim of 1e308 (an infinite objective) were found this way (`tests/tune.rs`).
//!
//! `ELASTOKIN_FUZZ_CASES` sets the cases per file, `ELASTOKIN_FUZZ_SEED` the seed, as for
//! `tests/fuzz_models.rs`.

use elastokin_suspensions::design::targets::read_targets;
use elastokin_suspensions::design::tolerance::{read_tolerances, stack_up};
use elastokin_suspensions::design::tune::{evaluate, tune};
use elastokin_suspensions::design::Parameters;
use elastokin_suspensions::study::batch::base_document;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Cases per file.
const CASES: usize = 1500;
const SEED: u64 = 0x7A26_E7F1;

fn env_number(name: &str) -> Option<u64> {
    std::env::var(name).ok()?.parse().ok()
}

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{}/../../{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// A model file as the commands read it.
fn model(path: &str) -> Value {
    base_document(&read(path), path).unwrap()
}

/// JSON pointers of every value in `v`.
fn pointers(v: &Value, at: String, out: &mut Vec<String>) {
    out.push(at.clone());
    match v {
        Value::Object(map) => {
            map.iter().for_each(|(k, x)| pointers(x, format!("{at}/{}", k.replace('~', "~0").replace('/', "~1")), out))
        }
        Value::Array(items) => items.iter().enumerate().for_each(|(k, x)| pointers(x, format!("{at}/{k}"), out)),
        _ => {}
    }
}

/// Applies one mutation somewhere in `doc`.
fn mutate(doc: &mut Value, rng: &mut ChaCha8Rng) {
    let mut all = Vec::new();
    pointers(doc, String::new(), &mut all);
    let at = all[rng.random_range(1..all.len())].clone();
    let others = [
        json!(0.0),
        json!(-1.0),
        json!(1e308),
        json!(-1e308),
        json!(1e-300),
        json!(-0.0),
        json!(7),
        json!("x"),
        json!(null),
        json!(true),
        json!([]),
        json!({}),
        json!([1.0]),
        json!([0.5, 0.1]),
        json!([1.0, 2.0, 3.0]),
        json!("15%"),
        json!("-5%"),
        json!("1e400%"),
        json!("parallel-travel/toe_deg"),
        json!("roll/no_such_figure"),
        json!("inf"),
        json!("NaN"),
        json!("1e999"),
        json!("0x10"),
        json!("nan%"),
    ];
    let (parent, key) = at.rsplit_once('/').unwrap();
    let control = ['\u{1b}', '\0', '\u{7}', '\u{b}', '\u{7f}', '\u{fffe}', '\u{2028}'][rng.random_range(0..7)];
    match rng.random_range(0..6) {
        4 => {
            if let Some(Value::String(text)) = doc.pointer_mut(&at) {
                text.push(control);
            }
        }
        5 => {
            if let Some(map) = doc.pointer_mut(parent).and_then(Value::as_object_mut) {
                let key = key.replace("~1", "/").replace("~0", "~");
                if let Some(v) = map.remove(&key) {
                    map.insert(format!("{key}{control}"), v);
                }
            }
        }
        0 => match doc.pointer_mut(parent).unwrap() {
            Value::Object(map) => {
                map.remove(&key.replace("~1", "/").replace("~0", "~"));
            }
            Value::Array(items) => {
                items.remove(key.parse::<usize>().unwrap());
            }
            _ => {}
        },
        1 => {
            if let Some(x) = doc.pointer(&at).and_then(Value::as_f64) {
                let by = [1e3, -1.0, 1e-3, 0.5, 2.0, 1e300][rng.random_range(0..6)];
                *doc.pointer_mut(&at).unwrap() =
                    serde_json::Number::from_f64(x * by).map_or(Value::Null, Value::Number);
            }
        }
        _ => *doc.pointer_mut(&at).unwrap() = others[rng.random_range(0..others.len())].clone(),
    }
}

/// The mutated files of `path`, one per case, with their case numbers.
fn cases(path: &str, stream: u64) -> impl Iterator<Item = (usize, String)> {
    let original: Value = serde_json::from_str(&read(path)).unwrap();
    let seed = env_number("ELASTOKIN_FUZZ_SEED").unwrap_or(SEED);
    let count = env_number("ELASTOKIN_FUZZ_CASES").map_or(CASES, |n| n as usize);
    (0..count).map(move |case| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(stream);
        rng.set_word_pos(u128::from(case as u64) << 20);
        let mut doc = original.clone();
        for _ in 0..rng.random_range(1..=2) {
            mutate(&mut doc, &mut rng);
        }
        let text = doc.to_string();
        // One case in ten: the first key given twice (the last would silently win in a JSON reader).
        if rng.random_range(0..10) == 0 {
            if let Some((key, _)) = text.get(1..).and_then(|t| t.split_once(':')) {
                return (case, text.replacen(&format!("{key}:"), &format!("{key}:1,{key}:"), 1));
            }
        }
        (case, text)
    })
}

/// A message a user can read: not empty, no non-finite number shown (but for the user's own text, which a
/// message may quote: a word the file holds), no raw control character.
fn check_message(message: &str, case: usize, text: &str) {
    let non_finite = message
        .split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| matches!(w, "NaN" | "inf" | "Infinity" | "infinity") && !text.contains(w));
    let raw = message.chars().any(|c| c.is_control() && c != '\n');
    assert!(!message.trim().is_empty() && !non_finite && !raw, "case {case}: {message:?}\n{text}");
}

/// What `read` reads of case `case`'s `text`, or `None` when it refuses it (counted in `refused`) with a
/// message a user can read; it must not panic.
fn read_or_refused<T, E: std::fmt::Display>(
    case: usize,
    text: &str,
    refused: &mut usize,
    read: impl FnOnce() -> Result<T, E> + std::panic::UnwindSafe,
) -> Option<T> {
    match catch_unwind(read).unwrap_or_else(|_| panic!("case {case} panicked when read:\n{text}")) {
        Err(e) => {
            check_message(&e.to_string(), case, text);
            *refused += 1;
            None
        }
        Ok(t) => Some(t),
    }
}

#[test]
fn mutated_targets_files_are_refused_with_a_message_or_tuned_without_panic() {
    for (stream, (targets, model_path)) in [
        ("examples/targets/bump_steer.json", "examples/generic/macpherson.json"),
        ("examples/targets/macpherson.json", "examples/macpherson.json"),
        ("examples/targets/double_wishbone.json", "examples/double_wishbone.json"),
        ("examples/targets/pushrod_rocker.json", "examples/pushrod_rocker.json"),
    ]
    .into_iter()
    .enumerate()
    {
        let base = model(model_path);
        let (mut refused, mut evaluated, mut tuned) = (0, 0, 0);
        for (case, text) in cases(targets, stream as u64) {
            let read = || read_targets(&text, "targets.json", &base, |f| Err(format!("no file {f}")));
            let Some(t) = read_or_refused(case, &text, &mut refused, read) else { continue };
            let pointers: Vec<String> = t.free.iter().map(|f| f.pointer.clone()).collect();
            let p = Parameters::new(&base, &pointers).unwrap();
            let ran = catch_unwind(AssertUnwindSafe(|| {
                if case % 20 == 0 {
                    tuned += 1;
                    tune(&p, &t, |_| {}).map(|t| t.end.residuals)
                } else if case % 4 == 0 {
                    evaluated += 1;
                    evaluate(&p, &t, &p.values).map(|e| {
                        assert!(e.jacobian.iter().flatten().all(|v| v.is_finite()), "case {case}:\n{text}");
                        e.residuals
                    })
                } else {
                    Ok(Vec::new())
                }
            }));
            match ran.unwrap_or_else(|_| panic!("case {case} panicked when evaluated or tuned:\n{text}")) {
                Err(e) => check_message(&e.to_string(), case, &text),
                Ok(residuals) => assert!(residuals.iter().all(|r| r.is_finite()), "case {case}:\n{text}"),
            }
        }
        println!("{targets}: {refused} refused, {evaluated} evaluated, {tuned} tuned");
    }
}

#[test]
fn mutated_tolerance_files_are_refused_with_a_message_or_stacked_up_without_panic() {
    for (tolerances, model_file) in [
        ("examples/targets/tolerances.json", "examples/generic/macpherson.json"),
        ("examples/targets/tolerances_as_built.json", "examples/twist_beam_template.json"),
    ] {
        mutated_tolerance_file(tolerances, model_file);
    }
}

fn mutated_tolerance_file(tolerances: &str, model_file: &str) {
    let base = model(model_file);
    let (mut refused, mut stacked) = (0, 0);
    for (case, text) in cases(tolerances, 7) {
        let read = || read_tolerances(&text, "tolerances.json", &base);
        let Some(t) = read_or_refused(case, &text, &mut refused, read) else { continue };
        if case % 50 != 0 {
            continue;
        }
        stacked += 1;
        let ran = catch_unwind(AssertUnwindSafe(|| {
            stack_up(&base, &t).map(|mut s| {
                s.monte_carlo(20, 1);
                s.table()
            })
        }));
        match ran.unwrap_or_else(|_| panic!("case {case} panicked in the stack-up:\n{text}")) {
            Err(e) => check_message(&e.to_string(), case, &text),
            Ok(table) => {
                for row in &table.rows {
                    assert!(row.iter().all(|c| c.number().is_none_or(f64::is_finite)), "case {case}:\n{text}");
                }
            }
        }
    }
    println!("{tolerances}: {refused} refused, {stacked} stacked up");
}

/// Found by the campaign: a design file's key with a control character in it was echoed raw in the
/// message that refused it ("unknown key 'constraints␛'"), so the terminal read the escape.
#[test]
fn a_design_files_key_or_text_with_a_control_character_is_refused_with_it_shown_escaped() {
    let base = model("examples/macpherson.json");
    let targets = read("examples/targets/macpherson.json").replacen("\"targets\"", "\"targets\\u001b\"", 1);
    let tolerances = read("examples/targets/tolerances.json").replacen("5%", "5%\\u0007", 1);
    let messages = [
        read_targets(&targets, "targets.json", &base, |f| Err(format!("no file {f}"))).unwrap_err().to_string(),
        read_tolerances(&tolerances, "tolerances.json", &base).unwrap_err().to_string(),
    ];
    for (message, code) in messages.iter().zip(["U+001B", "U+0007"]) {
        assert!(!message.chars().any(char::is_control), "{message:?}");
        assert!(message.contains(code), "the character is named: {message}");
    }
}
