//! Seeded mutation testing of `elastokin merge`: the three shards of a shipped batch, one of them mutated in
//! one place per case (a figure replaced by what no batch writes — "inf", "NaN", "abc", "1e999", "0x10", a
//! NUL —, a line lost, doubled or swapped, the file cut short, a character of the first line changed, a
//! variant number changed, a control character put in, a column added), then merged. Each case ends in one of
//! two ways: the merge exits 0 and its `batch.csv` holds one row per variant, every figure a finite number
//! or empty and no control character; or it exits 2 naming the shard, in printable words, and writes
//! nothing. Never a panic.

use std::path::{Path, PathBuf};
use std::process::Command;

const CASES: u64 = 400;
const SEED: u64 = 0x5EED_3E26;

fn elastokin(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_elastokin")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().unwrap()
}

/// A small seeded generator (xorshift64*): the case's choices, reproducible from the seed and its index.
struct Draw(u64);

impl Draw {
    fn new(case: u64) -> Self {
        Draw((SEED ^ case.wrapping_mul(0x9E37_79B9_7F4A_7C15)) | 1)
    }
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) as usize % n.max(1)
    }
}

/// The shard's text with one mutation, and what it was.
fn mutated(text: &str, draw: &mut Draw) -> (String, String) {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    // Lines 0 and 1: the stamp and the header; the rows below.
    let row = 2 + draw.below(lines.len().saturating_sub(2));
    let bad = ["inf", "NaN", "abc", "1e999", "0x10", "1\u{0}2", "-inf", "1e-400", "", "\u{1b}[31m", "1 5", "+"];
    let what = match draw.below(9) {
        0 if row < lines.len() => {
            let mut cells: Vec<String> = lines[row].split(',').map(String::from).collect();
            let c = 1 + draw.below(cells.len().saturating_sub(1));
            let b = bad[draw.below(bad.len())];
            if c < cells.len() {
                cells[c] = b.to_string();
            }
            lines[row] = cells.join(",");
            format!("row {row} cell {c} replaced by {b:?}")
        }
        1 if row < lines.len() => {
            lines.remove(row);
            format!("line {row} lost")
        }
        2 if row < lines.len() => {
            let copy = lines[row].clone();
            lines.insert(row, copy);
            format!("line {row} doubled")
        }
        3 if lines.len() > 3 => {
            let other = 2 + draw.below(lines.len() - 2);
            let last = lines.len() - 1;
            lines.swap(row.min(last), other);
            format!("lines {row} and {other} swapped")
        }
        4 => {
            let joined = lines.join("\n");
            let mut at = draw.below(joined.len());
            while !joined.is_char_boundary(at) {
                at -= 1;
            }
            return (joined[..at].to_string(), format!("cut at byte {at}"));
        }
        5 => {
            let first: Vec<char> = lines[0].chars().collect();
            let at = draw.below(first.len());
            let by = ['x', '9', ',', '/', '(', ' ', '\u{1b}'][draw.below(7)];
            lines[0] = first.iter().enumerate().map(|(i, c)| if i == at { by } else { *c }).collect();
            format!("first line's character {at} changed to {by:?}")
        }
        6 if row < lines.len() => {
            // The variant number is the last column.
            let cells: Vec<&str> = lines[row].rsplitn(2, ',').collect();
            let number = ["0", "1", "999999", "-1", "x", "1.5"][draw.below(6)];
            lines[row] = format!("{},{number}", cells.last().unwrap_or(&""));
            format!("row {row}'s variant number set to {number}")
        }
        7 => {
            let line = draw.below(lines.len());
            let c = ['\0', '\u{7}', '\u{b}', '\u{7f}', '\u{fffe}', '\u{2028}'][draw.below(6)];
            lines[line].push(c);
            format!("{c:?} put at the end of line {line}")
        }
        _ => {
            let line = 1 + draw.below(lines.len() - 1);
            lines[line].push_str(",extra");
            format!("a column added to line {line}")
        }
    };
    (lines.join("\n") + "\n", what)
}

/// The columns of the single batch that hold figures (every cell a number or empty).
fn check_merged(text: &str, variants: usize) -> Result<(), String> {
    if text.chars().any(|c| c.is_control() && c != '\n') {
        return Err("a control character in the merged table".into());
    }
    let (_, body) = text.split_once('\n').ok_or("no first line")?;
    let mut reader = csv::ReaderBuilder::new().from_reader(body.as_bytes());
    let header = reader.headers().map_err(|e| e.to_string())?.clone();
    let rows: Vec<csv::StringRecord> = reader.records().collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    if rows.len() != variants {
        return Err(format!("{} rows for {variants} variants", rows.len()));
    }
    for row in &rows {
        for (name, cell) in header.iter().zip(row.iter()).skip(1) {
            if name != "error" && !(cell.is_empty() || cell.parse::<f64>().is_ok_and(f64::is_finite)) {
                return Err(format!("{name} holds {cell:?}"));
            }
        }
    }
    Ok(())
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("elastokin-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn mutated_shards_are_merged_whole_or_refused_by_name() {
    let dir = scratch("fuzz-merge");
    let (model, variants) = ("examples/generic/macpherson.json", "examples/generic/macpherson_variants.txt");
    let shards: Vec<PathBuf> = (1..=3)
        .map(|i| {
            let out = dir.join(format!("shard-{i}"));
            let o =
                elastokin(&["batch", model, variants, "--shard", &format!("{i}/3"), "--out", out.to_str().unwrap()]);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            out.join("batch.csv")
        })
        .collect();
    let texts: Vec<String> = shards.iter().map(|s| std::fs::read_to_string(s).unwrap()).collect();
    // Every variant line but comments and blank lines, as the batch counts them.
    let count = std::fs::read_to_string(variants)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .count();
    let (mut merged, mut refused) = (0, 0);
    let mut failures = Vec::new();
    for case in 0..CASES {
        let mut draw = Draw::new(case);
        let k = draw.below(3);
        let (text, what) = mutated(&texts[k], &mut draw);
        let bad: &Path = &dir.join(format!("case-{case}.csv"));
        std::fs::write(bad, &text).unwrap();
        let given: Vec<String> =
            (0..3).map(|i| if i == k { bad.display().to_string() } else { shards[i].display().to_string() }).collect();
        let out = dir.join(format!("merged-{case}"));
        let o = elastokin(&["merge", "--out", out.to_str().unwrap(), &given[0], &given[1], &given[2]]);
        let err = String::from_utf8_lossy(&o.stderr);
        let verdict = match o.status.code() {
            Some(0) => {
                merged += 1;
                check_merged(&std::fs::read_to_string(out.join("batch.csv")).unwrap_or_default(), count)
            }
            Some(2) => {
                refused += 1;
                if err.chars().any(|c| c.is_control() && c != '\n') {
                    Err(format!("a control character in the message: {err:?}"))
                } else if !err.contains(&bad.display().to_string()) {
                    Err(format!("the message does not name the shard: {err}"))
                } else if out.join("batch.csv").exists() {
                    Err("a refused merge wrote its table".into())
                } else {
                    Ok(())
                }
            }
            code => Err(format!("exit {code:?}: {err}")),
        };
        if let Err(why) = verdict {
            failures.push(format!("case {case} (shard {}, {what}): {why}", k + 1));
        }
    }
    assert!(failures.is_empty(), "{} of {CASES} cases failed:\n{}", failures.len(), failures.join("\n"));
    println!("{merged} merged, {refused} refused");
    std::fs::remove_dir_all(&dir).ok();
}
