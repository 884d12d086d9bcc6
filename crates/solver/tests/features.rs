//! The optional parts: rayon element evaluation (`parallel`) and the Matrix Market dump (`matrix-market`).
//! Run with `cargo test -p elastokin-solver --all-features`.

use elastokin_core::{BodyRef, Mat3, Model, Pose, Vec3};
use elastokin_elements::{Bushing, PointForce};
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver};

/// `count` bodies, each on its own bushing to ground and pushed by its own force: deflection `F/k` each.
fn many_mounts(count: usize) -> Model {
    let mut m = Model::new();
    for b in 0..count {
        let p = Vec3::new(b as f64 * 0.1, 0.0, 0.0);
        let body = m.add_body(&format!("mass {b}"), Pose::at(p)).unwrap();
        let k = 1e5 * (1.0 + b as f64);
        m.add_element(
            Bushing::new(
                &format!("mount {b}"),
                BodyRef::Ground,
                body.into(),
                p,
                Mat3::identity(),
                Vec3::new(k, k, k),
                Vec3::new(1e3, 1e3, 1e3),
            )
            .unwrap(),
        )
        .unwrap();
        m.add_element(PointForce::new(&format!("push {b}"), body.into(), p, Vec3::new(0.0, 0.0, 100.0)).unwrap())
            .unwrap();
    }
    m
}

#[test]
fn every_mount_deflects_by_force_over_stiffness() {
    // 600 elements: above the threshold where the `parallel` feature evaluates them on the rayon pool.
    let count = 300;
    assert!(2 * count >= elastokin_solver::assembly::PARALLEL_ELEMENTS);
    let m = many_mounts(count);
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let sweep = solver.sweep(LoadPath::new(0.0, 1.0, 2), Mode::Corrected).unwrap();
    let last = sweep.steps.last().unwrap();
    for b in 0..count {
        let dz = last.poses[b].position.z;
        let expected = 100.0 / (1e5 * (1.0 + b as f64));
        assert!((dz - expected).abs() < 1e-12, "body {b}: {dz} vs {expected}");
    }
}

#[cfg(feature = "matrix-market")]
#[test]
fn kkt_dump_reads_back_as_the_same_matrix() {
    let m = many_mounts(3);
    let mut solver = StaticSolver::new(&m, SolverOptions::default()).unwrap();
    let state = solver.design_state(1.0);
    let dir = std::env::temp_dir().join(format!("elastokin-kkt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("kkt.mtx");
    solver.write_kkt_matrix_market(&state, &path).unwrap();
    let back: sprs::TriMat<f64> = sprs::io::read_matrix_market(&path).unwrap();
    let (size, triplets) = solver.kkt_triplets(&state);
    assert_eq!(back.rows(), size);
    let dense_back = back.to_csc::<usize>().to_dense();
    for (r, c, v) in triplets {
        assert!((dense_back[[r, c]] - v).abs() <= 1e-12 * v.abs().max(1.0), "({r},{c})");
    }
    std::fs::remove_dir_all(&dir).ok();
}
