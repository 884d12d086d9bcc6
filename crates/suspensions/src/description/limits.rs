//! Limits of what a description may say, and the checks that hold a description to them: how far a
//! hardpoint may lie, the rates and forces accepted, a steering axis and a steering arm that exist. Each
//! check names the model-file key it reads, so that a template and the general form refuse alike.

use crate::description::connection::{ArmMounts, Connection, SpringSpec, TieRodMounts};
use elastokin_core::{ModelError, Vec3};

/// Farthest a hardpoint may lie from its wheel centre (m). A corner spans a metre or two; far beyond,
/// lengths and lever arms lose every digit or overflow. A corner written in millimetres (a few thousand
/// "metres") still builds, so that the plausibility check can say what it is (`millimetres`); a point a
/// little off (a few metres) is named by it too (`far-hardpoint`).
pub const MAX_HARDPOINT_REACH: f64 = 5e3;

/// Least lateral position of the left wheel centre (m): half the narrowest track accepted.
pub const MIN_HALF_TRACK: f64 = 0.05;

/// Farthest a wheel centre may lie from the vehicle origin (m); as for [`MAX_HARDPOINT_REACH`], a corner
/// in millimetres still builds.
pub const MAX_WHEEL_CENTRE_DISTANCE: f64 = 5e3;

/// Refuses hardpoints no suspension has: a wheel centre more than [`MAX_WHEEL_CENTRE_DISTANCE`] from the
/// origin, or a point more than [`MAX_HARDPOINT_REACH`] from the wheel centre. `points` are the left
/// corner's hardpoints by their model-file names, the wheel centre first.
pub(crate) fn check_hardpoints(points: &[(&str, Vec3)]) -> Result<(), ModelError> {
    let Some(&(_, wheel_centre)) = points.first() else { return Ok(()) };
    let refuse = |name: &str, p: Vec3, what: String| {
        Err(ModelError::OutOfRange {
            item: "hardpoints".into(),
            why: format!(
                "{name} [{:.4e}, {:.4e}, {:.4e}] lies {what}: hardpoints are in metres (ISO 8855, x forward, \
                 y left, z up); move it or check its units",
                p.x, p.y, p.z
            ),
        })
    };
    if let Some(&(name, _)) = points.iter().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(ModelError::OutOfRange {
            item: "hardpoints".into(),
            why: format!("{name} has a coordinate that is not a finite number: give it in metres"),
        });
    }
    if wheel_centre.y.abs() < MIN_HALF_TRACK {
        // The right corner is the mirror image: a wheel centre near y = 0 puts the two wheels of an axle
        // on top of each other and leaves the track (Ackermann's T / L) nothing. A right corner given for
        // the left (y < 0) builds, mirrored, and the plausibility check names it (`wrong-side`).
        let what = format!(
            "within {MIN_HALF_TRACK} m of the centre line: the model describes the left corner (y > 0), half a \
             track out"
        );
        return refuse(points[0].0, wheel_centre, what);
    }
    if wheel_centre.norm() > MAX_WHEEL_CENTRE_DISTANCE {
        let what = format!("more than {MAX_WHEEL_CENTRE_DISTANCE} m from the vehicle origin");
        return refuse(points[0].0, wheel_centre, what);
    }
    for &(name, p) in &points[1..] {
        if (p - wheel_centre).norm() > MAX_HARDPOINT_REACH {
            return refuse(name, p, format!("more than {MAX_HARDPOINT_REACH} m from the wheel centre"));
        }
    }
    Ok(())
}

/// Range of the rates a model accepts: `(least, most)` for translational rates (N/m) and for rotational
/// ones (N·m/rad). Far wider than rubber or steel: below, a part is held by next to nothing and drifts
/// anywhere; above, the stiffness swamps every other digit of the equations and then overflows.
pub const TRANSLATIONAL_RATE_RANGE: (f64, f64) = (1.0, 1e15);
/// See [`TRANSLATIONAL_RATE_RANGE`].
pub const ROTATIONAL_RATE_RANGE: (f64, f64) = (1e-3, 1e15);

/// Refuses a rate outside its range, naming its model-file key. The key is written only into the error
/// (a build checks every rate of every bushing, and its keys are words for errors alone): give it as
/// `format_args!`.
pub(crate) fn check_rate(
    key: impl std::fmt::Display,
    value: f64,
    (least, most): (f64, f64),
    unit: &str,
) -> Result<(), ModelError> {
    if value >= least && value <= most {
        return Ok(());
    }
    let key = key.to_string();
    let (least, most, got) = (plain(least), plain(most), plain(value));
    let why = format!("{key} must be a rate in {unit} from {least} to {most}, got {got}");
    Err(ModelError::OutOfRange { item: key, why })
}

/// Refuses a bushing whose rates are outside [`TRANSLATIONAL_RATE_RANGE`] and [`ROTATIONAL_RATE_RANGE`];
/// `key` is the connection's model-file key (`lower_arm_mounts`, `tie_rod`, …).
pub(crate) fn check_connection(key: &str, connection: &Connection) -> Result<(), ModelError> {
    let Connection::Bushing(r) = connection else { return Ok(()) };
    for (what, value) in [("radial", r.radial), ("axial", r.axial)] {
        check_rate(format_args!("{key}.bushing.{what}"), value, TRANSLATIONAL_RATE_RANGE, "N/m")?;
    }
    for (what, value) in [("torsion", r.torsion), ("conical", r.conical)] {
        check_rate(format_args!("{key}.bushing.{what}"), value, ROTATIONAL_RATE_RANGE, "N·m/rad")?;
    }
    Ok(())
}

/// [`check_connection`] for each end of a tie rod.
pub(crate) fn check_tie_rod_mounts(key: &str, mounts: &TieRodMounts) -> Result<(), ModelError> {
    if mounts.inner == mounts.outer {
        return check_connection(key, &mounts.inner);
    }
    check_connection(&format!("{key}.inner"), &mounts.inner)?;
    check_connection(&format!("{key}.outer"), &mounts.outer)
}

/// [`check_connection`] for each end of an arm.
pub(crate) fn check_arm_mounts(key: &str, mounts: &ArmMounts) -> Result<(), ModelError> {
    if mounts.front == mounts.rear {
        return check_connection(key, &mounts.front);
    }
    check_connection(&format!("{key}.front"), &mounts.front)?;
    check_connection(&format!("{key}.rear"), &mounts.rear)
}

/// Largest spring force at design accepted (N): a hundred times a heavy truck's; beyond, the spring's
/// geometric stiffness (force over length) overflows.
pub const MAX_SPRING_FORCE: f64 = 1e8;

/// Refuses a coil spring whose design force and rate give no free length: `L₀ = L + F/k` must be a
/// positive length (a coil spring pushes; a tension larger than `k·L` would need a negative one).
pub(crate) fn check_spring(spring: &SpringSpec, design_length: f64) -> Result<(), ModelError> {
    check_rate("spring.rate", spring.rate, TRANSLATIONAL_RATE_RANGE, "N/m")?;
    check_spring_force("spring", spring.rate, spring.design_force, design_length)
}

/// [`check_spring`]'s design-force part for the spring at model-file key `key`, whose rate was checked.
pub(crate) fn check_spring_force(
    key: impl std::fmt::Display + Copy,
    rate: f64,
    design_force: f64,
    design_length: f64,
) -> Result<(), ModelError> {
    if design_force.is_nan() || design_force.abs() > MAX_SPRING_FORCE {
        return Err(ModelError::OutOfRange {
            item: key.to_string(),
            why: format!(
                "{key}.design_force must be a force in N from {} to {}, got {}",
                plain(-MAX_SPRING_FORCE),
                plain(MAX_SPRING_FORCE),
                plain(design_force)
            ),
        });
    }
    if !design_force.is_finite() {
        // The spring element names these with its own messages.
        return Ok(());
    }
    let free_length = design_length + design_force / rate;
    let why = if !free_length.is_finite() {
        format!(
            "{key}.design_force {design_force:.4e} N at {key}.rate {rate:.4e} N/m would compress the spring by \
             more than any length: give the rate in N/m and the push at design in N"
        )
    } else if free_length <= 0.0 {
        format!(
            "{key}.design_force {design_force:.4e} N at {key}.rate {rate:.4e} N/m would need a free length of \
             {free_length:.4e} m for a design length of {design_length:.4} m: a coil spring pushes, so give \
             {key}.design_force as its push at design (N, above -rate × design length)"
        )
    } else {
        return Ok(());
    };
    Err(ModelError::OutOfRange { item: key.to_string(), why })
}

/// Refuses a steering axis (from `axis.0` up to `axis.1`, named by `axis_names`) that is too short to
/// define a line or does not rise: the scrub radius, trail and kingpin offset are where it meets the
/// ground and the wheel-centre height, which a level axis never does. It must rise by a tenth of its
/// length (lean less than 84° from the vertical).
pub(crate) fn check_steering_axis(axis: (Vec3, Vec3), axis_names: (&str, &str)) -> Result<(), ModelError> {
    let u = axis.1 - axis.0;
    let (length, rise) = (u.norm(), u.z);
    let why = if length < 1e-3 {
        format!(
            "{} and {} are {length:.1e} m apart: they must be distinct to define the steering axis",
            axis_names.0, axis_names.1
        )
    } else if rise < 0.1 * length {
        format!(
            "the steering axis from {} up to {} rises {rise:.4} m over its {length:.4} m: it must rise (lean less than \
             84 deg from the vertical) to meet the ground; check the two points",
            axis_names.0, axis_names.1
        )
    } else {
        return Ok(());
    };
    Err(ModelError::OutOfRange { item: "steering axis".into(), why })
}

/// Shortest lever a tie-rod pull may have about the steering axis (m). Steering arms are 100–150 mm; a
/// tie rod along the axis, or through it, has none, and then only rubber holds the wheel's steer. A
/// micrometre keeps near-aligned geometry open to conditioning studies while refusing the degenerate.
pub const MIN_STEERING_ARM: f64 = 1e-6;

/// The lever of the tie rod about the steering axis (from `axis.0` to `axis.1`): the moment about the
/// axis of a unit pull along the rod, `û · ((outer − axis.0) × d̂)` (m, signed). `None` when the axis or
/// the rod has no length.
pub(crate) fn tie_rod_lever(axis: (Vec3, Vec3), tie_rod_inner: Vec3, tie_rod_outer: Vec3) -> Option<f64> {
    let (u, rod) = (axis.1 - axis.0, tie_rod_outer - tie_rod_inner);
    (u.norm() > 1e-9 && rod.norm() > 1e-9).then(|| u.normalize().dot(&(tie_rod_outer - axis.0).cross(&rod.normalize())))
}

/// Refuses a tie rod that cannot steer: the moment about the steering axis (from `axis.0` to `axis.1`,
/// named by `axis_names`) of a unit pull along the tie rod, `û · ((outer − lower) × d̂)`, is its lever.
pub(crate) fn check_steering_arm(
    axis: (Vec3, Vec3),
    axis_names: (&str, &str),
    tie_rod_inner: Vec3,
    tie_rod_outer: Vec3,
) -> Result<(), ModelError> {
    // Coincident points: the joints and bushings built on them refuse them with their own message.
    let Some(lever) = tie_rod_lever(axis, tie_rod_inner, tie_rod_outer) else { return Ok(()) };
    if lever.abs() >= MIN_STEERING_ARM {
        return Ok(());
    }
    Err(ModelError::OutOfRange {
        item: "tie rod".into(),
        why: format!(
            "a pull along the tie rod (tie_rod_inner to tie_rod_outer) has a lever of {:.1e} m about the steering \
             axis ({} to {}), under the {MIN_STEERING_ARM:e} m it needs to hold the wheel's steer: move \
             tie_rod_outer off the steering axis, to the side of it, by a steering arm (typically 100 to 150 mm)",
            lever.abs(),
            axis_names.0,
            axis_names.1
        ),
    })
}

/// Largest loaded tyre radius accepted when a corner is built (m): far beyond, the contact patch's lever
/// swamps every other length. As for [`MAX_HARDPOINT_REACH`], a corner in millimetres still builds (a
/// model file is held to a tyre's range, 0.05–2 m, where it is read).
pub const MAX_LOADED_RADIUS: f64 = 5e3;

/// The loaded tyre radii a model file takes (m): a car's tyre is 0.25–0.40 m.
pub const LOADED_RADIUS: std::ops::RangeInclusive<f64> = 0.05..=2.0;

/// Loaded tyre radius when a model file does not give one (m): a passenger car's tyre, about 0.30.
pub fn default_loaded_radius() -> f64 {
    0.30
}

/// Largest hardpoint coordinate accepted (m): a car fits in ±1000 m a thousand times over, so anything
/// beyond is a unit or typing mistake.
pub const MAX_COORDINATE: f64 = 1e3;
/// Largest rate accepted (N/m or N·m/rad): stiffer than steel parts of a suspension by far.
pub const MAX_RATE: f64 = 1e12;
/// Largest spring design force accepted (N).
pub const MAX_FORCE: f64 = 1e6;

/// Hardpoints farther than this from the wheel centre are named (m): a corner fits in a 2 m cube.
pub const FAR_FROM_WHEEL_CENTRE: f64 = 2.0;

/// Whether the hardpoints read as a corner in millimetres: the wheel centre more than 10 m from the centre
/// line, or a spread over 20 m that, divided by 1000, is a wheel centre 0.2–2 m out with every hardpoint
/// within 2 m of it.
pub(crate) fn looks_like_millimetres(points: &[(String, Vec3)], wc: Vec3) -> bool {
    let spread = points.iter().map(|(_, p)| (p - wc).norm()).fold(0.0, f64::max);
    let scaled_fits = (200.0..=2000.0).contains(&wc.y.abs()) && spread <= 1e3 * FAR_FROM_WHEEL_CENTRE;
    wc.y.abs() > 10.0 || (spread > 20.0 && scaled_fits)
}

/// `v` as a message writes a number a user gave or may give: the shortest text that reads back as `v`,
/// plain from 1e-3 to below 1e6 (`1.5`, `0.02`, `40000`), with an exponent beyond (`1e6`, `1e308`,
/// `2.5e-7`) rather than hundreds of digits; `not a finite number` where it is none.
pub fn plain(v: f64) -> String {
    if !v.is_finite() {
        "not a finite number".into()
    } else if v != 0.0 && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}
