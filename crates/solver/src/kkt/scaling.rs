//! Symmetric Ruiz equilibration of a KKT matrix, every row's largest entry driven towards 1 and the
//! scaling rounded to powers of two so that applying it is exact. Both backends scale this way.

/// Rounds an equilibration to the nearest powers of two, so that scaling by it is exact.
pub(crate) fn round_to_powers_of_two(scale: &mut [f64]) {
    for si in scale.iter_mut() {
        let p = si.log2().round().clamp(-1000.0, 1000.0);
        *si = if p.is_finite() { p.exp2() } else { 1.0 };
    }
}

/// Ruiz sweeps from the current `scale`: each measures every row's largest scaled entry into `row_max`
/// (`measure(scale, row_max)`, `row_max` zeroed before) and divides the row's scale by its square root,
/// until every row with a finite, positive maximum is within a factor 2 of 1 or `sweeps` were made; the
/// scaling is then rounded to powers of two. Each backend measures its own matrix; the sweeps and their
/// criterion are this one.
pub(crate) fn equilibrate(
    scale: &mut [f64],
    row_max: &mut [f64],
    sweeps: usize,
    mut measure: impl FnMut(&[f64], &mut [f64]),
) {
    for _ in 0..sweeps {
        row_max.fill(0.0);
        measure(scale, row_max);
        let mut done = true;
        for (s, &x) in scale.iter_mut().zip(row_max.iter()) {
            if x > 0.0 && x.is_finite() {
                if !(0.5..=2.0).contains(&x) {
                    done = false;
                }
                *s /= x.sqrt();
            }
        }
        if done {
            break;
        }
    }
    round_to_powers_of_two(scale);
}
