//! What the `elastokin` command writes, and how: provenance for every result, CSV through the csv crate
//! with numbers an engineer can read, an output directory that is replaced whole or not at all, standard
//! output that a closed pipe cannot crash, and progress on standard error.

pub use elastokin::provenance::{sha256_hex, Part, Provenance};
use elastokin::suspensions::file::key_path::printable;
use elastokin::suspensions::kc::{Cell, Failed, Table};
use indicatif::{ProgressBar, ProgressStyle};
use std::cell::Cell as Flag;
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Why the command stops short of success; each kind has its own exit status.
#[derive(Debug)]
pub enum Failure {
    /// Bad input: arguments, a model or variants file, an `--out` that cannot be used. Exit status 2, the
    /// same as the argument parser's usage errors.
    Input(String),
    /// The input was fine but the run failed: an analysis did not solve, a file could not be written.
    /// Exit status 1.
    Run(String),
}

impl Failure {
    /// The process exit status for this failure.
    pub fn exit_status(&self) -> u8 {
        match self {
            Failure::Input(_) => 2,
            Failure::Run(_) => 1,
        }
    }

    /// The message for standard error.
    pub fn message(&self) -> &str {
        match self {
            Failure::Input(m) | Failure::Run(m) => m,
        }
    }
}

/// The failed analyses, a line each: `name: reason`.
pub fn failed_lines(failed: &[Failed]) -> String {
    failed.iter().map(|f| format!("{}: {}", f.analysis.name(), f.reason)).collect::<Vec<_>>().join("\n")
}

/// The line that names the files a command wrote: `wrote A, B`.
pub fn wrote(paths: &[PathBuf]) -> String {
    format!("wrote {}", paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "))
}

/// A number as a CSV cell: at most 12 significant digits, no trailing zeros, plain decimal notation for
/// magnitudes from 1e-5 up to 1e15 and exponent notation beyond; a non-finite value is an empty cell.
///
/// Twelve digits is far beyond what a suspension measurement resolves, and drops the last bits of
/// floating-point noise: 0.1 + 0.2 is written `0.3`, not `0.30000000000000004`.
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    // Round to 12 significant digits, then print the shortest text that reads back as the rounded value.
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    if rounded == 0.0 {
        "0".into()
    } else if (1e-5..1e15).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

/// The CSV bytes of `table`: the provenance comment line, the header row, one row per table row. Text is
/// quoted only where CSV needs it; a missing or non-finite number is an empty cell.
pub fn write_table(table: &Table, provenance: &Provenance) -> Vec<u8> {
    write_table_after(&provenance.comment_line(), table)
}

/// The CSV bytes of `table` after the comment line `first` (without its line end): `merge` writes the
/// shards' line, not one of its own making, and the rows as [`write_table`] does.
pub fn write_table_after(first: &str, table: &Table) -> Vec<u8> {
    let mut bytes = first.as_bytes().to_vec();
    bytes.push(b'\n');
    // Rows may differ in length only by a mistake in an analysis; writing them as they are beats losing
    // the file.
    let mut writer = csv::WriterBuilder::new().flexible(true).from_writer(bytes);
    let rows = table.rows.iter().map(|row| {
        row.iter()
            .map(|cell| match cell {
                Cell::Number(v) => number(*v),
                Cell::Text(t) => t.clone(),
                Cell::Empty => String::new(),
            })
            .collect::<Vec<_>>()
    });
    // Writing into memory cannot fail: the only errors are I/O errors and unequal row lengths (allowed
    // above).
    for record in std::iter::once(table.columns.clone()).chain(rows) {
        writer.write_record(&record).expect("writing CSV into memory cannot fail");
    }
    writer.into_inner().expect("flushing CSV into memory cannot fail")
}

/// Standard output that a closed pipe cannot crash: `elastokin run MODEL | head -1` must not end in a
/// panic. Once the reader has gone, further lines are dropped and the command carries on with its real
/// work (writing its files), so its exit status still tells whether that work succeeded.
#[derive(Debug)]
pub struct Stdout {
    quiet: bool,
    closed: Flag<bool>,
}

impl Stdout {
    /// `quiet`: print nothing at all (the exit status and the files tell).
    pub fn new(quiet: bool) -> Stdout {
        Stdout { quiet, closed: Flag::new(false) }
    }

    /// Prints one line.
    pub fn line(&self, text: impl std::fmt::Display) -> Result<(), Failure> {
        if self.quiet || self.closed.get() {
            return Ok(());
        }
        let mut out = std::io::stdout().lock();
        match writeln!(out, "{}", printable(&text.to_string())).and_then(|()| out.flush()) {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed.set(true);
                Ok(())
            }
            Err(e) => Err(Failure::Run(format!("standard output: {e}"))),
        }
    }
}

/// Prints a line on standard error; a closed standard error is no reason to stop the work.
pub fn note(text: impl std::fmt::Display) {
    let _ = writeln!(std::io::stderr().lock(), "{}", printable(&text.to_string()));
}

/// The staging directories of this process not yet committed or dropped: what an interrupt removes
/// ([`on_interrupt_remove_staging`]).
static STAGED: std::sync::Mutex<Vec<(PathBuf, PathBuf, PathBuf)>> = std::sync::Mutex::new(Vec::new());

/// On Ctrl-C, SIGTERM or SIGHUP: every staging directory of this process removed (the previous results put
/// back where an interrupt came between moving them aside and renaming the new ones in), a line on standard
/// error, and exit status 130. An interrupted command leaves `--out` as it found it, and nothing beside it.
pub fn on_interrupt_remove_staging() {
    let handler = || {
        // A command that stops by itself (a server) is told to, and says what it leaves.
        if let Some(stop) = STOP.lock().ok().as_deref().and_then(Option::as_ref) {
            stop();
            return;
        }
        let staged = STAGED.lock().map(|s| s.clone()).unwrap_or_default();
        for (tmp, old, out) in &staged {
            if old.exists() && !out.exists() {
                let _ = std::fs::rename(old, out);
            }
            let _ = std::fs::remove_dir_all(tmp);
        }
        note("interrupted: nothing written");
        std::process::exit(130);
    };
    if let Err(e) = ctrlc::set_handler(handler) {
        note(format!("warning: an interrupt may leave a staging directory beside --out: {e}"));
    }
}

/// What an interrupt does instead of exiting, when a command set it ([`on_interrupt_stop`]).
type Stop = Box<dyn Fn() + Send>;
static STOP: std::sync::Mutex<Option<Stop>> = std::sync::Mutex::new(None);

/// On Ctrl-C, SIGTERM or SIGHUP from now on: `stop` called, for a command that then ends by itself (a
/// server finishing the request it is serving), instead of the exit of [`on_interrupt_remove_staging`].
pub fn on_interrupt_stop(stop: impl Fn() + Send + 'static) {
    if let Ok(mut slot) = STOP.lock() {
        *slot = Some(Box::new(stop));
    }
}

/// Keeps (`true`) or forgets a staging directory for [`on_interrupt_remove_staging`].
fn staged(tmp: &Path, old: &Path, out: &Path, keep: bool) {
    if let Ok(mut s) = STAGED.lock() {
        s.retain(|(t, ..)| t != tmp);
        if keep {
            s.push((tmp.to_path_buf(), old.to_path_buf(), out.to_path_buf()));
        }
    }
}

/// An output directory written whole or not at all.
///
/// The files go into a new directory beside `--out` (`.NAME.tmp-PID` in the same parent, so renaming is
/// atomic on one file system). [`Staging::commit`] then moves the previous `--out` aside, renames the new
/// one in and removes the old one: a reader sees the old results or the new ones, never a mix, except in
/// the instant between the two renames when `--out` does not exist. Dropped without a commit (a failed
/// run), the new directory is removed and the previous results are untouched.
#[derive(Debug)]
pub struct Staging {
    out: PathBuf,
    tmp: PathBuf,
    old: PathBuf,
    had_previous: bool,
    committed: bool,
}

impl Staging {
    /// Checks that `out` can be replaced and makes the temporary directory beside it.
    pub fn new(out: &Path) -> Result<Staging, Failure> {
        let shown = out.display();
        let name = out.file_name().ok_or_else(|| {
            Failure::Input(format!(
                "--out DIR: '{shown}' cannot be replaced as a whole; give a directory of its own, e.g. --out out"
            ))
        })?;
        let had_previous = match std::fs::symlink_metadata(out) {
            Ok(m) if m.is_dir() => {
                check_replaceable(out)?;
                true
            }
            Ok(m) if m.is_file() => {
                return Err(Failure::Input(format!("--out DIR: '{shown}' is a file; give a directory")))
            }
            Ok(_) => {
                return Err(Failure::Input(format!(
                    "--out DIR: '{shown}' is a link or special file; give a directory itself"
                )))
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
            Err(e) => return Err(Failure::Input(format!("--out DIR: '{shown}': {e}"))),
        };
        let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent)
            .map_err(|e| Failure::Input(format!("--out DIR: cannot make '{}': {e}", parent.display())))?;
        let (name, pid) = (name.to_string_lossy(), std::process::id());
        remove_stale_staging(parent, &name);
        let tmp = parent.join(format!(".{name}.tmp-{pid}"));
        let old = parent.join(format!(".{name}.old-{pid}"));
        std::fs::create_dir(&tmp)
            .map_err(|e| Failure::Input(format!("--out DIR: cannot make '{}': {e}", tmp.display())))?;
        staged(&tmp, &old, out, true);
        Ok(Staging { out: out.to_path_buf(), tmp, old, had_previous, committed: false })
    }

    /// Writes one file; returns the path it will have once committed.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, Failure> {
        let path = self.tmp.join(name);
        std::fs::write(&path, bytes).map_err(|e| Failure::Run(format!("{}: {e}", path.display())))?;
        Ok(self.out.join(name))
    }

    /// What a failure leaves behind, for its message.
    pub fn untouched(&self) -> String {
        if self.had_previous {
            format!("previous results in {} left untouched", self.out.display())
        } else {
            format!("nothing written to {}", self.out.display())
        }
    }

    /// A failure while the files were made, said with what it leaves behind: a run's failure (exit 1).
    pub fn failed(&self, failure: Failure) -> Failure {
        Failure::Run(format!("{}\n{}", failure.message(), self.untouched()))
    }

    /// Replaces `--out` by the new directory. Where another run made or replaced `--out` meanwhile, its
    /// results stay and this run's go, said.
    pub fn commit(mut self) -> Result<(), Failure> {
        let out = self.out.display().to_string();
        let fail = |what: String, e: std::io::Error| match e.kind() {
            std::io::ErrorKind::DirectoryNotEmpty
            | std::io::ErrorKind::AlreadyExists
            | std::io::ErrorKind::NotFound => Failure::Run(format!(
                "another run wrote {out} while this one ran: its results are kept and this run's are not; \
                     run again, or give each run its own --out"
            )),
            _ => Failure::Run(format!("{what}: {e}")),
        };
        let rename_in = || format!("renaming {} to {}", self.tmp.display(), self.out.display());
        if self.had_previous {
            std::fs::rename(&self.out, &self.old)
                .map_err(|e| fail(format!("moving {} aside", self.out.display()), e))?;
            if let Err(e) = std::fs::rename(&self.tmp, &self.out) {
                // Put the previous results back, unless another run's stand there now; the new ones go with
                // the drop.
                if std::fs::rename(&self.old, &self.out).is_err() {
                    let _ = std::fs::remove_dir_all(&self.old);
                }
                return Err(fail(rename_in(), e));
            }
            self.committed = true;
            if let Err(e) = std::fs::remove_dir_all(&self.old) {
                note(format!("warning: could not remove the previous results, moved to {}: {e}", self.old.display()));
            }
        } else {
            std::fs::rename(&self.tmp, &self.out).map_err(|e| fail(rename_in(), e))?;
            self.committed = true;
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
        staged(&self.tmp, &self.old, &self.out, false);
    }
}

/// Removes what an interrupted run of the same `--out` left beside it (Ctrl-C, SIGTERM or a kill between
/// making its staging directory and renaming it in): `.NAME.tmp-PID` and `.NAME.old-PID` of a process that
/// is gone, holding nothing but what the command writes. A directory of a process still running (another
/// run), one holding anything else (somebody's), or any directory where it cannot be told whether its
/// process is gone (a system without `/proc`) is left alone.
fn remove_stale_staging(parent: &Path, name: &str) {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(parent) else { return };
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        let pid = [".tmp-", ".old-"]
            .iter()
            .find_map(|kind| file_name.strip_prefix(&format!(".{name}{kind}")))
            .filter(|pid| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()));
        let Some(pid) = pid else { continue };
        let ours = || {
            std::fs::read_dir(entry.path()).is_ok_and(|files| {
                files.flatten().all(|f| {
                    let is_file = f.file_type().is_ok_and(|t| t.is_file());
                    matches!(classify(&f.path(), is_file), Ok(Found::Stamped | Found::Plot))
                })
            })
        };
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        if is_dir && !proc.join(pid).exists() && ours() {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// An existing `--out` is replaced whole, so it must be earlier results, recognisably written by the
/// command, and nothing else: somebody's directory, or one with a model file or measurements put beside the
/// results, must not be deleted by a run.
fn check_replaceable(out: &Path) -> Result<(), Failure> {
    let shown = out.display();
    let refuse = |why: String| {
        Failure::Input(format!(
            "--out DIR: '{shown}' {why}; the directory is replaced as a whole, so give a new directory or one \
             holding only earlier elastokin results"
        ))
    };
    let io = |e: std::io::Error| Failure::Input(format!("--out DIR: '{shown}': {e}"));
    let (mut stamped, mut earlier, mut unstamped, mut empty) = (false, false, None, true);
    for entry in std::fs::read_dir(out).map_err(io)? {
        let entry = entry.map_err(io)?;
        empty = false;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        match classify(&entry.path(), is_file).map_err(io)? {
            Found::Stamped => stamped = true,
            Found::EarlierVersion => earlier = true,
            Found::UnstampedCsv => unstamped = Some(name),
            Found::Plot => {}
            Found::Foreign => return Err(refuse(format!("holds '{name}', which elastokin does not write"))),
        }
    }
    match unstamped {
        // Earlier versions wrote CSVs without the provenance line; beside their summary they are results.
        Some(name) if !earlier => Err(refuse(format!("holds '{name}', which elastokin did not write"))),
        _ if empty || stamped || earlier => Ok(()),
        _ => {
            Err(refuse("does not hold elastokin results (no summary.json, no CSV with the '# elastokin' line)".into()))
        }
    }
}

/// File name endings of what the command writes besides CSV and `summary.json`: plots and reports.
pub const PLOT_EXTENSIONS: [&str; 3] = ["svg", "png", "html"];

/// What a file in an existing `--out` is.
enum Found {
    /// A CSV with the provenance line, or `summary.json` with its provenance.
    Stamped,
    /// `summary.json` or `batch.csv` of a version before provenance.
    EarlierVersion,
    /// A CSV without the provenance line.
    UnstampedCsv,
    /// A plot, report or tuned model file (`tune`'s `tuned.json`): written beside stamped CSVs.
    Plot,
    /// Anything else.
    Foreign,
}

fn classify(path: &Path, is_file: bool) -> std::io::Result<Found> {
    const OLD_BATCH: &[u8] = b"variant,bump_steer_deg_per_m,";
    let head = |n: u64| -> std::io::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        std::fs::File::open(path)?.take(n).read_to_end(&mut bytes)?;
        Ok(bytes)
    };
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or_default();
    Ok(match extension {
        _ if !is_file => Found::Foreign,
        "json" if name == "tuned.json" => Found::Plot,
        "json" if name == "summary.json" => match serde_json::from_slice::<serde_json::Value>(&head(16 << 20)?) {
            Ok(v) if v.get("provenance").is_some() => Found::Stamped,
            Ok(v) if v.get("analyses").is_some_and(serde_json::Value::is_object) => Found::EarlierVersion,
            _ => Found::Foreign,
        },
        "csv" => {
            let h = head(OLD_BATCH.len() as u64)?;
            if h.starts_with(b"# elastokin ") {
                Found::Stamped
            } else if name == "batch.csv" && h == OLD_BATCH {
                Found::EarlierVersion
            } else {
                Found::UnstampedCsv
            }
        }
        e if PLOT_EXTENSIONS.contains(&e) => Found::Plot,
        _ => Found::Foreign,
    })
}

/// Progress on standard error: a bar when standard error is a terminal, otherwise one plain line per
/// item (for logs), nothing when quiet.
#[derive(Debug)]
pub struct Progress {
    what: &'static str,
    total: u64,
    done: AtomicU64,
    bar: Option<ProgressBar>,
    quiet: bool,
}

impl Progress {
    /// Progress over `total` items of `what` (`"analyses"`, `"variants"`).
    pub fn new(what: &'static str, total: usize, quiet: bool) -> Progress {
        let total = total as u64;
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let style = ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg} ({elapsed})")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> ");
            ProgressBar::new(total).with_style(style).with_prefix(what)
        });
        Progress { what, total, done: AtomicU64::new(0), bar, quiet }
    }

    /// An item starts (sequential work such as `run`'s analyses).
    pub fn begin(&self, item: &str) {
        let n = self.done.load(Ordering::Relaxed) + 1;
        match &self.bar {
            Some(bar) => bar.set_message(item.to_string()),
            None if !self.quiet => note(format!("{} {n}/{}: {item}", self.what, self.total)),
            None => {}
        }
    }

    /// An item is done; `item` names it in the plain lines of work that runs in parallel.
    pub fn end(&self, item: Option<&str>) {
        let n = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        match (&self.bar, item) {
            (Some(bar), _) => bar.inc(1),
            (None, Some(item)) if !self.quiet => note(format!("{} {n}/{} done: {item}", self.what, self.total)),
            (None, _) => {}
        }
    }

    /// Runs `f` (which prints to the terminal) with the bar hidden, so the two do not garble each other.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.bar {
            Some(bar) => bar.suspend(f),
            None => f(),
        }
    }

    /// Clears the bar.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two runs into one `--out` that did not exist: the loser said "renaming ./.c10.tmp-2538 to c10:
    /// Directory not empty" and lost its results. It says another run wrote there and keeps that run's
    /// results. Where `--out` held earlier results, the later commit's stand. Either way nothing is left
    /// beside `--out`.
    #[test]
    fn a_run_whose_out_another_run_wrote_meanwhile_says_so_and_leaves_nothing_beside_it() {
        let dir = std::env::temp_dir().join(format!("elastokin-race-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("out");
        for had_previous in [false, true] {
            let _ = std::fs::remove_dir_all(&out);
            if had_previous {
                std::fs::create_dir(&out).unwrap();
            }
            let staging = Staging::new(&out).unwrap();
            staging.write("mine.csv", b"mine").unwrap();
            // The other run commits first.
            let _ = std::fs::remove_dir_all(&out);
            std::fs::create_dir(&out).unwrap();
            std::fs::write(out.join("theirs.csv"), "theirs").unwrap();
            match staging.commit() {
                Err(e) if !had_previous => {
                    let e = e.message().to_string();
                    assert!(e.starts_with(&format!("another run wrote {} while this one ran", out.display())), "{e}");
                    assert_eq!(std::fs::read_to_string(out.join("theirs.csv")).unwrap(), "theirs");
                }
                Ok(()) if had_previous => assert_eq!(std::fs::read_to_string(out.join("mine.csv")).unwrap(), "mine"),
                other => panic!("had previous: {had_previous}: {other:?}"),
            }
            let beside: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
            assert_eq!(beside, vec![std::ffi::OsString::from("out")], "had previous: {had_previous}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn numbers_have_twelve_significant_digits_and_no_noise() {
        assert_eq!(number(0.1 + 0.2), "0.3");
        assert_eq!(number(1.0 / 3.0), "0.333333333333");
        assert_eq!(number(-2.0 / 3.0), "-0.666666666667");
        assert_eq!(number(123456.789), "123456.789");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(32.0), "32");
        assert_eq!(number(1.0e-17 / 3.0), "3.33333333333e-18");
        assert_eq!(number(6.02214076e23), "6.02214076e23");
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(number(v), "");
        }
        // Whatever comes out reads back within twelve digits.
        for v in [1.0 / 7.0, 9.999_999_999_999e14, 1.0e-5, 0.999_999_999_999_9, -1234.5678e-9] {
            let back: f64 = number(v).parse().unwrap();
            assert!((back - v).abs() <= 5e-12 * v.abs(), "{v} → {}", number(v));
        }
    }

    #[test]
    fn tables_are_csv_with_the_provenance_line_first() {
        let table = Table {
            name: "t".into(),
            columns: vec!["component".into(), "force_n".into(), "note".into()],
            rows: vec![
                vec![Cell::Text("spring, coil".into()), Cell::Number(0.1 + 0.2), Cell::Empty],
                vec![Cell::Text("say \"hi\"".into()), Cell::Number(f64::NAN), Cell::Text("x".into())],
            ],
        };
        let p = Provenance::new(Path::new("m\n.json"), b"{}", "corrected", 8);
        let text = String::from_utf8(write_table(&table, &p)).unwrap();
        let sha = sha256_hex(b"{}");
        assert_eq!(sha, "44136fa355b3678a1146ad16f7e8649e94fb4fc21fe77e8310c060f61caaff8a");
        assert_eq!(
            text,
            format!(
                "# elastokin {}, model m?.json (sha256 {}), corrected mode, 8 steps\n\
                 component,force_n,note\n\"spring, coil\",0.3,\n\"say \"\"hi\"\"\",,x\n",
                env!("CARGO_PKG_VERSION"),
                &sha[..16]
            )
        );
    }
}
