//! Tracking over commits: `--save NAME` stores every figure with the commit id, `--compare NAME` prints the
//! ratio now/then of every figure and flags the ones that got slower (or larger) than a threshold.

use super::report::{Figure, Kind};
use serde_json::{json, Map, Value};
use std::process::Command;

/// Where the measurement was taken.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// `git rev-parse HEAD`, or why there is none.
    pub commit: String,
    /// Whether the work tree had uncommitted changes.
    pub dirty: bool,
    /// Whether this was a `--quick` run.
    pub quick: bool,
    /// Seconds since the Unix epoch.
    pub unix_time: u64,
    /// Threads available to the process.
    pub threads: usize,
}

impl Provenance {
    /// Reads the commit and work-tree state from git.
    pub fn current(quick: bool) -> Provenance {
        let git = |args: &[&str]| {
            Command::new("git")
                .args(args)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        };
        Provenance {
            commit: git(&["rev-parse", "HEAD"]).unwrap_or_else(|| "unknown (git rev-parse HEAD failed)".into()),
            dirty: git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty()),
            quick,
            unix_time: std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()),
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        }
    }
}

/// Saved results as JSON: provenance and every figure.
pub fn to_json(p: &Provenance, figures: &[Figure]) -> Value {
    let mut map = Map::new();
    for f in figures {
        map.insert(f.key.clone(), json!({ "value": f.value, "unit": f.unit, "kind": f.kind.name() }));
    }
    json!({
        "commit": p.commit,
        "dirty": p.dirty,
        "quick": p.quick,
        "unix_time": p.unix_time,
        "threads": p.threads,
        "figures": Value::Object(map),
    })
}

/// Reads saved results back.
pub fn from_json(v: &Value) -> Result<(Provenance, Vec<Figure>), String> {
    let field = |k: &str| v.get(k).ok_or_else(|| format!("saved results lack '{k}'"));
    let p = Provenance {
        commit: field("commit")?.as_str().unwrap_or_default().to_string(),
        dirty: field("dirty")?.as_bool().unwrap_or(false),
        quick: field("quick")?.as_bool().unwrap_or(false),
        unix_time: v.get("unix_time").and_then(Value::as_u64).unwrap_or(0),
        threads: v.get("threads").and_then(Value::as_u64).unwrap_or(0) as usize,
    };
    let figures = field("figures")?
        .as_object()
        .ok_or("'figures' is not an object")?
        .iter()
        .map(|(key, f)| {
            let value = f.get("value").and_then(Value::as_f64).ok_or_else(|| format!("figure '{key}' has no value"))?;
            let kind = f.get("kind").and_then(Value::as_str).and_then(Kind::from_name).unwrap_or(Kind::Other);
            let unit = f.get("unit").and_then(Value::as_str).unwrap_or_default().to_string();
            Ok(Figure { key: key.clone(), value, unit, kind })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok((p, figures))
}

/// One figure now against then.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Key.
    pub key: String,
    /// Unit.
    pub unit: String,
    /// Value now (`None`: not measured now).
    pub now: Option<f64>,
    /// Value then (`None`: not in the saved results).
    pub then: Option<f64>,
    /// now / then when both exist and then ≠ 0.
    pub ratio: Option<f64>,
    /// "slower", "larger" when past the threshold the wrong way; empty otherwise.
    pub flag: &'static str,
}

/// Compares every figure now with the saved one. A time or memory figure is flagged when now/then exceeds
/// `threshold`, a rate when then/now does; errors and counts are shown without a flag.
pub fn compare(now: &[Figure], then: &[Figure], threshold: f64) -> Vec<Comparison> {
    let mut out = Vec::new();
    for f in now {
        let old = then.iter().find(|g| g.key == f.key);
        let ratio = old.and_then(|g| (g.value != 0.0).then(|| f.value / g.value)).filter(|r| r.is_finite());
        let flag = match (ratio, f.kind) {
            (Some(r), Kind::Time) if r > threshold => "slower",
            (Some(r), Kind::Rate) if r > 0.0 && 1.0 / r > threshold => "slower",
            (Some(r), Kind::Memory) if r > threshold => "larger",
            _ => "",
        };
        out.push(Comparison {
            key: f.key.clone(),
            unit: f.unit.clone(),
            now: Some(f.value),
            then: old.map(|g| g.value),
            ratio,
            flag,
        });
    }
    for g in then.iter().filter(|g| !now.iter().any(|f| f.key == g.key)) {
        out.push(Comparison {
            key: g.key.clone(),
            unit: g.unit.clone(),
            now: None,
            then: Some(g.value),
            ratio: None,
            flag: "",
        });
    }
    out
}

/// A saved-results name: letters, digits, `.`, `_`, `-` (it becomes a file name).
pub fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig(key: &str, value: f64, kind: Kind) -> Figure {
        Figure { key: key.into(), value, unit: "u".into(), kind }
    }

    #[test]
    fn slower_times_and_rates_are_flagged_past_the_threshold_only() {
        let then = [
            fig("a", 1.0, Kind::Time),
            fig("b", 1.0, Kind::Time),
            fig("c", 100.0, Kind::Rate),
            fig("d", 100.0, Kind::Rate),
            fig("e", 1e-15, Kind::Accuracy),
            fig("m", 10.0, Kind::Memory),
            fig("gone", 3.0, Kind::Time),
        ];
        let now = [
            fig("a", 1.3, Kind::Time),
            fig("b", 1.2, Kind::Time),
            fig("c", 70.0, Kind::Rate),
            fig("d", 90.0, Kind::Rate),
            fig("e", 1e-13, Kind::Accuracy),
            fig("m", 20.0, Kind::Memory),
            fig("new", 1.0, Kind::Time),
        ];
        let c = compare(&now, &then, 1.25);
        let flag = |k: &str| c.iter().find(|x| x.key == k).unwrap().flag;
        assert_eq!(flag("a"), "slower");
        assert_eq!(flag("b"), "");
        assert_eq!(flag("c"), "slower", "a rate that fell to 0.7 of before is 1.43× slower");
        assert_eq!(flag("d"), "");
        assert_eq!(flag("e"), "", "errors are shown, not flagged");
        assert_eq!(flag("m"), "larger");
        let a = c.iter().find(|x| x.key == "a").unwrap();
        assert!((a.ratio.unwrap() - 1.3).abs() < 1e-12);
        let new = c.iter().find(|x| x.key == "new").unwrap();
        assert_eq!((new.then, new.ratio), (None, None));
        let gone = c.iter().find(|x| x.key == "gone").unwrap();
        assert_eq!((gone.now, gone.then), (None, Some(3.0)));
    }

    #[test]
    fn saved_results_round_trip() {
        let p = Provenance { commit: "abc".into(), dirty: true, quick: true, unix_time: 7, threads: 2 };
        let figures = vec![fig("x.y", 2.5e-6, Kind::Time), fig("z", 4.0, Kind::Other)];
        let (q, back) = from_json(&to_json(&p, &figures)).unwrap();
        assert_eq!(q, p);
        assert_eq!(back.len(), 2);
        assert!(back.contains(&figures[0]) && back.contains(&figures[1]));
    }

    #[test]
    fn names_cannot_leave_the_results_directory() {
        assert!(valid_name("baseline-2024.1"));
        assert!(!valid_name("../x") && !valid_name("a/b") && !valid_name("") && !valid_name(".hidden"));
    }
}
