//! `elastokin merge SHARD...`: the `batch.csv` files of `batch --shard I/N` runs joined into the
//! `batch.csv` that a single `batch` of the same files writes.
//!
//! A shard's first line is the batch's with `, shard I/N of V variants` added ([`Part::suffix`]), and its
//! rows are the batch's with the column `variant_number` added. The merge checks that the shards belong
//! together (one elastokin version, one model and one variants file by their SHA-256, one N), that each of
//! 1..N is given once and holds exactly the variants the split gives it, and only then writes the rows in
//! order without that column, after the first shard's line with `, merged from N shards` in place of its
//! shard. The cells are copied as text, so the rows are the single batch's byte for byte.

use super::batch::{self, Shard};
use super::input::read_input;
use crate::output::{write_table_after, Failure, Part, Staging, Stdout};
use clap::Args;
use elastokin::solver::Mode;
use elastokin::suspensions::file::key_path::unprintable;
use elastokin::suspensions::kc::{self, Cell, Table};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The shards: each a batch.csv that `batch --shard I/N` wrote, or the --out directory holding it
    #[arg(required = true, value_name = "SHARD")]
    pub shards: Vec<PathBuf>,
    /// Where the merged batch.csv goes; the directory is replaced as a whole when the merge succeeds
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
}

/// What to do with a file that is not a shard, for the messages.
const GIVE_SHARDS: &str =
    "give the batch.csv files (or their --out directories) that `elastokin batch MODEL VARIANTS --shard I/N` wrote";

/// One shard file, read and checked on its own.
struct ShardFile {
    /// The file, as given (or DIR/batch.csv).
    path: String,
    shard: Shard,
    /// V, the variants in the whole batch.
    variants: usize,
    /// The first line without the shard's part: the line a single batch writes.
    head: String,
    /// The first line read back.
    stamp: Stamp,
    /// The rows without their `variant_number`.
    rows: Vec<Vec<String>>,
}

/// What a batch's first line says about where it came from.
struct Stamp {
    version: String,
    /// The model file's path and the first 16 hex digits of its SHA-256, as the line has them.
    model: (String, String),
    /// The same for the variants file.
    variants: (String, String),
}

fn is_short_hash(text: &str) -> bool {
    text.len() == 16 && text.bytes().all(|b| b.is_ascii_hexdigit())
}

/// Reads back the line `Provenance::comment_line` writes for a batch:
/// `# elastokin VERSION, model PATH (sha256 HEX), corrected mode, 8 steps, variants PATH (sha256 HEX)`.
/// A line with other settings is not this version's batch.
fn read_stamp(head: &str) -> Option<Stamp> {
    let rest = head.strip_prefix("# elastokin ")?;
    let (version, rest) = rest.split_once(", model ")?;
    let settings = format!("), {} mode, {} steps, variants ", kc::mode_word(Mode::Corrected), batch::STEPS);
    // The model's path ends at the first hash followed by the batch's settings: a path may hold anything
    // else, even "(sha256 ".
    let (at, _) = rest.match_indices(" (sha256 ").find(|&(at, m)| {
        let after = &rest[at + m.len()..];
        after.get(..16).is_some_and(is_short_hash) && after.get(16..).is_some_and(|a| a.starts_with(&settings))
    })?;
    let sha_at = at + " (sha256 ".len();
    let model = (rest[..at].to_string(), rest[sha_at..sha_at + 16].to_string());
    let (path, sha) = rest[sha_at + 16 + settings.len()..].strip_suffix(')')?.rsplit_once(" (sha256 ")?;
    is_short_hash(sha).then(|| Stamp { version: version.into(), model, variants: (path.into(), sha.into()) })
}

/// Reads one shard file and checks it on its own: its first line, its columns, and that its rows are
/// the variants its shard holds.
fn read_shard(given: &Path) -> Result<ShardFile, Failure> {
    let file = if given.is_dir() { given.join("batch.csv") } else { given.to_path_buf() };
    let path = file.display().to_string();
    let (_, text) =
        read_input(&file, "SHARD").map_err(|e| Failure::Input(format!("{}; {GIVE_SHARDS}", e.message())))?;
    let not_a_shard = |why: &str| Failure::Input(format!("'{path}' is not a shard of a batch: {why}; {GIVE_SHARDS}"));
    let (first, body) = text.split_once('\n').ok_or_else(|| not_a_shard("it has no rows, not even a header"))?;
    let first = first.strip_suffix('\r').unwrap_or(first);
    // `, shard I/N of V variants`, read back and held to the exact form written.
    let (head, tail) = first
        .rsplit_once(", shard ")
        .ok_or_else(|| not_a_shard("its first line does not say `shard I/N of V variants`"))?;
    let part = tail.strip_suffix(" variants").and_then(|t| t.split_once(" of ")).and_then(|(i_n, v)| {
        let shard = Shard::parse(i_n).ok()?;
        Some((shard, v.parse::<usize>().ok()?))
    });
    let (shard, variants) = part
        .filter(|&(s, v)| {
            Part::Shard { index: s.index, count: s.count, variants: v }.suffix() == format!(", shard {tail}")
        })
        .ok_or_else(|| not_a_shard("its first line does not end in `, shard I/N of V variants` with 1 ≤ I ≤ N"))?;
    let stamp = read_stamp(head).ok_or_else(|| {
        not_a_shard(
            "its first line is not that of a batch of this elastokin (model, corrected mode, 8 steps, variants)",
        )
    })?;
    let mut reader = csv::ReaderBuilder::new().flexible(true).from_reader(body.as_bytes());
    let columns = batch::columns(true);
    let header = reader.headers().map_err(|e| not_a_shard(&format!("its header row is not CSV: {e}")))?;
    if header.iter().ne(columns.iter().map(String::as_str)) {
        return Err(not_a_shard(&format!("its columns are not {}", columns.join(","))));
    }
    let holds = shard.range(variants);
    let held = if holds.is_empty() {
        "none of them".to_string()
    } else {
        format!("variants {} to {}", holds.start + 1, holds.end)
    };
    let rerun = |why: String| {
        Failure::Input(format!(
            "'{path}': {why}, but shard {}/{} of {variants} variants holds {held}; the file is not as \
             `batch --shard` wrote it: run that shard again",
            shard.index, shard.count
        ))
    };
    let mut rows = Vec::new();
    for (k, record) in reader.records().enumerate() {
        let record = record.map_err(|e| rerun(format!("row {} is not CSV ({e})", k + 1)))?;
        let number = record.get(columns.len() - 1).and_then(|n| n.parse::<usize>().ok());
        if record.len() != columns.len() || number != Some(holds.start + k + 1) {
            let said = number.map_or("a row without its variant number".into(), |n| format!("variant {n}"));
            return Err(rerun(format!("row {} is {said}", k + 1)));
        }
        // A figure is a finite number, or empty where the variant failed: `batch` writes nothing else.
        for (figure, cell) in columns.iter().zip(record.iter()).skip(1).take(batch::FIGURES.len()) {
            if !(cell.is_empty() || cell.parse::<f64>().is_ok_and(f64::is_finite)) {
                return Err(rerun(format!("row {} has {cell:?} for {figure}, which is not a finite number", k + 1)));
            }
        }
        // A text (the variant's label, its error) is written printable by `batch`: copied as is, a control
        // character would reach the merged table and the terminal that shows it.
        if let Some((column, cell)) = columns.iter().zip(record.iter()).find(|(_, c)| c.chars().any(unprintable)) {
            return Err(rerun(format!("row {} has {cell:?} in {column}, a character no batch writes", k + 1)));
        }
        rows.push(record.iter().take(columns.len() - 1).map(String::from).collect());
    }
    if rows.len() != holds.len() {
        return Err(rerun(format!("it has {} rows", rows.len())));
    }
    Ok(ShardFile { path, shard, variants, head: head.to_string(), stamp, rows })
}

/// Checks that `b` is of the same batch as `a`.
fn same_batch(a: &ShardFile, b: &ShardFile) -> Result<(), Failure> {
    let differ = |what: &str, x: String, y: String| {
        Err(Failure::Input(format!(
            "'{}' is {what} {y}, but '{}' is {what} {x}: shards of different batches do not merge; give the shards \
             of one batch (one model file, one variants file, one N)",
            b.path, a.path
        )))
    };
    let file = |(path, sha): &(String, String)| format!("{path} (sha256 {sha})");
    if a.stamp.model.1 != b.stamp.model.1 {
        return differ("a shard of model", file(&a.stamp.model), file(&b.stamp.model));
    }
    if a.stamp.variants.1 != b.stamp.variants.1 {
        return differ("a shard of variants file", file(&a.stamp.variants), file(&b.stamp.variants));
    }
    if (a.shard.count, a.variants) != (b.shard.count, b.variants) {
        let of = |s: &ShardFile| format!("{}/{} of {} variants", s.shard.index, s.shard.count, s.variants);
        return differ("shard", of(a), of(b));
    }
    if a.stamp.version != b.stamp.version {
        return differ("written by elastokin", a.stamp.version.clone(), b.stamp.version.clone());
    }
    Ok(())
}

/// `merge`: reads and checks every shard, then writes the merged `batch.csv` (or nothing).
pub fn run(args: MergeArgs, out: &Stdout) -> Result<(), Failure> {
    let shards: Vec<ShardFile> = args.shards.iter().map(|p| read_shard(p)).collect::<Result<_, _>>()?;
    let count = shards[0].shard.count;
    for b in &shards[1..] {
        same_batch(&shards[0], b)?;
    }
    // A map, not a list of N: N comes from the files, and a damaged one may claim any number.
    let mut by_index = std::collections::BTreeMap::new();
    for s in &shards {
        if let Some(earlier) = by_index.insert(s.shard.index, s) {
            return Err(Failure::Input(format!(
                "shard {}/{count} is given twice, as '{}' and as '{}': give each shard once",
                s.shard.index, earlier.path, s.path
            )));
        }
    }
    let missing = count - by_index.len();
    if missing > 0 {
        let mut list: Vec<String> =
            (1..=count).filter(|i| !by_index.contains_key(i)).take(20).map(|i| i.to_string()).collect();
        let first = list[0].clone();
        if missing > list.len() {
            list.push(format!("… ({missing} in all)"));
        }
        let (shards, them) = if missing == 1 { ("shard", "it") } else { ("shards", "them") };
        return Err(Failure::Input(format!(
            "{shards} {} of {count} missing: run {them} (`elastokin batch MODEL VARIANTS --shard {first}/{count}` \
             …) and give the batch.csv of every shard from 1 to {count}",
            list.join(", ")
        )));
    }
    let ordered: Vec<&ShardFile> = by_index.into_values().collect();
    let table = Table {
        name: "batch".into(),
        columns: batch::columns(false),
        rows: ordered.iter().flat_map(|s| &s.rows).map(|r| r.iter().cloned().map(Cell::Text).collect()).collect(),
    };
    let first = format!("{}{}", ordered[0].head, Part::Merged { shards: count }.suffix());
    let staging = Staging::new(&args.out)?;
    let path = staging.write("batch.csv", &write_table_after(&first, &table)).map_err(|e| staging.failed(e))?;
    staging.commit()?;
    out.line(format!("merged {count} shards, {} variants: wrote {}", table.rows.len(), path.display()))
}
