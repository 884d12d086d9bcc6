//! Load sweeps of one corner: a vertical force with the wheel free, road loads (lateral, braking, drive)
//! at the contact patch with the wheel under its corner load, the model's own load case, and the static
//! load case; every row with the forces each joint and element carries.

use crate::analysis::sweep::{read_sweep, require_rig, walk, whole, Reading, SweepExtras, SweepOutput, Walked};
use crate::assembly::rig::WHEEL_TRAVEL;
use crate::assembly::{Corner, Rig};
use crate::wheel::WheelAttitude;
use elastokin_core::{BodyRef, JointId, Model, Vec3};
use elastokin_solver::replay::{Taping, NO_TAPING};
use elastokin_solver::{LoadPath, Mode, SolverError, SolverOptions, State, StaticSolver, StepResult, Sweep};
use std::sync::Arc;

/// The vertical force the rig applies at the wheel centre to hold the corner at design (N, up +): the
/// corner load the design position carries. The corner must hold its wheel-centre height
/// ([`Rig::WheelTravel`] at `t = 0`, or [`Rig::HeightHeld`]).
pub fn design_wheel_load(corner: &Corner) -> Result<f64, SolverError> {
    Ok(design_wheel_load_estimated(corner, false, &NO_TAPING)?.0)
}

/// [`design_wheel_load`] and, when `estimate`, its error estimate: the change of the load over one exact
/// Newton iteration from the equilibrium (the rows' estimate, [`SweepExtras::error_estimate`]). Its solver
/// takes part in `taping`.
pub fn design_wheel_load_estimated(
    corner: &Corner,
    estimate: bool,
    taping: &Taping,
) -> Result<(f64, Option<f64>), SolverError> {
    require_rig(corner, &[Rig::WheelTravel, Rig::HeightHeld])?;
    let Some(driver) = corner.model.joint_id(WHEEL_TRAVEL) else {
        return Err(SolverError::InvalidInput { what: "corner", why: "it has no \"wheel travel\" driver".into() });
    };
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), taping)?;
    let mut state = solver.design_state(0.0);
    let step = solver.equilibrium(&mut state)?;
    let load = |s: &elastokin_solver::StepResult| s.joint_reaction(&corner.model, driver).force.z;
    let error = if estimate { Some((load(&solver.newton_correction(&step)?) - load(&step)).abs()) } else { None };
    Ok((load(&step), error))
}

/// Force and moment that one joint or element applies at an equilibrium (global axes, N and N·m).
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentForce {
    /// The joint's or element's name.
    pub name: Arc<str>,
    /// The body the force is applied to: the component's body `j` ("ground" for a joint whose `j` is the
    /// ground, whose reaction on the ground is then given).
    pub body: Arc<str>,
    /// The body on the other side, which receives the opposite force and moment ("ground" for a part
    /// mounted on the chassis).
    pub other_body: Arc<str>,
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

/// The names of a model's joints and elements and of the bodies either side of each, as
/// [`ComponentForces`] gives them: made once per sweep and shared by its rows (a row names its
/// components without allocating).
#[derive(Debug, Clone)]
pub struct ComponentNames {
    joints: Vec<[Arc<str>; 3]>,
    elements: Vec<[Arc<str>; 3]>,
}

impl ComponentNames {
    /// The names of `model`'s components: each one's own, its body `j`'s, its body `i`'s.
    pub fn of(model: &Model) -> Self {
        let names =
            |name: &str, i: BodyRef, j: BodyRef| [name.into(), model.body_name(j).into(), model.body_name(i).into()];
        ComponentNames {
            joints: model.joints().iter().map(|jt| names(jt.name(), jt.spec.body_i, jt.spec.body_j)).collect(),
            elements: model
                .elements()
                .iter()
                .map(|e| {
                    let [i, j] = e.bodies();
                    names(e.name(), i, j)
                })
                .collect(),
        }
    }
}

impl ComponentForces {
    /// Every component, joints first, then elements: the order of a table's columns and rows.
    pub fn all(&self) -> impl Iterator<Item = &ComponentForce> {
        self.joints.iter().chain(&self.elements)
    }

    /// The `k`-th component of [`ComponentForces::all`], if there is one.
    pub fn get(&self, k: usize) -> Option<&ComponentForce> {
        match k.checked_sub(self.joints.len()) {
            None => self.joints.get(k),
            Some(e) => self.elements.get(e),
        }
    }

    /// Reads every joint reaction and element force of `step`, a solution of `model`.
    pub fn at(model: &Model, step: &StepResult) -> Self {
        Self::named(model, step, &ComponentNames::of(model))
    }

    /// [`ComponentForces::at`] with the names of `model`'s components made beforehand.
    pub fn named(model: &Model, step: &StepResult, names: &ComponentNames) -> Self {
        let component = |[name, body, other_body]: &[Arc<str>; 3], force, torque| ComponentForce {
            name: name.clone(),
            body: body.clone(),
            other_body: other_body.clone(),
            force,
            torque,
        };
        // For a joint on the ground as `j`, the reaction reported is the one on the ground.
        let joints = names
            .joints
            .iter()
            .zip(step.joint_reactions(model))
            .map(|(n, r)| component(n, r.force, r.torque))
            .collect();
        let elements = names
            .elements
            .iter()
            .zip(step.element_reports(model))
            .map(|(n, r)| component(n, r.force, r.torque))
            .collect();
        ComponentForces { joints, elements }
    }

    /// The joint named `name`.
    pub fn joint(&self, name: &str) -> Option<&ComponentForce> {
        self.joints.iter().find(|c| &*c.name == name)
    }

    /// The element named `name`.
    pub fn element(&self, name: &str) -> Option<&ComponentForce> {
        self.elements.iter().find(|c| &*c.name == name)
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
    /// Force in every joint and element (none where the sweep read its rows for the figures alone,
    /// [`SweepExtras::figures_only`]).
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
    let driver = model.joint_id(WHEEL_TRAVEL);
    // Named once per sweep, and only when the rows read the forces.
    let names = (!extras.figures_only).then(|| ComponentNames::of(model));
    read_sweep(solver, &corner.wheel, corner.partner.as_ref(), walked, extras, |_, s, reading| {
        let forces = match (&names, reading) {
            (Some(n), Reading::Row | Reading::Design) => ComponentForces::named(model, s, n),
            _ => ComponentForces::default(),
        };
        let contact_patch = s.poses[upright].point(&patch_local);
        // The driver's force from the forces read, else read alone.
        let driver_force =
            |d: JointId| forces.joints.get(d.0).map_or_else(|| s.joint_reaction(model, d).force, |c| c.force);
        Ok(LoadRow {
            load: s.t,
            attitude: corner.wheel.attitude(&s.poses),
            contact_patch,
            patch_displacement: contact_patch - patch_at_design,
            wheel_load: driver.map_or(0.0, |d| driver_force(d).z),
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
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), extras.taping())?;
    let mut start = solver.design_state(from);
    let walked = walk(&mut solver, &mut start, LoadPath::new(from, to, steps), mode, &extras)?;
    let local_patch = corner.model.bodies()[corner.wheel.upright.0].design_pose.to_local_point(&patch);
    load_rows(&mut solver, &corner, walked, local_patch, extras)
}

/// A force or torque a K&C rig applies to the wheel (signs as in [`PatchCompliance`](crate::analysis::PatchCompliance)).
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
/// zero load is the compliance [`patch_compliance`](crate::analysis::patch_compliance) takes from the tangent at that equilibrium; the
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
    whole(wheel_load_sweep_with(
        corner,
        load,
        corner_load,
        LoadPath::new(from, to, steps),
        mode,
        SweepExtras::default(),
    )?)
}

/// [`wheel_load_sweep`] along `path` (the load from `path.start` to `path.end`), with [`SweepExtras`].
pub fn wheel_load_sweep_with(
    corner: Corner,
    load: WheelLoad,
    corner_load: f64,
    path: LoadPath,
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
    loaded_sweep(corner, corner_load, path, mode, extras, add)
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
    let (mut start, patch_local) = rest_without_swept_load(&corner, &extras)?;
    let patch_at_design = corner.model.bodies()[corner.wheel.upright.0].design_pose.point(&patch_local);
    add(&mut corner, patch_at_design)?;
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), extras.taping())?;
    let walked = walk(&mut solver, &mut start, path, mode, &extras)?;
    load_rows(&mut solver, &corner, walked, patch_local, extras)
}

/// The equilibrium without the swept load (the load parameter at zero): where the patch loads act, and
/// where the path starts from; with the contact patch there as a point of the upright.
fn rest_without_swept_load(corner: &Corner, extras: &SweepExtras) -> Result<(State, Vec3), SolverError> {
    let mut solver = StaticSolver::taped(&corner.model, SolverOptions::default(), extras.taping())?;
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
pub fn static_load_case(corner: Corner, corner_load: f64) -> Result<StaticLoad, SolverError> {
    Ok(static_load_case_estimated(corner, corner_load, false, &NO_TAPING)?.0)
}

/// [`static_load_case`], and with `estimate` the rest position read again one exact Newton iteration on:
/// what it reads differs from the first by the error estimate of each (as every sweep's rows are read again,
/// [`SweepExtras::error_estimate`]). Its solver takes part in `taping`.
pub fn static_load_case_estimated(
    mut corner: Corner,
    corner_load: f64,
    estimate: bool,
    taping: &Taping,
) -> Result<(StaticLoad, Option<StaticLoad>), SolverError> {
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
    let mut solver = StaticSolver::taped(model, SolverOptions::default(), taping)?;
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
    let rest = read_rest(&corner, &mut solver, &state, &step, corner_load, &patch_local)?;
    let corrected = if estimate {
        let moved = solver.newton_correction(&step)?;
        let at = solver.state_of(&moved);
        Some(read_rest(&corner, &mut solver, &at, &moved, corner_load, &patch_local)?)
    } else {
        None
    };
    Ok((rest, corrected))
}

/// What [`static_load_case`] reads of the rest position `step` (at `state`) that `solver` found for the
/// corner under `corner_load`, applied at `patch_local` of the upright: refused where the corner has no
/// wheel rate there or is unstable.
fn read_rest(
    corner: &Corner,
    solver: &mut StaticSolver,
    state: &State,
    step: &StepResult,
    corner_load: f64,
    patch_local: &Vec3,
) -> Result<StaticLoad, SolverError> {
    let model = &corner.model;
    let upright = corner.wheel.upright.0;
    // Stability: the rise of the loaded point per newton of corner load, from the path tangent.
    let rates = solver.path_tangent(state)?;
    let contact_patch = step.poses[upright].point(patch_local);
    let rise = corner.wheel.point_velocity(&step.poses, &rates, contact_patch).z;
    let wheel_rate = 1.0 / rise;
    if !wheel_rate.is_finite() {
        // The patch does not rise with the load at all: its height is held by the joints alone.
        return Err(SolverError::InvalidInput {
            what: "corner load",
            why: format!(
                "the wheel does not move under the corner load ({rise:.1e} m per N): the joints alone hold its \
                 height (a locked linkage), so the spring carries nothing and the corner has no wheel rate; check \
                 the hardpoints with `elastokin check`"
            ),
        });
    }
    if wheel_rate <= 0.0 {
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
    let forces = ComponentForces::at(model, step);
    let attitude = corner.wheel.attitude(&step.poses);
    let spring = corner.spring.map(|e| step.element_report(model, e));
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
        poses: step.poses.clone(),
    })
}
