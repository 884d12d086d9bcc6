//! The predictor of corrected steps with a kept factorization: the polynomial through the last
//! equilibria, and the memory of the steps it extrapolates from.

use super::*;

impl<'m> StaticSolver<'m> {
    /// The predictor of a corrected step under [`SolverOptions::reuse_factorization`]: moves `state` (an
    /// equilibrium) by the increment extrapolated to a step of `dt` from the last steps' increments —
    /// the polynomial through the last equilibria, up to [`PREDICTOR_STEPS`] steps back — when the last
    /// step ended where `state` is. Returns the norm of the `Δq` it applied, `None` when it applied
    /// nothing.
    ///
    /// The increments are those the steps' Newton iterations summed in the tangent space: along a smooth
    /// path they are a smooth function of the load parameter, so a polynomial of degree `p` through the
    /// last `p + 1` equilibria errs by `O(dt^{p+1})`, and the chord iterations that follow start that
    /// much closer.
    pub(super) fn predict(&mut self, state: &mut State, dt: f64) -> Option<f64> {
        let n = self.work.assembly.n;
        if !self.options.reuse_factorization {
            return None;
        }
        let h = self.work.history.as_mut().filter(|h| h.t_end == state.t && h.count > 0)?;
        // Nodes: the load parameter of each equilibrium relative to the newest, 0, −dt₁, −dt₁−dt₂, …
        let mut nodes = [0.0; PREDICTOR_STEPS + 1];
        for k in 1..=h.count {
            nodes[k] = nodes[k - 1] - h.dts[k - 1];
        }
        // Lagrange weights of the equilibria at `dt`; the state at node k is minus the sum of the newer
        // increments, so increment i weighs minus the weights of every node older than it.
        let mut lagrange = [0.0; PREDICTOR_STEPS + 1];
        for (k, l) in lagrange.iter_mut().enumerate().take(h.count + 1) {
            *l = (0..=h.count).filter(|&j| j != k).map(|j| (dt - nodes[j]) / (nodes[k] - nodes[j])).product();
        }
        h.predicted.fill(0.0);
        for i in 0..h.count {
            let w = -lagrange[i + 1..=h.count].iter().sum::<f64>();
            for (p, d) in h.predicted.iter_mut().zip(&h.steps[i]) {
                *p += w * d;
            }
        }
        if h.predicted.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Self::apply(&mut state.poses, &h.predicted[..n], 1.0);
        for (l, d) in state.lambda.iter_mut().zip(&h.predicted[n..]) {
            *l += d;
        }
        Some(norm2(&h.predicted[..n]))
    }

    /// Keeps the increment of a corrected step that converged — the predictor's, if `predicted`, plus
    /// what Newton moved — for the next step's predictor.
    pub(super) fn remember_step(&mut self, predicted: bool, dt: f64, t_end: f64) {
        if !self.options.reuse_factorization {
            return;
        }
        let size = self.work.moved.len();
        let h = self.work.history.get_or_insert_with(|| PathHistory {
            steps: std::array::from_fn(|_| vec![0.0; size]),
            dts: [0.0; PREDICTOR_STEPS],
            count: 0,
            t_end,
            predicted: vec![0.0; size],
        });
        // Older steps stay only when this one began where the newest of them ended (it was predicted).
        h.count = if predicted { (h.count + 1).min(PREDICTOR_STEPS) } else { 1 };
        h.steps.rotate_right(1);
        h.dts.rotate_right(1);
        // Not `0 · predicted + moved`: a refused prediction may have left non-finite numbers there.
        if predicted {
            for ((s, p), d) in h.steps[0].iter_mut().zip(&h.predicted).zip(&self.work.moved) {
                *s = p + d;
            }
        } else {
            h.steps[0].copy_from_slice(&self.work.moved);
        }
        h.dts[0] = dt;
        h.t_end = t_end;
    }
}
