//! A swing arm on a rubber pivot bushing, held by a coil spring and loaded by a vertical force at the
//! wheel centre: the vertical-force sweep of the paper, walked in both modes.
//!
//! Run with `cargo run --example swing_arm`.

use elastokin::elements::{Bushing, Characteristic, CoilSpring, PointForce, SpringLength};
use elastokin::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Hardpoints (ISO 8855, metres): pivot on the chassis, wheel centre 0.45 m behind it, spring seats.
    let pivot = Vec3::new(0.0, 0.55, 0.0);
    let wheel_centre = Vec3::new(-0.45, 0.80, -0.02);
    let seat_arm = Vec3::new(-0.30, 0.62, 0.0);
    let seat_chassis = Vec3::new(-0.30, 0.62, 0.30);

    let mut model = Model::new();
    let arm = model.add_body("swing arm", Pose::at((pivot + wheel_centre) / 2.0))?;
    // Pivot bushing: local x along the pivot axis (lateral), radial 5 kN/mm, axial 1 kN/mm,
    // torsion about the axis 10 N·m/deg, conical 100 N·m/deg.
    let axis = Vec3::y();
    let frame = Mat3::from_columns(&[axis, Vec3::z().cross(&axis), Vec3::z()]);
    model.add_element(Bushing::new(
        "pivot bushing",
        BodyRef::Ground,
        arm.into(),
        pivot,
        frame,
        Vec3::new(1e6, 5e6, 5e6),
        Vec3::new(10.0f64.to_degrees(), 100.0f64.to_degrees(), 100.0f64.to_degrees()),
    )?)?;
    // Coil spring 60 N/mm, 3 kN of preload at design.
    model.add_element(CoilSpring::seated(
        "spring",
        [(BodyRef::Ground, seat_chassis), (arm.into(), seat_arm)],
        Characteristic::Rate(60e3),
        SpringLength::DesignForce(3000.0),
    )?)?;
    // Vertical wheel force: 2 kN of corner load plus 1.5 kN per unit load parameter (t from −1 to 1),
    // the paper's vertical force sweep.
    model.add_element(
        PointForce::new("wheel force", arm.into(), wheel_centre, Vec3::new(0.0, 0.0, 1500.0))?
            .with_constant(Vec3::new(0.0, 0.0, 2000.0))?,
    )?;

    let mut solver = StaticSolver::new(&model, SolverOptions::default())?;
    let path = LoadPath::new(-1.0, 1.0, 20);
    // `complete` refuses a path that stopped at a limit point (a load the arm cannot carry).
    let corrected = solver.sweep(path, Mode::Corrected)?.complete()?;
    let paper = solver.sweep(path, Mode::Paper)?.complete()?;

    println!("vertical force sweep of a swing arm (wheel-centre height, arm pitch, spring and bushing loads)");
    println!(
        "{:>8} {:>12} {:>12} {:>10} {:>12} {:>12} {:>10}",
        "Fz [N]", "dz [mm]", "paper dz", "iters", "spring [N]", "bushing [N]", "pitch [°]"
    );
    for (c, p) in corrected.steps.iter().zip(&paper.steps) {
        let local_wc = model.bodies()[0].design_pose.to_local_point(&wheel_centre);
        let z = c.poses[0].point(&local_wc).z - wheel_centre.z;
        let zp = p.poses[0].point(&local_wc).z - wheel_centre.z;
        let reports = c.element_reports(&model);
        let pitch = c.poses[0].orientation.scaled_axis().y.to_degrees();
        println!(
            "{:>8.0} {:>12.4} {:>12.4} {:>10} {:>12.1} {:>12.1} {:>10.4}",
            2000.0 + 1500.0 * c.t,
            z * 1e3,
            zp * 1e3,
            c.iterations,
            reports[1].force.norm(),
            reports[0].force.norm(),
            pitch
        );
    }
    let c = solver.counters();
    println!(
        "symbolic analyses {}, numeric factorizations {}, solves {}",
        c.factor.symbolic_analyses, c.factor.numeric_factorizations, c.factor.solves
    );
    Ok(())
}
