//! Symmetric Ruiz equilibration of a KKT matrix, every row's largest entry driven towards 1 and the
//! scaling rounded to powers of two so that applying it is exact. Both backends scale this way.

/// Rounds an equilibration to the nearest powers of two, so that scaling by it is exact.
pub(crate) fn round_to_powers_of_two(scale: &mut [f64]) {
    for si in scale.iter_mut() {
        let p = si.log2().round().clamp(-1000.0, 1000.0);
        *si = if p.is_finite() { p.exp2() } else { 1.0 };
    }
}
