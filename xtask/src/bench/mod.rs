//! `cargo xtask bench`: the benchmark instrument.
//!
//! ```text
//! cargo xtask bench [--quick] [--out DIR] [--save NAME] [--compare NAME] [--threshold X] [--only SECTIONS]
//! ```
//!
//! Sections (each a module named for what it measures): error against run time on the shipped models,
//! the cost of one step against a bare factorization + solve, scaling with the number of bodies, stiff and
//! extreme cases, batch throughput, the cost of sensitivities, a move in `elastokin live`, and (when Python with Exudyn is installed) the same sweep in Exudyn,
//! side by side. Output in `bench/results/` (or `--out`): `latest.md`, one CSV per
//! table, SVG plots; `--save NAME` writes `NAME.json` with the commit id and every figure, `--compare NAME`
//! prints now/then per figure and flags what got slower than `--threshold` (default 1.25).
//!
//! Timings are medians of repeated runs on whatever machine this is; ratios measured in one run are the
//! figures to read when the machine is shared.

pub mod alloc;
mod batch;
mod big_models;
mod elastic_members;
mod error_vs_time;
mod exudyn;
mod live;
mod models;
pub mod report;
mod report_page;
mod scaling;
mod sensitivity;
mod settings;
pub mod stats;
mod step_cost;
mod stiff_cases;
pub mod track;
mod tuning;

use report::{significant, SectionOutput, Table, Target};
pub use settings::Settings;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// A section: its name for `--only` and what runs it.
type Section = (&'static str, fn(&Settings) -> SectionOutput);

/// The sections, in the order they run and appear.
const SECTIONS: [Section; 12] = [
    ("error-vs-time", error_vs_time::run),
    ("step-cost", step_cost::run),
    ("scaling", scaling::run),
    ("big-models", big_models::run),
    ("stiff-cases", stiff_cases::run),
    ("batch", batch::run),
    ("sensitivity", sensitivity::run),
    ("tuning", tuning::run),
    ("report-page", report_page::run),
    ("live", live::run),
    ("elastic-members", elastic_members::run),
    ("exudyn", exudyn::run),
];

const USAGE: &str = "\
usage: cargo xtask bench [--quick] [--out DIR] [--save NAME] [--compare NAME] [--threshold X] [--only SECTIONS]
    --quick          fewer repetitions and sizes (N up to 1000): about a minute
    --out DIR        where results go (default bench/results)
    --save NAME      also write DIR/NAME.json: the commit id and every figure
    --compare NAME   print now/then for every figure of DIR/NAME.json, flag the slower ones
    --threshold X    flag figures slower than X times then (default 1.25)
    --only LIST      comma-separated sections: error-vs-time, step-cost, scaling, big-models, stiff-cases, batch,
                     sensitivity, tuning, report-page, live, elastic-members, exudyn
                     (exudyn needs Python with Exudyn, `pip install exudyn`; without it, it is skipped)";

/// Parsed command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// `--quick`.
    pub quick: bool,
    /// `--out DIR`, when given.
    pub out: Option<PathBuf>,
    /// `--save NAME`.
    pub save: Option<String>,
    /// `--compare NAME`.
    pub compare: Option<String>,
    /// Flag threshold of `--compare`.
    pub threshold: f64,
    /// Sections to run (all when `None`).
    pub only: Option<Vec<String>>,
}

impl Options {
    /// Where the report, tables and plots go: `--out`, else `bench/results` (the committed full-run
    /// results) or, for `--quick`, `bench/results/quick` (ignored by git, so a check before a commit leaves
    /// the committed results alone).
    pub fn report_dir(&self) -> PathBuf {
        let results = models::root().join("bench").join("results");
        match &self.out {
            Some(dir) => dir.clone(),
            None if self.quick => results.join("quick"),
            None => results,
        }
    }

    /// Where `--save` writes and `--compare` reads `NAME.json`: `--out`, else `bench/results`, whether the
    /// run is quick or not.
    pub fn saved_dir(&self) -> PathBuf {
        self.out.clone().unwrap_or_else(|| models::root().join("bench").join("results"))
    }
}

/// Parses the arguments after `bench`.
pub fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options { quick: false, out: None, save: None, compare: None, threshold: 1.25, only: None };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || it.next().cloned().ok_or_else(|| format!("{flag} needs a value"));
        match flag.as_str() {
            "--quick" => o.quick = true,
            "--out" => o.out = Some(PathBuf::from(value()?)),
            "--save" | "--compare" => {
                let v = value()?;
                if !track::valid_name(&v) {
                    return Err(format!("{flag} '{v}': use letters, digits, '.', '_' and '-' only"));
                }
                if flag == "--save" {
                    o.save = Some(v);
                } else {
                    o.compare = Some(v);
                }
            }
            "--threshold" => {
                let v = value()?;
                o.threshold = v
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && *x >= 1.0)
                    .ok_or_else(|| format!("--threshold '{v}': a number ≥ 1 (e.g. 1.25)"))?;
            }
            "--only" => {
                let v = value()?;
                let names: Vec<String> = v.split(',').map(|s| s.trim().to_string()).filter(|s| !s.is_empty()).collect();
                if let Some(bad) = names.iter().find(|n| !SECTIONS.iter().any(|(s, _)| s == n)) {
                    return Err(format!("--only: no section '{bad}'"));
                }
                o.only = Some(names);
            }
            "-h" | "--help" => return Err(USAGE.into()),
            other => return Err(format!("unknown option '{other}'\n{USAGE}")),
        }
    }
    Ok(o)
}

/// `cargo xtask bench …`.
pub fn main(args: &[String]) -> ExitCode {
    let options = match parse(args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    // Read the saved results first: a bad name should not cost a whole run.
    let then = match &options.compare {
        Some(name) => {
            let path = options.saved_dir().join(format!("{name}.json"));
            match std::fs::read_to_string(&path)
                .map_err(|e| format!("{}: {e}", path.display()))
                .and_then(|t| serde_json::from_str(&t).map_err(|e| format!("{}: {e}", path.display())))
                .and_then(|v| track::from_json(&v).map_err(|e| format!("{}: {e}", path.display())))
            {
                Ok(x) => Some((name.clone(), x)),
                Err(e) => {
                    eprintln!("--compare: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        None => None,
    };
    let out = options.report_dir();
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("{}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    let settings = Settings { quick: options.quick };
    let provenance = track::Provenance::current(options.quick);
    let start = Instant::now();
    let mut sections = Vec::new();
    for (name, run) in SECTIONS {
        if options.only.as_ref().is_some_and(|only| !only.iter().any(|n| n == name)) {
            continue;
        }
        let t = Instant::now();
        eprint!("bench: {name} … ");
        let out = run(&settings);
        eprintln!("{:.1} s", t.elapsed().as_secs_f64());
        sections.push((name, out, t.elapsed().as_secs_f64()));
    }
    let total = start.elapsed().as_secs_f64();

    let figures: Vec<report::Figure> = sections.iter().flat_map(|(_, s, _)| s.figures.iter().cloned()).collect();
    let targets: Vec<Target> = sections.iter().flat_map(|(_, s, _)| s.targets.iter().cloned()).collect();
    let targets_table = Target::table(&targets);
    let comparison = then.as_ref().map(|(name, (p, old))| {
        let rows = track::compare(&figures, old, options.threshold);
        (name.clone(), p.clone(), rows)
    });

    let mut written = Vec::new();
    let mut write = |path: PathBuf, text: &str| -> Result<(), String> {
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        written.push(path);
        Ok(())
    };
    let mut result = Ok(());
    result = result.and_then(|_| write(out.join(&targets_table.csv), &targets_table.csv_text()));
    for (_, s, _) in &sections {
        for t in &s.tables {
            result = result.and_then(|_| write(out.join(&t.csv), &t.csv_text()));
        }
        for (file, svg, _) in &s.plots {
            result = result.and_then(|_| write(out.join(file), svg));
        }
    }
    let compare_table = comparison.as_ref().map(|(name, p, rows)| compare_table(name, p, rows, options.threshold));
    if let Some(t) = &compare_table {
        result = result.and_then(|_| write(out.join(&t.csv), &t.csv_text()));
    }
    let kind = run_kind(&options);
    let md = markdown(&provenance, &kind, &targets_table, &sections, compare_table.as_ref(), total);
    result = result.and_then(|_| write(out.join("latest.md"), &md));
    if let Some(name) = &options.save {
        let json = track::to_json(&provenance, &figures);
        let text = serde_json::to_string_pretty(&json).unwrap_or_default() + "\n";
        let dir = options.saved_dir();
        result = result
            .and_then(|_| std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display())))
            .and_then(|_| write(dir.join(format!("{name}.json")), &text));
    }

    println!(
        "## Targets ({kind}, commit {}{})\n",
        short(&provenance.commit),
        if provenance.dirty { ", uncommitted changes" } else { "" }
    );
    println!("{}", targets_table.markdown());
    if let (Some(t), Some((_, _, rows))) = (&compare_table, &comparison) {
        let times: Vec<f64> = rows.iter().filter(|r| r.unit == "s").filter_map(|r| r.ratio).collect();
        let mut flagged = t.clone();
        flagged.rows.retain(|r| matches!(r.last(), Some(report::Cell::Text(f)) if !f.is_empty()));
        println!(
            "## {}\n\n{} figures compared; median now/then of the {} times: {}. Every figure: {} and `{}`.\n",
            t.title,
            rows.iter().filter(|r| r.ratio.is_some()).count(),
            times.len(),
            stats::median(&times).map_or("none".into(), |m| format!("{m:.3}")),
            out.join("latest.md").display(),
            t.csv
        );
        if let Some((_, (then, _))) = &then {
            if then.quick != options.quick {
                println!(
                    "(The saved run was {}: the figures both runs have are compared, but their repetitions differ.)\n",
                    if then.quick { "a --quick run" } else { "a full run" }
                );
            }
        }
        if !flagged.rows.is_empty() {
            println!("{}", flagged.markdown());
        }
    }
    let failed: usize = sections
        .iter()
        .flat_map(|(_, s, _)| s.tables.iter())
        .flat_map(|t| t.rows.iter())
        .filter(|r| r.iter().any(|c| matches!(c, report::Cell::Text(x) if x.starts_with("failed"))))
        .count();
    if failed > 0 {
        println!("{failed} row(s) marked failed: see {}", out.join("latest.md").display());
    }
    println!("{:.1} s; results in {}", total, out.display());
    match result {
        Ok(()) => {
            for p in &written {
                eprintln!("wrote {}", p.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}

fn short(commit: &str) -> &str {
    commit.get(..12).unwrap_or(commit)
}

fn compare_table(name: &str, then: &track::Provenance, rows: &[track::Comparison], threshold: f64) -> Table {
    let flagged = rows.iter().filter(|r| !r.flag.is_empty()).count();
    let mut t = Table::new(
        &format!(
            "Compared with '{name}' (commit {}{}): {flagged} figure(s) flagged past {threshold}×",
            short(&then.commit),
            if then.quick { ", --quick" } else { "" }
        ),
        &format!("compare_{name}.csv"),
        &["figure", "unit", "now", "then", "now / then", "flag"],
    );
    for r in rows {
        t.row(vec![
            report::Cell::text(&r.key),
            report::Cell::text(&r.unit),
            report::Cell::opt(r.now),
            report::Cell::opt(r.then),
            r.ratio.map_or(report::Cell::Empty, |x| report::Cell::Num(x, 3)),
            report::Cell::text(r.flag),
        ]);
    }
    t
}

/// "full run", "`--quick` run", or either "of" the sections asked with `--only`.
fn run_kind(o: &Options) -> String {
    let kind = if o.quick { "`--quick` run" } else { "full run" };
    match &o.only {
        Some(only) => format!("{kind} of {} only", only.join(", ")),
        None => kind.to_string(),
    }
}

fn markdown(
    p: &track::Provenance,
    kind: &str,
    targets: &Table,
    sections: &[(&str, SectionOutput, f64)],
    compare: Option<&Table>,
    total: f64,
) -> String {
    let mut md = String::from("# elastokin benchmark\n\n");
    let _ = writeln!(
        md,
        "Commit `{}`{}, {kind}, {} thread(s) available, {} s in all. Times are medians of repeated runs on a \
         machine that may be shared: read ratios measured in the same run rather than absolute times.\n",
        p.commit,
        if p.dirty { " with uncommitted changes" } else { "" },
        p.threads,
        significant(total, 3)
    );
    let _ = writeln!(md, "## Targets\n\n{}", targets.markdown());
    if let Some(c) = compare {
        let _ = writeln!(md, "## {}\n\n{}", c.title, c.markdown());
    }
    for (name, s, seconds) in sections {
        let _ = writeln!(md, "## {}\n\n{}\n\n(`--only {name}`, {} s)\n", s.title, s.intro, significant(*seconds, 2));
        for (file, _, caption) in &s.plots {
            let _ = writeln!(md, "![{caption}]({file})\n");
        }
        for t in &s.tables {
            let _ = writeln!(md, "### {} (`{}`)\n\n{}", t.title, t.csv, t.markdown());
        }
        for n in &s.notes {
            let _ = writeln!(md, "- {n}");
        }
        if !s.notes.is_empty() {
            md.push('\n');
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    #[test]
    fn quick_reports_stay_out_of_the_committed_results_but_saved_names_do_not() {
        let quick = parse(&args("--quick")).unwrap();
        assert!(quick.report_dir().ends_with("bench/results/quick"));
        assert!(quick.saved_dir().ends_with("bench/results"));
        let full = parse(&args("")).unwrap();
        assert_eq!(full.report_dir(), full.saved_dir());
        let elsewhere = parse(&args("--quick --out /tmp/x")).unwrap();
        assert_eq!((elsewhere.report_dir(), elsewhere.saved_dir()), (PathBuf::from("/tmp/x"), PathBuf::from("/tmp/x")));
    }

    #[test]
    fn partial_runs_say_so() {
        assert_eq!(run_kind(&parse(&args("--quick")).unwrap()), "`--quick` run");
        assert_eq!(run_kind(&parse(&args("--only scaling,batch")).unwrap()), "full run of scaling, batch only");
    }

    #[test]
    fn options_parse_and_refuse_nonsense() {
        let o = parse(&args("--quick --save base --threshold 1.5 --only scaling,step-cost")).unwrap();
        assert!(o.quick);
        assert_eq!(o.save.as_deref(), Some("base"));
        assert_eq!(o.threshold, 1.5);
        assert_eq!(o.only, Some(vec!["scaling".to_string(), "step-cost".to_string()]));
        assert!(parse(&args("--threshold 0.5")).is_err());
        assert!(parse(&args("--save ../x")).is_err());
        assert!(parse(&args("--only nothing")).is_err());
        assert!(parse(&args("--frobnicate")).is_err());
        assert!(parse(&args("--out")).is_err());
    }
}
