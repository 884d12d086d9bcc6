//! The model file's own load case (`loads` of the general form), from zero to its full value
//! ([`super::load_sweep`]).

use crate::kc::models::Models;
use crate::kc::report::AnalysisReport;
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use elastokin_solver::replay::Taping;

/// The model file's own load case, as the command and the reports name it.
pub(super) const DECLARATION: Declaration = Declaration {
    name: "loads",
    parameter: "fraction of the model file's loads applied, 0 to 1",
    quantity: Quantity::Fraction,
    rig_words: None,
    default_range: DefaultRange::Ends(0.0, 1.0),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::LastRow,
};

/// The model file's own load case (`loads` of the general form), applied from zero to its full value.
pub(super) fn model_loads(models: &Models, s: &Settings, taping: &Taping) -> Result<AnalysisReport, Cause> {
    super::load_sweep::loaded(models, Analysis::ModelLoads, s, taping)
}
