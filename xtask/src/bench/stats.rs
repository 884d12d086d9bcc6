//! Statistics of measurements: medians of repeated timings and the least-squares exponent of a power law.

use std::hint::black_box;
use std::time::Instant;

/// Median of `values` (the mean of the two middle values for an even count); `None` when empty or when a
/// value is not finite.
pub fn median(values: &[f64]) -> Option<f64> {
    if values.is_empty() || values.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let k = v.len() / 2;
    Some(if v.len() % 2 == 1 { v[k] } else { 0.5 * (v[k - 1] + v[k]) })
}

/// Least-squares slope of `ln y` against `ln x`: the exponent `p` of `y ≈ c xᵖ`. `None` with fewer than two
/// points, a non-positive or non-finite coordinate, or all `x` equal.
pub fn power_law_exponent(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 2 || points.iter().any(|&(x, y)| !(x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0)) {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return None;
    }
    Some(sxy / sxx)
}

/// How long to keep repeating one measurement.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// Wall time to spend on the repetitions of one measurement (s), after one warm-up run.
    pub seconds: f64,
    /// At least this many timed repetitions.
    pub min_reps: usize,
    /// At most this many.
    pub max_reps: usize,
}

/// A timed measurement: the median of the repetitions.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    /// Median wall time of one repetition (s).
    pub median: f64,
    /// Number of timed repetitions.
    pub reps: usize,
}

impl Budget {
    /// Runs `f` once to warm up and to size the repetitions, then times it `min_reps..=max_reps` times
    /// (as many as fit in `seconds`).
    pub fn time<R>(&self, mut f: impl FnMut() -> R) -> Timing {
        let start = Instant::now();
        black_box(f());
        let first = start.elapsed().as_secs_f64().max(1e-9);
        let reps = ((self.seconds / first) as usize).clamp(self.min_reps.max(1), self.max_reps.max(1));
        let times: Vec<f64> = (0..reps)
            .map(|_| {
                let t = Instant::now();
                black_box(f());
                t.elapsed().as_secs_f64()
            })
            .collect();
        Timing { median: median(&times).unwrap_or(first), reps }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&[7.0]), Some(7.0));
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn exponent_of_an_exact_power_law() {
        let pts: Vec<(f64, f64)> = [1e3, 2e3, 5e3, 1e4].iter().map(|&n: &f64| (n, 3e-7 * n.powf(1.2))).collect();
        assert!((power_law_exponent(&pts).unwrap() - 1.2).abs() < 1e-12);
        let linear = [(10.0, 1.0), (100.0, 10.0)];
        assert!((power_law_exponent(&linear).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn exponent_is_the_least_squares_fit_of_noisy_points() {
        // ln y = 2 ln x ± 0.1 alternating: the symmetric noise leaves the slope at 2 for points placed
        // symmetrically in ln x.
        let pts =
            [(1.0, (0.1f64).exp()), (std::f64::consts::E, (2.0 - 0.1f64).exp()), ((2.0f64).exp(), (4.1f64).exp())];
        let p = power_law_exponent(&pts).unwrap();
        assert!((p - 2.0).abs() < 1e-12, "{p}");
    }

    #[test]
    fn exponent_refuses_what_it_cannot_fit() {
        assert_eq!(power_law_exponent(&[(1.0, 1.0)]), None);
        assert_eq!(power_law_exponent(&[(1.0, 1.0), (1.0, 2.0)]), None);
        assert_eq!(power_law_exponent(&[(1.0, 1.0), (2.0, 0.0)]), None);
        assert_eq!(power_law_exponent(&[(1.0, 1.0), (f64::NAN, 2.0)]), None);
    }

    #[test]
    fn budget_respects_its_repetition_bounds() {
        let mut calls = 0;
        let t = Budget { seconds: 0.0, min_reps: 3, max_reps: 5 }.time(|| calls += 1);
        assert_eq!(t.reps, 3);
        assert_eq!(calls, 4, "one warm-up and three timed runs");
        assert!(t.median.is_finite() && t.median >= 0.0);
    }
}
