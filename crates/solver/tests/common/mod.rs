//! Random KKT systems and error measures shared by the factorization tests.
#![allow(dead_code, reason = "each test file uses the helpers it needs")]

use elastokin_solver::kkt::KktPattern;
use nalgebra::DMatrix;

/// xorshift64* — deterministic, dependency-free.
pub struct Rng(pub u64);
impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [-1, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    pub fn below(&mut self, k: usize) -> usize {
        (self.next_u64() % k as u64) as usize
    }
}

/// Dense K (symmetric, diagonal always stored) and J → pattern + values.
/// Off-diagonal entries that are exactly zero are not stored.
pub fn to_sparse(k: &DMatrix<f64>, j: &DMatrix<f64>) -> (KktPattern, Vec<f64>, Vec<f64>) {
    let n = k.nrows();
    let m = j.nrows();
    let mut p = KktPattern { n, m, k_col_ptr: vec![0], j_col_ptr: vec![0], ..KktPattern::default() };
    let (mut kv, mut jv) = (Vec::new(), Vec::new());
    for c in 0..n {
        for r in 0..=c {
            if r == c || k[(r, c)] != 0.0 {
                p.k_row_idx.push(r);
                kv.push(k[(r, c)]);
            }
        }
        p.k_col_ptr.push(p.k_row_idx.len());
        for r in 0..m {
            if j[(r, c)] != 0.0 {
                p.j_row_idx.push(r);
                jv.push(j[(r, c)]);
            }
        }
        p.j_col_ptr.push(p.j_row_idx.len());
    }
    (p, kv, jv)
}

/// Random sparse SPD K = BᵀB + shift·I with a sparse, diagonally heavy B.
pub fn random_spd(rng: &mut Rng, n: usize, shift: f64) -> DMatrix<f64> {
    let mut b = DMatrix::<f64>::zeros(n, n);
    for i in 0..n {
        b[(i, i)] = 1.0 + rng.uniform().abs();
        for _ in 0..2 {
            let c = rng.below(n);
            b[(i, c)] += rng.uniform();
        }
    }
    b.transpose() * b + DMatrix::identity(n, n) * shift
}

/// Random sparse J, about `per_row + 1` nonzeros per row, one of them ≥ 1.
pub fn random_j(rng: &mut Rng, m: usize, n: usize, per_row: usize) -> DMatrix<f64> {
    let mut j = DMatrix::<f64>::zeros(m, n);
    for i in 0..m {
        for _ in 0..per_row {
            let c = rng.below(n);
            j[(i, c)] = rng.uniform();
        }
        let c = rng.below(n);
        j[(i, c)] += 1.0 + rng.uniform().abs();
    }
    j
}

pub fn random_vec(rng: &mut Rng, len: usize) -> Vec<f64> {
    (0..len).map(|_| rng.uniform()).collect()
}

/// max |a − b| / max |b|.
pub fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    let num = a.iter().zip(b).fold(0.0f64, |acc, (x, y)| acc.max((x - y).abs()));
    let den = b.iter().fold(0.0f64, |acc, y| acc.max(y.abs()));
    if den == 0.0 {
        num
    } else {
        num / den
    }
}

pub fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}
