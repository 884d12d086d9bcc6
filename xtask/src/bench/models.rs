//! The scenes the benchmark measures: the shipped suspension models on their K&C rigs.

use elastokin_core::Vec3;
use elastokin_solver::SolverOptions;
use elastokin_suspensions::analysis::design_wheel_load;
use elastokin_suspensions::{Corner, Rig, Side, SuspensionFile};

pub(crate) use crate::workspace_root as root;

/// The shipped models: display name and file stem under `examples/`.
pub const SHIPPED: [(&str, &str); 2] =
    [("MacPherson", "generic/macpherson"), ("double wishbone", "generic/double_wishbone")];

/// Reads `examples/{stem}.json`.
pub fn shipped(stem: &str) -> Result<SuspensionFile, String> {
    SuspensionFile::read(&root().join("examples").join(format!("{stem}.json"))).map_err(|e| e.to_string())
}

/// Which load path a case walks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sweep {
    /// Vertical force at the contact patch, wheel free on its spring (the paper's case): `t` in N, from
    /// 0.5 to 1.5 times the design wheel load (the `elastokin run` default).
    VerticalForce,
    /// Parallel wheel travel, wheel-centre height driven: `t` in m, ±80 mm.
    ParallelTravel,
}

impl Sweep {
    /// Both.
    pub const ALL: [Sweep; 2] = [Sweep::VerticalForce, Sweep::ParallelTravel];

    /// Display name.
    pub fn name(self) -> &'static str {
        match self {
            Sweep::VerticalForce => "vertical force",
            Sweep::ParallelTravel => "parallel travel",
        }
    }
}

/// A corner on its rig with the load path to walk.
#[derive(Debug)]
pub struct Case {
    /// The corner (for the vertical force sweep, with the force added at the contact patch).
    pub corner: Corner,
    /// First load parameter.
    pub from: f64,
    /// Last load parameter.
    pub to: f64,
}

/// Builds the corner of `file` for `sweep`.
pub fn case(file: &SuspensionFile, sweep: Sweep) -> Result<Case, String> {
    let text = |e: &dyn std::fmt::Display| e.to_string();
    match sweep {
        Sweep::ParallelTravel => {
            let corner = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| text(&e))?;
            Ok(Case { corner, from: -0.08, to: 0.08 })
        }
        Sweep::VerticalForce => {
            let held = file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| text(&e))?;
            let load = design_wheel_load(&held).map_err(|e| text(&e))?;
            let mut corner = file.suspension.build(Side::Left, Rig::Free).map_err(|e| text(&e))?;
            let patch = corner.wheel.contact_patch;
            corner.add_wheel_force("vertical force", patch, Vec3::z()).map_err(|e| text(&e))?;
            Ok(Case { corner, from: 0.5 * load, to: 1.5 * load })
        }
    }
}

/// The reference's solver options: a thousand times tighter than the defaults.
pub fn tight_options() -> SolverOptions {
    SolverOptions {
        force_tolerance: 1e-12,
        constraint_tolerance: 1e-13,
        max_iterations: 50,
        ..SolverOptions::default()
    }
}

/// `examples/{stem}.json` as the document batch variants and parameters edit.
pub fn shipped_document(stem: &str) -> Result<serde_json::Value, String> {
    let path = format!("examples/{stem}.json");
    let text = std::fs::read_to_string(root().join(&path)).map_err(|e| format!("{path}: {e}"))?;
    elastokin_suspensions::study::batch::base_document(&text, &path).map_err(|e| e.to_string())
}
