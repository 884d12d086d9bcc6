//! K&C analyses: load paths walked by the engine, reduced to wheel characteristics.

use crate::corner::{Corner, Rig, SteeringGeometry, WheelAttitude};
use elastokin_core::{Model, Vec3};
use elastokin_solver::{ArcStep, LoadPath, Mode, SolverError, SolverOptions, State, StaticSolver, StepResult, Sweep};
use serde::{Deserialize, Serialize};

/// One row of a driven sweep (wheel travel or steering).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TravelRow {
    /// The driven travel (m): wheel travel (bump positive) or rack travel (towards +y).
    pub travel: f64,
    /// Wheel attitude.
    pub attitude: WheelAttitude,
    /// Steering-axis geometry.
    pub steering: SteeringGeometry,
    /// Vertical force the rig applies at the wheel centre to hold its height (N, up +); zero when the
    /// rig does not hold the height. Its slope against wheel travel is the wheel rate.
    pub wheel_load: f64,
    /// Spring deflection `L − L₀` (m, compression negative). Its slope against wheel travel is the
    /// (signed) spring motion ratio.
    pub spring_deflection: f64,
}

/// Parallel wheel travel from `from` to `to` metres in `steps` steps (the corner must be built with
/// [`Rig::WheelTravel`]). Starts from the equilibrium at `from`.
pub fn parallel_wheel_travel(
    corner: &Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    driven_sweep(corner, Rig::WheelTravel, from, to, steps, mode)
}

/// Steering: rack travel from `from` to `to` metres (towards +y) with the wheel-centre height held (the
/// corner must be built with [`Rig::Steering`]). The rows' `travel` is the rack travel.
pub fn steering(corner: &Corner, from: f64, to: f64, steps: usize, mode: Mode) -> Result<Vec<TravelRow>, SolverError> {
    driven_sweep(corner, Rig::Steering, from, to, steps, mode)
}

/// The vertical force the rig applies at the wheel centre to hold the corner at design (N, up +): the
/// corner load the design position carries. The corner must hold its wheel-centre height
/// ([`Rig::WheelTravel`] at `t = 0`, or [`Rig::HeightHeld`]).
pub fn design_wheel_load(corner: &Corner) -> Result<f64, SolverError> {
    require_rig(corner, &[Rig::WheelTravel, Rig::HeightHeld])?;
    let Some(driver) = corner.model.joint_id("wheel travel") else {
        return Err(SolverError::InvalidInput { what: "corner", why: "it has no \"wheel travel\" driver".into() });
    };
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(0.0);
    let step = solver.equilibrium(&mut state)?;
    Ok(step.joint_reactions(&corner.model)[driver.0].force.z)
}

/// Refuses a corner held differently from what the analysis needs: `rigs` lists the rigs it accepts.
fn require_rig(corner: &Corner, rigs: &[Rig]) -> Result<(), SolverError> {
    if rigs.contains(&corner.rig) {
        return Ok(());
    }
    let held = |rig: &Rig| match rig {
        Rig::WheelTravel => "the wheel-centre height driven",
        Rig::Steering => "the rack driven and the wheel-centre height held",
        Rig::HeightHeld => "the wheel-centre height held",
        Rig::Free => "the wheel free on its spring",
    };
    let accepted: Vec<&str> = rigs.iter().map(held).collect();
    Err(SolverError::InvalidInput {
        what: "corner",
        why: format!(
            "this analysis needs the corner on the rig with {}, but it is held with {}",
            accepted.join(" or "),
            held(&corner.rig)
        ),
    })
}

/// Slope of `y` against `x` at `x = at` over sweep rows (in either order): a central difference of the
/// rows on either side when a row sits exactly at `at`, else the chord of the two rows that bracket it.
/// `None` when `at` is outside the rows' range or there are fewer than two rows.
pub fn slope_at<R>(rows: &[R], at: f64, x: impl Fn(&R) -> f64, y: impl Fn(&R) -> f64) -> Option<f64> {
    let xs: Vec<f64> = rows.iter().map(&x).collect();
    let (a, b) = match xs.iter().position(|&v| v == at) {
        Some(k) if rows.len() >= 2 => (k.saturating_sub(1), (k + 1).min(rows.len() - 1)),
        Some(_) => return None,
        None => {
            let i = xs.windows(2).position(|w| (w[0] - at) * (w[1] - at) < 0.0)?;
            (i, i + 1)
        }
    };
    Some((y(&rows[b]) - y(&rows[a])) / (xs[b] - xs[a]))
}

fn driven_sweep(
    corner: &Corner,
    rig: Rig,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<TravelRow>, SolverError> {
    whole(driven_sweep_with(corner, rig, from, to, steps, mode, SweepExtras::default())?)
}

/// What a sweep can do besides walking its rows: read more at every step, at the cost of more
/// factorizations, and go on through a limit point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SweepExtras {
    /// Every row read again one exact Newton iteration away ([`StaticSolver::newton_correction`]): the
    /// difference is the row's error estimate. One factorization per row.
    pub error_estimate: bool,
    /// The 6×6 wheel compliance ([`wheel_compliance`]) at every step. One factorization and six
    /// back-substitutions per row.
    pub compliance: bool,
    /// What to do at a limit point (a load the corner cannot carry, a travel its linkage cannot reach):
    /// `None` stops there; `Some(step)` follows the path on through it by arc length
    /// ([`StaticSolver::arc_length_sweep_from`]) from the last step before it, with steps of `step` in the
    /// sweep's own unit (N, N·m or m): the change of load or travel of the first arc-length step
    /// ([`ArcStep::Load`]). At most [`MAX_ARC_STEPS_PER_RANGE`] steps of that size per range are taken,
    /// and at most [`crate::kc::MAX_STEPS`].
    pub through_limits: Option<f64>,
}

/// How many arc-length steps of [`SweepExtras::through_limits`] a path through a limit point may take,
/// per step that would span the sweep's range: room for the displacement the path makes where it
/// carries no more load.
pub const MAX_ARC_STEPS_PER_RANGE: f64 = 10.0;

/// Where a sweep met a limit point, and what it did there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepLimit {
    /// The load parameter of the limit point (N, N·m or m: the sweep's own unit), located to
    /// [`elastokin_solver::LIMIT_POINT_TOLERANCE`] of the range.
    pub at: f64,
    /// How the rows go on past it: `None` when the sweep stopped there (its last row is then the
    /// equilibrium at the limit point).
    pub through: Option<ArcLengthRows>,
}

/// The rows of a sweep that followed its path through a limit point by arc length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcLengthRows {
    /// Index of the first row walked by arc length: the rows before it are the sweep's own steps, up to
    /// the last one before the limit point.
    pub first_row: usize,
    /// The arc-length step asked for ([`SweepExtras::through_limits`]).
    pub step: f64,
    /// Whether the path left the range (its last row lies just beyond it); if not, it stopped after the
    /// most steps allowed.
    pub left_range: bool,
}

/// A sweep's rows, and what [`SweepExtras`] asked for, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepOutput<R> {
    /// The rows: every step of the sweep; up to the limit point, or through it, if it met one.
    pub rows: Vec<R>,
    /// Where the sweep met a limit point, if it did.
    pub limit: Option<SweepLimit>,
    /// The rows read one Newton iteration closer to the exact equilibrium at their load parameter.
    pub corrected: Option<Vec<R>>,
    /// The force and constraint residuals of every step: `(‖Φ_qᵀλ − Q‖∞ / force scale, ‖Φ‖∞)`.
    pub residuals: Vec<(f64, f64)>,
    /// The 6×6 wheel compliance at every step (rows: wheel-centre translation, rotation; columns: unit
    /// force, torque at the wheel centre).
    pub compliance: Option<Vec<[[f64; 6]; 6]>>,
}

/// The equilibria of a walked load path, and where it met a limit point.
#[derive(Debug, Clone, PartialEq)]
pub struct Walked {
    /// The equilibria in the order of the path: the start, then every step; at a limit point, the
    /// equilibrium there last, or the path on through it (see [`SweepLimit`]).
    pub steps: Vec<StepResult>,
    /// Where the path met a limit point, if it did.
    pub limit: Option<SweepLimit>,
}

/// Walks `path` from `state` in `mode`, as every analysis walks its sweep. At a limit point the rows
/// stop with the equilibrium there, or, with `through` (see [`SweepExtras::through_limits`]), go on
/// through it by arc length from the last step before it.
pub fn walk(
    solver: &mut StaticSolver,
    state: &mut State,
    path: LoadPath,
    mode: Mode,
    through: Option<f64>,
) -> Result<Walked, SolverError> {
    let Sweep { mut steps, limit, .. } = solver.sweep_from(state, path, mode)?;
    let Some(limit) = limit else { return Ok(Walked { steps, limit: None }) };
    let Some(step) = through else {
        steps.push(limit.step);
        return Ok(Walked { steps, limit: Some(SweepLimit { at: limit.t, through: None }) });
    };
    let range = (path.end - path.start).abs();
    if !(step.is_finite() && step > 0.0) {
        return Err(SolverError::InvalidInput {
            what: "arc-length step",
            why: format!("it must be a positive length in the sweep's own unit (N, N·m or m), got {step}"),
        });
    }
    let most = (MAX_ARC_STEPS_PER_RANGE * range / step).ceil().clamp(1.0, crate::kc::MAX_STEPS as f64) as usize;
    let first_row = steps.len();
    let mut from = solver.state_of(&steps[first_row - 1]);
    let arc =
        solver.arc_length_sweep_from(&mut from, LoadPath::new(path.start, path.end, most), ArcStep::Load(step))?;
    let (lo, hi) = (path.start.min(path.end), path.start.max(path.end));
    let left_range = arc.steps.last().is_some_and(|s| !(lo..=hi).contains(&s.t));
    // Its first equilibrium is the last step's.
    steps.extend(arc.steps.into_iter().skip(1));
    let through = Some(ArcLengthRows { first_row, step, left_range });
    Ok(Walked { steps, limit: Some(SweepLimit { at: limit.t, through }) })
}

/// The rows of a sweep that must cover its whole range: a limit point is [`SolverError::LimitPoint`].
pub(crate) fn whole<R>(out: SweepOutput<R>) -> Result<Vec<R>, SolverError> {
    match out.limit {
        Some(limit) => Err(SolverError::LimitPoint { reached: limit.at }),
        None => Ok(out.rows),
    }
}

/// Reads a sweep's rows, and what `extras` asks for, with the solver that walked it.
pub(crate) fn read_sweep<R>(
    solver: &mut StaticSolver,
    wheel: &crate::corner::Wheel,
    partner: Option<&crate::corner::Wheel>,
    walked: Walked,
    extras: SweepExtras,
    mut read: impl FnMut(&mut StaticSolver, &StepResult) -> Result<R, SolverError>,
) -> Result<SweepOutput<R>, SolverError> {
    let Walked { steps, limit } = walked;
    let steps = &steps[..];
    let rows = steps.iter().map(|s| read(solver, s)).collect::<Result<Vec<R>, _>>()?;
    let corrected = if extras.error_estimate {
        let mut out = Vec::with_capacity(steps.len());
        for s in steps {
            let c = solver.newton_correction(s)?;
            out.push(read(solver, &c)?);
        }
        Some(out)
    } else {
        None
    };
    let compliance = if extras.compliance {
        Some(
            steps
                .iter()
                .map(|s| compliance_with(solver, wheel, partner, &solver.state_of(s)))
                .collect::<Result<_, _>>()?,
        )
    } else {
        None
    };
    let residuals = steps.iter().map(|s| (s.force_residual / s.force_scale, s.constraint_residual)).collect();
    Ok(SweepOutput { rows, limit, corrected, residuals, compliance })
}

/// [`parallel_wheel_travel`] with [`SweepExtras`].
pub fn parallel_wheel_travel_with(
    corner: &Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<TravelRow>, SolverError> {
    driven_sweep_with(corner, Rig::WheelTravel, from, to, steps, mode, extras)
}

fn driven_sweep_with(
    corner: &Corner,
    rig: Rig,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<TravelRow>, SolverError> {
    require_rig(corner, &[rig])?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, extras.through_limits)?;
    let driver = corner.model.joint_id("wheel travel");
    let spring = corner.spring;
    read_sweep(&mut solver, &corner.wheel, corner.partner.as_ref(), walked, extras, |_, s| {
        Ok(TravelRow {
            travel: s.t,
            attitude: corner.wheel.attitude(&s.poses),
            steering: corner.wheel.steering_geometry(&s.poses),
            wheel_load: driver.map_or(0.0, |d| s.joint_reactions(&corner.model)[d.0].force.z),
            spring_deflection: spring.map_or(0.0, |e| s.element_reports(&corner.model)[e.0].deflection.x),
        })
    })
}

/// The 6×6 compliance of the wheel at the equilibrium of load parameter `t`: column `k` is the response
/// `(Δ wheel centre, Δ rotation)` to a unit force (k < 3, N, global axes) or unit torque (k ≥ 3, N·m) at
/// the wheel centre, in m/N and rad/(N·m). It is the inverse tangent of the constrained system, so it
/// costs one factorization and six back-substitutions. Drivers present in the corner stay held (a
/// wheel-travel driver makes the vertical row and column zero, as on a K&C rig holding the wheel-centre
/// height). With a partner wheel (a solid axle) each unit load acts on both wheels alike, in phase, as the
/// load sweeps apply them; the response is the corner's own wheel's.
pub fn wheel_compliance(corner: &Corner, t: f64) -> Result<[[f64; 6]; 6], SolverError> {
    Ok(compliance_at(corner, t)?.0)
}

/// The wheel compliance and the equilibrium poses it was taken at.
fn compliance_at(corner: &Corner, t: f64) -> Result<([[f64; 6]; 6], Vec<elastokin_core::Pose>), SolverError> {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(t);
    solver.equilibrium(&mut state)?;
    Ok((compliance_with(&mut solver, &corner.wheel, corner.partner.as_ref(), &state)?, state.poses))
}

/// The wheel compliance at `state` (an equilibrium of `solver`'s model): see [`wheel_compliance`].
fn compliance_with(
    solver: &mut StaticSolver,
    wheel: &crate::corner::Wheel,
    partner: Option<&crate::corner::Wheel>,
    state: &elastokin_solver::State,
) -> Result<[[f64; 6]; 6], SolverError> {
    let n = solver.model().dofs();
    let m = solver.active_rows().len();
    // Generalized force on `w`'s upright of a force `f` at its wheel centre and a torque `moment`.
    let load = |rhs: &mut [f64], w: &crate::corner::Wheel, f: Vec3, moment: Vec3| {
        let pose = state.poses[w.upright.0];
        let arm = pose.point(&w.wheel_centre_local) - pose.position;
        let (f, moment) = (f, arm.cross(&f) + moment);
        let base = w.upright.0 * elastokin_core::BODY_DOFS;
        for c in 0..3 {
            rhs[base + c] += f[c];
            rhs[base + 3 + c] += moment[c];
        }
    };
    let pose = state.poses[wheel.upright.0];
    let s = pose.point(&wheel.wheel_centre_local) - pose.position;
    let base = wheel.upright.0 * elastokin_core::BODY_DOFS;
    let mut columns = [[0.0; 6]; 6];
    let mut rhs = vec![0.0; n + m];
    solver.factorize_tangent(state)?;
    for (k, column) in columns.iter_mut().enumerate() {
        rhs.fill(0.0);
        let mut unit = Vec3::zeros();
        unit[k % 3] = 1.0;
        // A force at the wheel centre, or a torque.
        let (f, moment) = if k < 3 { (unit, Vec3::zeros()) } else { (Vec3::zeros(), unit) };
        load(&mut rhs, wheel, f, moment);
        if let Some(partner) = partner {
            // The same load on the partner's wheel centre, in phase (as `Corner::add_wheel_force`).
            load(&mut rhs, partner, f, moment);
        }
        solver.solve_factored(&mut rhs)?;
        let dr = Vec3::new(rhs[base], rhs[base + 1], rhs[base + 2]);
        let dpi = Vec3::new(rhs[base + 3], rhs[base + 4], rhs[base + 5]);
        let dwc = dr + dpi.cross(&s);
        for c in 0..3 {
            column[c] = dwc[c];
            column[3 + c] = dpi[c];
        }
    }
    // Stored by columns above; return rows × columns.
    let mut out = [[0.0; 6]; 6];
    for r in 0..6 {
        for c in 0..6 {
            out[r][c] = columns[c][r];
        }
    }
    Ok(out)
}

/// Force and moment that one joint or element applies at an equilibrium (global axes, N and N·m).
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentForce {
    /// The joint's or element's name.
    pub name: String,
    /// The body the force is applied to: the component's body `j` ("ground" for a joint whose `j` is the
    /// ground, whose reaction on the ground is then given).
    pub body: String,
    /// The body on the other side, which receives the opposite force and moment ("ground" for a part
    /// mounted on the chassis).
    pub other_body: String,
    /// Force applied to `body` (N).
    pub force: Vec3,
    /// Moment applied to `body` (N·m), about the joint's hardpoint or the element's point on `body` as the
    /// body carries it.
    pub torque: Vec3,
}

/// The force in every joint and every element at an equilibrium, by name, in model order: what a
/// durability engineer takes from a K&C load case, and the forces through which the chassis holds the
/// corner.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ComponentForces {
    /// Joints and drivers (a driver's force is what the rig applies to hold it).
    pub joints: Vec<ComponentForce>,
    /// Bushings, springs and the applied loads.
    pub elements: Vec<ComponentForce>,
}

impl ComponentForces {
    /// Reads every joint reaction and element force of `step`, a solution of `model`.
    pub fn at(model: &Model, step: &StepResult) -> Self {
        let joints = model
            .joints()
            .iter()
            .zip(step.joint_reactions(model))
            .map(|(joint, reaction)| {
                let (i, j) = (joint.spec.body_i, joint.spec.body_j);
                // For a joint on the ground as `j`, the reaction reported is the one on the ground.
                ComponentForce {
                    name: joint.name().to_string(),
                    body: model.body_name(j).to_string(),
                    other_body: model.body_name(i).to_string(),
                    force: reaction.force,
                    torque: reaction.torque,
                }
            })
            .collect();
        let elements = model
            .elements()
            .iter()
            .zip(step.element_reports(model))
            .map(|(element, report)| {
                let [i, j] = element.bodies();
                ComponentForce {
                    name: element.name().to_string(),
                    body: model.body_name(j).to_string(),
                    other_body: model.body_name(i).to_string(),
                    force: report.force,
                    torque: report.torque,
                }
            })
            .collect();
        ComponentForces { joints, elements }
    }

    /// The joint named `name`.
    pub fn joint(&self, name: &str) -> Option<&ComponentForce> {
        self.joints.iter().find(|c| c.name == name)
    }

    /// The element named `name`.
    pub fn element(&self, name: &str) -> Option<&ComponentForce> {
        self.elements.iter().find(|c| c.name == name)
    }
}

/// One row of a force or torque sweep at the wheel ([`vertical_force_sweep`], [`wheel_load_sweep`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadRow {
    /// The applied load: the load parameter (N, or N·m for the aligning torque).
    pub load: f64,
    /// Wheel attitude.
    pub attitude: WheelAttitude,
    /// The upright's contact-patch point (global): the material point of the upright that sat at the
    /// contact patch where the sweep defines it (see each sweep).
    pub contact_patch: Vec3,
    /// Displacement of that point from where it was at design (m). Its slope against a lateral or
    /// braking load is the inverse of the stiffness at the contact patch.
    pub patch_displacement: Vec3,
    /// Vertical force the rig applies at the wheel centre to hold its height (N, up +); zero when the
    /// wheel is free on its spring.
    pub wheel_load: f64,
    /// Force in every joint and element.
    pub forces: ComponentForces,
}

/// Name of the vertical force of the corner's share of the vehicle weight in the load analyses.
const CORNER_LOAD: &str = "corner load";

/// Reads the rows of a load sweep; `patch_local` is the upright's contact-patch point (local).
fn load_rows(
    solver: &mut StaticSolver,
    corner: &Corner,
    walked: Walked,
    patch_local: Vec3,
    extras: SweepExtras,
) -> Result<SweepOutput<LoadRow>, SolverError> {
    let model = &corner.model;
    let upright = corner.wheel.upright.0;
    let patch_at_design = model.bodies()[upright].design_pose.point(&patch_local);
    let driver = model.joint_id("wheel travel");
    read_sweep(solver, &corner.wheel, corner.partner.as_ref(), walked, extras, |_, s| {
        let forces = ComponentForces::at(model, s);
        let contact_patch = s.poses[upright].point(&patch_local);
        Ok(LoadRow {
            load: s.t,
            attitude: corner.wheel.attitude(&s.poses),
            contact_patch,
            patch_displacement: contact_patch - patch_at_design,
            wheel_load: driver.map_or(0.0, |d| forces.joints[d.0].force.z),
            forces,
        })
    })
}

/// Vertical force at the contact patch from `from` to `to` newtons (upward positive) in `steps` steps —
/// the paper's vertical force sweep. The corner must be built with [`Rig::Free`]: the wheel is free and
/// the spring and bushings carry the load. The force acts at the upright's point at the design contact
/// patch (the rows' `contact_patch`); the path starts from the equilibrium at `from`, found from design.
pub fn vertical_force_sweep(
    corner: Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<LoadRow>, SolverError> {
    whole(vertical_force_sweep_with(corner, from, to, steps, mode, SweepExtras::default())?)
}

/// [`vertical_force_sweep`] with [`SweepExtras`].
pub fn vertical_force_sweep_with(
    mut corner: Corner,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<LoadRow>, SolverError> {
    require_rig(&corner, &[Rig::Free])?;
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force("vertical force", corner.load_point_at(patch), Vec3::z())?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, extras.through_limits)?;
    let local_patch = corner.model.bodies()[corner.wheel.upright.0].design_pose.to_local_point(&patch);
    load_rows(&mut solver, &corner, walked, local_patch, extras)
}

/// A force or torque a K&C rig applies to the wheel (signs as in [`PatchCompliance`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WheelLoad {
    /// Lateral force at the contact patch, N, positive inboard: the cornering force on the outer wheel
    /// of a turn.
    Lateral,
    /// Longitudinal force at the contact patch, N, positive rearward: braking with brakes on the upright,
    /// which react the brake torque there, so the upright carries the tyre's force where the tyre makes it.
    Braking,
    /// Longitudinal force at the wheel centre, N, positive forward: drive through a half-shaft from a
    /// chassis-mounted differential, whose torque the chassis reacts, so the upright receives only the
    /// force, at the wheel bearing.
    Traction,
    /// Torque about +z (global), N·m: the tyre's aligning moment.
    AligningTorque,
}

/// Sweeps one [`WheelLoad`] from `from` to `to` (N, or N·m for the aligning torque) in `steps` steps,
/// walked in `mode`: compliance steer and camber, and the displacement of the contact patch, under road
/// loads.
///
/// The corner must be built with [`Rig::HeightHeld`] (the wheel-centre height held, as a K&C rig does;
/// the rows then give the rig's holding force) or [`Rig::Free`] (the wheel rides on its spring). Through
/// the whole sweep the wheel also carries `corner_load` (N, upward, constant) at the design contact
/// patch: the corner's share of the vehicle's weight, which a free wheel needs to stay near its design
/// height (with the height held it only changes the holding force).
///
/// The patch loads act at the upright's material point at the contact patch of the equilibrium without
/// the swept load (the lowest point of the wheel there; the rows' `contact_patch`), so that their slope at
/// zero load is the compliance [`patch_compliance`] takes from the tangent at that equilibrium; the
/// traction force acts at the wheel centre. With [`Corner::load_point`] at the wheel centre, the lateral
/// and braking forces act there too. Loads keep their global direction as the wheel moves.
pub fn wheel_load_sweep(
    corner: Corner,
    load: WheelLoad,
    corner_load: f64,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
) -> Result<Vec<LoadRow>, SolverError> {
    whole(wheel_load_sweep_with(corner, load, corner_load, from, to, steps, mode, SweepExtras::default())?)
}

/// [`wheel_load_sweep`] with [`SweepExtras`].
pub fn wheel_load_sweep_with(
    corner: Corner,
    load: WheelLoad,
    corner_load: f64,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<LoadRow>, SolverError> {
    let inboard = Vec3::new(0.0, -corner.wheel.side.sign(), 0.0);
    let add = |corner: &mut Corner, patch_at_design: Vec3| -> Result<(), SolverError> {
        match load {
            WheelLoad::Lateral => {
                corner.add_wheel_force("lateral force", corner.load_point_at(patch_at_design), inboard)?
            }
            WheelLoad::Braking => {
                corner.add_wheel_force("braking force", corner.load_point_at(patch_at_design), -Vec3::x())?
            }
            WheelLoad::Traction => corner.add_wheel_force("traction force", corner.wheel.wheel_centre, Vec3::x())?,
            WheelLoad::AligningTorque => corner.add_wheel_torque("aligning torque", Vec3::z())?,
        };
        Ok(())
    };
    loaded_sweep(corner, corner_load, LoadPath::new(from, to, steps), mode, extras, add)
}

/// The sweep of loads that `add` puts on the corner (given the contact patch as a design point of the
/// upright, at rest without them), with `corner_load` carried: the road loads and the model's own.
fn loaded_sweep(
    mut corner: Corner,
    corner_load: f64,
    path: LoadPath,
    mode: Mode,
    extras: SweepExtras,
    add: impl FnOnce(&mut Corner, Vec3) -> Result<(), SolverError>,
) -> Result<SweepOutput<LoadRow>, SolverError> {
    require_rig(&corner, &[Rig::HeightHeld, Rig::Free])?;
    add_corner_load(&mut corner, corner_load)?;
    let (mut start, patch_local) = rest_without_swept_load(&corner)?;
    let patch_at_design = corner.model.bodies()[corner.wheel.upright.0].design_pose.point(&patch_local);
    add(&mut corner, patch_at_design)?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let walked = walk(&mut solver, &mut start, path, mode, extras.through_limits)?;
    load_rows(&mut solver, &corner, walked, patch_local, extras)
}

/// The equilibrium without the swept load (the load parameter at zero): where the patch loads act, and
/// where the path starts from; with the contact patch there as a point of the upright.
fn rest_without_swept_load(corner: &Corner) -> Result<(State, Vec3), SolverError> {
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state)?;
    let patch = corner.wheel.steering_geometry(&state.poses).contact_patch;
    let patch_local = state.poses[corner.wheel.upright.0].to_local_point(&patch);
    Ok((state, patch_local))
}

/// Sweeps the loads a model file describes (`loads` of the general form, added to `corner` by
/// [`crate::GeneralCorner::add_loads`], each ramped by the load parameter) from `from` to `to` times their
/// values, in `steps` steps walked in `mode`, with `corner_load` carried at the contact patch as in
/// [`wheel_load_sweep`]. The corner must be built with [`Rig::HeightHeld`] or [`Rig::Free`].
pub fn model_load_sweep_with(
    corner: Corner,
    corner_load: f64,
    from: f64,
    to: f64,
    steps: usize,
    mode: Mode,
    extras: SweepExtras,
) -> Result<SweepOutput<LoadRow>, SolverError> {
    loaded_sweep(corner, corner_load, LoadPath::new(from, to, steps), mode, extras, |_, _| Ok(()))
}

/// Adds the constant upward `corner_load` (N) at the design contact patch, named [`CORNER_LOAD`].
fn add_corner_load(corner: &mut Corner, corner_load: f64) -> Result<(), SolverError> {
    if !corner_load.is_finite() {
        return Err(SolverError::InvalidInput {
            what: "corner load",
            why: format!("the vertical load on the wheel must be a finite force in newtons, got {corner_load}"),
        });
    }
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force_with_constant(CORNER_LOAD, patch, Vec3::zeros(), Vec3::new(0.0, 0.0, corner_load))?;
    Ok(())
}

/// Compliance characteristics at the contact patch, read from the wheel compliance matrix (SI: rad/N,
/// rad/(N·m), N/m). Lateral force is positive inboard (the cornering force on a loaded outer wheel),
/// longitudinal force positive rearward (braking at the contact patch), aligning torque positive about +z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchCompliance {
    /// Toe change per lateral force (rad/N).
    pub lateral_steer: f64,
    /// Camber change per lateral force (rad/N).
    pub lateral_camber: f64,
    /// Lateral stiffness at the contact patch: inboard force per inboard patch displacement (N/m).
    pub lateral_stiffness: f64,
    /// Toe change per braking force (rad/N).
    pub braking_steer: f64,
    /// Longitudinal stiffness at the contact patch under braking force (N/m).
    pub longitudinal_stiffness: f64,
    /// Toe change per aligning torque (rad/(N·m)).
    pub aligning_torque_steer: f64,
}

/// Toe and camber changes of a small rotation `dpi` of the wheel with outward spin axis `a` on side `s`.
fn attitude_change(a: &Vec3, s: f64, dpi: &Vec3) -> (f64, f64) {
    let da = dpi.cross(a);
    let (ax, ay, az) = (a.x, s * a.y, a.z);
    let (dax, day, daz) = (da.x, s * da.y, da.z);
    let h2 = ax * ax + ay * ay;
    let h = h2.sqrt();
    let dtoe = (ay * dax - ax * day) / h2;
    let dh = (ax * dax + ay * day) / h;
    let dcamber = (-daz * h + az * dh) / (h2 + az * az);
    (dtoe, dcamber)
}

/// [`PatchCompliance`] at the equilibrium of load parameter `t` (see [`wheel_compliance`]).
pub fn patch_compliance(corner: &Corner, t: f64) -> Result<PatchCompliance, SolverError> {
    let (c, poses) = compliance_at(corner, t)?;
    let pose = poses[corner.wheel.upright.0];
    let a = pose.direction(&corner.wheel.spin_axis_local);
    let w = pose.point(&corner.wheel.wheel_centre_local);
    let patch = corner.wheel.steering_geometry(&poses).contact_patch;
    let arm = patch - w;
    let s = corner.wheel.side.sign();
    // Response (Δ patch, Δπ) to a unit force `f` at the patch or a unit torque `m`.
    let respond = |f: Vec3, m: Vec3| {
        let load = [f, arm.cross(&f) + m];
        let mut out = [0.0; 6];
        for r in 0..6 {
            out[r] = (0..3).map(|k| c[r][k] * load[0][k] + c[r][3 + k] * load[1][k]).sum();
        }
        let dw = Vec3::new(out[0], out[1], out[2]);
        let dpi = Vec3::new(out[3], out[4], out[5]);
        (dw + dpi.cross(&arm), dpi)
    };
    let inboard = Vec3::new(0.0, -s, 0.0);
    let rearward = Vec3::new(-1.0, 0.0, 0.0);
    let zero = Vec3::zeros();
    let (dp_lat, dpi_lat) = respond(inboard, zero);
    let (dp_long, dpi_long) = respond(rearward, zero);
    let (_, dpi_mz) = respond(zero, Vec3::z());
    let (lateral_steer, lateral_camber) = attitude_change(&a, s, &dpi_lat);
    Ok(PatchCompliance {
        lateral_steer,
        lateral_camber,
        lateral_stiffness: 1.0 / dp_lat.dot(&inboard),
        braking_steer: attitude_change(&a, s, &dpi_long).0,
        longitudinal_stiffness: 1.0 / dp_long.dot(&rearward),
        aligning_torque_steer: attitude_change(&a, s, &dpi_mz).0,
    })
}

/// The corner at rest under its share of the vehicle's weight: see [`static_load_case`].
#[derive(Debug, Clone, PartialEq)]
pub struct StaticLoad {
    /// The corner load (N, upward at the contact patch).
    pub corner_load: f64,
    /// Wheel attitude at rest.
    pub attitude: WheelAttitude,
    /// Wheel-centre displacement from design (m); its z is the change of ride height at the wheel, bump
    /// positive.
    pub wheel_centre_displacement: Vec3,
    /// The upright's point at the design contact patch, where the corner load acts, at rest (global).
    pub contact_patch: Vec3,
    /// Wheel rate at rest: corner load per metre of rise of the contact-patch point (N/m), from the
    /// tangent of the equilibrium (tyre not included). Positive, or the rest position is refused.
    pub wheel_rate: f64,
    /// Spring force (N, compression positive).
    pub spring_force: f64,
    /// Spring deflection `L − L₀` (m, compression negative).
    pub spring_deflection: f64,
    /// Force in every joint and element (the corner load among the elements, as "corner load").
    pub forces: ComponentForces,
    /// Body poses at rest.
    pub poses: Vec<elastokin_core::Pose>,
    /// The converged residuals at rest: force residual over the force scale, and `‖Φ‖∞` (m and rad).
    pub residuals: (f64, f64),
}

/// Sub-steps of the load walk that [`static_load_case`] falls back to.
const STATIC_LOAD_STEPS: usize = 20;

/// The static load case at design: the corner (built with [`Rig::Free`]) carries `corner_load` newtons
/// upward at the design contact patch, applied at once, and comes to rest on its spring.
///
/// The design position is in general not at rest under the corner load (the spring's design force need
/// not match it), so the rest position is found by Newton's method on the exact equilibrium equations
/// from the design position. (The paper's incremental method has no part here: it needs a state at rest
/// to start from, and that state is what this analysis finds.) Newton can fail from design when the
/// rest position lies near a limit point of the linkage; the load is then walked instead, with step
/// cutting, from where the wheel hangs unloaded (spring at its free length) — a walk that also tells a
/// load the corner cannot carry by the limit point it meets.
///
/// A rest position is only one if it is stable: the wheel rate there (see [`StaticLoad::wheel_rate`])
/// must be positive. Newton finds unstable equilibria as readily as stable ones (a spring so soft that
/// the linkage's falling motion ratio outweighs its rate has only those), so they are refused.
///
/// Errors: another rig or a non-finite load is [`SolverError::InvalidInput`]; a load beyond what the
/// corner carries is [`SolverError::LimitPoint`] (the largest load it carries, located to 1e-6 of the
/// load) or
/// [`SolverError::InvalidInput`] on the corner load when no rest position is found or the one found is
/// unstable; model and factorization failures pass through.
pub fn static_load_case(mut corner: Corner, corner_load: f64) -> Result<StaticLoad, SolverError> {
    require_rig(&corner, &[Rig::Free])?;
    if !corner_load.is_finite() {
        return Err(SolverError::InvalidInput {
            what: "corner load",
            why: format!("the vertical load on the wheel must be a finite force in newtons, got {corner_load}"),
        });
    }
    let patch = corner.wheel.contact_patch;
    corner.add_wheel_force(CORNER_LOAD, patch, Vec3::z())?;
    let model = &corner.model;
    let upright = corner.wheel.upright.0;
    let patch_local = model.bodies()[upright].design_pose.to_local_point(&patch);
    let mut solver = StaticSolver::new(model, SolverOptions::default())?;
    let mut state = solver.design_state(corner_load);
    let step = match solver.equilibrium(&mut state) {
        Ok(step) => step,
        Err(SolverError::NoConvergence { .. }) => {
            state = solver.design_state(0.0);
            solver.equilibrium(&mut state).map_err(|e| SolverError::InvalidInput {
                what: "corner load",
                why: format!(
                    "no rest position under {corner_load} N was found from the design position, nor the unloaded \
                     position to walk the load from ({e}); check the spring's rate and design force against the \
                     corner load"
                ),
            })?;
            let path = LoadPath::new(0.0, corner_load, STATIC_LOAD_STEPS);
            let sweep = solver.sweep_from(&mut state, path, Mode::Corrected).and_then(Sweep::complete);
            let mut sweep = sweep.map_err(|e| match e {
                SolverError::NoConvergence { last_converged: Some(reached), .. } => SolverError::InvalidInput {
                    what: "corner load",
                    why: format!(
                        "no rest position under {corner_load} N: walking the load up from the unloaded position \
                         found equilibria only up to {reached} N ({e}); check the corner load against the spring's \
                         rate and design force"
                    ),
                },
                other => other,
            })?;
            sweep.steps.pop().expect("a sweep has its starting equilibrium")
        }
        Err(e) => return Err(e),
    };
    // Stability: the rise of the loaded point per newton of corner load, from the path tangent.
    let rates = solver.path_tangent(&state)?;
    let contact_patch = step.poses[upright].point(&patch_local);
    let wheel_rate = 1.0 / corner.wheel.point_velocity(&step.poses, &rates, contact_patch).z;
    if !(wheel_rate.is_finite() && wheel_rate > 0.0) {
        return Err(SolverError::InvalidInput {
            what: "corner load",
            why: format!(
                "the only equilibrium found under {corner_load} N is unstable (wheel rate {wheel_rate:.4e} N/m, \
                 wheel centre {:+.4} m from design): the spring cannot hold the corner at rest under this load; \
                 check the spring's rate and design force against the corner load",
                corner.wheel.attitude(&step.poses).wheel_centre.z - corner.wheel.wheel_centre.z
            ),
        });
    }
    let forces = ComponentForces::at(model, &step);
    let attitude = corner.wheel.attitude(&step.poses);
    let spring = corner.spring.map(|e| step.element_reports(model)[e.0]);
    let spring_deflection = spring.map_or(0.0, |r| r.deflection.x);
    // The templates' springs carry no preload beside k·(L₀ − L) (the free length is set from the design
    // force), so the push has the sign of the shortening; its size is the force the report gives.
    let spring_force = spring.map_or(0.0, |r| -spring_deflection.signum() * r.force.norm());
    Ok(StaticLoad {
        corner_load,
        attitude,
        wheel_centre_displacement: attitude.wheel_centre - corner.wheel.wheel_centre,
        contact_patch,
        wheel_rate,
        spring_force,
        spring_deflection,
        forces,
        residuals: (step.force_residual / step.force_scale, step.constraint_residual),
        poses: step.poses,
    })
}

/// Which axle a corner is on: it decides which pitch the braking and drive forces resist.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxlePosition {
    /// Front axle: braking dives it, drive lifts it.
    Front,
    /// Rear axle: braking lifts it, drive squats it.
    Rear,
}

/// What the vehicle-level analyses need from the vehicle (SI units): the static load case and the road
/// loads carry `corner_load`, the anti-pitch percentages use the rest. A model file's `vehicle` section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleParameters {
    /// The corner's share of the vehicle's weight, N: the vertical force at the contact patch at rest.
    pub corner_load: f64,
    /// Wheelbase `L` (m).
    pub wheelbase: f64,
    /// Height `h` of the centre of gravity above the ground (m).
    pub cg_height: f64,
    /// Share `p_f` of the braking force made by the front axle, 0 to 1.
    pub brake_front_fraction: f64,
    /// Share `d_f` of the drive force made by the front axle, 0 to 1 (0: rear drive, 1: front drive).
    pub drive_front_fraction: f64,
    /// The axle the corner is on.
    pub axle: AxlePosition,
    /// Vertical rate of the tyre (N/m), for the ride rate (wheel rate and tyre in series); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tyre_rate: Option<f64>,
    /// Rack travel per turn of the steering wheel (m/rev, the pinion's "c-factor"), for the overall
    /// steering ratio; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rack_travel_per_revolution: Option<f64>,
}

impl VehicleParameters {
    /// Refuses values no vehicle has, naming the field.
    pub fn validate(&self) -> Result<(), SolverError> {
        let invalid = |why: String| Err(SolverError::InvalidInput { what: "vehicle parameters", why });
        // Upper bounds well beyond any road vehicle: past them the figures (anti-pitch = slope × L / h, the
        // forces of the corner load) lose their meaning and then overflow.
        for (field, value, what, limit) in [
            ("wheelbase", Some(self.wheelbase), "a length in metres", 50.0),
            ("cg_height", Some(self.cg_height), "a height in metres", 20.0),
            ("corner_load", Some(self.corner_load), "a force in newtons", 1e7),
            ("tyre_rate", self.tyre_rate, "a rate in N/m", 1e10),
            ("rack_travel_per_revolution", self.rack_travel_per_revolution, "a rack travel in metres", 1.0),
        ] {
            if let Some(v) = value.filter(|v| !(*v > 0.0 && *v <= limit)) {
                return invalid(format!("`{field}` must be {what}, above 0 and at most {limit:e}, got {v:e}"));
            }
        }
        for (field, value) in
            [("brake_front_fraction", self.brake_front_fraction), ("drive_front_fraction", self.drive_front_fraction)]
        {
            if !(0.0..=1.0).contains(&value) {
                return invalid(format!(
                    "`{field}` is the front axle's share of the force and must lie in [0, 1], got {value}"
                ));
            }
        }
        Ok(())
    }
}

/// Side-view geometry of the wheel's motion in bump and the anti-pitch it gives: see [`anti_pitch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AntiPitch {
    /// Velocity of the upright's point at the contact patch per metre of wheel-centre travel (m/m).
    pub patch_velocity: Vec3,
    /// Velocity of the wheel centre per metre of wheel-centre travel (m/m; its z is 1).
    pub wheel_centre_velocity: Vec3,
    /// Side-view swing-arm slope at the contact patch, `tan θ_P = v_P,x / v_P,z`: positive when the patch
    /// moves forward in bump (the side-view instant centre behind and above a front patch).
    pub patch_slope: f64,
    /// Side-view swing-arm slope at the wheel centre, `tan θ_W = v_W,x / v_W,z`.
    pub wheel_centre_slope: f64,
    /// `θ_P = atan(tan θ_P)` (rad).
    pub patch_swing_arm_angle: f64,
    /// `θ_W = atan(tan θ_W)` (rad).
    pub wheel_centre_swing_arm_angle: f64,
    /// Under braking: anti-dive on a front axle, anti-lift on a rear axle (%): the share of the load
    /// transfer onto (front) or off (rear) the axle that the braking forces carry through the linkage
    /// instead of the springs. 100 % leaves the springs unchanged; negative adds to the pitch.
    pub braking: f64,
    /// Under drive: anti-lift on a front axle, anti-squat on a rear axle (%), likewise.
    pub traction: f64,
}

/// Anti-dive, anti-lift and anti-squat of the corner from the instantaneous motion of its wheel at
/// design (the corner must be built with [`Rig::WheelTravel`]).
///
/// The path tangent at design gives the velocity `v_P` of the upright's point at the contact patch and
/// `v_W` of the wheel centre per metre of bump. By virtual work, a force `F` at a point moving with `v`
/// acts on the wheel's vertical motion like a vertical force `F·v / v_z` at the patch (whose `v_z` equals
/// the wheel centre's while the patch lies below the wheel centre, as it does at design).
///
/// Braking with brakes on the upright puts the force at the patch: `B` rearward on each wheel is
/// equivalent to `−B tan θ_P` upward. Deceleration `a` of a car of mass `m` moves `m a h / L` of load from
/// the rear axle to the front one, and the front wheels brake with `p_f m a` in all:
/// * front: the springs see `ΔF − B tan θ_P` per wheel with `ΔF = m a h / (2L)` and `B = p_f m a / 2`,
///   so the linkage carries the share `anti-dive = p_f tan θ_P L / h` (×100 %);
/// * rear: the wheel loses `ΔF` and brakes with `B = (1 − p_f) m a / 2`, so `anti-lift = (1 − p_f)
///   (−tan θ_P) L / h`.
///
/// Drive through half-shafts from a chassis-mounted differential puts a forward force `T` at the wheel
/// centre (the chassis reacts the torque), equivalent to `+T tan θ_W` upward. Acceleration moves `m a h / L`
/// onto the rear axle:
/// * front: the wheel loses `ΔF` and pushes with `T = d_f m a / 2`, so `anti-lift = d_f tan θ_W L / h`;
/// * rear: the wheel gains `ΔF` and pushes with `T = (1 − d_f) m a / 2`, so `anti-squat = (1 − d_f)
///   (−tan θ_W) L / h`.
///
/// So the same geometry serves both ends of a car: a front wheel moving forward in bump resists dive and
/// lift, a rear wheel moving rearward in bump resists lift and squat.
pub fn anti_pitch(corner: &Corner, vehicle: &VehicleParameters) -> Result<AntiPitch, SolverError> {
    require_rig(corner, &[Rig::WheelTravel])?;
    vehicle.validate()?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default())?;
    let mut state = solver.design_state(0.0);
    solver.equilibrium(&mut state)?;
    let rates = solver.path_tangent(&state)?;
    let wheel = &corner.wheel;
    let patch = wheel.steering_geometry(&state.poses).contact_patch;
    let wheel_centre = wheel.attitude(&state.poses).wheel_centre;
    let patch_velocity = wheel.point_velocity(&state.poses, &rates, patch);
    let wheel_centre_velocity = wheel.point_velocity(&state.poses, &rates, wheel_centre);
    if !patch_velocity.iter().all(|v| v.is_finite()) {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: "the contact patch's motion in bump cannot be computed (the path tangent at design is not \
                  finite): no side-view swing arm; check the hardpoints with `elastokin check`"
                .into(),
        });
    }
    if patch_velocity.z.abs() <= 1e-6 {
        return Err(SolverError::InvalidInput {
            what: "corner",
            why: format!(
                "the contact patch does not rise with the wheel centre (it moves ({:.4}, {:.4}, {:.4}) m per metre \
                 of travel): no side-view swing arm; check the hardpoints",
                patch_velocity.x, patch_velocity.y, patch_velocity.z
            ),
        });
    }
    let patch_slope = patch_velocity.x / patch_velocity.z;
    let wheel_centre_slope = wheel_centre_velocity.x / wheel_centre_velocity.z;
    let lever = vehicle.wheelbase / vehicle.cg_height;
    let (p_f, d_f) = (vehicle.brake_front_fraction, vehicle.drive_front_fraction);
    let (braking, traction) = match vehicle.axle {
        AxlePosition::Front => (p_f * patch_slope * lever, d_f * wheel_centre_slope * lever),
        AxlePosition::Rear => ((1.0 - p_f) * -patch_slope * lever, (1.0 - d_f) * -wheel_centre_slope * lever),
    };
    Ok(AntiPitch {
        patch_velocity,
        wheel_centre_velocity,
        patch_slope,
        wheel_centre_slope,
        patch_swing_arm_angle: patch_slope.atan(),
        wheel_centre_swing_arm_angle: wheel_centre_slope.atan(),
        braking: 100.0 * braking,
        traction: 100.0 * traction,
    })
}
