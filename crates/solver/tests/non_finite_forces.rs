//! A force that comes out NaN is no equilibrium. The residual's largest entry was taken with `f64::max`,
//! which passes a NaN over: a block on its mount with a NaN moment on it was reported in equilibrium with a
//! force residual of 0, and a sweep walked on with the NaN in it. Now every path refuses it and names the
//! element.

use elastokin_core::{
    BodyRef, ElementEval, ElementReport, ElementRole, ForceElement, Mat3, Model, ModelError, Pose, Vec3,
};
use elastokin_elements::Bushing;
use elastokin_solver::{ArcStep, LoadPath, Mode, SolverError, SolverOptions, StaticSolver};

/// A moment about z on `body` that is NaN (or infinite) once the load parameter passes `from`, zero before.
#[derive(Debug, Clone, PartialEq)]
struct BrokenMoment {
    body: BodyRef,
    from: f64,
    value: f64,
}

impl ForceElement for BrokenMoment {
    fn name(&self) -> &str {
        "broken moment"
    }
    fn bodies(&self) -> [BodyRef; 2] {
        [BodyRef::Ground, self.body]
    }
    fn role(&self) -> ElementRole {
        ElementRole::Load
    }
    fn bind(&mut self, _: &Pose, _: &Pose) -> Result<(), ModelError> {
        Ok(())
    }
    fn evaluate(&self, _: &Pose, _: &Pose, t: f64, out: &mut ElementEval, _with_stiffness: bool) {
        out.force.fill(0.0);
        out.stiffness.fill(0.0);
        // Body j's rotation about z.
        out.force[11] = if t > self.from { self.value } else { 0.0 };
    }
    fn report(&self, _: &Pose, _: &Pose, t: f64) -> ElementReport {
        let torque = Vec3::new(0.0, 0.0, if t > self.from { self.value } else { 0.0 });
        ElementReport { force: Vec3::zeros(), torque, deflection: Vec3::zeros(), rotation: Vec3::zeros() }
    }
}

/// A block on a six-axis mount to the ground, with the broken moment on it.
fn block(from: f64, value: f64) -> Model {
    let mut m = Model::new();
    let b = m.add_body("block", Pose::at(Vec3::zeros())).unwrap();
    let mount = Bushing::new(
        "mount",
        BodyRef::Ground,
        b.into(),
        Vec3::zeros(),
        Mat3::identity(),
        Vec3::repeat(1e5),
        Vec3::repeat(1e3),
    )
    .unwrap();
    m.add_element(mount).unwrap();
    m.add_element(BrokenMoment { body: b.into(), from, value }).unwrap();
    m
}

fn assert_named(result: Result<impl std::fmt::Debug, SolverError>, after: f64) {
    match result {
        Err(e @ SolverError::NonFiniteForce { .. }) => {
            let SolverError::NonFiniteForce { element, t } = &e else { unreachable!() };
            assert_eq!(element, "broken moment");
            assert!(*t > after && *t <= 1.0, "{e}");
            assert!(e.to_string().starts_with("the force of 'broken moment' is no finite number at"), "{e}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_nan_force_at_design_is_no_equilibrium_and_its_element_is_named() {
    for value in [f64::NAN, f64::INFINITY] {
        let model = block(-1.0, value);
        let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
        let mut state = solver.design_state(0.0);
        assert_named(solver.equilibrium(&mut state), -1.0);
    }
}

#[test]
fn a_force_that_turns_nan_on_the_path_stops_every_stepping_mode_there() {
    for value in [f64::NAN, f64::INFINITY] {
        let model = block(0.5, value);
        for reuse in [false, true] {
            let options = SolverOptions { reuse_factorization: reuse, ..SolverOptions::default() };
            for mode in [Mode::Corrected, Mode::Paper] {
                let mut solver = StaticSolver::new(&model, options.clone()).unwrap();
                assert_named(solver.sweep(LoadPath::new(0.0, 1.0, 4), mode), 0.5);
            }
            let mut solver = StaticSolver::new(&model, options).unwrap();
            assert_named(solver.arc_length_sweep(LoadPath::new(0.0, 1.0, 4), ArcStep::Load(0.25)), 0.5);
        }
    }
}
