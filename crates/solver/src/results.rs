//! What a solve returns: per-step states, joint reactions, element forces, diagnostics.

use crate::error::SolverError;
use crate::options::Mode;
use elastokin_core::{ElementId, ElementReport, ForceElement, Joint, JointId, Model, Pose, Vec3};

/// A constraint row dropped because it repeats what other rows already constrain.
#[derive(Debug, Clone, PartialEq)]
pub struct RedundantRow {
    /// Model row index.
    pub row: usize,
    /// The joint it belongs to.
    pub joint: String,
    /// The row's label within the joint.
    pub label: &'static str,
}

/// What the analysis of a model found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diagnostics {
    /// Redundant rows (dropped from the solve; their multipliers are reported as zero and the load they
    /// would share is carried by the rows they repeat).
    pub redundant: Vec<RedundantRow>,
}

impl Diagnostics {
    /// One line per finding, for people.
    pub fn messages(&self) -> Vec<String> {
        self.redundant
            .iter()
            .map(|r| {
                format!(
                    "joint '{}' repeats what other joints already hold (its '{}' constraint): it carries no load \
                     of its own, the joints it repeats carry it; remove it, or make it a bushing if it is meant \
                     to share the load",
                    r.joint, r.label
                )
            })
            .collect()
    }
}

/// Equilibrium (or paper-mode state) at one load parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct StepResult {
    /// Load parameter.
    pub t: f64,
    /// Body poses.
    pub poses: Vec<Pose>,
    /// Multiplier of every model constraint row (zero for dropped redundant rows).
    pub multipliers: Vec<f64>,
    /// `‖Φ_qᵀλ − Q‖∞` (N and N·m).
    pub force_residual: f64,
    /// The force scale the residual is judged against (largest element or reaction force, at least 1 N).
    pub force_scale: f64,
    /// `‖Φ‖∞` (m and rad).
    pub constraint_residual: f64,
    /// Newton iterations used for this step (0 in paper mode).
    pub iterations: usize,
}

/// The rates of an equilibrium along its load path ([`StaticSolver::path_rates_factored`]).
///
/// [`StaticSolver::path_rates_factored`]: crate::StaticSolver::path_rates_factored
#[derive(Debug, Clone, PartialEq)]
pub struct PathRates {
    /// `dq/dt`, `BODY_DOFS` per body (translation of the reference point, then rotation as in Δπ).
    pub dq: Vec<f64>,
    /// `dλ/dt` of each active constraint row, in the order of the solver's active rows.
    pub dlambda: Vec<f64>,
}

/// Reaction of one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointReaction {
    /// Force the joint applies to its body `j` (global, N).
    pub force: Vec3,
    /// Moment the joint applies to body `j` about the joint's hardpoint (global, N·m).
    pub torque: Vec3,
}

impl StepResult {
    /// Reaction force and moment of every joint on its second body `j`, at the joint's hardpoint.
    /// For a joint whose `j` is the ground, the reaction on the ground (minus the action on `i`).
    pub fn joint_reactions(&self, model: &Model) -> Vec<JointReaction> {
        let mut row = 0;
        model
            .joints()
            .iter()
            .map(|jt| {
                let reaction = self.reaction_of(jt, row);
                row += jt.rows.len();
                reaction
            })
            .collect()
    }

    /// The reaction of joint `id` alone, as [`StepResult::joint_reactions`] gives it: a row read without
    /// every other joint's.
    pub fn joint_reaction(&self, model: &Model, id: JointId) -> JointReaction {
        let first_row = model.joints()[..id.0].iter().map(|jt| jt.rows.len()).sum();
        self.reaction_of(&model.joints()[id.0], first_row)
    }

    /// The reaction of `jt`, whose rows start at model row `first_row`.
    fn reaction_of(&self, jt: &Joint, first_row: usize) -> JointReaction {
        let (pi, pj) = (jt.spec.body_i.pose(&self.poses), jt.spec.body_j.pose(&self.poses));
        let mut g = elastokin_core::RowGradient::zeros();
        for (k, r) in jt.rows.iter().enumerate() {
            g += r.evaluate(&pi, &pj, self.t).gradient * self.multipliers[first_row + k];
        }
        // The constraint force applied to the bodies is −Φ_qᵀλ.
        let anchor = pj.point(&jt.anchor_on_j);
        if jt.spec.body_j.id().is_some() {
            let f = -Vec3::new(g[6], g[7], g[8]);
            let m_ref = -Vec3::new(g[9], g[10], g[11]);
            JointReaction { force: f, torque: m_ref - (anchor - pj.position).cross(&f) }
        } else {
            let f = -Vec3::new(g[0], g[1], g[2]);
            let m_ref = -Vec3::new(g[3], g[4], g[5]);
            JointReaction { force: -f, torque: -(m_ref - (anchor - pi.position).cross(&f)) }
        }
    }

    /// Which piece of its force law every element is on at this step
    /// ([`ForceElement::piece`]), in model order: where two steps differ, a stop touched or left between
    /// them.
    pub fn element_pieces(&self, model: &Model) -> Vec<u8> {
        self.per_element(model, |e, pi, pj, t| e.piece(pi, pj, t))
    }

    /// Force, moment and deflection of every element at this step.
    pub fn element_reports(&self, model: &Model) -> Vec<ElementReport> {
        self.per_element(model, |e, pi, pj, t| e.report(pi, pj, t))
    }

    /// Force, moment and deflection of element `id` alone, as [`StepResult::element_reports`] gives it.
    pub fn element_report(&self, model: &Model, id: ElementId) -> ElementReport {
        let e = &model.elements()[id.0];
        let [i, j] = e.bodies();
        e.report(&i.pose(&self.poses), &j.pose(&self.poses), self.t)
    }

    /// `read` of every element at this step's poses of its two bodies, in model order.
    fn per_element<T>(&self, model: &Model, read: impl Fn(&dyn ForceElement, &Pose, &Pose, f64) -> T) -> Vec<T> {
        model
            .elements()
            .iter()
            .map(|e| {
                let [i, j] = e.bodies();
                read(e.as_ref(), &i.pose(&self.poses), &j.pose(&self.poses), self.t)
            })
            .collect()
    }
}

/// Where a load-controlled path folds: the load parameter beyond which it has no equilibrium nearby (a
/// load the structure cannot carry, or a driven motion the mechanism cannot make). There the tangent
/// `[K Jᵀ; J 0]` turns singular.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitPoint {
    /// Load parameter of the limit point: the furthest along the path at which equilibrium was found,
    /// within [`LIMIT_POINT_TOLERANCE`](crate::solver::LIMIT_POINT_TOLERANCE)` · |end − start|` of the
    /// fold.
    pub t: f64,
    /// The nearest load parameter past `t` at which no equilibrium was found: the fold lies between `t`
    /// and `beyond`.
    pub beyond: f64,
    /// The equilibrium at `t`.
    pub step: StepResult,
}

/// A walked load path.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// How it was walked.
    pub mode: Mode,
    /// The starting equilibrium, then one result per step: every step when the path was walked to its
    /// end, the steps before the limit point when it stopped at one (a step on the limit point itself is
    /// left to [`Sweep::limit`]; the starting equilibrium is always kept).
    pub steps: Vec<StepResult>,
    /// The limit point where the path stopped, if it met one (always `None` for an arc-length path,
    /// which goes through them).
    pub limit: Option<LimitPoint>,
    /// Where an arc-length path could be followed no further, if it stopped so: the load parameter of its
    /// last equilibrium, from which no step, however short, stays within its predictor's reach (the path
    /// branches there, or bends too sharply to follow). Always `None` for a sweep in load steps, which
    /// stops at a limit point instead.
    pub stuck: Option<f64>,
}

impl Sweep {
    /// Whether the path was walked to its end (it met no limit point).
    pub fn is_complete(&self) -> bool {
        self.limit.is_none()
    }

    /// The sweep if it was walked to its end, else [`SolverError::LimitPoint`] with the limit point's
    /// load parameter: for a caller that needs the whole path.
    pub fn complete(self) -> Result<Sweep, SolverError> {
        match &self.limit {
            None => Ok(self),
            Some(limit) => Err(SolverError::LimitPoint { reached: limit.t }),
        }
    }

    /// Every equilibrium found, in the order of the path: the steps, then the limit point's.
    pub fn equilibria(&self) -> impl Iterator<Item = &StepResult> {
        self.steps.iter().chain(self.limit.as_ref().map(|l| &l.step))
    }
}
