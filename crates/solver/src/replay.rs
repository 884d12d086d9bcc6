//! A run recorded and replayed with a moved model: how a derivative of anything a run computes is taken
//! through its equilibria without solving them again.
//!
//! [`record`] runs a computation as it is and hands it a [`Taping`], which the computation passes to its
//! solvers ([`StaticSolver::taped`](crate::StaticSolver::taped)); for every
//! [`StaticSolver`](crate::StaticSolver) created with it (in the order they are created) the recording
//! keeps what each of its solves returned: each
//! [`StaticSolver::equilibrium`](crate::StaticSolver::equilibrium), [`StaticSolver::sweep_from`](crate::StaticSolver::sweep_from) and
//! [`StaticSolver::arc_length_sweep_from`](crate::StaticSolver::arc_length_sweep_from) (and the calls built on them). [`replay`] runs the same computation again, typically on a model read
//! with one number moved by `δ`, handing it the replay's [`Taping`]: each solver it creates with it takes the place of the recorded one of the same
//! rank, and each of its solves, instead of solving, returns the recorded equilibria each moved by one
//! Newton iteration of the moved model, at the load parameter the replayed call asks for. Everything the
//! computation then reads off the equilibria (rows, slopes, compliances, reactions) is read as usual.
//!
//! Why this gives the derivatives through the equilibrium: at a recorded equilibrium `z` of the model `p`, one Newton iteration
//! of the model `p + δ` solved with the recorded tangent `A₀ = A(z, p)` lands on `z − A₀⁻¹ F(z, p+δ)`, a
//! smooth function of `δ` whose derivative at `δ = 0` is `−A₀⁻¹ ∂F/∂p = dz/dp`, the implicit function
//! theorem's rate of the equilibrium (its error against the moved equilibrium is of order `δ²`, as the
//! exact tangent's would be). So what the replayed run returns, as a function of `δ`, has at `δ = 0` the
//! derivative of what the run computes; a difference quotient of replays, Richardson extrapolated, gives it
//! to the order of the quotient, with no equilibrium solved again. The solver's tolerance enters only as the
//! recorded equilibria's distance from the exact ones, a relative error of that size (1e-9), not divided by
//! the step as in differences of re-solves.
//!
//! What a replay costs: the recording factorizes the exact tangent at each equilibrium it keeps (when the
//! solver's backend is the dense LU) and keeps the factors, with the recorded model's Newton right-hand
//! side there and a copy of each solver's model; every replay's iteration there solves with them
//! (`StaticSolver::kept_chord_correction`) a right-hand side that is
//! the recorded one corrected by the few elements and joints the move touched (the moved model's
//! differing from the recorded one's, found once per solver), or, at another load parameter, the moved
//! model's assembled whole. A path tangent or a compliance read at a moved equilibrium
//! ([`StaticSolver::path_tangent`](crate::StaticSolver::path_tangent),
//! [`StaticSolver::factorize_tangent`](crate::StaticSolver::factorize_tangent)) is solved with the
//! recorded factors there and one step of refinement against the moved model's tangent, assembled
//! there and never factorized: it is the moved model's own to the square of the move, and its rate
//! with respect to the move is the exact one's, `d(A⁻¹b) = A⁻¹(db − dA·x)`. No replay
//! assembles the residual at its moved equilibria (a moved equilibrium reports the
//! recorded one's residuals: its own are of the second order in the move), and a replayed solver whose
//! recorded one kept every constraint row checks neither redundancy nor restraint again
//! (`replays_independent_rows`). Where no factors were kept (the sparse backend), the iteration is the exact one
//! ([`StaticSolver::newton_correction`](crate::StaticSolver::newton_correction)).
//!
//! A run that reads only some rows of a sweep (a slope at one load parameter, the last row) may ask its
//! solver to move only those ([`ReplayRows`]): the replayed sweep has those steps alone. A replay's solver
//! takes the workspace (KKT pattern, analysis, buffers) a solver of an earlier replay of the recording left
//! on the tape, and what a run decided of its model's form ([`Taping::decided`]) is its replays' without deciding
//! again.
//!
//! A replay that takes another path than the recording (a solver of other parts, another sequence of
//! solves) is reported, never papered over: [`replay`] returns [`Diverged`].

use crate::error::SolverError;
use crate::kkt::LuFactors;
use crate::options::LoadPath;
use crate::results::{StepResult, Sweep};
use elastokin_core::Model;
use std::any::Any;
use std::sync::{Arc, Mutex};

/// Which steps of a sweep a replay moves, for a run that reads only some of a sweep's rows (those about one
/// load parameter, the last row): the steps whose load parameter lies within one step of `near`, and the
/// last step if `last`. The replayed sweep has those steps alone, in order: nothing is
/// spent on rows nobody reads, neither moving nor copying nor reading them (a caller that sets this finds
/// the rows it reads by their load parameters or as the last, not by their place in the whole sweep). Set
/// on a solver with
/// [`StaticSolver::replay_rows`](crate::StaticSolver::replay_rows); outside a replay it changes nothing.
///
/// A run that also reads a row it finds by its value (where a reading is largest over the sweep) sets
/// `extremes` and names those rows after reading them ([`Taping::rows_read`]): the recording keeps every step's
/// factors, and the replays move the rows named too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplayRows {
    /// The load parameter whose neighbouring steps are moved, if any.
    pub near: Option<f64>,
    /// Whether the last step is moved too.
    pub last: bool,
    /// Whether the run names further rows it read once it has read the recorded sweep ([`Taping::rows_read`]).
    pub extremes: bool,
}

impl ReplayRows {
    /// Whether the step at load parameter `t`, the `index`-th of `count`, of a sweep along `path` is moved.
    pub(crate) fn moves(&self, t: f64, index: usize, count: usize, path: &LoadPath) -> bool {
        let step = (path.end - path.start).abs() / path.steps.max(1) as f64;
        // A step's own rounding aside: a row one step away is a neighbour.
        self.near.is_some_and(|near| (t - near).abs() <= step * (1.0 + 1e-9)) || (self.last && index + 1 == count)
    }
}

/// What one solve of a recorded solver returned.
#[derive(Debug, Clone)]
enum Call {
    /// An equilibrium at one load parameter, and the pieces of its elements' laws and the factors of its
    /// tangent there.
    Equilibrium(Result<StepResult, SolverError>, Pieces, Option<Factors>),
    /// A sweep, shared with the replays, which read it in place.
    Sweep(Arc<RecordedSweep>),
}

/// One recorded solver: its model (a copy, for a replay to tell what its move touched), the constraint rows
/// it kept, and its solves in order.
#[derive(Debug, Clone)]
struct Recorded {
    model: Arc<Model>,
    active: Vec<usize>,
    calls: Vec<Call>,
}

/// The solves of a recorded run ([`record`]), to [`replay`] it.
#[derive(Debug, Clone, Default)]
pub struct Tape {
    solvers: Vec<Recorded>,
    /// The workspaces of its replays' spent solvers, for the next replays' (replays run on many threads).
    spare: Spare,
    /// The last sweep kept: its solver and call, for [`Taping::rows_read`].
    last_sweep: Option<(usize, usize)>,
    /// What the run decided of its model's form, in order ([`Taping::decided`]).
    decisions: Vec<Decision>,
}

impl Tape {
    /// How many solvers the run created.
    pub fn solvers(&self) -> usize {
        self.solvers.len()
    }

    /// How many equilibria the run's solves returned.
    pub fn equilibria(&self) -> usize {
        let count = |c: &Call| match c {
            Call::Equilibrium(r, ..) => usize::from(r.is_ok()),
            Call::Sweep(s) => s.result.as_ref().map_or(0, |s| s.steps.len()),
        };
        self.solvers.iter().flat_map(|s| &s.calls).map(count).sum()
    }

    /// The load parameter of the first limit point a recorded sweep met, if any: where the path has no
    /// derivative with respect to the model.
    pub fn limit_point(&self) -> Option<f64> {
        self.solvers.iter().flat_map(|s| &s.calls).find_map(|c| match c {
            Call::Sweep(s) => s.result.as_ref().ok()?.limit.as_ref().map(|l| l.t),
            Call::Equilibrium(..) => None,
        })
    }
}

/// Workspaces of spent solvers (`SolverWorkspace`, kept by type here, below the solver): a replay's solver
/// takes one of its topology instead of allocating and analysing its own (`StaticSolver::with_workspace`),
/// and leaves its own when dropped. A copy of a tape has none.
#[derive(Default)]
struct Spare(std::sync::Mutex<Vec<Box<dyn Any + Send>>>);

impl Clone for Spare {
    fn clone(&self) -> Self {
        Spare::default()
    }
}

impl std::fmt::Debug for Spare {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let count = self.0.lock().map_or(0, |s| s.len());
        write!(f, "Spare({count} workspaces)")
    }
}

/// The most workspaces a tape keeps: a few per recorded solver, for replays on several threads.
const MOST_SPARE: usize = 64;

impl Taping {
    /// A spare workspace of type `W` that `fits`, from the tape of the replay under way, if any.
    pub(crate) fn spare_workspace<W: Any>(&self, fits: impl Fn(&W) -> bool) -> Option<W> {
        self.with(|active| match active {
            Active::Replaying { tape, .. } => {
                let mut spare = tape.spare.0.lock().ok()?;
                let k = spare.iter().position(|w| w.downcast_ref::<W>().is_some_and(&fits))?;
                spare.swap_remove(k).downcast::<W>().ok().map(|w| *w)
            }
            Active::Recording(_) => None,
        })
        .flatten()
    }

    /// Leaves a spent replaying solver's workspace to the replay's tape; returns it when the tape keeps no
    /// more (or no replay is under way), for the caller to drop.
    pub(crate) fn leave_workspace<W: Any + Send>(&self, workspace: W) -> Option<W> {
        let mut workspace = Some(workspace);
        self.with(|active| {
            let Active::Replaying { tape, .. } = active else { return };
            let Ok(mut spare) = tape.spare.0.lock() else { return };
            if spare.len() < MOST_SPARE {
                spare.extend(workspace.take().map(|w| Box::new(w) as Box<dyn Any + Send>));
            }
        });
        workspace
    }
}

/// A replay that took another path than its recording: the replayed computation created a solver of
/// other parts, or asked for other solves.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the moved model's run took another path than the model's own: {0}")]
pub struct Diverged(pub String);

/// What a recording or replay under way is doing with its solvers.
enum Active {
    Recording(Tape),
    Replaying {
        tape: Arc<Tape>,
        next_solver: usize,
        used: Vec<usize>,
        diverged: Option<String>,
        kinked: bool,
        next_decision: usize,
    },
}

/// A recording ([`record`]) or replay ([`replay`]) under way, handed to the computation it runs, which
/// passes it to every solver that takes part ([`StaticSolver::taped`](crate::StaticSolver::taped)):
/// a solver created with it records its solves, or replays the recorded solver of its rank. The default
/// takes part in none: its solvers solve. Clones share the one recording or replay; once [`record`] or
/// [`replay`] has returned, a solver that still holds one solves as if it held none.
#[derive(Clone, Default)]
pub struct Taping(Option<Arc<Mutex<Option<Active>>>>);

impl std::fmt::Debug for Taping {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = self.with(|a| match a {
            Active::Recording(_) => "recording",
            Active::Replaying { .. } => "replaying",
        });
        write!(f, "Taping({})", what.unwrap_or("none"))
    }
}

/// The taping that takes part in nothing (`Taping::default()`), for a `&'static` reference where none is
/// given.
pub static NO_TAPING: Taping = Taping(None);

/// Two tapings are equal when they are the same recording or replay (or both none).
impl PartialEq for Taping {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        }
    }
}

impl Taping {
    fn of(active: Active) -> Taping {
        Taping(Some(Arc::new(Mutex::new(Some(active)))))
    }

    /// The recording or replay, locked; `None` for a taping of none.
    fn lock(&self) -> Option<std::sync::MutexGuard<'_, Option<Active>>> {
        // A computation that panicked while holding the lock left nothing half-done that matters here.
        self.0.as_ref().map(|cell| cell.lock().unwrap_or_else(|e| e.into_inner()))
    }

    /// `f` of the recording or replay under way, if any.
    fn with<R>(&self, f: impl FnOnce(&mut Active) -> R) -> Option<R> {
        self.lock()?.as_mut().map(f)
    }

    /// Whether this taping records or replays: solves that take part must then be made in the order the
    /// recording made them, one after another.
    pub fn takes_part(&self) -> bool {
        self.lock().is_some_and(|active| active.is_some())
    }

    /// What was recorded or replayed, the taping ended: its solvers solve from now on.
    fn finish(&self) -> Option<Active> {
        self.lock()?.take()
    }
}

/// Runs `run` with a new recording, which `run` passes to the solvers whose solves it keeps
/// ([`StaticSolver::taped`](crate::StaticSolver::taped)).
pub fn record<R>(run: impl FnOnce(&Taping) -> R) -> (R, Tape) {
    let taping = Taping::of(Active::Recording(Tape::default()));
    let out = run(&taping);
    match taping.finish() {
        Some(Active::Recording(tape)) => (out, tape),
        _ => unreachable!("the recording is this call's"),
    }
}

/// What a replay returned: the computation's result, and whether an element changed the piece of its force
/// law between a recorded equilibrium and its move ([`ForceElement::piece`](elastokin_core::ForceElement::piece):
/// a stop touched or left), so that what the replay read has a kink between the model and the moved one.
#[derive(Debug, Clone, PartialEq)]
pub struct Replay<R> {
    /// What the computation returned.
    pub value: R,
    /// Whether a stop touched or left at some equilibrium as the model moved.
    pub kinked: bool,
}

/// Runs `run` with a replay of `tape`, which `run` passes to its solvers as the recorded run did (see the
/// module's documentation). [`Diverged`] when the run created solvers of other parts or in another number,
/// or asked for other solves than were recorded.
pub fn replay<R>(tape: &Arc<Tape>, run: impl FnOnce(&Taping) -> R) -> Result<Replay<R>, Diverged> {
    let used = vec![0; tape.solvers.len()];
    let taping = Taping::of(Active::Replaying {
        tape: tape.clone(),
        next_solver: 0,
        used,
        diverged: None,
        kinked: false,
        next_decision: 0,
    });
    let out = run(&taping);
    let Some(Active::Replaying { next_solver, used, diverged, kinked, .. }) = taping.finish() else {
        unreachable!("the replay is this call's")
    };
    if let Some(why) = diverged {
        return Err(Diverged(why));
    }
    if next_solver != tape.solvers.len() {
        return Err(Diverged(format!("it created {next_solver} solvers where {} were recorded", tape.solvers.len())));
    }
    if let Some(k) = (0..used.len()).find(|&k| used[k] != tape.solvers[k].calls.len()) {
        return Err(Diverged(format!(
            "solver {k} asked for {} solves where {} were recorded",
            used[k],
            tape.solvers[k].calls.len()
        )));
    }
    Ok(Replay { value: out, kinked })
}

impl Taping {
    /// Names rows of the recording's last sweep that a run read besides those of its solver's
    /// [`ReplayRows`] (set with `extremes`): rows it found by their values, such as where a reading is
    /// largest. The replays move them too. Outside a recording it does nothing: a replay moves what its
    /// recording named.
    pub fn rows_read(&self, rows: &[usize]) {
        self.with(|active| {
            let Active::Recording(tape) = active else { return };
            let Some((solver, call)) = tape.last_sweep else { return };
            // The recording holds its sweeps alone until it ends.
            if let Some(Call::Sweep(sweep)) = tape.solvers[solver].calls.get_mut(call) {
                if let Some(sweep) = Arc::get_mut(sweep) {
                    for &r in rows {
                        if !sweep.read.contains(&r) {
                            sweep.read.push(r);
                        }
                    }
                }
            }
        });
    }
}

/// One decision of [`Taping::decided`], kept by type.
#[derive(Clone)]
struct Decision(Arc<dyn Any + Send + Sync>);

impl std::fmt::Debug for Decision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Decision")
    }
}

impl Taping {
    /// What `decide` decides of a run's model: decided and kept when recording; the recording's when
    /// replaying, not decided again; decided otherwise. For a property of the model's form that a move
    /// small enough for a derivative keeps, as it keeps its rows' independence
    /// (`replays_independent_rows`): which ways its joints alone hold a point, read from the rank of their
    /// Jacobian with a margin. A replay that asks for more decisions than were recorded, or of another
    /// kind, decides them.
    pub fn decided<T: Clone + Send + Sync + 'static>(&self, decide: impl FnOnce() -> T) -> T {
        let kept = self.with(|active| match active {
            Active::Replaying { tape, next_decision, .. } => {
                let kept = tape.decisions.get(*next_decision).and_then(|d| d.0.downcast_ref::<T>().cloned());
                *next_decision += 1;
                kept
            }
            Active::Recording(_) => None,
        });
        if let Some(kept) = kept.flatten() {
            return kept;
        }
        let value = decide();
        self.with(|active| {
            if let Active::Recording(tape) = active {
                tape.decisions.push(Decision(Arc::new(value.clone())));
            }
        });
        value
    }

    /// Notes in the replay that a stop touched or left as the model moved.
    pub(crate) fn note_kink(&self) {
        self.with(|active| {
            if let Active::Replaying { kinked, .. } = active {
                *kinked = true;
            }
        });
    }
}

/// A new solver's part in the recording or replay, if any, and in a replay the recorded model.
pub(crate) type Registered = Option<(Taped, Option<Arc<Model>>)>;

/// A solver's part in a recording or replay: its rank among the run's solvers.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Taped {
    solver: usize,
}

/// What a taped solver's solve is to do.
pub(crate) enum Replayed<T> {
    /// No recording or replay: solve.
    Solve,
    /// Recording: solve, and keep what it returned.
    Record(Taped),
    /// Replaying: move what was recorded.
    Call(T),
}

/// Which piece of its force law each element of a model is on at an equilibrium
/// ([`StepResult::element_pieces`]).
pub(crate) type Pieces = Vec<u8>;

/// What a recording keeps at an equilibrium for the replays there, when its solver's backend is the dense
/// LU: the factors of the recorded model's exact tangent (every replay's iteration there solves with them
/// instead of factorizing the moved model's tangent), and the load parameter and Newton right-hand side
/// (`Q − Jᵀλ`, `−Φ`) of the recorded model there, which a replay's iteration at the same load parameter
/// corrects by the elements and joints its move touched instead of assembling the moved model whole.
/// Shared by the replays, which may run on other threads.
#[derive(Debug)]
pub(crate) struct Kept {
    pub(crate) lu: LuFactors,
    pub(crate) t: f64,
    pub(crate) rhs: Vec<f64>,
}

/// [`Kept`], shared.
pub(crate) type Factors = Arc<Kept>;

/// What a replay's model differs from its recorded one in: the elements and joints (by index) whose numbers
/// its move changed. A replay's iteration at a recorded equilibrium, at the recorded load parameter, then
/// corrects the recorded right-hand side by these alone (`StaticSolver::touched_rhs`): every other
/// element and row gives what it gave the recording, to the bit.
#[derive(Debug)]
pub(crate) struct Touched {
    pub(crate) recorded: Arc<Model>,
    pub(crate) elements: Vec<usize>,
    pub(crate) joints: Vec<bool>,
}

impl Touched {
    /// What `moved` differs from `recorded` in; `None` when its parts differ (then nothing is corrected:
    /// the replay assembles its model whole).
    pub(crate) fn between(recorded: Arc<Model>, moved: &Model) -> Option<Touched> {
        let (old, new) = (&recorded, moved);
        if old.bodies().len() != new.bodies().len()
            || old.elements().len() != new.elements().len()
            || old.joints().len() != new.joints().len()
        {
            return None;
        }
        let elements =
            (0..new.elements().len()).filter(|&e| !new.elements()[e].same_as(old.elements()[e].as_ref())).collect();
        let joints = new.joints().iter().zip(old.joints()).map(|(a, b)| a != b).collect();
        Some(Touched { recorded, elements, joints })
    }
}

/// A recorded equilibrium, the pieces of the recorded model's elements there and its tangent's factors.
pub(crate) type RecordedEquilibrium = (Result<StepResult, SolverError>, Pieces, Option<Factors>);

/// A recorded sweep (by load steps or by arc length), which its replays read in place (a replay copies the
/// steps it moves alone).
#[derive(Debug)]
pub(crate) struct RecordedSweep {
    /// Its path.
    pub(crate) path: LoadPath,
    /// What it returned.
    pub(crate) result: Result<Sweep, SolverError>,
    /// The pieces of the recorded model's elements at each of its steps.
    pub(crate) pieces: Vec<Pieces>,
    /// The recorded tangent's factors at each of its steps, where kept.
    pub(crate) factors: Vec<Option<Factors>>,
    /// The steps the run named as read once it had read the sweep ([`Taping::rows_read`]).
    pub(crate) read: Vec<usize>,
}

impl Taping {
    /// Whether a replay is under way: every solve a solver of it makes is then a recorded one moved.
    pub(crate) fn replaying(&self) -> bool {
        self.with(|active| matches!(active, Active::Replaying { .. })).unwrap_or(false)
    }

    /// Whether a new solver of a model with `rows` constraint rows replays a recorded solver of as many
    /// rows that kept every one of them. Its model is then known without looking again to have no
    /// redundant rows and every body restrained: both hold with a margin on the recorded model (rows
    /// independent to the redundancy check's tolerance, a tangent the restraint check found regular), and a
    /// margin is not lost in a move small enough for a derivative. Where the recorded solver dropped rows,
    /// the moved model is checked again, since a move can make a dropped row independent (a second hinge
    /// turned off the first's axis locks what it duplicated): [`Taping::register`] then refuses a replay
    /// whose rows differ.
    pub(crate) fn replays_independent_rows(&self, rows: usize) -> bool {
        self.with(|active| match active {
            Active::Replaying { tape, next_solver, .. } => tape
                .solvers
                .get(*next_solver)
                .is_some_and(|r| r.model.constraint_rows() == rows && r.active.len() == rows),
            Active::Recording(_) => false,
        })
        .unwrap_or(false)
    }

    /// Registers a new solver of `model` with kept constraint rows `active` with the recording or replay.
    /// In a replay, a solver unlike the recorded one of its rank is refused, and the recorded model comes
    /// with it, to tell what the move touched.
    pub(crate) fn register(&self, model: &Model, active: &[usize]) -> Result<Registered, SolverError> {
        let registered = self.with(|taping| match taping {
            Active::Recording(tape) => {
                let model = Arc::new(model.clone());
                tape.solvers.push(Recorded { model, active: active.to_vec(), calls: Vec::new() });
                Ok(Some((Taped { solver: tape.solvers.len() - 1 }, None)))
            }
            Active::Replaying { tape, next_solver, diverged, .. } => {
                let k = *next_solver;
                *next_solver += 1;
                let Some(r) = tape.solvers.get(k) else {
                    let why = format!("it created more solvers than the {} recorded", tape.solvers.len());
                    return Err(diverge(diverged, why));
                };
                let (dofs, recorded_dofs) = (model.dofs(), r.model.dofs());
                if dofs != recorded_dofs || model.constraint_rows() != r.model.constraint_rows() || r.active != active {
                    let why = format!(
                        "solver {k} has {dofs} body coordinates and {} kept constraint rows where the recorded one \
                         had {recorded_dofs} and {}: the parts or the redundant joints differ",
                        active.len(),
                        r.active.len()
                    );
                    return Err(diverge(diverged, why));
                }
                Ok(Some((Taped { solver: k }, Some(r.model.clone()))))
            }
        });
        registered.unwrap_or(Ok(None))
    }

    /// What a taped solver's next single equilibrium is to do.
    pub(crate) fn next_equilibrium(&self, taped: Option<Taped>) -> Result<Replayed<RecordedEquilibrium>, SolverError> {
        self.next(taped, false, |call| match call {
            Call::Equilibrium(r, pieces, factors) => Some((r.clone(), pieces.clone(), factors.clone())),
            Call::Sweep { .. } => None,
        })
    }

    /// What a taped solver's next sweep is to do.
    pub(crate) fn next_sweep(&self, taped: Option<Taped>) -> Result<Replayed<Arc<RecordedSweep>>, SolverError> {
        self.next(taped, true, |call| match call {
            Call::Sweep(sweep) => Some(sweep.clone()),
            Call::Equilibrium(..) => None,
        })
    }

    /// What a taped solver's next solve is to do; in a replay, `take` reads the recorded call.
    fn next<T>(
        &self,
        taped: Option<Taped>,
        sweep: bool,
        take: impl Fn(&Call) -> Option<T>,
    ) -> Result<Replayed<T>, SolverError> {
        let Some(taped) = taped else { return Ok(Replayed::Solve) };
        let next = self.with(|active| match active {
            Active::Replaying { tape, used, diverged, .. } => {
                let k = taped.solver;
                let Some(call) = tape.solvers[k].calls.get(used[k]) else {
                    return Err(diverge(diverged, format!("solver {k} asked for more solves than were recorded")));
                };
                used[k] += 1;
                match take(call) {
                    Some(t) => Ok(Replayed::Call(t)),
                    None => Err(diverge(
                        diverged,
                        format!("solver {k} asked for a {} where a {} was recorded", kind(sweep), kind(!sweep)),
                    )),
                }
            }
            Active::Recording(_) => Ok(Replayed::Record(taped)),
        });
        // A solver registered with a recording that has since ended solves as usual.
        next.unwrap_or(Ok(Replayed::Solve))
    }

    /// Keeps what a recorded solver of `model` returned for an equilibrium, with its tangent's factors.
    pub(crate) fn keep_equilibrium(
        &self,
        taped: Taped,
        model: &Model,
        result: &Result<StepResult, SolverError>,
        factors: Option<Factors>,
    ) {
        let pieces = result.as_ref().map_or_else(|_| Vec::new(), |s| s.element_pieces(model));
        self.keep(taped, Call::Equilibrium(result.clone(), pieces, factors));
    }

    /// Keeps what a recorded solver of `model` returned for a sweep along `path`, with the tangent's
    /// factors at each step.
    pub(crate) fn keep_sweep(
        &self,
        taped: Taped,
        model: &Model,
        path: LoadPath,
        result: &Result<Sweep, SolverError>,
        factors: Vec<Option<Factors>>,
    ) {
        let pieces =
            result.as_ref().map_or_else(|_| Vec::new(), |s| s.steps.iter().map(|s| s.element_pieces(model)).collect());
        let sweep = RecordedSweep { path, result: result.clone(), pieces, factors, read: Vec::new() };
        self.keep(taped, Call::Sweep(Arc::new(sweep)));
    }

    fn keep(&self, taped: Taped, call: Call) {
        self.with(|active| {
            if let Active::Recording(tape) = active {
                if let Some(r) = tape.solvers.get_mut(taped.solver) {
                    if matches!(call, Call::Sweep { .. }) {
                        tape.last_sweep = Some((taped.solver, r.calls.len()));
                    }
                    r.calls.push(call);
                }
            }
        });
    }
}

fn diverge(diverged: &mut Option<String>, why: String) -> SolverError {
    diverged.get_or_insert(why.clone());
    SolverError::InvalidInput { what: "replay", why }
}

fn kind(sweep: bool) -> &'static str {
    if sweep {
        "sweep"
    } else {
        "single equilibrium"
    }
}

/// Where the load parameter of a recorded sweep's `index`-th equilibrium (`None`: a limit point) lies on the replayed path: the
/// same step of it, computed as the sweep computes its steps, when the recorded one sat on a step (a
/// replayed run may sweep from another start, a load that depends on the model, and a reading that looks
/// for the row at a point must find it as the sweep itself would); else the same fraction of the way.
pub(crate) fn moved_t(t: f64, index: Option<usize>, recorded: &LoadPath, path: &LoadPath) -> f64 {
    if let Some(i) = index.filter(|_| recorded.steps == path.steps) {
        let on_step = |p: &LoadPath| p.start + (p.end - p.start) / p.steps as f64 * i as f64;
        if t == on_step(recorded) {
            return on_step(path);
        }
    }
    let span = recorded.end - recorded.start;
    if span == 0.0 {
        t - recorded.start + path.start
    } else {
        path.start + (t - recorded.start) / span * (path.end - path.start)
    }
}
