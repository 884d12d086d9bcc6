//! Sensitivities through the equilibrium. At an equilibrium `F(z, p) = 0` of the corner (`z` the body
//! poses and joint multipliers, `F = [Jᵀλ − Q; Φ]`, `p` the parameters), the implicit function theorem
//! gives the rates of every pose and joint force at once: `A · dz/dp = −∂F/∂p` with `A = [K Jᵀ; J 0]`, the
//! tangent the step is solved with, so each parameter costs one back-substitution. `∂F/∂p` is the change of
//! the residual at the fixed state when the model is read again with `p` moved (a central difference of
//! the residual alone, which is smooth in `p`: no equilibrium is solved again), and a figure read from the
//! poses (toe, camber, the wheel centre) is differentiated along `(dz/dp, 1)` the same way. Figures that
//! are slopes of rows (bump steer, camber gain) are the same slope of the rows' derivatives.
//!
//! Only corrected-mode rows are equilibria: sensitivities are of the corrected path.

use super::parameter::Parameters;
use crate::analysis::{slope_at, travel_row};
use crate::build::{Corner, Rig};
use crate::description::Side;
use elastokin_core::{Pose, Vec3, BODY_DOFS};
use elastokin_solver::assembly::Assembly;
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver, StepResult};

/// A parameter is moved by this fraction of its size (at least of 0.1 in the file's units: 10 µm of a
/// hardpoint near the origin) and twice that for the central differences of the residual, Richardson
/// extrapolated. The residual is smooth in every parameter: the error is of order `step⁴`, the rounding of
/// order `ε / step` (a step of 1e-6 left 2e-4 of a small toe rate to rounding; 1e-4 leaves 1e-6 and less).
pub const RELATIVE_STEP: f64 = 1e-4;

/// Parallel wheel travel and its derivatives with respect to each parameter: every row's toe, camber and
/// wheel centre, and the bump steer and camber gain at design (SI: rad, m, rad/m, per unit of the
/// parameter as the file gives it).
#[derive(Debug, Clone, PartialEq)]
pub struct TravelSensitivity {
    /// The parameters' pointers.
    pub pointers: Vec<String>,
    /// Wheel travel of each row (m).
    pub travel: Vec<f64>,
    /// Toe of each row (rad, toe-in +).
    pub toe: Vec<f64>,
    /// Camber of each row (rad, top outward +).
    pub camber: Vec<f64>,
    /// Wheel centre of each row (m).
    pub wheel_centre: Vec<Vec3>,
    /// `d toe / d p`: row × parameter.
    pub d_toe: Vec<Vec<f64>>,
    /// `d camber / d p`: row × parameter.
    pub d_camber: Vec<Vec<f64>>,
    /// `d wheel centre / d p`: row × parameter.
    pub d_wheel_centre: Vec<Vec<Vec3>>,
    /// Bump steer at design: the slope of toe against travel (rad/m).
    pub bump_steer: f64,
    /// Its derivative per parameter.
    pub d_bump_steer: Vec<f64>,
    /// Camber gain at design (rad/m).
    pub camber_gain: f64,
    /// Its derivative per parameter.
    pub d_camber_gain: Vec<f64>,
    /// The columns of the K&C report's parallel-travel table.
    pub columns: Vec<String>,
    /// Their derivatives: parameter × row × column (`None` where a cell is empty).
    pub d_columns: Vec<Vec<Vec<Option<f64>>>>,
    /// Every headline figure of the K&C report's parallel travel read from its rows, with its derivative
    /// per parameter (`None` where the figure is missing, or has no derivative), in the report's units.
    pub report_figures: Vec<(crate::kc::Figure, Vec<Option<f64>>)>,
}

/// One parameter moved both ways by one and two steps: the corners built from the model read again
/// (`+h, −h, +2h, −2h`), and their residuals' assemblies on the base model's active rows.
struct Moved {
    step: f64,
    files: [crate::file::SuspensionFile; 4],
    corners: [Corner; 4],
    assemblies: [Assembly; 4],
}

/// The derivative from central differences over one and two steps, Richardson extrapolated: `values` at
/// `+h, −h, +2h, −2h`.
fn richardson(values: [f64; 4], h: f64) -> f64 {
    (8.0 * (values[0] - values[1]) - (values[2] - values[3])) / (12.0 * h)
}

/// `[Jᵀλ − Q; Φ]` of `corner`'s model at the state, assembled on `assembly`.
fn residual(assembly: &mut Assembly, corner: &Corner, poses: &[Pose], t: f64, lambda: &[f64]) -> Vec<f64> {
    assembly.assemble(&corner.model, poses, t, lambda, None);
    let n = assembly.n;
    let mut out = vec![0.0; n + assembly.m()];
    assembly.jt_times(lambda, &mut out[..n]);
    for (o, q) in out[..n].iter_mut().zip(&assembly.applied) {
        *o -= q;
    }
    out[n..].copy_from_slice(&assembly.phi);
    out
}

/// The poses moved by `scale · dq` (`BODY_DOFS` per body).
fn moved_poses(poses: &[Pose], dq: &[f64], scale: f64) -> Vec<Pose> {
    poses
        .iter()
        .enumerate()
        .map(|(b, pose)| {
            let mut p = *pose;
            let d: Vec<f64> = dq[b * BODY_DOFS..(b + 1) * BODY_DOFS].iter().map(|v| v * scale).collect();
            p.apply_increment6(&d);
            p
        })
        .collect()
}

/// Parallel wheel travel from `from` to `to` (m, `steps` steps, corrected mode) of the left corner, and
/// its derivatives with respect to `parameters`. A parameter whose move changes the model's parts (a
/// connection's kind) has no derivative and is refused by name, as is a path that meets a limit point.
pub fn parallel_travel_sensitivity(
    parameters: &Parameters,
    from: f64,
    to: f64,
    steps: usize,
) -> Result<TravelSensitivity, String> {
    let build = |file: crate::file::SuspensionFile| {
        file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())
    };
    let corner = build(parameters.file()?)?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).map_err(|e| e.to_string())?;
    let sweep = solver.sweep(LoadPath::new(from, to, steps), Mode::Corrected).map_err(|e| e.to_string())?;
    if let Some(limit) = sweep.limit {
        return Err(format!(
            "the travel meets a limit point at {:.6} m, where the corner's motion has no derivative; narrow the range",
            limit.t
        ));
    }
    let active = solver.active_rows().to_vec();
    let n = corner.model.dofs();
    let same_parts = |c: &Corner| {
        c.model.dofs() == n
            && c.model.constraint_rows() == corner.model.constraint_rows()
            && c.model.elements().len() == corner.model.elements().len()
    };
    let mut moved = Vec::with_capacity(parameters.len());
    for (k, pointer) in parameters.pointers.iter().enumerate() {
        let step = RELATIVE_STEP * parameters.values[k].abs().max(0.1);
        let files = [step, -step, 2.0 * step, -2.0 * step].map(|d| parameters.file_moved(k, d));
        let [a, b, c, d] = files;
        let files = [a?, b?, c?, d?];
        let corners =
            [0, 1, 2, 3].map(|i| build(files[i].clone()).map_err(|e| format!("parameter '{pointer}' moved: {e}")));
        let [a, b, c, d] = corners;
        let corners = [a?, b?, c?, d?];
        if !corners.iter().all(same_parts) {
            return Err(format!(
                "parameter '{pointer}' changes the model's parts when moved (its joints or elements): it has no \
                 derivative; give a number that moves a part, not one that chooses what the parts are"
            ));
        }
        let assemblies = [0, 1, 2, 3].map(|i| Assembly::new(&corners[i].model, active.clone()));
        moved.push(Moved { step, files, corners, assemblies });
    }

    let rows = sweep.steps.len();
    let mut out = TravelSensitivity {
        pointers: parameters.pointers.clone(),
        travel: Vec::with_capacity(rows),
        toe: Vec::with_capacity(rows),
        camber: Vec::with_capacity(rows),
        wheel_centre: Vec::with_capacity(rows),
        d_toe: Vec::with_capacity(rows),
        d_camber: Vec::with_capacity(rows),
        d_wheel_centre: Vec::with_capacity(rows),
        bump_steer: 0.0,
        d_bump_steer: Vec::new(),
        camber_gain: 0.0,
        d_camber_gain: Vec::new(),
        columns: Vec::new(),
        d_columns: Vec::new(),
        report_figures: Vec::new(),
    };
    // dz/dp of every row, per parameter: the equilibria moved with each parameter, read below by the K&C
    // reduction as every row is.
    let mut rates: Vec<Vec<Vec<f64>>> = vec![Vec::with_capacity(rows); parameters.len()];
    for step in &sweep.steps {
        let state = solver.state_of(step);
        let attitude = corner.wheel.attitude(&state.poses);
        out.travel.push(state.t);
        out.toe.push(attitude.toe);
        out.camber.push(attitude.camber);
        out.wheel_centre.push(attitude.wheel_centre);
        solver.factorize_tangent(&state).map_err(|e| e.to_string())?;
        let (mut d_toe, mut d_camber, mut d_centre) = (Vec::new(), Vec::new(), Vec::new());
        for (k, m) in moved.iter_mut().enumerate() {
            let f: Vec<Vec<f64>> = (0..4)
                .map(|i| residual(&mut m.assemblies[i], &m.corners[i], &state.poses, state.t, &state.lambda))
                .collect();
            let mut dz: Vec<f64> =
                (0..f[0].len()).map(|r| -richardson([f[0][r], f[1][r], f[2][r], f[3][r]], m.step)).collect();
            solver.solve_factored(&mut dz).map_err(|e| e.to_string())?;
            // Read along (dz/dp, 1): the poses moved with the parameter, each read by its own model's wheel.
            let read: Vec<_> = [1.0, -1.0, 2.0, -2.0]
                .iter()
                .zip(&m.corners)
                .map(|(s, c)| c.wheel.attitude(&moved_poses(&state.poses, &dz[..n], s * m.step)))
                .collect();
            d_toe.push(richardson([0, 1, 2, 3].map(|i| read[i].toe), m.step));
            d_camber.push(richardson([0, 1, 2, 3].map(|i| read[i].camber), m.step));
            let centre = |k: usize| richardson([0, 1, 2, 3].map(|i| read[i].wheel_centre[k]), m.step);
            d_centre.push(Vec3::new(centre(0), centre(1), centre(2)));
            rates[k].push(dz);
        }
        out.d_toe.push(d_toe);
        out.d_camber.push(d_camber);
        out.d_wheel_centre.push(d_centre);
    }
    let no_design = || format!("the travel {from} to {to} m does not contain the design position: no slope at design");
    let rows: Vec<usize> = (0..rows).collect();
    let slope = |y: &dyn Fn(usize) -> f64| slope_at(&rows, 0.0, |&i| out.travel[i], |&i| y(i)).ok_or_else(no_design);
    let bump_steer = slope(&|i| out.toe[i])?;
    let camber_gain = slope(&|i| out.camber[i])?;
    let mut d_bump_steer = Vec::with_capacity(parameters.len());
    let mut d_camber_gain = Vec::with_capacity(parameters.len());
    for k in 0..parameters.len() {
        d_bump_steer.push(slope(&|i| out.d_toe[i][k])?);
        d_camber_gain.push(slope(&|i| out.d_camber[i][k])?);
    }
    out.bump_steer = bump_steer;
    out.camber_gain = camber_gain;
    out.d_bump_steer = d_bump_steer;
    out.d_camber_gain = d_camber_gain;

    // Every column and figure of the K&C report's parallel travel, differentiated as it is defined: the same
    // reduction applied to the rows read at (z ± s·dz/dp, p ± s) and (z ± 2s·dz/dp, p ± 2s), each by its own
    // model, Richardson extrapolated.
    let file = parameters.file()?;
    let base_rows: Vec<_> = sweep.steps.iter().map(|s| travel_row(&corner, s)).collect();
    let table = crate::kc::parallel_travel_table(&corner, &base_rows);
    out.report_figures = crate::kc::parallel_travel_figures(&file, &corner, (from, to), &base_rows)
        .into_iter()
        .map(|f| (f, Vec::with_capacity(parameters.len())))
        .collect();
    out.columns = table.columns.clone();
    for (k, m) in moved.iter().enumerate() {
        let mut tables = Vec::with_capacity(4);
        let mut figures = Vec::with_capacity(4);
        for (i, shift) in [1.0, -1.0, 2.0, -2.0].into_iter().enumerate() {
            let rows: Vec<_> = sweep
                .steps
                .iter()
                .zip(&rates[k])
                .map(|(step, dz)| travel_row(&m.corners[i], &moved_step(step, dz, shift * m.step, n, &active)))
                .collect();
            tables.push(crate::kc::parallel_travel_table(&m.corners[i], &rows));
            figures.push(crate::kc::parallel_travel_figures(&m.files[i], &m.corners[i], (from, to), &rows));
        }
        let number = |t: &crate::kc::Table, r: usize, c: usize| t.rows[r][c].number();
        out.d_columns.push(
            (0..table.rows.len())
                .map(|r| {
                    (0..table.columns.len())
                        .map(|c| {
                            let v = [0, 1, 2, 3].map(|i| number(&tables[i], r, c));
                            let [Some(a), Some(b), Some(c), Some(d)] = v else { return None };
                            Some(richardson([a, b, c, d], m.step)).filter(|x| x.is_finite())
                        })
                        .collect()
                })
                .collect(),
        );
        for (j, (_, derivatives)) in out.report_figures.iter_mut().enumerate() {
            let v = [0, 1, 2, 3].map(|i| figures[i].get(j).and_then(|f| f.value));
            let d = match v {
                [Some(a), Some(b), Some(c), Some(d)] => {
                    Some(richardson([a, b, c, d], m.step)).filter(|x| x.is_finite())
                }
                _ => None,
            };
            derivatives.push(d);
        }
    }
    Ok(out)
}

/// A step's equilibrium moved by `scale · dz` (`dz`: `n` body coordinates, then the active rows'
/// multipliers).
fn moved_step(step: &StepResult, dz: &[f64], scale: f64, n: usize, active: &[usize]) -> StepResult {
    let mut moved = step.clone();
    moved.poses = moved_poses(&step.poses, &dz[..n], scale);
    for (k, &row) in active.iter().enumerate() {
        moved.multipliers[row] += scale * dz[n + k];
    }
    moved
}

/// How a parameter's effect is told: per millimetre of a length (a hardpoint coordinate, a Chrono part's
/// `Location …` point, a loaded radius), per percent of anything else (a rate, a force).
pub fn effect_unit(pointer: &str) -> &'static str {
    let chrono_point = pointer.split('/').any(super::parameter::is_chrono_point);
    if pointer.contains("/hardpoints/") || chrono_point || pointer.ends_with("/loaded_radius") {
        "mm"
    } else {
        "%"
    }
}

/// A figure's derivative as an effect: per millimetre of a length, per percent of its value otherwise.
pub fn effect(pointer: &str, value: f64, derivative: f64) -> f64 {
    match effect_unit(pointer) {
        "mm" => derivative * 1e-3,
        _ => derivative * value.abs() * 1e-2,
    }
}

impl TravelSensitivity {
    /// `sensitivity.csv`: one row per figure and parameter — the figure, its unit and value, the parameter
    /// and its value, the derivative (figure unit per unit of the parameter in the file) and the effect per
    /// millimetre or per percent. A figure the report leaves out, or one without a derivative, has empty
    /// cells.
    pub fn figure_table(&self, parameters: &Parameters) -> crate::kc::Table {
        use crate::kc::Cell;
        let columns =
            ["figure", "figure_unit", "value", "parameter", "parameter_value", "derivative", "effect", "effect_per"];
        let mut rows = Vec::new();
        for (figure, derivatives) in &self.report_figures {
            for (k, d) in derivatives.iter().enumerate() {
                let pointer = &parameters.pointers[k];
                rows.push(vec![
                    Cell::Text(figure.key.clone()),
                    Cell::Text(figure.unit.clone()),
                    figure.value.map_or(Cell::Empty, Cell::from),
                    Cell::Text(pointer.clone()),
                    Cell::from(parameters.values[k]),
                    d.map_or(Cell::Empty, Cell::from),
                    d.map_or(Cell::Empty, |d| Cell::from(effect(pointer, parameters.values[k], d))),
                    Cell::Text(effect_unit(pointer).into()),
                ]);
            }
        }
        crate::kc::Table { name: "sensitivity".into(), columns: columns.map(String::from).to_vec(), rows }
    }

    /// `sensitivity_rows.csv`: per parameter and row, the derivative of every column of the K&C report's
    /// parallel-travel table (named `d_<column>`, per unit of the parameter in the file).
    pub fn row_table(&self) -> crate::kc::Table {
        use crate::kc::Cell;
        let mut columns = vec!["parameter".to_string(), "wheel_travel_m".to_string()];
        columns.extend(self.columns.iter().skip(1).map(|c| format!("d_{c}")));
        let mut rows = Vec::new();
        for (k, pointer) in self.pointers.iter().enumerate() {
            for (r, travel) in self.travel.iter().enumerate() {
                let mut row = vec![Cell::Text(pointer.clone()), Cell::from(*travel)];
                row.extend(self.d_columns[k][r].iter().skip(1).map(|d| d.map_or(Cell::Empty, Cell::from)));
                rows.push(row);
            }
        }
        crate::kc::Table { name: "sensitivity_rows".into(), columns, rows }
    }
}
