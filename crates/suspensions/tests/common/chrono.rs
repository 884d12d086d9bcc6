//! What the tests of Chrono's files share, most of it the axle tests': the fixtures as Chrono gives them,
//! points of a Chrono file and their mirror images, the axle tube as a moved rigid body, toe and camber
//! from a spin axis, the travels the rigs drive, the engine's rows over those travels, and the walk of a
//! loop closure along them from the design row, and the part every closure of a tube the wheels turn with
//! shares (the wheel heights driven, toe and camber read). The linkages themselves, each template's written
//! out from its own file, stay in the test files: each test checks one reading against its own equations.

use elastokin_solver::{LoadPath, Mode, StaticSolver};
use elastokin_suspensions::analysis::axle_sweep;
use elastokin_suspensions::analysis::{parallel_wheel_travel, TravelRow};
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::import::chrono::{without_comments, Imported};
use elastokin_suspensions::kc::{self, KcReport};
use elastokin_suspensions::{Axle, AxleRig, AxleRow, Rig, Side, SuspensionFile, WheelAttitude};
use nalgebra::{DVector, Rotation3, Vector3};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A point or a direction in a Chrono file's frame (m).
pub type V = Vector3<f64>;

/// Where the Chrono fixtures are: `tests/data/chrono/` at the repository root.
pub fn fixture_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/chrono")
}

/// Every shipped Chrono file, by its path under [`fixture_dir`], sorted.
pub fn every_file() -> Vec<String> {
    let mut files: Vec<String> = Vec::new();
    let mut dirs = vec![fixture_dir()];
    while let Some(dir) = dirs.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "json") {
                files.push(p.strip_prefix(fixture_dir()).unwrap().to_string_lossy().into_owned());
            }
        }
    }
    files.sort();
    files
}

/// A fixture's text, `tests/data/chrono/<path>`; a missing one panics with its full path.
pub fn fixture(path: &str) -> String {
    let full = fixture_dir().join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

/// A fixture as JSON, its `//` comments taken out: the figures the tests check the import against are read
/// from it, not from the import.
pub fn chrono_json(path: &str) -> Value {
    serde_json::from_str(&without_comments(&fixture(path))).unwrap()
}

/// A fixture as JSON, and the model imported from its text as shipped (panics when it is refused).
pub fn read(path: &str) -> (Value, SuspensionFile) {
    let text = fixture(path);
    let chrono = serde_json::from_str(&without_comments(&text)).unwrap();
    (chrono, import_chrono(&text, path, None).unwrap_or_else(|e| panic!("{path}: {e}")).file)
}

/// A fixture as JSON with `edit` applied, and the model imported from that (panics when it is refused):
/// for files read with something put right, the JSON the closures read is the one imported.
pub fn read_edited(path: &str, edit: impl FnOnce(&mut Value)) -> (Value, SuspensionFile) {
    let mut chrono = chrono_json(path);
    edit(&mut chrono);
    let file = import_chrono(&chrono.to_string(), path, None).unwrap_or_else(|e| panic!("{path}: {e}")).file;
    (chrono, file)
}

/// The import of a fixture with `edit` applied to its JSON: what it reads, or the refusal's text (the
/// tests of refusals look for the keys it names).
pub fn edited(path: &str, edit: impl FnOnce(&mut Value)) -> Result<Imported, String> {
    let mut chrono = chrono_json(path);
    edit(&mut chrono);
    import_chrono(&chrono.to_string(), path, None).map_err(|e| e.to_string())
}

/// Swaps a spring's `Minimum Length` and `Maximum Length` where they are crossed (the minimum above the
/// maximum), as the import's refusal of such files asks; says whether it did. Neither length moves the
/// linkage, so the closures read the same points either way.
pub fn uncross_stops(spring: &mut Value) -> bool {
    let (min, max) = (spring["Minimum Length"].clone(), spring["Maximum Length"].clone());
    let crossed = min.as_f64() > max.as_f64();
    if crossed {
        spring["Minimum Length"] = max;
        spring["Maximum Length"] = min;
    }
    crossed
}

/// The point at `path` (keys joined by `/`) of a Chrono file: the left side's, as Chrono gives it.
pub fn point(chrono: &Value, path: &str) -> V {
    let v = path.split('/').fold(chrono, |v, key| &v[key]);
    let c: Vec<f64> = v.as_array().unwrap_or_else(|| panic!("{path}")).iter().map(|x| x.as_f64().unwrap()).collect();
    V::new(c[0], c[1], c[2])
}

/// The number at `path` (keys joined by `/`) of a Chrono file: a rate, a length or a bias.
pub fn number(chrono: &Value, path: &str) -> f64 {
    path.split('/').fold(chrono, |v, key| &v[key]).as_f64().unwrap_or_else(|| panic!("{path}"))
}

/// The right side's mirror image of a left point, as Chrono places it (y → −y).
pub fn mirror(p: V) -> V {
    V::new(p.x, -p.y, p.z)
}

/// The axle tube (or housing) as a rigid body moved by `x[0..3]` (translation) and `x[3..6]` (rotation
/// vector about `centre`, the tube's `COM`): the first six unknowns of every solid axle's closure.
#[derive(Clone, Copy, Debug)]
pub struct Tube {
    pub centre: V,
}

impl Tube {
    /// The tube's rotation from design at `x`.
    pub fn rotation(&self, x: &[f64]) -> Rotation3<f64> {
        Rotation3::new(V::new(x[3], x[4], x[5]))
    }

    /// Where the tube moved by `x` puts its design point `p`.
    pub fn moved(&self, x: &[f64], p: V) -> V {
        self.centre + V::new(x[0], x[1], x[2]) + self.rotation(x) * (p - self.centre)
    }
}

/// A solid axle whose wheels turn with the tube, held by `held` (its joints' residuals for the tube moved
/// by `x`): Newton on those and on both wheel-centre heights as `travel` drives them at `t`, then each
/// wheel's toe and camber from the tube's turn. Unknowns: the tube's six.
pub fn wheels_on_tube(
    tube: Tube,
    wc: V,
    travel: Travel,
    held: impl Fn(&[f64]) -> Vec<f64>,
) -> impl Fn(f64, &mut [f64; 6]) -> [(f64, f64); 2] {
    move |t, x| {
        let residual = |x: &[f64; 6]| {
            let mut f = held(x);
            let (left, right, _) = travel.at(t);
            f.push(tube.moved(x, wc).z - wc.z - left);
            f.push(tube.moved(x, mirror(wc)).z - wc.z - right);
            DVector::from_vec(f)
        };
        super::newton_fd(residual, x);
        let r = tube.rotation(x);
        [toe_camber(r * V::y(), 1.0), toe_camber(r * -V::y(), -1.0)]
    }
}

/// What a solid axle that its joints lock in roll says of itself: opposite travel is refused by name, a
/// corner's travel drives the left wheel alone (the right follows), and the K&C suite skips roll with that
/// reason. Returns the suite's report for what a test checks further.
pub fn assert_roll_locked(file: &SuspensionFile) -> KcReport {
    let e = Axle::build(&file.suspension, AxleRig::OppositeTravel).unwrap_err().to_string();
    assert!(e.contains("its roll is locked"), "{e}");
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    assert!(corner.model.joint_id("wheel travel").is_some());
    assert!(corner.model.joint_id("right wheel travel").is_none());
    let report = kc::run_suite(file, &[], &kc::Settings { steps: 4, ..Default::default() }, |_| {}).complete().unwrap();
    let roll = report.skipped.iter().find(|s| s.analysis == kc::Analysis::Roll).unwrap();
    assert!(roll.reason.contains("lock its roll"), "{}", roll.reason);
    // Nor has it a roll centre in parallel travel: the column is empty at every row.
    let travel = report.analyses.iter().find(|a| a.analysis == kc::Analysis::ParallelTravel).unwrap();
    let c = travel.table.columns.iter().position(|n| n == "roll_centre_height_m").unwrap();
    assert!(travel.table.rows.iter().all(|r| r[c] == kc::Cell::Empty));
    report
}

/// Toe and camber of a wheel on side `s` (+1 left) whose outward spin axis is `a`, from their definitions:
/// toe = atan2(aₓ, s·a_y), camber = atan2(−a_z, √(aₓ² + a_y²)).
pub fn toe_camber(a: V, s: f64) -> (f64, f64) {
    (a.x.atan2(s * a.y), (-a.z).atan2(a.x.hypot(a.y)))
}

/// What a rig drives with `t`, as [`Travel::at`] gives it to a closure.
#[derive(Clone, Copy, Debug)]
pub enum Travel {
    /// Both wheel-centre heights by `t` (on an axle that cannot roll the right wheel follows the left, and
    /// a closure drives the left's alone).
    Parallel,
    /// The left wheel-centre height by `t`, the right by `−t`.
    Opposite,
    /// The left wheel-centre height by `t`, the right by `t/2`: the axle travels and rolls at once.
    Uneven,
    /// The steering by `t`, both heights held: the steering box's or steering arm's end of the drag link
    /// moved along the drag link, or, without a drag link, the tie rods' inner ends moved across the car.
    Steering,
}

impl Travel {
    /// Left and right wheel-centre travel, and steering travel, at `t`.
    pub fn at(self, t: f64) -> (f64, f64, f64) {
        match self {
            Travel::Parallel => (t, t, 0.0),
            Travel::Opposite => (t, -t, 0.0),
            Travel::Uneven => (t, t / 2.0, 0.0),
            Travel::Steering => (0.0, 0.0, t),
        }
    }

    /// The axle rig that drives this travel. An uneven travel has none: its tests drive the free axle's
    /// wheel heights themselves.
    pub fn rig(self) -> AxleRig {
        match self {
            Travel::Parallel => AxleRig::ParallelTravel,
            Travel::Opposite => AxleRig::OppositeTravel,
            Travel::Steering => AxleRig::Steering,
            Travel::Uneven => panic!("no axle rig drives uneven travel: drive the free axle's wheel heights"),
        }
    }
}

/// One row of both wheels' toe and camber: the travel, then (toe, camber) of the left wheel and of the
/// right (rad).
pub type Angles = (f64, [(f64, f64); 2]);

/// `row` of each of the axle's rows over `rig`'s sweep of ±`reach`, in 12 steps (design at row 6).
pub fn axle_rows_of<R>(file: &SuspensionFile, rig: AxleRig, reach: f64, row: impl Fn(&AxleRow) -> R) -> Vec<R> {
    let axle = Axle::build(&file.suspension, rig).unwrap();
    let rows = axle_sweep(&axle, -reach, reach, 12, Mode::Corrected).unwrap();
    rows.iter().map(row).collect()
}

/// Both wheels' toe and camber over `rig`'s sweep of ±`reach`, in 12 steps (design at row 6).
pub fn axle_rows(file: &SuspensionFile, rig: AxleRig, reach: f64) -> Vec<Angles> {
    axle_rows_of(file, rig, reach, |r| (r.travel, [(r.left.toe, r.left.camber), (r.right.toe, r.right.camber)]))
}

/// `row` of each row of the corner's parallel travel of ±80 mm in 16 steps (design at row 8), the axle
/// built whole, with the partner wheel's attitude: a corner's rows give its own wheel only, so the same
/// path is walked again with the poses kept and the partner read from them.
pub fn corner_rows_of<R>(file: &SuspensionFile, row: impl Fn(&TravelRow, WheelAttitude) -> R) -> Vec<R> {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let partner = corner.partner.expect("an axle builds whole");
    let solver_rows = parallel_wheel_travel(&corner, -0.08, 0.08, 16, Mode::Corrected).unwrap();
    let mut solver = StaticSolver::new(&corner.model, Default::default()).unwrap();
    let mut state = solver.design_state(-0.08);
    let sweep = solver.sweep_from(&mut state, LoadPath::new(-0.08, 0.08, 16), Mode::Corrected).unwrap();
    solver_rows.iter().zip(&sweep.steps).map(|(r, s)| row(r, partner.attitude(&s.poses))).collect()
}

/// Both wheels' toe and camber over the corner's parallel travel of ±80 mm in 16 steps (design at row 8),
/// the axle built whole.
pub fn corner_rows(file: &SuspensionFile) -> Vec<Angles> {
    corner_rows_of(file, |r, p| (r.travel, [(r.attitude.toe, r.attitude.camber), (p.toe, p.camber)]))
}

/// Visits `rows` outwards from the design row (index `design`), up to the last and then down to the first,
/// each with the guess of a closure's unknowns its neighbour's solution left (zero at design, both ways):
/// a closure solved from there follows the branch the engine's sweep is on.
pub fn walk_out<R, const N: usize>(rows: &[R], design: usize, mut visit: impl FnMut(&R, &mut [f64; N])) {
    for half in [rows[design..].iter().collect::<Vec<_>>(), rows[..=design].iter().rev().collect()] {
        let mut guess = [0.0; N];
        for row in half {
            visit(row, &mut guess);
        }
    }
}

/// How far `value` moves over `rows`: its largest less its smallest.
pub fn spread<R>(rows: &[R], value: impl Fn(&R) -> f64) -> f64 {
    let (lo, hi) = rows.iter().map(value).fold((f64::MAX, f64::MIN), |(lo, hi), a| (lo.min(a), hi.max(a)));
    hi - lo
}

/// Largest toe or camber difference (rad) of both wheels between `rows` and `closure` (toe and camber of
/// both wheels at a travel, from the guess of its unknowns), walked out from the design row (index
/// `design`, see [`walk_out`]); and the largest range of the four angles over the rows, which says the
/// comparison has content.
pub fn against<const N: usize>(
    rows: &[Angles],
    design: usize,
    closure: impl Fn(f64, &mut [f64; N]) -> [(f64, f64); 2],
) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    walk_out(rows, design, |(t, engine), guess| {
        let reference = closure(*t, guess);
        for (e, r) in engine.iter().zip(reference) {
            worst = worst.max((e.0 - r.0).abs()).max((e.1 - r.1).abs());
        }
    });
    let mut range: f64 = 0.0;
    for k in 0..4 {
        range = range.max(spread(rows, |r| if k % 2 == 0 { r.1[k / 2].0 } else { r.1[k / 2].1 }));
    }
    (worst, range)
}
