//! Project Chrono's SAE leaf-spring axles (`SAELeafspringAxle`, `SAEToeBarLeafspringAxle`; the UAZ bus's
//! files copied unchanged into `tests/data/chrono/uaz/`, BSD-3-Clause), read into the general model with an
//! `axle`. Both files give their spring a `Minimum Length` above its `Maximum Length` and are refused for
//! it; with the two swapped they read whole.
//!
//! Each leaf is Chrono's linkage of rigid bodies on joints with rotational springs, so with both wheel
//! heights driven the axle still has two ways to move (its wind-up and its lateral give), which the springs
//! hold: the axle's pose is an equilibrium. It is checked against the stationary energy of the linkage
//! written out here from the Chrono file's own points and Chrono's own conversion of its rates (virtual
//! work, not the import), and the toe-bar axle against a second reading of the same suspension, Chrono's
//! generic-wheeled replica of it.

mod common;

use common::chrono::{
    axle_rows_of, chrono_json, fixture, mirror, number, point, spread, toe_camber, uncross_stops, Travel, V,
};
use elastokin_suspensions::document::import_chrono;
use elastokin_suspensions::SuspensionFile;
use nalgebra::{DMatrix, DVector, Rotation3, Unit};
use serde_json::{json, Value};

const REAR: &str = "uaz/UAZBUS_RearSAELeafspringAxle.json";
const FRONT: &str = "uaz/UAZBUS_FrontSAELeafspringAxle.json";
const REPLICA: &str = "uaz/UAZBUS_FrontSAELeafspringAxle_replica.json";

/// The Chrono file as JSON, its spring's `Minimum Length` and `Maximum Length` swapped (the spring is the
/// template's `Auxiliary Spring`, or the replica's first TSDA).
fn swapped(path: &str) -> Value {
    let mut v = chrono_json(path);
    let spring = if v.get("TSDAs").is_some() { &mut v["TSDAs"][0] } else { &mut v["Auxiliary Spring"] };
    assert!(uncross_stops(spring), "{path}: the stops are not crossed");
    v
}

fn read(v: &Value) -> SuspensionFile {
    import_chrono(&v.to_string(), "swapped", None).unwrap_or_else(|e| panic!("{e}")).file
}

fn turn(axis: V, angle: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Unit::new_normalize(axis), angle)
}

/// A wheel's toe, camber and centre.
type Wheel = (f64, f64, V);

/// A row of a sweep: the driven travel and both wheels.
type Row = (f64, [Wheel; 2]);

/// Both wheels of the axle over `travel`'s sweep of ±`reach`, in 12 steps (design at row 6).
fn axle_rows(file: &SuspensionFile, travel: Travel, reach: f64) -> Vec<Row> {
    let wheel = |w: &elastokin_suspensions::WheelAttitude| (w.toe, w.camber, w.wheel_centre);
    axle_rows_of(file, travel.rig(), reach, |r| (r.travel, [wheel(&r.left), wheel(&r.right)]))
}

/// The toe bar's points: the kingpin (`Location Lower` to `Location Upper`), the toe bar's end on the left
/// knuckle, the drag link's ends on the steering box and on the knuckle (as given: the right knuckle's when
/// its y is negative).
struct ToeBar {
    lower: V,
    upper: V,
    tie_rod: V,
    steering_box: V,
    drag: V,
}

/// Chrono's SAE leaf-spring axle, from the file: the tube (its six: translation and rotation vector about
/// `Axle Tube / COM`), and on each side the half clamps A and B turned by γ about the tube's z at their
/// points, the front leaf turned by θ_A about −y on clamp A, the rear leaf by θ_B about −y on clamp B, the
/// shackle by ψ about −y at the rear hanger (`x[6 + 5s ..]` = γ_A, γ_B, θ_A, θ_B, ψ for side s, the right
/// side the left's mirror image), and with a toe bar each knuckle by δ about its kingpin on the tube
/// (`x[16]`, `x[17]`). The front leaf's far end stays on the front hanger, the rear leaf's on the shackle.
///
/// The energy is Chrono's: each RSDA `½ k θ² − P θ` (`ChLinkRSDA` pushes `P − k θ` on its second body, θ
/// its turn relative to the first about the RSDA's axis, zero at construction), with the rates and preloads
/// of `SAELeafspringAxle::Create` written out below, and the auxiliary spring's `½ k (L − L₀)²`.
struct LeafAxle {
    centre: V,
    wheel: V,
    hanger: V,
    clamp_a: V,
    clamp_b: V,
    shackle: V,
    rear_hanger: V,
    /// Front and rear half's lateral (about z) and vertical (about −y) rates, N·m/rad.
    lateral: [f64; 2],
    vertical: [f64; 2],
    /// The vertical springs' preload torques, N·m.
    preload: [f64; 2],
    /// The auxiliary spring: chassis seat, axle seat, rate, free length.
    spring: (V, V, f64, f64),
    toe_bar: Option<ToeBar>,
}

/// The two coordinates left free by the drivers and the joints: the tube's lateral shift and its turn about
/// y (its wind-up).
const FREE: [usize; 2] = [1, 4];

impl LeafAxle {
    fn from_chrono(v: &Value) -> LeafAxle {
        let p = |k: &str| point(v, &format!("Leafspring/{k}"));
        let (hanger, clamp_a, clamp_b, shackle) =
            (p("Location Front Hanger"), p("Location Clamp A"), p("Location Clamp B"), p("Location Shackle"));
        // `SAELeafspringAxle::Create`: the translational rates shared by the bias, times the leaf's squared
        // length; the preload's moment divided by the rate, which Chrono's functor takes as a torque.
        let (ra, rb) = (clamp_a - hanger, clamp_b - shackle);
        let bias = number(v, "Leafspring/Stiffness Bias");
        let share = [1.0 / (1.0 + bias), bias / (1.0 + bias)];
        let squared = [ra.norm_squared(), rb.norm_squared()];
        let rates = |k: f64| [k * share[0] * squared[0], k * share[1] * squared[1]];
        let lateral = rates(number(v, "Leafspring/Lateral Stiffness"));
        let vertical = rates(number(v, "Leafspring/Vertical Stiffness"));
        let force = V::new(0.0, 0.0, number(v, "Leafspring/Vertical Preload Force") / 2.0);
        let preload = [force.cross(&ra).y / vertical[0], force.cross(&rb).y / vertical[1]];
        let s = |k: &str| point(v, &format!("Auxiliary Spring/{k}"));
        let spring = (
            s("Location Chassis"),
            s("Location Axle"),
            number(v, "Auxiliary Spring/Spring Coefficient"),
            number(v, "Auxiliary Spring/Free Length"),
        );
        let toe_bar = v.get("Knuckle").map(|_| ToeBar {
            lower: point(v, "Knuckle/Location Lower"),
            upper: point(v, "Knuckle/Location Upper"),
            tie_rod: point(v, "Tierod/Location Knuckle"),
            steering_box: point(v, "Draglink/Location Chassis"),
            drag: point(v, "Knuckle/Location Draglink"),
        });
        LeafAxle {
            centre: point(v, "Axle Tube/COM"),
            wheel: point(v, "Spindle/COM"),
            hanger,
            clamp_a,
            clamp_b,
            shackle,
            rear_hanger: p("Location Rear Hanger"),
            lateral,
            vertical,
            preload,
            spring,
            toe_bar,
        }
    }

    fn unknowns(&self) -> usize {
        if self.toe_bar.is_some() {
            18
        } else {
            16
        }
    }

    fn tube(&self, x: &DVector<f64>, p: V) -> V {
        let r = Rotation3::new(V::new(x[3], x[4], x[5]));
        self.centre + V::new(x[0], x[1], x[2]) + r * (p - self.centre)
    }

    /// A point of side `s`'s wheel carrier (given as the left's): the tube, or its knuckle turned about the
    /// kingpin.
    fn carrier(&self, x: &DVector<f64>, s: usize, p: V) -> V {
        let m = |q: V| if s == 0 { q } else { mirror(q) };
        match &self.toe_bar {
            None => self.tube(x, m(p)),
            Some(t) => {
                let (lower, upper) = (m(t.lower), m(t.upper));
                self.tube(x, lower + turn(upper - lower, x[16 + s]) * (m(p) - lower))
            }
        }
    }

    fn constraints(&self, x: &DVector<f64>, (left, right, rack): (f64, f64, f64)) -> DVector<f64> {
        let r = Rotation3::new(V::new(x[3], x[4], x[5]));
        let mut f = Vec::new();
        for s in 0..2 {
            let m = |q: V| if s == 0 { q } else { mirror(q) };
            let q = &x.as_slice()[6 + 5 * s..11 + 5 * s];
            let front_leaf = r * turn(V::z(), q[0]) * turn(-V::y(), q[2]);
            let rear_leaf = r * turn(V::z(), q[1]) * turn(-V::y(), q[3]);
            let shackle = m(self.rear_hanger) + turn(-V::y(), q[4]) * (m(self.shackle) - m(self.rear_hanger));
            let a = self.tube(x, m(self.clamp_a)) + front_leaf * (m(self.hanger) - m(self.clamp_a)) - m(self.hanger);
            let b = self.tube(x, m(self.clamp_b)) + rear_leaf * (m(self.shackle) - m(self.clamp_b)) - shackle;
            f.extend(a.iter().chain(b.iter()));
        }
        f.push(self.carrier(x, 0, self.wheel).z - self.wheel.z - left);
        f.push(self.carrier(x, 1, self.wheel).z - self.wheel.z - right);
        if let Some(t) = &self.toe_bar {
            let box_now = t.steering_box + (t.drag - t.steering_box).normalize() * rack;
            let (side, drag) = if t.drag.y < 0.0 { (1, mirror(t.drag)) } else { (0, t.drag) };
            f.push((self.carrier(x, side, drag) - box_now).norm() - (t.drag - t.steering_box).norm());
            let across = self.carrier(x, 0, t.tie_rod) - self.carrier(x, 1, t.tie_rod);
            f.push(across.norm() - (t.tie_rod - mirror(t.tie_rod)).norm());
        }
        DVector::from_vec(f)
    }

    fn energy(&self, x: &DVector<f64>) -> f64 {
        let (seat_chassis, seat_axle, rate, free) = self.spring;
        let mut e = 0.0;
        for s in 0..2 {
            let m = |q: V| if s == 0 { q } else { mirror(q) };
            let q = &x.as_slice()[6 + 5 * s..11 + 5 * s];
            for half in 0..2 {
                e += 0.5 * self.lateral[half] * q[half].powi(2);
                e += 0.5 * self.vertical[half] * q[2 + half].powi(2) - self.preload[half] * q[2 + half];
            }
            let length = (self.tube(x, m(seat_axle)) - m(seat_chassis)).norm();
            e += 0.5 * rate * (length - free).powi(2);
        }
        e
    }

    fn dependent(&self) -> Vec<usize> {
        (0..self.unknowns()).filter(|i| !FREE.contains(i)).collect()
    }

    /// Closes the linkage with the two free coordinates held: Newton on the others (central-difference
    /// Jacobian).
    fn close(&self, x: &mut DVector<f64>, travel: (f64, f64, f64)) {
        let dep = self.dependent();
        for _ in 0..40 {
            let f = self.constraints(x, travel);
            if f.norm() < 1e-15 {
                return;
            }
            let mut jac = DMatrix::zeros(f.len(), dep.len());
            for (c, &i) in dep.iter().enumerate() {
                let (mut xp, mut xm) = (x.clone(), x.clone());
                xp[i] += 1e-7;
                xm[i] -= 1e-7;
                jac.set_column(c, &((self.constraints(&xp, travel) - self.constraints(&xm, travel)) / 2e-7));
            }
            let dx = jac.lu().solve(&(-f)).expect("the linkage closes away from lock-up");
            for (c, &i) in dep.iter().enumerate() {
                x[i] += dx[c];
            }
            if dx.norm() < 1e-15 {
                break;
            }
        }
        let f = self.constraints(x, travel);
        assert!(f.norm() < 1e-12, "the linkage did not close: {f:?}");
    }

    /// The energy's rate along each free coordinate, the others following on the closed linkage: the
    /// virtual work of the springs in the two motions the joints and drivers leave.
    fn virtual_work(&self, x: &DVector<f64>, travel: (f64, f64, f64)) -> [f64; 2] {
        let n = self.unknowns();
        let h = 1e-6;
        let mut jac = DMatrix::zeros(n - 2, n);
        let mut grad = DVector::zeros(n);
        for i in 0..n {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[i] += h;
            xm[i] -= h;
            jac.set_column(i, &((self.constraints(&xp, travel) - self.constraints(&xm, travel)) / (2.0 * h)));
            grad[i] = (self.energy(&xp) - self.energy(&xm)) / (2.0 * h);
        }
        let dep = self.dependent();
        let lu = jac.select_columns(dep.iter()).lu();
        FREE.map(|free| {
            let follow = lu.solve(&(-jac.column(free))).expect("the linkage closes away from lock-up");
            grad[free] + dep.iter().zip(follow.iter()).map(|(&i, d)| grad[i] * d).sum::<f64>()
        })
    }

    /// The equilibrium at `travel`: Newton on the virtual work of the two free motions (a central-difference
    /// Jacobian), the linkage closed at each step; from the guess in `x`.
    fn equilibrium(&self, x: &mut DVector<f64>, travel: (f64, f64, f64)) {
        let h = 1e-6;
        for _ in 0..40 {
            self.close(x, travel);
            let g = self.virtual_work(x, travel);
            let mut hess = nalgebra::Matrix2::zeros();
            for (c, &free) in FREE.iter().enumerate() {
                let (mut xp, mut xm) = (x.clone(), x.clone());
                xp[free] += h;
                xm[free] -= h;
                self.close(&mut xp, travel);
                self.close(&mut xm, travel);
                let (gp, gm) = (self.virtual_work(&xp, travel), self.virtual_work(&xm, travel));
                hess.set_column(c, &nalgebra::Vector2::new(gp[0] - gm[0], gp[1] - gm[1]).scale(0.5 / h));
            }
            let step = hess.lu().solve(&-nalgebra::Vector2::new(g[0], g[1])).expect("the springs hold the axle");
            for (c, &free) in FREE.iter().enumerate() {
                x[free] += step[c];
            }
            if step.norm() < 1e-14 {
                break;
            }
        }
        self.close(x, travel);
    }

    fn wheels(&self, x: &DVector<f64>) -> [Wheel; 2] {
        [0, 1].map(|s| {
            let (centre, outward) = (self.carrier(x, s, self.wheel), self.carrier(x, s, self.wheel + V::y()));
            let (toe, camber) = toe_camber(outward - centre, if s == 0 { 1.0 } else { -1.0 });
            (toe, camber, centre)
        })
    }
}

/// The largest toe or camber difference (rad) and wheel-centre difference (m) of both wheels between `rows`
/// and `reference` (each row's wheels at its travel), walked outwards from the design row (6) both ways.
fn compare(rows: &[Row], mut reference: impl FnMut(f64, usize) -> [Wheel; 2]) -> (f64, f64) {
    let (mut angle, mut place): (f64, f64) = (0.0, 0.0);
    for (k, (t, wheels)) in rows[6..].iter().chain(rows[..=6].iter().rev()).enumerate() {
        let other = reference(*t, k);
        for (e, r) in wheels.iter().zip(other) {
            angle = angle.max((e.0 - r.0).abs()).max((e.1 - r.1).abs());
            place = place.max((e.2 - r.2).norm());
        }
    }
    (angle, place)
}

/// How far the wheels move over `rows`: the largest range of any toe or camber (rad), and of a wheel
/// centre's x (m).
fn ranges(rows: &[Row]) -> (f64, f64) {
    let mut angle: f64 = 0.0;
    let mut x: f64 = 0.0;
    for s in 0..2 {
        angle = angle.max(spread(rows, |r| r.1[s].0)).max(spread(rows, |r| r.1[s].1));
        x = x.max(spread(rows, |r| r.1[s].2.x));
    }
    (angle, x)
}

/// The engine's rows against the equilibrium of the leaf linkage written out above, each step starting
/// from its neighbour's solution (the design row from the design).
fn against_equilibrium(leaves: &LeafAxle, rows: &[Row], travel: Travel) -> (f64, f64) {
    let mut x = DVector::zeros(leaves.unknowns());
    let mut design = x.clone();
    compare(rows, |t, k| {
        if k == 7 {
            x = design.clone();
        }
        leaves.equilibrium(&mut x, travel.at(t));
        if k == 0 {
            design = x.clone();
        }
        leaves.wheels(&x)
    })
}

/// Chrono's files give the auxiliary spring a `Minimum Length` (0.28 m) above its `Maximum Length`
/// (0.12 m): both are refused by name. Swapped, each reads whole, every key read or noted: the leaf's
/// parts per corner, the tube on the axle (the toe bar as a distance link across), and the rear's spring of
/// no rate left out with its stops kept; the suite runs on both, steering only the toe-bar axle.
#[test]
fn the_uaz_leaf_spring_axles_are_refused_for_their_stops_and_read_whole_when_swapped() {
    for path in [REAR, FRONT] {
        let e = import_chrono(&fixture(path), path, None).unwrap_err().to_string();
        for said in ["\"Auxiliary Spring\"", "\"Minimum Length\" 0.28", "\"Maximum Length\" 0.12", "swapped"] {
            assert!(e.contains(said), "{path}: no '{said}' in: {e}");
        }
        let imported = import_chrono(&swapped(path).to_string(), path, None).unwrap();
        assert!(!imported.notes.iter().any(|n| n.contains("not understood")), "{:#?}", imported.notes);
        let elastokin_suspensions::Template::General(g) = &imported.file.suspension else { panic!("general") };
        let bodies: Vec<&str> = g.bodies.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(bodies, ["upright", "front leaf", "rear leaf", "clamp A", "clamp B", "shackle"], "{path}");
        assert_eq!(g.bushings.len(), 4, "{path}: the four rotational springs of a side");
        assert_eq!(g.stops.len(), 2, "{path}: the bump and rebound stops");
        // The rear's `Spring Coefficient` is 0: its spring pushes nothing.
        assert_eq!(g.springs.len(), usize::from(path == FRONT), "{path}");
        let axle = g.axle.as_ref().unwrap();
        assert_eq!(axle.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>(), ["axle tube"]);
        let report = elastokin_suspensions::kc::run_suite(
            &imported.file,
            &[],
            &elastokin_suspensions::kc::Settings { steps: 4, ..Default::default() },
            |_| {},
        )
        .complete()
        .unwrap();
        let steering = report.analyses.iter().any(|a| a.analysis == elastokin_suspensions::kc::Analysis::Steering);
        assert_eq!(steering, path == FRONT, "{path}: steered by its drag link only on the toe-bar axle");
    }
}

/// One sweep against the leaf linkage's equilibrium: the largest toe or camber and wheel-centre
/// differences, within `tolerance`; the wheels move (`moves`: the largest range of a toe or camber in rad,
/// or of a wheel centre's x in m, whichever is larger than it says); and the comparison tells both the
/// equilibrium (the linkage with its two free coordinates held at design misses by more than a hundred
/// times the tolerance) and Chrono's preload torques of a few hundredths of a newton-metre (without them it
/// misses by more than ten times).
fn settles(path: &str, travel: Travel, reach: f64, tolerance: (f64, f64), moves: (f64, f64)) {
    let v = swapped(path);
    let (file, leaves) = (read(&v), LeafAxle::from_chrono(&v));
    let rows = axle_rows(&file, travel, reach);
    let (angle, place) = against_equilibrium(&leaves, &rows, travel);
    assert!(angle < tolerance.0 && place < tolerance.1, "{path} {travel:?}: {angle:e} rad, {place:e} m");
    let (angle_range, x_range) = ranges(&rows);
    assert!(angle_range > moves.0 || x_range > moves.1, "{path} {travel:?}: {angle_range} rad, {x_range} m");
    let misses = |(a, p): (f64, f64), times: f64| a > times * tolerance.0 || p > times * tolerance.1;
    let mut held = DVector::zeros(leaves.unknowns());
    let kinematic = compare(&rows, |t, k| {
        if k == 7 {
            held.fill(0.0);
        }
        (held[FREE[0]], held[FREE[1]]) = (0.0, 0.0);
        leaves.close(&mut held, travel.at(t));
        leaves.wheels(&held)
    });
    assert!(misses(kinematic, 100.0), "{path} {travel:?}: held, {kinematic:?}");
    let unloaded = LeafAxle { preload: [0.0; 2], ..leaves };
    let without = against_equilibrium(&unloaded, &rows, travel);
    assert!(misses(without, 10.0), "{path} {travel:?}: without the preload, {without:?}");
}

/// `SAELeafspringAxle` (the UAZ rear, the spindles on the tube): in parallel travel the wheels keep their
/// toe and camber and move fore and aft as the leaves swing and wind up; in opposite travel they camber
/// with the tube and toe with its yaw. Against the linkage's equilibrium written out from the file.
#[test]
fn the_rear_leaf_spring_axle_settles_where_its_linkage_does() {
    // Measured: 1.6e-14 rad, 4.1e-12 m (toe and camber stay at zero, the wheel centres move 6.1 mm fore and
    // aft; without the preload they miss by 1.0e-8 m, with the free coordinates held by 4.8e-4 m).
    settles(REAR, Travel::Parallel, 0.05, (1e-12, 1e-10), (f64::INFINITY, 5e-3));
    // Measured: 2.2e-12 rad, 2.3e-12 m (camber moves 0.14 rad; without the preload 2.7e-8 m, held 6.8e-3 m).
    settles(REAR, Travel::Opposite, 0.05, (5e-11, 5e-11), (0.1, f64::INFINITY));
}

/// `SAEToeBarLeafspringAxle` (the UAZ front): the knuckles on kingpins, the toe bar across and the drag link
/// from the held steering box, which steers the wheels as the axle travels; and steering by the drag link.
/// Against the linkage's equilibrium written out from the file.
#[test]
fn the_toe_bar_leaf_spring_axle_settles_where_its_linkage_does() {
    // Measured: 2.9e-11 rad, 6.2e-12 m (the wheels toe 0.05 rad; without the preload 4.8e-8 rad, held
    // 3.9e-3 rad).
    settles(FRONT, Travel::Parallel, 0.05, (5e-10, 1e-10), (0.04, f64::INFINITY));
    // Measured: 8.3e-12 rad, 1.6e-12 m (camber moves 0.14 rad; without the preload 4.4e-8 rad, held
    // 8.2e-5 rad).
    settles(FRONT, Travel::Opposite, 0.05, (2e-10, 5e-11), (0.1, f64::INFINITY));
    // Measured: 5.2e-11 rad, 3.9e-12 m (the wheels steer 0.75 rad; without the preload 7.3e-8 rad, held
    // 1.6e-5 rad).
    settles(FRONT, Travel::Steering, 0.04, (1e-9, 1e-10), (0.5, f64::INFINITY));
}

/// Chrono's generic-wheeled replica of the UAZ front writes its figures rounded: joint positions to about
/// 10⁻⁵ m (its right toe-bar end at x = −0.1906 for the template's −0.190569), the kingpin's quaternion
/// and the rates to five digits, the vertical springs' preloads ±0.0468 for ±0.046844 N·m. Read as it is,
/// it travels and steers as the template's reading within what that rounding moves; with those figures
/// put back to the template file's (its points, and Chrono's conversion of its rates written out in
/// `LeafAxle`), the two readings agree to the solver's precision.
#[test]
fn the_toe_bar_axle_reads_as_its_generic_wheeled_replica() {
    let template = swapped(FRONT);
    let (file, rounded, exact) = (read(&template), read(&swapped(REPLICA)), read(&restored_replica(&template)));
    // Measured, rounded: 6.3e-6 rad, 5.0e-7 m (parallel); 4.1e-6 rad, 3.0e-7 m (opposite); 9.9e-5 rad,
    // 6.9e-6 m (steering): the rounding's own size (3e-5 m on a 0.19 m steering arm is 1.6e-4 rad).
    for (travel, reach, rounding, tolerance) in [
        // Measured, restored: 2.9e-11 rad, 6.2e-12 m.
        (Travel::Parallel, 0.05, (2e-5, 2e-6), (1e-9, 1e-10)),
        // Measured, restored: 6.2e-12 rad, 1.2e-12 m.
        (Travel::Opposite, 0.05, (2e-5, 2e-6), (2e-10, 5e-11)),
        // Measured, restored: 7.0e-12 rad, 7.6e-13 m.
        (Travel::Steering, 0.04, (3e-4, 2e-5), (2e-10, 2e-11)),
    ] {
        let rows = axle_rows(&file, travel, reach);
        let (angle, place) = between(&rows, &axle_rows(&rounded, travel, reach));
        assert!(angle < rounding.0 && place < rounding.1, "{travel:?}, rounded: {angle:e} rad, {place:e} m");
        let (angle, place) = between(&rows, &axle_rows(&exact, travel, reach));
        assert!(angle < tolerance.0 && place < tolerance.1, "{travel:?}, restored: {angle:e} rad, {place:e} m");
        // The wheels toe, camber or steer by hundredths of a radian at least: the comparison has content.
        assert!(ranges(&rows).0 > 0.02, "{travel:?}: {:?}", ranges(&rows));
    }
}

/// The largest toe or camber difference (rad) and wheel-centre difference (m) of both wheels between two
/// sweeps of the same travels.
fn between(a: &[Row], b: &[Row]) -> (f64, f64) {
    let (mut angle, mut place): (f64, f64) = (0.0, 0.0);
    for (r, q) in a.iter().zip(b) {
        assert_eq!(r.0, q.0);
        for (e, o) in r.1.iter().zip(&q.1) {
            angle = angle.max((e.0 - o.0).abs()).max((e.1 - o.1).abs());
            place = place.max((e.2 - o.2).norm());
        }
    }
    (angle, place)
}

/// The replica (stops swapped) with the figures it rounds put back to the template's `template`: its joints'
/// positions at the template's points, the kingpin's axis from them, its rotational springs' rates and
/// preloads by Chrono's conversion, and its spring's rate.
fn restored_replica(template: &Value) -> Value {
    let leaves = LeafAxle::from_chrono(template);
    let bar = leaves.toe_bar.as_ref().unwrap();
    let mut v = swapped(REPLICA);
    let points = [
        ("Front Leaf Spherical", leaves.hanger),
        ("Rear Leaf Spherical", leaves.shackle),
        ("Shackle Revolute", leaves.rear_hanger),
        ("Half Clamp A Revolute", leaves.clamp_a),
        ("Half Clamp B Revolute", leaves.clamp_b),
        ("Front Leaf Revolute", leaves.clamp_a),
        ("Rear Leaf Revolute", leaves.clamp_b),
        ("Tierod Spherical", bar.tie_rod),
        ("Tierod Universal", mirror(bar.tie_rod)),
        ("Kingpin Revolute", (bar.lower + bar.upper) / 2.0),
    ];
    let mut restored = 0;
    for joint in v["Joints"].as_array_mut().unwrap() {
        let name = joint["Name"].as_str().unwrap().to_string();
        if let Some((_, p)) = points.iter().find(|(n, _)| *n == name) {
            joint["Position"] = json!([p.x, p.y, p.z]);
            restored += 1;
        }
        if name == "Kingpin Revolute" {
            // Chrono's kingpin frame has z from the upper point to the lower.
            let q = nalgebra::UnitQuaternion::rotation_between(&V::z(), &(bar.lower - bar.upper)).unwrap();
            joint["Rotation"] = json!([q.w, q.i, q.j, q.k]);
        }
    }
    for rsda in v["RSDAs"].as_array_mut().unwrap() {
        let (rate, preload) = match rsda["Name"].as_str().unwrap() {
            "Half Clamp A to Axle Tube RSDA" => (leaves.lateral[0], 0.0),
            "Half Clamp B to Axle Tube RSDA" => (leaves.lateral[1], 0.0),
            "Half Clamp A to Frontleaf RSDA" => (leaves.vertical[0], leaves.preload[0]),
            "Half Clamp B to Rearleaf RSDA" => (leaves.vertical[1], leaves.preload[1]),
            other => panic!("an RSDA the replica does not have: {other}"),
        };
        rsda["Spring Coefficient"] = json!(rate);
        rsda["Preload"] = json!(preload);
        restored += 1;
    }
    v["TSDAs"][0]["Spring Coefficient"] = json!(leaves.spring.2);
    assert_eq!(restored, points.len() + 4);
    v
}

/// Bushing data goes where Chrono puts it: `Leafspring Bushing Data` on the shackle's joint (Chrono reads it
/// there, in place of `Shackle Bushing Data`), the leaves' joints staying revolute; `Clamp Bushing Data`,
/// under the lateral rotational springs, is refused by name, as are rates Chrono would divide by zero.
#[test]
fn leaf_spring_bushings_and_rates_are_read_as_chrono_reads_them() {
    let bushing = json!({ "Stiffness Linear": 7e6, "Damping Linear": 0, "Stiffness Rotational": 9e3,
        "Damping Rotational": 0, "DOF": { "Stiffness Linear": 0, "Damping Linear": 0,
        "Stiffness Rotational": 50, "Damping Rotational": 0 } });
    let mut v = swapped(REAR);
    v["Leafspring"]["Leafspring Bushing Data"] = bushing.clone();
    v["Leafspring"]["Shackle Bushing Data"] = bushing.clone();
    let imported = import_chrono(&v.to_string(), "bushings", None).unwrap();
    assert!(!imported.notes.iter().any(|n| n.contains("not understood")), "{:#?}", imported.notes);
    assert!(imported.notes.iter().any(|n| n.contains("replaced by Leafspring Bushing Data")), "{:#?}", imported.notes);
    let elastokin_suspensions::Template::General(g) = &imported.file.suspension else { panic!("general") };
    let names = |list: Vec<&str>| list.into_iter().map(str::to_string).collect::<Vec<_>>();
    assert!(names(g.bushings.iter().map(|b| b.name.as_str()).collect()).contains(&"shackle pivot".to_string()));
    let joints = names(g.joints.iter().map(|j| j.name.as_str()).collect());
    assert!(!joints.contains(&"shackle pivot".to_string()), "{joints:?}");
    assert!(joints.contains(&"front leaf clamp".to_string()) && joints.contains(&"rear leaf clamp".to_string()));

    let mut v = swapped(REAR);
    v["Leafspring"]["Clamp Bushing Data"] = bushing;
    let e = import_chrono(&v.to_string(), "clamp", None).unwrap_err().to_string();
    assert!(e.contains("\"Clamp Bushing Data\"") && e.contains("remove"), "{e}");

    for (key, value) in [("Stiffness Bias", 0.0), ("Vertical Stiffness", -1.0), ("Lateral Stiffness", 0.0)] {
        let mut v = swapped(FRONT);
        v["Leafspring"][key] = json!(value);
        let e = import_chrono(&v.to_string(), "rates", None).unwrap_err().to_string();
        assert!(e.contains(&format!("\"{key}\" {value}")) && e.contains("give positive rates"), "{e}");
    }
}
