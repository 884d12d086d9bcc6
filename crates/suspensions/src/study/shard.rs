//! A study cut into shards: shard I of N is a contiguous, nearly equal block of the variants, so that a
//! job array (`elastokin batch --shard I/N`) or the workers of a Python study each take one block and the
//! blocks join back in order.

/// Shard `index` of `count` (1-based, as a job array numbers its tasks).
///
/// The split is contiguous and nearly equal: variant k (counting from 0) of V belongs to shard
/// ⌊k·N/V⌋ + 1, so shard I holds variants ⌈(I−1)·V/N⌉ up to, not including, ⌈I·V/N⌉; shard sizes differ
/// by at most one, and with more shards than variants some shards are empty.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// I, from 1 to `count`.
    pub index: usize,
    /// N, at least 1.
    pub count: usize,
}

impl Shard {
    /// Reads `I/N` with 1 ≤ I ≤ N.
    pub fn parse(text: &str) -> Result<Shard, NotAShard> {
        let said = || text.to_string();
        let (i, n) = text.split_once('/').ok_or_else(|| NotAShard::NoSlash { said: said() })?;
        let whole = |s: &str| s.trim().parse::<usize>().ok();
        match (whole(i), whole(n)) {
            (Some(index), Some(count)) if 1 <= index && index <= count => Ok(Shard { index, count }),
            (Some(_), Some(0)) => Err(NotAShard::NoShards { said: said() }),
            (Some(_), Some(_)) => Err(NotAShard::Beyond { said: said() }),
            _ => Err(NotAShard::NotWhole { said: said() }),
        }
    }

    /// The variants (0-based positions) of this shard among `total`.
    pub fn range(self, total: usize) -> std::ops::Range<usize> {
        // u128: I·V cannot overflow however large a shard count is given.
        let start = |i: usize| ((i as u128 * total as u128).div_ceil(self.count as u128)) as usize;
        start(self.index - 1)..start(self.index)
    }
}

/// How a shard is written, said with every refusal of one.
const FORM: &str = "give the shard as I/N with 1 ≤ I ≤ N, e.g. --shard 3/16 for the third of 16 (I counts from 1, \
                    as SLURM_ARRAY_TASK_ID does with --array=1-16)";

/// A shard that is not `I/N` with 1 ≤ I ≤ N, naming what was given.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NotAShard {
    /// No `/`.
    #[error("'{said}' is not I/N: {FORM}")]
    NoSlash {
        /// What was given.
        said: String,
    },
    /// N of 0.
    #[error("'{said}': N must be at least 1; {FORM}")]
    NoShards {
        /// What was given.
        said: String,
    },
    /// I of 0 or beyond N.
    #[error("'{said}': I must be from 1 to N; {FORM}")]
    Beyond {
        /// What was given.
        said: String,
    },
    /// I or N not a whole number.
    #[error("'{said}' is not two whole numbers I/N: {FORM}")]
    NotWhole {
        /// What was given.
        said: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_split_the_variants_contiguously_and_nearly_equally() {
        for total in [1, 2, 5, 6, 7, 16, 100] {
            for count in [1, 2, 3, 4, 7, 8, 16, 150] {
                let ranges: Vec<_> = (1..=count).map(|index| Shard { index, count }.range(total)).collect();
                // Back to back from 0 to V: every variant in exactly one shard.
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[count - 1].end, total);
                for pair in ranges.windows(2) {
                    assert_eq!(pair[0].end, pair[1].start);
                }
                let sizes: Vec<usize> = ranges.iter().map(|r| r.len()).collect();
                assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 1, "{total}/{count}: {sizes:?}");
                // The documented rule: variant k is in shard ⌊k·N/V⌋ + 1.
                for (i, r) in ranges.iter().enumerate() {
                    for k in r.clone() {
                        assert_eq!(k * count / total, i, "variant {k} of {total} in {count} shards");
                    }
                }
            }
        }
    }

    #[test]
    fn a_shard_is_i_of_n_with_i_from_1_to_n() {
        assert_eq!(Shard::parse("1/3"), Ok(Shard { index: 1, count: 3 }));
        assert_eq!(Shard::parse("16/16"), Ok(Shard { index: 16, count: 16 }));
        for bad in ["0/3", "4/3", "1/0", "abc", "1/", "/3", "-1/3", "1.5/3", "1/3/4"] {
            let e = Shard::parse(bad).unwrap_err().to_string();
            assert!(e.contains("I/N with 1 ≤ I ≤ N") && e.contains(bad), "{bad}: {e}");
        }
    }

    /// A shard beyond its count: `NotAShard::Beyond`, naming what was given.
    #[test]
    fn a_shard_beyond_its_count_is_refused_naming_it() {
        let e = Shard::parse("5/4").unwrap_err();
        assert!(matches!(e, NotAShard::Beyond { .. }), "{e:?}");
        assert!(e.to_string().starts_with("'5/4': I must be from 1 to N; give the shard as I/N"), "{e}");
    }
}
