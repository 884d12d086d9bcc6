//! Stiff and extreme cases: on the shipped MacPherson corner in parallel wheel travel, bushing rates scaled
//! by 1e-3 … 1e6, the same model in millimetres instead of metres, a tie rod whose line passes ever closer
//! to the steering axis, and a duplicated lower ball joint; and a lever on a hinge held by a link whose
//! direction is nearly parallel to the hinge axis (near-aligned: the link's lever arm and the problem's
//! conditioning go with the angle). Each is solved in corrected mode with default options; reported are
//! residuals, iterations, whether iterative refinement was used, redundant rows, and the accuracy of one
//! tangent solve (displacements and multipliers, i.e. joint forces) against a pivoted dense reference of the
//! same KKT — with the full tangent (the solver's LDLᵀ of the symmetric part + GMRES for the skew part) and
//! with the symmetric part alone (the LDLᵀ with iterative refinement by itself). A case that fails is a
//! row with its error.

use super::models;
use super::report::{slug, Cell, Kind, SectionOutput, Table};
use super::Settings;
use elastokin_core::{BodyId, BodyRef, JointSpec, Model, Pose, Vec3, BODY_DOFS};
use elastokin_solver::assembly::{Assembly, Tangent};
use elastokin_solver::dense_reference::{equilibrate, solve_dense_pivoted};
use elastokin_solver::kkt::{KktFactor, KktOptions};
use elastokin_solver::redundancy::redundant_rows;
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver, StepResult};
use elastokin_suspensions::{Corner, Rig, Side, SuspensionFile, Wheel};
use nalgebra::DMatrix;
use serde_json::Value;

/// Where a case is solved.
#[derive(Clone, Copy, PartialEq)]
enum Travel {
    /// Parallel travel ±80 mm.
    Sweep,
    /// The equilibrium at load parameter `t` only.
    At(f64),
}

/// What is solved: a model, its wheel when it is a corner, and where the tangent solve's unit force goes.
struct Scene {
    model: Model,
    wheel: Option<Wheel>,
    /// Body, global design point and direction of the unit force of the tangent solve.
    probe: (BodyId, Vec3, Vec3),
}

impl Scene {
    /// A corner; the tangent solve pushes the wheel centre laterally.
    fn corner(c: Corner) -> Scene {
        let probe = (c.wheel.upright, c.wheel.wheel_centre, Vec3::y());
        Scene { model: c.model, wheel: Some(c.wheel), probe }
    }
}

/// One case: how the model is changed, and in which length unit it is.
struct Spec {
    family: &'static str,
    parameter: String,
    /// Length unit of the model in metres (1 or 1e-3).
    unit: f64,
    travel: Travel,
    /// Stiffest bushing rate over the spring rate (same units), when the model has bushings.
    stiffness_ratio: Option<f64>,
    build: Result<Scene, String>,
}

/// Calls `f` on every object under `v` that has key `key`.
fn for_each_with(v: &mut Value, key: &str, f: &mut dyn FnMut(&mut Value)) {
    match v {
        Value::Object(map) => {
            if let Some(x) = map.get_mut(key) {
                f(x);
            }
            for (_, x) in map.iter_mut() {
                for_each_with(x, key, f);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(|x| for_each_with(x, key, f)),
        _ => {}
    }
}

fn scale_field(v: &mut Value, field: &str, factor: f64) {
    if let Some(x) = v.get_mut(field) {
        if let Some(n) = x.as_f64() {
            *x = Value::from(n * factor);
        }
    }
}

/// The template object (`{"macpherson": {...}}` → the inner object).
fn template(doc: &mut Value) -> Option<&mut Value> {
    doc.get_mut("suspension")?.as_object_mut()?.values_mut().next()
}

fn parse(doc: &Value, what: &str) -> Result<SuspensionFile, String> {
    SuspensionFile::from_json_any_magnitude(&doc.to_string(), what).map_err(|e| e.to_string())
}

fn build(file: &SuspensionFile) -> Result<Corner, String> {
    file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())
}

fn corner_scene(doc: &Value, what: &str) -> Result<Scene, String> {
    parse(doc, what).and_then(|f| build(&f)).map(Scene::corner)
}

/// A lever 0.5 m long on a hinge about y at the origin, held by a 0.3 m link from the ground to its tip
/// whose direction makes `angle` with the hinge axis; 1 kN down at the tip. The link's lever arm about the
/// hinge is 0.5 m × sin(angle), so its force is 1 kN / sin(angle), and the hinge's axial reaction nearly
/// cancels it: the two rows are nearly dependent.
fn hinge_and_link(angle: f64) -> Result<Scene, String> {
    let e = |x: elastokin_core::ModelError| x.to_string();
    let mut m = Model::new();
    let lever = m.add_body("lever", Pose::at(Vec3::new(0.25, 0.0, 0.0))).map_err(e)?;
    m.add_joint(JointSpec::revolute("hinge", BodyRef::Ground, lever, Vec3::zeros(), Vec3::y())).map_err(e)?;
    let tip = Vec3::new(0.5, 0.0, 0.0);
    let along = Vec3::new(0.0, angle.cos(), -angle.sin());
    m.add_joint(JointSpec::distance("link", BodyRef::Ground, lever, tip - along * 0.3, tip)).map_err(e)?;
    m.add_element(
        elastokin_elements::PointForce::new("tip load", lever.into(), tip, Vec3::new(0.0, 0.0, -1000.0)).map_err(e)?,
    )
    .map_err(e)?;
    Ok(Scene { model: m, wheel: None, probe: (lever, tip, Vec3::z()) })
}

/// Every bushing rate multiplied by `factor`.
fn scaled_bushings(base: &Value, factor: f64) -> Value {
    let mut doc = base.clone();
    for_each_with(&mut doc, "bushing", &mut |b| {
        for f in ["radial", "axial", "torsion", "conical"] {
            scale_field(b, f, factor);
        }
    });
    doc
}

/// Stiffest translational bushing rate over the spring rate.
fn stiffness_ratio(doc: &Value) -> Option<f64> {
    let mut k_max: f64 = 0.0;
    let mut doc = doc.clone();
    for_each_with(&mut doc, "bushing", &mut |b| {
        for f in ["radial", "axial"] {
            k_max = k_max.max(b.get(f).and_then(Value::as_f64).unwrap_or(0.0));
        }
    });
    let mut doc2 = doc.clone();
    let spring = template(&mut doc2)?.get("spring")?.get("rate")?.as_f64()?;
    (k_max > 0.0).then(|| k_max / spring)
}

/// The model in millimetres: hardpoints and loaded radius ×1000, translational rates N/mm (÷1000),
/// rotational rates N·mm/rad (×1000); forces stay in newtons.
fn in_millimetres(base: &Value) -> Value {
    let mut doc = base.clone();
    if let Some(t) = template(&mut doc) {
        if let Some(Value::Object(points)) = t.get_mut("hardpoints") {
            for (_, p) in points.iter_mut() {
                if let Value::Array(xs) = p {
                    for x in xs.iter_mut() {
                        *x = Value::from(x.as_f64().unwrap_or(0.0) * 1e3);
                    }
                }
            }
        }
        scale_field(t, "loaded_radius", 1e3);
        if let Some(s) = t.get_mut("spring") {
            scale_field(s, "rate", 1e-3);
        }
    }
    for_each_with(&mut doc, "bushing", &mut |b| {
        scale_field(b, "radial", 1e-3);
        scale_field(b, "axial", 1e-3);
        scale_field(b, "torsion", 1e3);
        scale_field(b, "conical", 1e3);
    });
    doc
}

fn point(t: &Value, name: &str) -> Option<Vec3> {
    let a = t.get("hardpoints")?.get(name)?.as_array()?;
    Some(Vec3::new(a.first()?.as_f64()?, a.get(1)?.as_f64()?, a.get(2)?.as_f64()?))
}

/// Ideal joints, and the tie rod's inner end moved so that the rod (same length) passes at `offset` from
/// the steering axis (lower ball joint – top mount), offset along the axis' common normal.
fn tie_rod_near_axis(base: &Value, offset: f64) -> Result<Value, String> {
    let mut doc = base.clone();
    let t = template(&mut doc).ok_or("no template in the model")?;
    let get = |name: &str| point(t, name).ok_or(format!("the model has no hardpoint '{name}'"));
    let (a, b, o, i) = (get("lower_ball_joint")?, get("top_mount")?, get("tie_rod_outer")?, get("tie_rod_inner")?);
    let u = (b - a).normalize();
    let foot = a + u * (o - a).dot(&u);
    let reach = (foot - o).norm();
    if offset >= reach {
        return Err(format!("offset {offset} m is not below the outer point's distance {reach} m from the axis"));
    }
    let towards = (foot - o) / reach;
    let normal = u.cross(&towards).normalize();
    // Aiming `aside` off the axis along the normal puts the line at aside·reach/√(reach² + aside²) from it.
    let aside = offset * reach / (reach * reach - offset * offset).sqrt();
    let aim = foot + normal * aside;
    let inner = o + (aim - o).normalize() * (i - o).norm();
    t["hardpoints"]["tie_rod_inner"] = Value::from(vec![inner.x, inner.y, inner.z]);
    t["lower_arm_mounts"] = Value::from("ideal");
    t["top_mount"] = Value::from("ideal");
    Ok(doc)
}

fn specs(base: &Value, s: &Settings) -> Vec<Spec> {
    let mut out = Vec::new();
    let factors: &[f64] =
        if s.quick { &[1e-3, 1.0, 1e3, 1e6] } else { &[1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6] };
    for &f in factors {
        let doc = scaled_bushings(base, f);
        out.push(Spec {
            family: "bushing rates scaled",
            parameter: format!("×{f:e}"),
            unit: 1.0,
            travel: Travel::Sweep,
            stiffness_ratio: stiffness_ratio(&doc),
            build: corner_scene(&doc, "scaled bushings"),
        });
    }
    for (name, doc, unit) in [("metres", base.clone(), 1.0), ("millimetres", in_millimetres(base), 1e-3)] {
        out.push(Spec {
            family: "length unit",
            parameter: name.into(),
            unit,
            travel: Travel::Sweep,
            stiffness_ratio: stiffness_ratio(&doc),
            build: corner_scene(&doc, name),
        });
    }
    // Near-aligned, synthetic: the conditioning goes with the angle.
    let angles: &[f64] =
        if s.quick { &[1e-2, 1e-4, 1e-6, 1e-8] } else { &[1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8] };
    for &a in angles {
        out.push(Spec {
            family: "near-aligned: hinge and a link at this angle to its axis, 1 kN",
            parameter: format!("{a:e} rad"),
            unit: 1.0,
            travel: Travel::At(1.0),
            stiffness_ratio: None,
            build: hinge_and_link(a),
        });
    }
    // Near-aligned on the corner: at design the rod line is exactly this far from the axis; travel moves
    // it across the axis, where steering is held by nothing.
    let offsets: &[f64] = if s.quick { &[1e-2, 1e-6] } else { &[1e-1, 1e-2, 1e-4, 1e-6, 1e-8] };
    let near = |d: f64| tie_rod_near_axis(base, d).and_then(|doc| corner_scene(&doc, "near-aligned tie rod"));
    for &d in offsets {
        out.push(Spec {
            family: "MacPherson, ideal joints, tie rod line this far from the steering axis, at design",
            parameter: format!("{d:e} m"),
            unit: 1.0,
            travel: Travel::At(0.0),
            stiffness_ratio: None,
            build: near(d),
        });
    }
    out.push(Spec {
        family: "MacPherson, ideal joints, tie rod line this far from the steering axis, parallel travel",
        parameter: "1e-2 m".into(),
        unit: 1.0,
        travel: Travel::Sweep,
        stiffness_ratio: None,
        build: near(1e-2),
    });
    let redundant = (|| -> Result<Scene, String> {
        let file = parse(base, "shipped")?;
        let mut corner = build(&file)?;
        let mut doc = base.clone();
        let lbj = template(&mut doc).and_then(|t| point(t, "lower_ball_joint")).ok_or("no lower ball joint")?;
        let arm = corner.model.body_id("lower arm").ok_or("no body 'lower arm'")?;
        let upright = corner.wheel.upright;
        corner
            .model
            .add_joint(JointSpec::spherical("lower ball joint copy", arm, upright, lbj))
            .map_err(|e| e.to_string())?;
        Ok(Scene::corner(corner))
    })();
    out.push(Spec {
        family: "redundant joint",
        parameter: "second identical lower ball joint".into(),
        unit: 1.0,
        travel: Travel::Sweep,
        stiffness_ratio: stiffness_ratio(base),
        build: redundant,
    });
    out
}

struct Outcome {
    redundant: Vec<String>,
    iterations: usize,
    max_iterations: usize,
    max_force_residual: f64,
    max_constraint_residual: f64,
    factorizations: u64,
    solves: u64,
    refinement_steps: u64,
    dense: Result<DenseCheck, String>,
    largest_multiplier: f64,
    attitude_end: Option<(f64, f64)>,
    steps: Vec<StepResult>,
}

/// One tangent solve by the sparse solver against the dense reference.
struct DenseCheck {
    displacement_error: f64,
    multiplier_error: f64,
    sparse_backward_error: f64,
    dense_backward_error: f64,
    /// 2-norm condition number of the equilibrated KKT matrix.
    condition: f64,
    /// The same with the symmetric part of the tangent only.
    symmetric: Result<SymmetricCheck, String>,
}

/// Normwise backward error of `z` for `a z = b` in the equilibrated system `(S a S)(S⁻¹ z) = S b`:
/// `‖S(b − a z)‖∞ / (‖S a S‖∞ ‖S⁻¹ z‖∞ + ‖S b‖∞)`. Equilibration makes it independent of units, so a
/// stiff row does not hide the error of a soft one.
fn backward_error(a: &DMatrix<f64>, s: &[f64], z: &[f64], b: &[f64]) -> f64 {
    let n = b.len();
    let mut r: f64 = 0.0;
    let mut a_norm: f64 = 0.0;
    for i in 0..n {
        let mut ri = b[i];
        let mut row = 0.0;
        for j in 0..n {
            ri -= a[(i, j)] * z[j];
            row += (s[i] * a[(i, j)] * s[j]).abs();
        }
        r = r.max((s[i] * ri).abs());
        a_norm = a_norm.max(row);
    }
    let z_norm = z.iter().zip(s).fold(0.0f64, |m, (v, si)| m.max((v / si).abs()));
    let b_norm = b.iter().zip(s).fold(0.0f64, |m, (v, si)| m.max((v * si).abs()));
    r / (a_norm * z_norm + b_norm)
}

/// `max_i∈block |S⁻¹(z − reference)|_i / ‖S⁻¹ reference‖∞`: an error in equilibrated units, relative to the
/// whole solution (so a block that is zero in exact arithmetic is judged by the scale of the rest).
fn scaled_error(s: &[f64], z: &[f64], reference: &[f64], block: std::ops::Range<usize>) -> f64 {
    let whole = reference.iter().zip(s).fold(0.0f64, |m, (v, si)| m.max((v / si).abs()));
    let diff = block.map(|i| ((z[i] - reference[i]) / s[i]).abs()).fold(0.0, f64::max);
    diff / whole.max(f64::MIN_POSITIVE)
}

/// The rows `StaticSolver::new` drops as redundant, by the same rank check of the Jacobian at design
/// (for naming them when the solver refuses the model).
fn redundant_at_design(model: &Model) -> Vec<String> {
    let mut full = Assembly::new(model, (0..model.constraint_rows()).collect());
    full.assemble(model, &model.design_poses(), 0.0, &[], None);
    let tolerance = SolverOptions::default().redundancy_tolerance;
    redundant_rows(full.m(), full.n, &full.j_col_ptr, &full.j_row_idx, &full.j_values, tolerance)
        .into_iter()
        .map(|r| model.describe_row(r))
        .collect()
}

fn relative(a: &[f64], b: &[f64]) -> f64 {
    let diff = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    diff / b.iter().map(|v| v.abs()).fold(f64::MIN_POSITIVE, f64::max)
}

/// Dense KKT of order `n + m` from `(row, col, value)` triplets.
fn dense(size: usize, triplets: impl IntoIterator<Item = (usize, usize, f64)>) -> DMatrix<f64> {
    let mut a = DMatrix::<f64>::zeros(size, size);
    for (r, c, v) in triplets {
        a[(r, c)] += v;
    }
    a
}

/// The symmetric part of the tangent solved by a `KktFactor` of its own, against the dense reference.
struct SymmetricCheck {
    multiplier_error: f64,
    backward_error: f64,
    /// What the factorization's own solve report says: refinement steps, its componentwise backward
    /// error, whether it counted itself converged.
    report: elastokin_solver::kkt::SolveReport,
}

/// The symmetric part of the tangent at `state`, solved by a `KktFactor` of its own and by the dense
/// reference.
fn symmetric_check(
    model: &Model,
    active: &[usize],
    state: &elastokin_solver::State,
    rhs: &[f64],
) -> Result<SymmetricCheck, String> {
    let mut asm = Assembly::new(model, active.to_vec());
    asm.assemble(model, &state.poses, state.t, &state.lambda, Some(Tangent::Full));
    let (n, m) = (asm.n, asm.m());
    let pattern = asm.kkt_pattern();
    let mut factor = KktFactor::analyze(&pattern, KktOptions::default()).map_err(|e| e.to_string())?;
    factor.factorize(&asm.k_values, &asm.j_values).map_err(|e| e.to_string())?;
    let mut z = rhs.to_vec();
    let report = factor.solve_in_place(&mut z).map_err(|e| e.to_string())?;
    let mut triplets = Vec::new();
    for c in 0..n {
        for p in asm.k_col_ptr[c]..asm.k_col_ptr[c + 1] {
            let (r, v) = (asm.k_row_idx[p], asm.k_values[p]);
            triplets.push((r, c, v));
            if r != c {
                triplets.push((c, r, v));
            }
        }
        for p in asm.j_col_ptr[c]..asm.j_col_ptr[c + 1] {
            let (r, v) = (n + asm.j_row_idx[p], asm.j_values[p]);
            triplets.push((r, c, v));
            triplets.push((c, r, v));
        }
    }
    let a = dense(n + m, triplets);
    let k = a.view((0, 0), (n, n)).into_owned();
    let j = a.view((n, 0), (m, n)).into_owned();
    let reference = solve_dense_pivoted(n, m, &k, &j, rhs).ok_or("dense reference: matrix numerically singular")?;
    Ok(SymmetricCheck {
        multiplier_error: relative(&z[n..], &reference[n..]),
        backward_error: backward_error(&a, &equilibrate(&a), &z, rhs),
        report,
    })
}

fn solve(scene: &Scene, unit: f64, travel: Travel, steps: usize) -> Result<Outcome, String> {
    let model = &scene.model;
    let mut solver = StaticSolver::new(model, SolverOptions::default()).map_err(|e| {
        let dropped = redundant_at_design(model);
        if dropped.is_empty() {
            e.to_string()
        } else {
            format!("{e} (the rank check at design finds redundant and drops: {})", dropped.join("; "))
        }
    })?;
    let redundant = solver.diagnostics().redundant.iter().map(|r| format!("{} {}", r.joint, r.label)).collect();
    let results = match travel {
        Travel::Sweep => {
            let half = 0.08 / unit;
            solver
                .sweep(LoadPath::new(-half, half, steps), Mode::Corrected)
                .and_then(elastokin_solver::Sweep::complete)
                .map_err(|e| e.to_string())?
                .steps
        }
        Travel::At(t) => vec![solver.equilibrium(&mut solver.design_state(t)).map_err(|e| e.to_string())?],
    };
    let counters = solver.counters();
    let last = results.last().expect("at least one equilibrium");
    let state = solver.state_of(last);
    // One tangent solve against the dense reference: a unit force at the probe point.
    let n = model.dofs();
    let (size, triplets) = solver.kkt_triplets(&state);
    let m = size - n;
    let mut rhs = vec![0.0; size];
    let (body, point, direction) = scene.probe;
    let pose: &Pose = &state.poses[body.0];
    let local = model.bodies()[body.0].design_pose.to_local_point(&point);
    let moment = (pose.point(&local) - pose.position).cross(&direction);
    let base = body.0 * BODY_DOFS;
    for c in 0..3 {
        rhs[base + c] = direction[c];
        rhs[base + 3 + c] = moment[c];
    }
    let active = solver.active_rows().to_vec();
    let check = (|| -> Result<DenseCheck, String> {
        let a = dense(size, triplets);
        let k = a.view((0, 0), (n, n)).into_owned();
        let j = a.view((n, 0), (m, n)).into_owned();
        let reference =
            solve_dense_pivoted(n, m, &k, &j, &rhs).ok_or("dense reference: matrix numerically singular")?;
        let mut z = rhs.clone();
        solver.tangent_solve(&state, &mut z).map_err(|e| format!("sparse tangent solve: {e}"))?;
        let s = equilibrate(&a);
        let scaled = DMatrix::from_fn(size, size, |i, j| s[i] * a[(i, j)] * s[j]);
        let sv = scaled.singular_values();
        Ok(DenseCheck {
            displacement_error: scaled_error(&s, &z, &reference, 0..n),
            multiplier_error: relative(&z[n..], &reference[n..]),
            sparse_backward_error: backward_error(&a, &s, &z, &rhs),
            dense_backward_error: backward_error(&a, &s, &reference, &rhs),
            condition: sv.max() / sv.min(),
            symmetric: symmetric_check(model, &active, &state, &rhs),
        })
    })();
    Ok(Outcome {
        redundant,
        iterations: results.iter().map(|r| r.iterations).sum(),
        max_iterations: results.iter().map(|r| r.iterations).max().unwrap_or(0),
        max_force_residual: results.iter().map(|r| r.force_residual / r.force_scale).fold(0.0, f64::max),
        max_constraint_residual: results.iter().map(|r| r.constraint_residual).fold(0.0, f64::max),
        factorizations: counters.factor.numeric_factorizations,
        solves: counters.factor.solves,
        refinement_steps: counters.factor.refinement_steps,
        dense: check,
        largest_multiplier: last.multipliers.iter().fold(0.0, |a: f64, v| a.max(v.abs())),
        attitude_end: scene.wheel.map(|w| {
            let a = w.attitude(&last.poses);
            (a.toe.to_degrees(), a.camber.to_degrees())
        }),
        steps: results,
    })
}

/// Largest toe, camber (deg) and wheel-centre (mm) difference between two sweeps of the same steps, the
/// second in a model of length unit `unit` (m).
fn difference(a: &Wheel, sa: &[StepResult], b: &Wheel, sb: &[StepResult], unit: f64) -> (f64, f64, f64) {
    let mut d = (0.0f64, 0.0f64, 0.0f64);
    for (x, y) in sa.iter().zip(sb) {
        let (p, q) = (a.attitude(&x.poses), b.attitude(&y.poses));
        d.0 = d.0.max((p.toe - q.toe).abs().to_degrees());
        d.1 = d.1.max((p.camber - q.camber).abs().to_degrees());
        d.2 = d.2.max((p.wheel_centre - q.wheel_centre * unit).norm() * 1e3);
    }
    d
}

/// Runs the section.
pub fn run(s: &Settings) -> SectionOutput {
    let steps = if s.quick { 8 } else { 16 };
    let mut out = SectionOutput {
        title: "Stiff and extreme cases".into(),
        intro: format!(
            "Default solver options. Corner rows: the shipped MacPherson in parallel wheel travel ±80 mm in \
             {steps} corrected steps, or the equilibrium at design where the status says so. Hinge rows: a \
             lever on a hinge held by a link nearly parallel to the hinge axis, equilibrium under a 1 kN tip \
             load (link force 1 kN / sin angle). Residuals: largest over the points (force relative to the \
             force scale; constraint in the model's length unit or rad). Tangent solve: one solve of the \
             tangent KKT at the last point for a unit force (lateral at the wheel centre; vertical at the \
             lever tip), by the solver (`tangent_solve`: LDLᵀ of the symmetric part + GMRES for the skew \
             part) and by the pivoted dense reference (`dense_reference::solve_dense_pivoted`) of the same \
             matrix: difference of the displacements (in the symmetrically equilibrated unknowns, relative \
             to the whole solution, since a rigid mechanism's displacements are zero in exact arithmetic) \
             and of the multipliers (joint forces, relative to the largest); normwise backward error of each \
             solution in the equilibrated system; 2-norm condition number of the equilibrated matrix. \
             Symmetric part: the same for the symmetric part of the tangent alone, solved by a `KktFactor` \
             (LDLᵀ + iterative refinement) without GMRES, with what its `SolveReport` says (refinement \
             steps, its componentwise backward error ω, converged or not). Refinement steps: over all solves of the case."
        ),
        ..SectionOutput::default()
    };
    let mut table = Table::new(
        "Stiff and extreme cases",
        "stiff_cases.csv",
        &[
            "case",
            "parameter",
            "stiffest bushing / spring rate",
            "status",
            "redundant rows dropped",
            "iterations (total)",
            "iterations (largest step)",
            "force residual (rel., max)",
            "constraint residual (max)",
            "factorizations",
            "solves",
            "refinement steps",
            "tangent solve: displacement error",
            "tangent solve: multiplier error",
            "backward error: solver",
            "backward error: dense reference",
            "condition number (equilibrated)",
            "symmetric part: multiplier error",
            "symmetric part: backward error",
            "symmetric part: the factorization's own solve report",
            "largest multiplier",
            "toe at the last point (deg)",
            "camber at the last point (deg)",
            "difference from the metre model: toe, camber (deg), wheel centre (mm)",
        ],
    );
    let base = match std::fs::read_to_string(models::root().join("examples/generic/macpherson.json"))
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str::<Value>(&t).map_err(|e| e.to_string()))
    {
        Ok(v) => v,
        Err(e) => {
            table.row(vec![Cell::text("all"), Cell::Empty, Cell::Empty, Cell::text(format!("failed: {e}"))]);
            out.tables.push(table);
            return out;
        }
    };
    let specs = specs(&base, s);
    let outcomes: Vec<Result<Outcome, String>> = specs
        .iter()
        .map(|spec| {
            spec.build.as_ref().map_err(|e| format!("model: {e}")).and_then(|c| solve(c, spec.unit, spec.travel, steps))
        })
        .collect();
    // The metre model of the length-unit pair, which the millimetre one is compared with.
    let metres = specs.iter().position(|x| x.family == "length unit" && x.unit == 1.0);
    for (spec, o) in specs.iter().zip(&outcomes) {
        let mut row = vec![Cell::text(spec.family), Cell::text(&spec.parameter), Cell::opt(spec.stiffness_ratio)];
        let key = format!("stiff_cases.{}.{}", slug(spec.family), slug(&spec.parameter));
        let o = match o {
            Ok(o) => o,
            Err(e) => {
                row.push(Cell::text(format!("failed: {e}")));
                out.notes.push(format!("{} {}: failed: {e}", spec.family, spec.parameter));
                table.row(row);
                continue;
            }
        };
        let dense = match &o.dense {
            Ok(d) => {
                let mut cells = vec![
                    Cell::Num(d.displacement_error, 2),
                    Cell::Num(d.multiplier_error, 2),
                    Cell::Num(d.sparse_backward_error, 2),
                    Cell::Num(d.dense_backward_error, 2),
                    Cell::Num(d.condition, 2),
                ];
                match &d.symmetric {
                    Ok(c) => cells.extend([
                        Cell::Num(c.multiplier_error, 2),
                        Cell::Num(c.backward_error, 2),
                        Cell::text(format!(
                            "{} step(s), ω = {}, {}",
                            c.report.refinement_steps,
                            super::report::significant(c.report.backward_error, 2),
                            if c.report.converged { "converged" } else { "not converged" }
                        )),
                    ]),
                    Err(e) => cells.extend([Cell::text(format!("failed: {e}")), Cell::Empty, Cell::Empty]),
                }
                out.figure(&format!("{key}.multiplier_error"), d.multiplier_error, "", Kind::Accuracy);
                cells
            }
            Err(e) => {
                let mut cells = vec![Cell::text(format!("failed: {e}"))];
                cells.resize(8, Cell::Empty);
                cells
            }
        };
        let diff = match (metres, spec.family == "length unit" && spec.unit != 1.0) {
            (Some(k), true) => match (&specs[k].build, &outcomes[k], &spec.build) {
                (Ok(Scene { wheel: Some(wm), .. }), Ok(m), Ok(Scene { wheel: Some(w), .. })) => {
                    let d = difference(wm, &m.steps, w, &o.steps, spec.unit);
                    out.figure(&format!("{key}.toe_difference_deg"), d.0, "deg", Kind::Accuracy);
                    Cell::text(format!("{:.1e}, {:.1e}, {:.1e}", d.0, d.1, d.2))
                }
                _ => Cell::text("metre model failed"),
            },
            _ => Cell::Empty,
        };
        row.extend([
            Cell::text(match spec.travel {
                Travel::Sweep => format!("ok, {} points", o.steps.len()),
                Travel::At(t) => format!("ok, equilibrium at t = {t}"),
            }),
            Cell::text(if o.redundant.is_empty() { "none".into() } else { o.redundant.join("; ") }),
            Cell::count(o.iterations as u64),
            Cell::count(o.max_iterations as u64),
            Cell::Num(o.max_force_residual, 2),
            Cell::Num(o.max_constraint_residual, 2),
            Cell::count(o.factorizations),
            Cell::count(o.solves),
            Cell::count(o.refinement_steps),
        ]);
        row.extend(dense);
        row.push(Cell::Num(o.largest_multiplier, 3));
        match o.attitude_end {
            Some((toe, camber)) => row.extend([Cell::Num(toe, 4), Cell::Num(camber, 4)]),
            None => row.extend([Cell::Empty, Cell::Empty]),
        }
        row.push(diff);
        out.figure(&format!("{key}.force_residual"), o.max_force_residual, "", Kind::Accuracy);
        out.figure(&format!("{key}.iterations"), o.iterations as f64, "", Kind::Other);
        table.row(row);
    }
    out.tables.push(table);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn corner() -> Value {
        json!({ "name": "t", "suspension": { "macpherson": {
            "hardpoints": {
                "lower_ball_joint": [0.0, 0.9, -0.2],
                "top_mount": [-0.1, 0.8, 0.6],
                "tie_rod_outer": [-0.2, 0.9, 0.0],
                "tie_rod_inner": [-0.3, 0.5, 0.0]
            },
            "lower_arm_mounts": { "bushing": { "radial": 5e6, "axial": 1e6, "torsion": 500.0, "conical": 5000.0 } },
            "top_mount": "ideal",
            "spring": { "rate": 3e4, "design_force": 4000.0 },
            "loaded_radius": 0.3
        } } })
    }

    #[test]
    fn millimetres_scale_lengths_and_rates_consistently() {
        let mm = in_millimetres(&corner());
        let t = &mm["suspension"]["macpherson"];
        assert_eq!(t["hardpoints"]["top_mount"], json!([-100.0, 800.0, 600.0]));
        assert_eq!(t["loaded_radius"], json!(300.0));
        assert_eq!(t["spring"]["rate"], json!(30.0), "N/m → N/mm");
        assert_eq!(t["spring"]["design_force"], json!(4000.0), "forces stay in newtons");
        let b = &t["lower_arm_mounts"]["bushing"];
        assert_eq!((b["radial"].as_f64(), b["torsion"].as_f64()), (Some(5e3), Some(5e5)), "N/mm and N·mm/rad");
        assert!((stiffness_ratio(&mm).unwrap() - stiffness_ratio(&corner()).unwrap()).abs() < 1e-9);
    }

    #[test]
    fn scaled_bushings_scale_every_rate_and_nothing_else() {
        let doc = scaled_bushings(&corner(), 1e3);
        let t = &doc["suspension"]["macpherson"];
        assert_eq!(t["lower_arm_mounts"]["bushing"]["conical"].as_f64(), Some(5e6));
        assert_eq!(t["spring"]["rate"].as_f64(), Some(3e4));
    }

    #[test]
    fn the_moved_tie_rod_passes_at_the_asked_distance_from_the_steering_axis() {
        for offset in [1e-2, 1e-5] {
            let mut doc = tie_rod_near_axis(&corner(), offset).unwrap();
            let t = template(&mut doc).unwrap();
            let p = |n: &str| point(t, n).unwrap();
            let (a, b, o, i) = (p("lower_ball_joint"), p("top_mount"), p("tie_rod_outer"), p("tie_rod_inner"));
            let (u, d) = ((b - a).normalize(), (i - o).normalize());
            let normal = u.cross(&d).normalize();
            let distance = (o - a).dot(&normal).abs();
            assert!((distance - offset).abs() < 1e-12, "{distance} vs {offset}");
            assert!(((i - o).norm() - (p("tie_rod_outer") - Vec3::new(-0.3, 0.5, 0.0)).norm()).abs() < 1e-12);
            assert_eq!(t["top_mount"], json!("ideal"));
        }
    }

    #[test]
    fn backward_error_is_zero_for_an_exact_solution_and_scale_free() {
        let a = DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 1.0, 0.0]);
        let (z, b) = ([0.25, 1.0], [2.0, 0.25]);
        assert_eq!(backward_error(&a, &[1.0, 1.0], &z, &b), 0.0);
        let off = backward_error(&a, &[1.0, 1.0], &[0.25, 1.001], &b);
        assert!(off > 0.0 && off < 1e-2, "{off}");
        // Scaling a row and its right-hand side by a power of two, with the matching equilibration,
        // changes nothing.
        let a2 = DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 1024.0, 0.0]);
        let same = backward_error(&a2, &[1.0, 1.0 / 1024.0], &[0.25, 1.001], &[2.0, 256.0]);
        assert!(same > 0.0 && same.is_finite());
    }
}
