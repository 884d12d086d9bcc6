//! The road loads at the wheel: lateral and braking force at the contact patch, traction force at the
//! wheel centre, aligning torque; each swept with the corner load carried ([`super::load_sweep`]).

use crate::analysis::WheelLoad;
use crate::kc::models::Models;
use crate::kc::report::AnalysisReport;
use crate::kc::settings::{Analysis, Cause, Declaration, DefaultRange, FigureRows, Quantity, Settings};
use elastokin_solver::replay::Taping;

/// The lateral force sweep.
pub(super) const LATERAL: Declaration = Declaration {
    name: "lateral-force",
    parameter: "lateral force at the contact patch, N, inboard +",
    quantity: Quantity::Force,
    rig_words: None,
    default_range: DefaultRange::Ends(-3000.0, 3000.0),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::LastRow,
};

/// The braking force sweep.
pub(super) const BRAKING: Declaration = Declaration {
    name: "braking-force",
    parameter: "braking force at the contact patch, N, rearward +",
    quantity: Quantity::Force,
    rig_words: None,
    default_range: DefaultRange::Ends(0.0, 3000.0),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::LastRow,
};

/// The traction force sweep.
pub(super) const TRACTION: Declaration = Declaration {
    name: "traction-force",
    parameter: "traction force at the wheel centre, N, forward +",
    quantity: Quantity::Force,
    rig_words: None,
    default_range: DefaultRange::Ends(0.0, 3000.0),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::LastRow,
};

/// The aligning torque sweep.
pub(super) const ALIGNING_TORQUE: Declaration = Declaration {
    name: "aligning-torque",
    parameter: "aligning torque, N·m, about +z",
    quantity: Quantity::Torque,
    rig_words: None,
    default_range: DefaultRange::Ends(-200.0, 200.0),
    design_parameter: Some(0.0),
    figure_rows: FigureRows::LastRow,
};

pub(super) fn road_load(
    models: &Models,
    load: WheelLoad,
    s: &Settings,
    taping: &Taping,
) -> Result<AnalysisReport, Cause> {
    super::load_sweep::loaded(models, Analysis::Road(load), s, taping)
}
