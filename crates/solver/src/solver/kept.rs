//! The tangent of a moved equilibrium as a replay solves it (`StaticSolver::solve_kept`): with the
//! recorded factors there and one step of refinement against the moved tangent, whose residual is summed
//! with its rounding carried.

use crate::assembly::Assembly;
use crate::kkt::LuFactors;
use crate::replay::Factors;

/// The tangent of a moved equilibrium as a replay solves with it (`StaticSolver::solve_kept`): its values
/// and the load path's rates as assembled there (the assembly's own are written over by any later one,
/// such as a path's second rates' residuals), and the residual of the solve under way with its rounding.
#[derive(Debug, Default)]
pub(crate) struct KeptTangent {
    k: Vec<Split>,
    skew: Vec<Split>,
    has_skew: bool,
    j: Vec<Split>,
    load_rate: Vec<f64>,
    phi_rate: Vec<f64>,
    x: Vec<Split>,
    residual: Vec<Exact>,
    correction: Vec<f64>,
}

/// A number and its two halves of half its digits each (Veltkamp's splitting), for exact products.
#[derive(Debug, Clone, Copy)]
struct Split {
    value: f64,
    high: f64,
    low: f64,
}

impl Split {
    #[inline]
    fn of(value: f64) -> Split {
        // 2²⁷ + 1: half of a double's 53 digits, rounded up.
        let scaled = 134_217_729.0 * value;
        let high = scaled - (scaled - value);
        Split { value, high, low: value - high }
    }

    /// `(a·b, its rounding)`: the two add up to `a·b` exactly (Dekker's product; for numbers far from
    /// overflow).
    #[inline]
    fn times(self, b: Split) -> (f64, f64) {
        let product = self.value * b.value;
        (product, ((self.high * b.high - product) + self.high * b.low + self.low * b.high) + self.low * b.low)
    }
}

/// A sum carried with its rounding: `sum + rounding` is the exact sum of what was added, to the rounding
/// of `rounding` itself.
#[derive(Debug, Clone, Copy, Default)]
struct Exact {
    sum: f64,
    rounding: f64,
}

impl Exact {
    /// Adds `a·b`.
    #[inline]
    fn add(&mut self, a: Split, b: Split) {
        let (product, product_rounding) = a.times(b);
        let (sum, sum_rounding) = exact_sum(self.sum, product);
        self.sum = sum;
        self.rounding += sum_rounding + product_rounding;
    }

    /// Takes away `a·b`.
    #[inline]
    fn take(&mut self, a: Split, b: Split) {
        let (product, product_rounding) = a.times(b);
        let (sum, sum_rounding) = exact_sum(self.sum, -product);
        self.sum = sum;
        self.rounding += sum_rounding - product_rounding;
    }

    /// Takes away another carried sum.
    #[inline]
    fn take_sum(&mut self, other: Exact) {
        let (sum, sum_rounding) = exact_sum(self.sum, -other.sum);
        self.sum = sum;
        self.rounding += sum_rounding - other.rounding;
    }
}

/// `(a + b, its rounding)`: the two add up to `a + b` exactly (Knuth's sum).
#[inline]
fn exact_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let b_taken = sum - a;
    (sum, (a - (sum - b_taken)) + (b - b_taken))
}

impl KeptTangent {
    /// Keeps the tangent `a` holds (assembled at a moved equilibrium), split for exact products.
    pub(crate) fn keep(&mut self, a: &Assembly) {
        let split = |to: &mut Vec<Split>, from: &[f64]| {
            to.clear();
            to.extend(from.iter().map(|&v| Split::of(v)));
        };
        split(&mut self.k, &a.k_values);
        split(&mut self.skew, &a.k_skew);
        self.has_skew = a.has_skew;
        split(&mut self.j, &a.j_values);
        self.load_rate.clone_from(&a.load_rate);
        self.phi_rate.clone_from(&a.phi_rate);
    }

    /// The load path's rates assembled with the kept tangent: `∂Q/∂t` and `∂Φ/∂t`.
    pub(crate) fn rates(&self) -> (&[f64], &[f64]) {
        (&self.load_rate, &self.phi_rate)
    }

    /// `x ← M b + M (b − A M b)` for `b` in `x`, with `A` the kept tangent (on the pattern of `a`) and `M`
    /// the recorded `factors`; the residual summed with its rounding carried.
    pub(crate) fn solve(&mut self, a: &Assembly, factors: &LuFactors, x: &mut [f64]) {
        let n = a.n;
        self.residual.clear();
        self.residual.extend(x.iter().map(|&b| Exact { sum: b, rounding: 0.0 }));
        factors.solve_in_place(x);
        self.x.clear();
        self.x.extend(x.iter().map(|&v| Split::of(v)));
        let (r, xs) = (&mut self.residual, &self.x);
        for c in 0..n {
            // Row `c` of `A` times `x` (below the diagonal of `K`, and `Jᵀ`), summed here; column `c` of
            // `K` and of `J` times `x[c]` taken from the rows they fall in.
            let mut row_c = Exact::default();
            let xc = xs[c];
            for p in a.k_col_ptr[c]..a.k_col_ptr[c + 1] {
                let (row, v) = (a.k_row_idx[p], self.k[p]);
                r[row].take(v, xc);
                if row != c {
                    row_c.add(v, xs[row]);
                    if self.has_skew {
                        let s = self.skew[p];
                        r[row].take(s, xc);
                        row_c.take(s, xs[row]);
                    }
                }
            }
            for p in a.j_col_ptr[c]..a.j_col_ptr[c + 1] {
                let (row, v) = (n + a.j_row_idx[p], self.j[p]);
                r[row].take(v, xc);
                row_c.add(v, xs[row]);
            }
            r[c].take_sum(row_c);
        }
        self.correction.clear();
        self.correction.extend(r.iter().map(|e| e.sum + e.rounding));
        factors.solve_in_place(&mut self.correction);
        for (x, d) in x.iter_mut().zip(&self.correction) {
            *x += d;
        }
    }
}

/// The tangent a replayed solver solves with at one of its moved equilibria (`StaticSolver::keep_tangent`):
/// which one, and the recorded factors there.
#[derive(Debug)]
pub(crate) struct KeptAt {
    pub(crate) at: usize,
    pub(crate) factors: Factors,
}
