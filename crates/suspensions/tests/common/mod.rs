//! Reference machinery of the loop-closure tests, independent of the engine.

use nalgebra::{DMatrix, DVector};

/// Newton's method with a central-difference Jacobian on `residual(x) = 0`, from the guess in `x`;
/// panics when it does not close (the tests start it near a solution).
pub fn newton_fd<const N: usize>(residual: impl Fn(&[f64; N]) -> DVector<f64>, x: &mut [f64; N]) {
    for _ in 0..60 {
        let f = residual(x);
        if f.norm() < 1e-14 {
            return;
        }
        let mut jac = DMatrix::zeros(f.len(), N);
        for c in 0..N {
            let (mut xp, mut xm) = (*x, *x);
            xp[c] += 1e-7;
            xm[c] -= 1e-7;
            jac.set_column(c, &((residual(&xp) - residual(&xm)) / 2e-7));
        }
        let dx = jac.lu().solve(&(-f)).expect("loop closure Jacobian is regular away from lock-up");
        for c in 0..N {
            x[c] += dx[c];
        }
    }
    assert!(residual(x).norm() < 1e-12, "loop closure did not close: {:?}", residual(x));
}

/// Toe and camber of a left wheel whose upright is turned by `r` from design (spin axis +y there),
/// written out from their definitions: toe = atan2(aₓ, a_y), camber = atan2(−a_z, √(aₓ² + a_y²)).
pub fn left_toe_camber(r: &nalgebra::Matrix3<f64>) -> (f64, f64) {
    let a = r * nalgebra::Vector3::y();
    (a.x.atan2(a.y), (-a.z).atan2((a.x * a.x + a.y * a.y).sqrt()))
}
