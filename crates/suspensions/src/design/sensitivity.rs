//! Sensitivities through the equilibrium. At an equilibrium `F(z, p) = 0` of the corner (`z` the body
//! poses and joint multipliers, `F = [Jᵀλ − Q; Φ]`, `p` the parameters), the implicit function theorem
//! gives the rates of every pose and joint force at once: `A · dz/dp = −∂F/∂p` with `A = [K Jᵀ; J 0]`, the
//! tangent the step is solved with, so each parameter costs one back-substitution. `∂F/∂p` is the change of
//! the residual at the fixed state when the model is read again with `p` moved (a central difference of
//! the residual alone, which is smooth in `p`: no equilibrium is solved again). Every column and figure of
//! the K&C report is then differentiated as it is defined: the report's own reduction applied to the rows
//! read at the equilibria moved along `(dz/dp, 1)`, each by its own moved model.
//!
//! Only corrected-mode rows are equilibria: sensitivities are of the corrected path.

use super::parameter::Parameters;
use crate::analysis::travel_row;
use crate::build::{Corner, Rig};
use crate::description::Side;
use crate::file::SuspensionFile;
use crate::kc::{Cell, Figure, Table};
use elastokin_core::{Pose, BODY_DOFS};
use elastokin_solver::assembly::Assembly;
use elastokin_solver::{LoadPath, Mode, SolverOptions, StaticSolver, StepResult};

/// A parameter is moved by this fraction of its size (at least of 0.1 in the file's units: 10 µm of a
/// hardpoint near the origin) and twice that for the central differences of the residual, Richardson
/// extrapolated. The residual is smooth in every parameter: the error is of order `step⁴`, the rounding of
/// order `ε / step` (a step of 1e-6 left 2e-4 of a small toe rate to rounding; 1e-4 leaves 1e-6 and less).
pub const RELATIVE_STEP: f64 = 1e-4;

/// The moves of a parameter the differences take, in steps: `+h, −h, +2h, −2h`.
const SHIFTS: [f64; 4] = [1.0, -1.0, 2.0, -2.0];

/// Parallel wheel travel as the K&C report gives it, and the derivatives of its table and row-read
/// figures with respect to each parameter, per unit of the parameter as the file gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct TravelSensitivity {
    /// The parameters' pointers.
    pub pointers: Vec<String>,
    /// The K&C report's parallel-travel table of the model as it is (its first column the wheel travel).
    pub table: Table,
    /// The table's derivatives: parameter × row × column (`None` where a cell is empty).
    pub d_columns: Vec<Vec<Vec<Option<f64>>>>,
    /// Every headline figure of the K&C report's parallel travel read from its rows, with its derivative
    /// per parameter (`None` where the figure is missing, or has no derivative), in the report's units.
    pub report_figures: Vec<(Figure, Vec<Option<f64>>)>,
}

impl TravelSensitivity {
    /// The values of the table's column `name` (`None` where a cell is empty, or there is no such column).
    pub fn column(&self, name: &str) -> Vec<Option<f64>> {
        let c = self.table.columns.iter().position(|x| x == name);
        self.table.rows.iter().map(|r| c.and_then(|c| r[c].number())).collect()
    }

    /// The derivatives of column `name` with respect to parameter `k`, row by row.
    pub fn d_column(&self, name: &str, k: usize) -> Vec<Option<f64>> {
        let c = self.table.columns.iter().position(|x| x == name);
        self.d_columns[k].iter().map(|r| c.and_then(|c| r[c])).collect()
    }

    /// The figure `key` and its derivatives.
    pub fn figure(&self, key: &str) -> Option<&(Figure, Vec<Option<f64>>)> {
        self.report_figures.iter().find(|(f, _)| f.key == key)
    }

    /// The parameters with the largest effects on figure `index` of [`TravelSensitivity::report_figures`]
    /// (per mm or per %, see [`effect`]), largest first, at most `count`: `(parameter, effect)`.
    pub fn largest_effects(&self, index: usize, parameters: &Parameters, count: usize) -> Vec<(usize, f64)> {
        let mut ranked: Vec<(usize, f64)> = self.report_figures[index]
            .1
            .iter()
            .enumerate()
            .filter_map(|(k, d)| d.map(|d| (k, effect(&parameters.pointers[k], parameters.values[k], d))))
            .collect();
        ranked.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        ranked.truncate(count);
        ranked
    }

    /// `sensitivity.csv`: one row per figure and parameter — the figure, its unit and value, the parameter
    /// and its value, the derivative (figure unit per unit of the parameter in the file) and the effect per
    /// millimetre or per percent. A figure the report leaves out, or one without a derivative, has empty
    /// cells.
    pub fn figure_table(&self, parameters: &Parameters) -> Table {
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
        Table { name: "sensitivity".into(), columns: columns.map(String::from).to_vec(), rows }
    }

    /// `sensitivity_rows.csv`: per parameter and row, the derivative of every column of the K&C report's
    /// parallel-travel table (named `d_<column>`, per unit of the parameter in the file).
    pub fn row_table(&self) -> Table {
        let mut columns = vec!["parameter".to_string(), "wheel_travel_m".to_string()];
        columns.extend(self.table.columns.iter().skip(1).map(|c| format!("d_{c}")));
        let mut rows = Vec::new();
        for (k, pointer) in self.pointers.iter().enumerate() {
            for (r, base) in self.table.rows.iter().enumerate() {
                let mut row = vec![Cell::Text(pointer.clone()), base[0].clone()];
                row.extend(self.d_columns[k][r].iter().skip(1).map(|d| d.map_or(Cell::Empty, Cell::from)));
                rows.push(row);
            }
        }
        Table { name: "sensitivity_rows".into(), columns, rows }
    }
}

/// Whether a travel range can have sensitivities of figures at design: it must hold the design position.
pub fn check_range(from: f64, to: f64) -> Result<(), String> {
    if from < 0.0 && to > 0.0 {
        Ok(())
    } else {
        Err(format!("the range {from},{to} must hold the design position (0): the figures are slopes at design"))
    }
}

/// One parameter moved by the [`SHIFTS`]: the model read again and built, and its residual's assembly on
/// the base model's active rows.
struct Moved {
    step: f64,
    files: [SuspensionFile; 4],
    corners: [Corner; 4],
    assemblies: [Assembly; 4],
}

/// The derivative from central differences over one and two steps, Richardson extrapolated: `values` at
/// the [`SHIFTS`] of `h`.
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

/// A step's equilibrium moved by `scale · dz` (`dz`: `n` body coordinates, `BODY_DOFS` per body, then the
/// active rows' multipliers).
fn moved_step(step: &StepResult, dz: &[f64], scale: f64, n: usize, active: &[usize]) -> StepResult {
    let mut moved = step.clone();
    for (b, pose) in moved.poses.iter_mut().enumerate() {
        let d: [f64; BODY_DOFS] = std::array::from_fn(|i| scale * dz[b * BODY_DOFS + i]);
        pose.apply_increment6(&d);
    }
    for (k, &row) in active.iter().enumerate() {
        moved.multipliers[row] += scale * dz[n + k];
    }
    moved
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
    check_range(from, to)?;
    let build = |file: &SuspensionFile| file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string());
    let file = parameters.file()?;
    let corner = build(&file)?;
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
        let [a, b, c, d] = SHIFTS.map(|s| parameters.file_moved(k, s * step));
        let files = [a?, b?, c?, d?];
        let [a, b, c, d] = files.each_ref().map(|f| build(f).map_err(|e| format!("parameter '{pointer}' moved: {e}")));
        let corners = [a?, b?, c?, d?];
        if !corners.iter().all(same_parts) {
            return Err(format!(
                "parameter '{pointer}' changes the model's parts when moved (its joints or elements): it has no \
                 derivative; give a number that moves a part, not one that chooses what the parts are"
            ));
        }
        let assemblies = corners.each_ref().map(|c| Assembly::new(&c.model, active.clone()));
        moved.push(Moved { step, files, corners, assemblies });
    }

    // dz/dp of every row, per parameter: one back-substitution with the row's tangent each.
    let mut rates: Vec<Vec<Vec<f64>>> = vec![Vec::with_capacity(sweep.steps.len()); parameters.len()];
    for step in &sweep.steps {
        let state = solver.state_of(step);
        solver.factorize_tangent(&state).map_err(|e| e.to_string())?;
        for (k, m) in moved.iter_mut().enumerate() {
            let f: Vec<Vec<f64>> = (0..4)
                .map(|i| residual(&mut m.assemblies[i], &m.corners[i], &state.poses, state.t, &state.lambda))
                .collect();
            let mut dz: Vec<f64> =
                (0..f[0].len()).map(|r| -richardson([f[0][r], f[1][r], f[2][r], f[3][r]], m.step)).collect();
            solver.solve_factored(&mut dz).map_err(|e| e.to_string())?;
            rates[k].push(dz);
        }
    }

    // Every column and figure, differentiated as it is defined: the report's reduction applied to the rows
    // read at (z + s·dz/dp, p + s) for each shift s, each by its own model, Richardson extrapolated.
    let base_rows: Vec<_> = sweep.steps.iter().map(|s| travel_row(&corner, s)).collect();
    let table = crate::kc::parallel_travel_table(&corner, &base_rows);
    let mut report_figures: Vec<(Figure, Vec<Option<f64>>)> =
        crate::kc::parallel_travel_figures(&file, &corner, (from, to), &base_rows)
            .into_iter()
            .map(|f| (f, Vec::with_capacity(parameters.len())))
            .collect();
    let mut d_columns = Vec::with_capacity(parameters.len());
    for (m, rates) in moved.iter().zip(&rates) {
        let (mut tables, mut figures) = (Vec::with_capacity(4), Vec::with_capacity(4));
        for (i, shift) in SHIFTS.into_iter().enumerate() {
            let rows: Vec<_> = sweep
                .steps
                .iter()
                .zip(rates)
                .map(|(step, dz)| travel_row(&m.corners[i], &moved_step(step, dz, shift * m.step, n, &active)))
                .collect();
            tables.push(crate::kc::parallel_travel_table(&m.corners[i], &rows));
            figures.push(crate::kc::parallel_travel_figures(&m.files[i], &m.corners[i], (from, to), &rows));
        }
        let derivative = |v: [Option<f64>; 4]| match v {
            [Some(a), Some(b), Some(c), Some(d)] => Some(richardson([a, b, c, d], m.step)).filter(|x| x.is_finite()),
            _ => None,
        };
        d_columns.push(
            (0..table.rows.len())
                .map(|r| {
                    (0..table.columns.len())
                        .map(|c| derivative([0, 1, 2, 3].map(|i| tables[i].rows[r][c].number())))
                        .collect()
                })
                .collect(),
        );
        for (j, (_, derivatives)) in report_figures.iter_mut().enumerate() {
            derivatives.push(derivative([0, 1, 2, 3].map(|i| figures[i].get(j).and_then(|f| f.value))));
        }
    }
    Ok(TravelSensitivity { pointers: parameters.pointers.clone(), table, d_columns, report_figures })
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
