//! Plausibility of a model before it is solved: how many ways the corner can move, how well conditioned
//! its stiffness is at design, and named warnings for geometry that parses but cannot be what the author
//! meant (millimetres for metres, a right corner given for the left, a tie rod with no lever to steer, an
//! arm whose pivot axis runs through its own ball joint, …).
//!
//! Every warning names the hardpoints involved and says what to change, in the model file's words.

use crate::analysis::TravelRow;
use crate::assembly::mobility::{joint_mobility, mobility, reduced_condition};
use crate::assembly::{Corner, Rig};
use crate::description::layout::Layout;
use crate::description::limits::{looks_like_millimetres, plain, FAR_FROM_WHEEL_CENTRE};
use crate::description::{Connection, Side};
use crate::file::SuspensionFile;
use elastokin_core::{ModelError, Vec3, BODY_DOFS};
use serde::Serialize;

/// Something in a model that is probably not what its author meant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// Short stable name of the finding: `millimetres`, `wrong-side`, `far-hardpoint`,
    /// `tie-rod-on-steering-axis`, `pivot-through-ball-joint`, `near-singular`, `motion-ratio`, `toe-range`,
    /// `camber-range`, `wheel-rate`, `spring-rate`.
    pub code: &'static str,
    /// The model file's hardpoint names involved (empty when the finding is not about hardpoints).
    pub hardpoints: Vec<String>,
    /// What is wrong and what to change.
    pub message: String,
}

/// What [`check_model`] found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelCheck {
    /// Ways the corner can move with the wheel free, counting only its joints (bushings and springs hold
    /// motions but do not remove them): body coordinates − independent joint rows. An all-ideal corner has
    /// one, the wheel travel; each bushed arm adds the motions its bushings hold elastically.
    pub degrees_of_freedom: usize,
    /// The same with the rig's wheel-travel driver holding the wheel-centre height: one fewer when the
    /// driver adds a new restraint.
    pub degrees_of_freedom_on_rig: usize,
    /// Joint rows that repeat others (each makes one joint row carry no load of its own).
    pub redundant_rows: usize,
    /// Stiffness of the stiffest body coordinate over that of the softest way the corner can move at design
    /// with the wheel-centre height held (the elastic stiffness reduced to the motions the joints allow;
    /// rotations counted at 1 m of lever). `None` when the joints leave no motion (an all-ideal corner on
    /// the rig).
    pub condition_estimate: Option<f64>,
    /// Findings, most fundamental first.
    pub warnings: Vec<Warning>,
}

impl ModelCheck {
    /// The findings as lines for people: degrees of freedom, condition, then `warning [code]: message`.
    pub fn report(&self) -> Vec<String> {
        let mut out = vec![format!(
            "degrees of freedom: {} with the wheel free (counting joints only: bushings and springs hold motions \
             without removing them), {} with the rig's wheel-travel driver",
            self.degrees_of_freedom, self.degrees_of_freedom_on_rig
        )];
        out.push(match self.condition_estimate {
            Some(c) if !c.is_finite() => {
                "condition at design: infinite: some motion is held by nothing (see the warnings)".into()
            }
            Some(c) => format!(
                "condition at design: {c:.1e} (stiffest mount over the softest motion, wheel-centre height held; \
                 above {NEAR_SINGULAR:.0e} the corner is near-singular)"
            ),
            None => "condition at design: the joints leave no motion with the wheel-centre height held".into(),
        });
        out.extend(self.warnings.iter().map(|w| format!("warning [{}]: {}", w.code, w.message)));
        out
    }
}

/// The tie rod's lever about the steering axis below which it cannot steer the wheel (m). A passenger
/// car's steering arm is 0.10–0.20 m.
pub const MIN_STEERING_LEVER: f64 = 0.02;
/// A ball joint closer than this to its arm's pivot axis sits on it (m).
pub const MIN_ARM_LENGTH: f64 = 0.01;
/// Condition estimates above this mean a motion held by next to nothing at design (the shipped corners
/// measure 79 and 300; the twist-beam axle, steel beams beside rubber, 1.2e6). A solve in double precision
/// keeps about 16 − log₁₀(condition) digits, so above 1e10 fewer than six are left; below it a wide spread
/// of rates (steel and rubber) is no fault, and the run's own error estimate says what it reached.
pub const NEAR_SINGULAR: f64 = 1e10;
/// Spring motion ratios below this mean the spring barely changes length with wheel travel.
pub const MIN_MOTION_RATIO: f64 = 0.1;
/// Toe and camber beyond this inside the requested travel are not a suspension working as meant (°).
pub const MAX_WHEEL_ANGLE_DEG: f64 = 10.0;

fn point(points: &[(String, Vec3)], name: &str) -> Vec3 {
    points.iter().find(|(n, _)| n == name).map(|(_, p)| *p).expect("the layout names the template's hardpoints")
}

fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

fn quoted(list: &[String]) -> String {
    list.iter().map(|s| format!("'{s}'")).collect::<Vec<_>>().join(", ")
}

/// Checks a model without a sweep: degrees of freedom, the condition of its stiffness at design, and the
/// warnings of the geometry (see [`Warning::code`]); the spring's motion ratio takes one equilibrium at
/// design. Errors only when the corner cannot be built.
pub fn check_model(file: &SuspensionFile) -> Result<ModelCheck, ModelError> {
    let template = &file.suspension;
    // Building first: it refuses, by name, anything the layout below would look up and not find.
    let free = Corner::build(template, Side::Left, Rig::Free)?;
    let on_rig = Corner::build(template, Side::Left, Rig::WheelTravel)?;
    let points = template.hardpoints();
    let layout = template.layout();
    let mut warnings = Vec::new();
    let wc = point(&points, &layout.wheel_centre);

    let units = units_and_side(&points, wc);
    // Millimetres make every other figure of the geometry meaningless: say that alone.
    let in_millimetres = units.iter().any(|w| w.code == "millimetres");
    warnings.extend(units);
    if !in_millimetres {
        warnings.extend(far_hardpoints(&points, wc));
        warnings.extend(steering_lever(&points, &layout));
        warnings.extend(arm_pivots(&points, &layout));
    }

    let (dof, redundant) = mobility(&free.model);
    let on_rig_mobility = joint_mobility(&on_rig.model);
    let dof_on_rig = on_rig_mobility.degrees_of_freedom;
    let condition_estimate = reduced_condition(&on_rig.model, &on_rig_mobility);
    if let (false, Some(c)) = (in_millimetres, condition_estimate) {
        if c > NEAR_SINGULAR {
            warnings.push(Warning {
                code: "near-singular",
                hardpoints: Vec::new(),
                message: if c.is_finite() {
                    format!(
                        "with the wheel-centre height held, some part of the corner is held {c:.1e} times more \
                         softly than its stiffest mount: it is held by next to nothing at design and the results \
                         will be dominated by rounding; look for an arm, tie rod or bushing line that passes \
                         through another hardpoint, or a bushing rate far below the others"
                    )
                } else {
                    "with the wheel-centre height held, some part of the corner can move with nothing at all \
                     resisting it at design: no joint, bushing or spring holds that motion; look for an arm, \
                     tie rod or link that passes through another hardpoint, or an arm of no length"
                        .to_string()
                },
            });
        }
    }
    if !in_millimetres {
        warnings.extend(motion_ratio(&points, &layout, &on_rig));
    }
    warnings.extend(spring_rates(template));
    Ok(ModelCheck {
        degrees_of_freedom: dof,
        degrees_of_freedom_on_rig: dof_on_rig,
        redundant_rows: redundant,
        condition_estimate,
        warnings,
    })
}

/// Millimetres for metres, and a right corner given for the left.
fn units_and_side(points: &[(String, Vec3)], wc: Vec3) -> Vec<Warning> {
    let mut out = Vec::new();
    let spread = points.iter().map(|(_, p)| (p - wc).norm()).fold(0.0, f64::max);
    if looks_like_millimetres(points, wc) {
        out.push(Warning {
            code: "millimetres",
            hardpoints: points.iter().map(|(n, _)| n.clone()).collect(),
            message: format!(
                "the wheel centre is {:.0} m from the car's centre line and the hardpoints spread over {spread:.0} m: \
                 they look like millimetres; give every hardpoint in metres (divide by 1000)",
                wc.y.abs()
            ),
        });
        return out;
    }
    let inboard: Vec<String> = points.iter().filter(|(_, p)| p.y < 0.0).map(|(n, _)| n.clone()).collect();
    if wc.y < 0.0 || 2 * inboard.len() > points.len() {
        out.push(Warning {
            code: "wrong-side",
            hardpoints: inboard.clone(),
            message: format!(
                "{} of {} hardpoints ({}) are at y < 0, on the right of the car: a model file describes the \
                 left corner (y > 0, ISO 8855: x forward, y left, z up) and mirrors it for the right; \
                 change the sign of every y",
                inboard.len(),
                points.len(),
                quoted(&inboard)
            ),
        });
    }
    out
}

/// Hardpoints too far from the wheel centre to belong to the same corner.
fn far_hardpoints(points: &[(String, Vec3)], wc: Vec3) -> Vec<Warning> {
    points
        .iter()
        .filter(|(_, p)| (p - wc).norm() > FAR_FROM_WHEEL_CENTRE)
        .map(|(name, p)| Warning {
            code: "far-hardpoint",
            hardpoints: vec![name.clone()],
            message: format!(
                "hardpoint '{name}' is {:.3} m from the wheel centre (more than {FAR_FROM_WHEEL_CENTRE} m): \
                 check its coordinates (metres, ISO 8855: x forward, y left, z up)",
                (p - wc).norm()
            ),
        })
        .collect()
}

/// The moment arm of the tie rod about the steering axis: the moment a unit tie-rod force makes about it.
/// Zero when the tie-rod line meets the axis or runs parallel to it: the rod then cannot steer the wheel.
fn steering_lever(points: &[(String, Vec3)], layout: &Layout) -> Vec<Warning> {
    let (Some([lower, upper]), Some([inner_name, outer_name])) = (&layout.steering_axis, &layout.tie_rod) else {
        return Vec::new();
    };
    let axis = (point(points, lower), point(points, upper));
    let (inner, outer) = (point(points, inner_name), point(points, outer_name));
    // Coincident points are refused with their own error when the corner is built.
    let Some(lever) = crate::description::limits::tie_rod_lever(axis, inner, outer) else { return Vec::new() };
    let lever = lever.abs();
    if lever >= MIN_STEERING_LEVER {
        return Vec::new();
    }
    vec![Warning {
        code: "tie-rod-on-steering-axis",
        hardpoints: vec![inner_name.clone(), outer_name.clone(), lower.clone(), upper.clone()],
        message: format!(
            "the tie rod ('{inner_name}' to '{outer_name}') passes {:.1} mm from the steering axis ('{lower}' \
             to '{upper}'): it has no lever to hold the wheel's steer (at least {:.0} mm is needed, a car's \
             steering arm is 100–200 mm); move '{outer_name}' ahead of or behind the axis",
            lever * 1e3,
            MIN_STEERING_LEVER * 1e3
        ),
    }]
}

/// Arms whose pivot axis passes through their ball joint: the arm then cannot move the ball joint.
fn arm_pivots(points: &[(String, Vec3)], layout: &Layout) -> Vec<Warning> {
    let mut out = Vec::new();
    for (arm, [front, rear, ball], connection) in &layout.arms {
        let (f, r, j) = (point(points, front), point(points, rear), point(points, ball));
        let axis = r - f;
        if axis.norm() == 0.0 {
            continue;
        }
        let reach = (j - f).cross(&(axis / axis.norm())).norm();
        if reach >= MIN_ARM_LENGTH {
            continue;
        }
        let mounts = match (connection.front, connection.rear) {
            (Connection::Ideal, Connection::Ideal) => "hinge",
            (Connection::Bushing(_), Connection::Bushing(_)) => "bushings",
            _ => "mounts",
        };
        out.push(Warning {
            code: "pivot-through-ball-joint",
            hardpoints: names(&[front, rear, ball]),
            message: format!(
                "the {arm}'s pivot axis ('{front}' to '{rear}') passes {:.1} mm from its ball joint '{ball}': \
                 the arm cannot swing the ball joint up and down, and nothing but its {mounts} holds it from \
                 spinning about that line; move '{ball}' outboard or the pivots inboard",
                reach * 1e3
            ),
        });
    }
    out
}

/// The softest rate a car's coil spring has (N/m): 1 N/mm. A rate below it is most likely one in N/mm given
/// where N/m is read (70 for 70 N/mm), which solves, but to a spring deflected by metres.
const SOFTEST_SPRING_RATE: f64 = 1e3;

/// Springs whose rate looks like N/mm given for N/m.
fn spring_rates(template: &crate::description::Template) -> Vec<Warning> {
    let general = template.expand();
    let axle_springs = general.axle.iter().flat_map(|a| &a.springs);
    let springs = general.springs.iter().chain(axle_springs);
    springs
        .filter_map(|spring| {
            let rate = spring.rate.filter(|r| *r > 0.0 && *r < SOFTEST_SPRING_RATE)?;
            Some(Warning {
                code: "spring-rate",
                hardpoints: Vec::new(),
                message: format!(
                    "the spring '{}' has a rate of {} N/m ({} N/mm): a car's springs are 10 to 300 N/mm; rates \
                     are in N/m, so for {} N/mm give {}",
                    spring.name,
                    plain(rate),
                    plain(rate * 1e-3),
                    plain(rate),
                    plain(rate * 1e3)
                ),
            })
        })
        .collect()
}

/// Spring length change per metre of wheel travel at design, from the rig's exact path tangent.
fn motion_ratio(points: &[(String, Vec3)], layout: &Layout, corner: &Corner) -> Vec<Warning> {
    let Some((seats, body, what)) = &layout.spring else { return Vec::new() };
    let Some(ratio) = spring_motion_ratio(points, seats, body, corner) else { return Vec::new() };
    if ratio.abs() >= MIN_MOTION_RATIO {
        return Vec::new();
    }
    vec![Warning {
        code: "motion-ratio",
        hardpoints: seats.to_vec(),
        message: format!(
            "the spring ('{}' to '{}') changes length by {:.3} m per metre of wheel travel at design: it \
             barely carries the wheel (a car's is 0.5–1); {what}",
            seats[0],
            seats[1],
            ratio.abs()
        ),
    }]
}

fn spring_motion_ratio(points: &[(String, Vec3)], seats: &[String; 2], body: &str, corner: &Corner) -> Option<f64> {
    use elastokin_solver::{SolverOptions, StaticSolver};
    let (a, b) = (point(points, &seats[0]), point(points, &seats[1]));
    let body = corner.model.body_id(body)?;
    let mut solver = StaticSolver::new(&corner.model, SolverOptions::default()).ok()?;
    let mut state = solver.design_state(0.0);
    // The tangent of the path through the rest position; the design position is close to it.
    if solver.equilibrium(&mut state).is_err() {
        state = solver.design_state(0.0);
    }
    let rates = solver.path_tangent(&state).ok()?;
    let pose = state.poses[body.0];
    let base = body.0 * BODY_DOFS;
    let v = Vec3::new(rates[base], rates[base + 1], rates[base + 2]);
    let w = Vec3::new(rates[base + 3], rates[base + 4], rates[base + 5]);
    let seat = pose.point(&corner.model.bodies()[body.0].design_pose.to_local_point(&b));
    let velocity = v + w.cross(&(seat - pose.position));
    let along = (seat - a) / (seat - a).norm();
    let ratio = along.dot(&velocity);
    ratio.is_finite().then_some(ratio)
}

/// Warnings of a parallel-travel sweep (the rows of [`crate::analysis::parallel_wheel_travel`]: other
/// sweeps carry no wheel load): toe or camber beyond ±10° inside the travel, or a wheel rate that is not
/// positive (the corner does not push the wheel back down).
pub fn check_travel_rows(rows: &[TravelRow]) -> Vec<Warning> {
    let mut out = Vec::new();
    let worst = |f: &dyn Fn(&TravelRow) -> f64| {
        rows.iter().map(|r| (r.travel, f(r).to_degrees())).fold(None, |best: Option<(f64, f64)>, (t, v)| match best {
            Some((_, b)) if b.abs() >= v.abs() || v.is_nan() => best,
            _ => Some((t, v)),
        })
    };
    for (code, what, f) in [
        ("toe-range", "toe", &(|r: &TravelRow| r.attitude.toe) as &dyn Fn(&TravelRow) -> f64),
        ("camber-range", "camber", &|r: &TravelRow| r.attitude.camber),
    ] {
        if let Some((t, v)) = worst(f) {
            if v.abs() > MAX_WHEEL_ANGLE_DEG || v.is_nan() {
                out.push(Warning {
                    code,
                    hardpoints: Vec::new(),
                    message: format!(
                        "{what} reaches {v:.1}° at {:.0} mm of wheel travel (more than ±{MAX_WHEEL_ANGLE_DEG}°): \
                         the wheel is not guided as a suspension should be; check the tie rod and arm \
                         hardpoints, or narrow the travel",
                        t * 1e3
                    ),
                });
            }
        }
    }
    // The wheel rate is the slope of the rig's force against travel: it must be positive everywhere.
    for pair in rows.windows(2) {
        let dz = pair[1].travel - pair[0].travel;
        if dz == 0.0 {
            continue;
        }
        let rate = (pair[1].wheel_load - pair[0].wheel_load) / dz;
        if rate <= 0.0 || rate.is_nan() {
            out.push(Warning {
                code: "wheel-rate",
                hardpoints: Vec::new(),
                message: format!(
                    "the wheel rate is {:.1} N/mm between {:.0} and {:.0} mm of wheel travel: the corner does \
                     not push the wheel back; check the spring rate and its seats",
                    rate * 1e-3,
                    pair[0].travel * 1e3,
                    pair[1].travel * 1e3
                ),
            });
            break;
        }
    }
    out
}

/// Largest bushing deflection at the design position that rubber takes: beyond it a bushing bottoms
/// out, and a model whose bushings go further holds its design position with rates far too soft.
pub const MAX_DESIGN_DEFLECTION: (f64, f64) = (0.010, 10.0);

/// Bushings that the design position (wheel-centre height held, the spring at its design force) deflects
/// by more than [`MAX_DESIGN_DEFLECTION`] (m, deg): each a warning naming it. None when the design
/// position cannot be solved (the analyses then say why).
pub fn bushing_deflection_at_design(file: &SuspensionFile) -> Vec<Warning> {
    use elastokin_core::ElementRole;
    use elastokin_solver::{SolverOptions, StaticSolver};
    let Ok(corner) = file.suspension.build(Side::Left, Rig::WheelTravel) else { return Vec::new() };
    let Ok(mut solver) = StaticSolver::new(&corner.model, SolverOptions::default()) else { return Vec::new() };
    let mut state = solver.design_state(0.0);
    let Ok(step) = solver.equilibrium(&mut state) else { return Vec::new() };
    let (most_m, most_deg) = MAX_DESIGN_DEFLECTION;
    // The model's bushings, and the tie rod's that the rig adds: springs and stops deflect by design.
    let mut bushings: Vec<String> = file.suspension.expand().bushings.into_iter().map(|b| b.name).collect();
    bushings.extend(["tie rod inner bushing".to_string(), "tie rod outer bushing".to_string()]);
    corner
        .model
        .elements()
        .iter()
        .zip(step.element_reports(&corner.model))
        .filter(|(e, _)| e.role() == ElementRole::Elastic && bushings.iter().any(|b| b == e.name()))
        .filter_map(|(e, r)| {
            let (moved, turned) = (r.deflection.norm(), r.rotation.norm().to_degrees());
            (moved > most_m || turned > most_deg).then(|| Warning {
                code: "bushing-deflection",
                hardpoints: Vec::new(),
                message: format!(
                    "at the design position '{}' deflects {:.1} mm and {:.1} deg, where rubber takes {} mm and {} \
                     deg: its rates are too soft for the spring's design force (check the bushing's radial, axial, \
                     torsion and conical rates, N/m and N·m/rad, and spring.design_force)",
                    e.name(),
                    moved * 1e3,
                    turned,
                    most_m * 1e3,
                    most_deg
                ),
            })
        })
        .collect()
}
