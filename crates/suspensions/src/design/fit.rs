//! What a tune's fit can know of the numbers it fitted: each one's standard uncertainty and their
//! correlations, the directions the targets cannot see, and the numbers a bound holds.
//!
//! At the end of a tune the residuals `r` (each miss over its tolerance) and their Jacobian `J` give the
//! Gauss–Newton covariance of the numbers the fit moved freely, `s² (JᵀJ)⁻¹`, with `s² = Σ r² / (m − n)`
//! the residuals' own variance over the degrees of freedom (`m` residuals, `n` numbers not at a bound):
//! the standard estimate when the data's noise is not given, and one that does not depend on the
//! tolerances chosen (they scale `r` and `J` alike). A number a bound holds is not a fitted number: it is
//! named, and left out.
//!
//! The covariance is read through the singular values of `J` with each number measured by its bounds'
//! span (`J D`, `D` the spans): along a singular direction the fit is uncertain by `s / σ` of the spans.
//! A direction the data cannot place within half the spans, or that `J` does not see at all (`σ` below
//! 1e-8 of the largest), is one the targets cannot tell: the fit's answer is not unique along it.

use nalgebra::{DMatrix, DVector};

/// Beyond this uncertainty along a direction, as a share of the free numbers' bounds' spans, the targets
/// cannot place the fit along it.
pub const UNSEEN_SHARE: f64 = 0.5;

/// Below this share of the largest singular value, a direction is not seen at all.
const RANK: f64 = 1e-8;

/// Below this share of the largest variance, a number's variance is rounding's: the packaging holds it.
const PINNED: f64 = 1e-20;

/// The combinations of the `fitted` numbers (each measured by its `span`) that the packaging constraints
/// whose rates are `held` leave free: an orthonormal basis, a column each, of what their rates do not see
/// (all of them when none holds).
fn free_combinations(fitted: &[usize], span: &[f64], held: &[Vec<f64>]) -> DMatrix<f64> {
    let f = fitted.len();
    let g = DMatrix::from_fn(held.len(), f, |c, j| held[c][fitted[j]] * span[fitted[j]]);
    if held.is_empty() || f == 0 {
        return DMatrix::identity(f, f);
    }
    let eigen = (g.transpose() * &g).symmetric_eigen();
    let largest = eigen.eigenvalues.iter().copied().fold(0.0, f64::max);
    let free: Vec<usize> = (0..f).filter(|&i| eigen.eigenvalues[i] <= RANK * RANK * largest).collect();
    DMatrix::from_fn(f, free.len(), |i, j| eigen.eigenvectors[(i, free[j])])
}

/// How close to a bound a number counts as held by it, as a share of its bounds' span: the interior-point
/// steps of a tune stop a little inside a bound that holds a number.
const AT_BOUND: f64 = 1e-4;

/// Which bound of `(lo, hi)` holds a number at `x`, if one does: `Some(lo)` or `Some(hi)`. The one rule
/// for the fit's uncertainty and the tune's verdicts.
pub fn held_at(x: f64, (lo, hi): (f64, f64)) -> Option<f64> {
    let near = AT_BOUND * (hi - lo);
    if (x - lo).abs() <= near {
        Some(lo)
    } else if (hi - x).abs() <= near {
        Some(hi)
    } else {
        None
    }
}

/// The uncertainty of a fit's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct FitUncertainty {
    /// Each free number's standard uncertainty, in its own unit: `None` for one a bound holds, or where
    /// the fit leaves no degree of freedom or a direction unseen.
    pub standard: Vec<Option<f64>>,
    /// The correlation of each two free numbers (`None` where either has no standard uncertainty).
    pub correlation: Vec<Vec<Option<f64>>>,
    /// The residuals' root mean square per degree of freedom, `s`, which scales the covariance.
    pub residual_scale: Option<f64>,
    /// The degrees of freedom, residuals less numbers fitted (none when there are as many numbers as
    /// residuals, or more).
    pub degrees_of_freedom: usize,
    /// The free numbers a bound holds, by index.
    pub at_bound: Vec<usize>,
    /// How many combinations of the numbers the packaging holds: the rank of the constraints at their
    /// limits, which the fit moves along, not across.
    pub held_by_packaging: usize,
    /// The directions the targets cannot tell, most uncertain first.
    pub unseen: Vec<Unseen>,
}

/// A combination of the free numbers the targets cannot place.
#[derive(Debug, Clone, PartialEq)]
pub struct Unseen {
    /// Its direction, a unit vector in the numbers measured by their bounds' spans, one entry per free
    /// number (zero for one a bound holds); its sign is chosen so that its largest entry is positive.
    pub direction: Vec<f64>,
    /// The uncertainty along it as a share of the spans; `None` where `J` does not see it at all.
    pub share: Option<f64>,
}

impl Unseen {
    /// In the engineer's words, for free numbers of `pointers`: the numbers that make up the direction
    /// (each with its share, a tenth or more) and how uncertain the fit is along it.
    pub fn said(&self, pointers: &[String]) -> String {
        let parts: Vec<String> = self
            .direction
            .iter()
            .zip(pointers)
            .filter(|(d, _)| d.abs() >= 0.1)
            .map(|(d, p)| format!("{} ({d:+.2})", super::parameter_words(p)))
            .collect();
        let how = match self.share {
            Some(share) => format!("the fit is uncertain along it by {:.0} % of their bounds' spans", share * 100.0),
            None => "the targets do not move with it at all".to_string(),
        };
        format!("{}: {how}", parts.join(" with "))
    }
}

impl FitUncertainty {
    /// The uncertainty of the numbers `x` fitted within `bounds` whose residuals `residuals` and their
    /// Jacobian `jacobian` (a row per residual) are those at the end of the fit, where the packaging
    /// constraints whose rates are `held` (a row each, over the numbers) are at their limits.
    ///
    /// A constraint at its limit holds the fit on it: the numbers move along it only, so the covariance is
    /// the one of the fit in the combinations it leaves free, `N (Nᵀ JᵀJ N)⁻¹ Nᵀ s²` with `N` a basis of
    /// what the constraints' rates do not see, and each constraint that holds takes a degree of freedom
    /// from the fitted numbers as a bound does.
    pub fn of(
        x: &[f64],
        bounds: &[(f64, f64)],
        residuals: &[f64],
        jacobian: &[Vec<f64>],
        held: &[Vec<f64>],
    ) -> FitUncertainty {
        let n = x.len();
        let span: Vec<f64> = bounds.iter().map(|(lo, hi)| hi - lo).collect();
        let at_bound: Vec<usize> = (0..n).filter(|&k| held_at(x[k], bounds[k]).is_some()).collect();
        let fitted: Vec<usize> = (0..n).filter(|k| !at_bound.contains(k)).collect();
        let free = free_combinations(&fitted, &span, held);
        let m = residuals.len();
        let degrees_of_freedom = m.saturating_sub(free.ncols());
        let none = FitUncertainty {
            standard: vec![None; n],
            correlation: vec![vec![None; n]; n],
            residual_scale: None,
            degrees_of_freedom,
            at_bound: at_bound.clone(),
            held_by_packaging: fitted.len() - free.ncols(),
            unseen: Vec::new(),
        };
        if free.ncols() == 0 || degrees_of_freedom == 0 {
            return none;
        }
        let s = (residuals.iter().map(|r| r * r).sum::<f64>() / degrees_of_freedom as f64).sqrt();
        // J D N over the combinations fitted: each number measured by its span.
        let scaled = DMatrix::from_fn(m, fitted.len(), |i, j| jacobian[i][fitted[j]] * span[fitted[j]]) * &free;
        let svd = scaled.svd(false, true);
        let Some(v_t) = svd.v_t.as_ref() else { return none };
        let largest = svd.singular_values.max();
        let mut unseen = Vec::new();
        for (i, &sigma) in svd.singular_values.iter().enumerate() {
            let blind = sigma.is_nan() || sigma <= RANK * largest;
            let share = (!blind).then(|| s / sigma);
            if blind || share.is_some_and(|share| share > UNSEEN_SHARE) {
                let mut direction = vec![0.0; n];
                let along = &free * v_t.row(i).transpose();
                for (j, &k) in fitted.iter().enumerate() {
                    direction[k] = along[j];
                }
                let biggest = direction.iter().copied().fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
                if biggest < 0.0 {
                    direction.iter_mut().for_each(|d| *d = -*d);
                }
                unseen.push(Unseen { direction, share });
            }
        }
        unseen.sort_by(|a, b| b.share.unwrap_or(f64::INFINITY).total_cmp(&a.share.unwrap_or(f64::INFINITY)));
        let mut out = FitUncertainty { residual_scale: Some(s), unseen, ..none };
        if out.unseen.iter().any(|u| u.share.is_none()) {
            // A direction J does not see has no finite uncertainty: none is claimed for any number.
            return out;
        }
        // The covariance in the spans' measure, N V Σ⁻² Vᵀ Nᵀ s², then in the numbers' own units. A number
        // the packaging holds alone (its variance rounding's) is held, not fitted.
        let inverse = DVector::from_iterator(free.ncols(), svd.singular_values.iter().map(|sigma| s / sigma));
        let root = &free * v_t.transpose() * DMatrix::from_diagonal(&inverse);
        let covariance = &root * root.transpose();
        let largest = covariance.diagonal().max();
        let fit: Vec<(usize, usize)> =
            fitted.iter().copied().enumerate().filter(|&(a, _)| covariance[(a, a)] > PINNED * largest).collect();
        for &(a, k) in &fit {
            out.standard[k] = Some(covariance[(a, a)].sqrt() * span[k]);
            for &(b, l) in &fit {
                out.correlation[k][l] = Some(covariance[(a, b)] / (covariance[(a, a)] * covariance[(b, b)]).sqrt());
            }
        }
        out
    }

    /// How the standard uncertainties were taken, or why there are none, in words (the command and the
    /// report say it alike).
    pub fn basis(&self) -> String {
        match self.residual_scale {
            Some(s) => format!(
                "uncertainties: one standard deviation, from the residuals' spread ({} of the tolerances over {} \
                 degrees of freedom){}",
                crate::kc::significant(s, 3),
                self.degrees_of_freedom,
                match self.held_by_packaging {
                    0 => String::new(),
                    k => format!(", along the packaging that holds {k} combination(s) of the numbers"),
                }
            ),
            None => "uncertainties: none, the targets leave no degree of freedom (as many numbers fitted as target \
                     points): give more points, or free fewer numbers"
                .to_string(),
        }
    }

    /// What the fit cannot tell along `unseen`, with what to do, for free numbers of `pointers`.
    pub fn not_unique(unseen: &Unseen, pointers: &[String]) -> String {
        format!(
            "NOT unique: the targets cannot tell {}; fix one of these numbers, or add a target that moves them",
            unseen.said(pointers)
        )
    }

    /// Whether the fit's answer is unique: no direction unseen.
    pub fn unique(&self) -> bool {
        self.unseen.is_empty()
    }
}
