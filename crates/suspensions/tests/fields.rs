//! Field elements in models: a bushing written as a field gives the bushing's results, a coupled field's
//! right corner is the mirror image of the left, and one body on a coupled field moves as the inverse of
//! its matrix says.

use elastokin_core::{BodyRef, Model, Pose, Vec3};
use elastokin_elements::{Field, FieldSpec, PointForce};
use elastokin_solver::{SolverOptions, StaticSolver};
use elastokin_suspensions::description::general::{FieldDef, GeneralCorner};
use elastokin_suspensions::description::Template;
use elastokin_suspensions::kc::{self, Analysis, Settings, Table};
use elastokin_suspensions::SuspensionFile;
use nalgebra::{Matrix6, Vector6};
use std::path::Path;

fn macpherson_general() -> SuspensionFile {
    let mut file =
        SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/macpherson.json")).unwrap();
    file.suspension = Template::General(Box::new(file.suspension.expand()));
    file
}

fn general(file: &mut SuspensionFile) -> &mut GeneralCorner {
    match &mut file.suspension {
        Template::General(g) => g,
        _ => unreachable!("made general above"),
    }
}

/// The lower arm's front bushing written as a field of its rates (axial along its axis, radial across;
/// torsion about it, conical across), `couple` times the geometric mean of each pair of rates off the
/// diagonal between the axial deflection and the twist.
fn as_field(file: &mut SuspensionFile, couple: f64) {
    let g = general(file);
    let k = g.bushings.iter().position(|b| b.name == "lower arm front bushing").unwrap();
    let b = g.bushings.remove(k);
    let rate = |s: &Option<elastokin_suspensions::description::general::Stiffness>| match s.as_ref().unwrap() {
        elastokin_suspensions::description::general::Stiffness::Rate(r) => *r,
        other => panic!("{other:?}"),
    };
    let (axial, radial, torsion, conical) = (rate(&b.axial), rate(&b.radial), rate(&b.torsion), rate(&b.conical));
    let mut m = [[0.0; 6]; 6];
    for (i, v) in [axial, radial, radial, torsion, conical, conical].into_iter().enumerate() {
        m[i][i] = v;
    }
    let c = couple * (axial * torsion).sqrt();
    (m[0][3], m[3][0]) = (c, c);
    let c = couple * (radial * conical).sqrt();
    (m[1][5], m[5][1]) = (c, c);
    g.fields.push(FieldDef {
        name: b.name,
        bodies: b.bodies,
        at: b.at,
        axis: b.axis,
        y_axis: b.y_axis,
        stiffness: m,
        preload_force: None,
        preload_torque: None,
    });
}

/// The largest difference between two tables' numbers, column by column of the same name, relative to the
/// column's largest (a field is built after the bushings, so its columns come later).
fn table_difference(a: &Table, b: &Table) -> f64 {
    let mut columns = a.columns.clone();
    columns.sort();
    let mut theirs = b.columns.clone();
    theirs.sort();
    assert_eq!(columns, theirs);
    let largest = a.rows.iter().flatten().filter_map(|v| v.number()).fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0f64;
    for (c, name) in a.columns.iter().enumerate() {
        let d = b.columns.iter().position(|x| x == name).unwrap();
        let scale = a.rows.iter().filter_map(|r| r[c].number()).fold(0.0_f64, |m, v| m.max(v.abs()));
        for (x, y) in a.rows.iter().zip(&b.rows) {
            if let (Some(x), Some(y)) = (x[c].number(), y[d].number()) {
                // A column that is zero throughout (a ball joint's moment) holds the rounding of the sums it
                // comes from, which are of the table's largest numbers: judged against those.
                worst = worst.max((x - y).abs() / scale.max(largest));
            }
        }
    }
    worst
}

#[test]
fn a_bushing_written_as_a_field_gives_the_bushings_results() {
    let bushing = macpherson_general();
    let mut field = bushing.clone();
    as_field(&mut field, 0.0);
    let mut worst = 0.0f64;
    for analysis in
        [Analysis::ParallelTravel, Analysis::Roll, Analysis::Road(elastokin_suspensions::analysis::WheelLoad::Lateral)]
    {
        let (a, b) = (
            kc::run(analysis, &bushing, &Settings::default()).unwrap(),
            kc::run(analysis, &field, &Settings::default()).unwrap(),
        );
        worst = worst.max(table_difference(&a.table, &b.table));
    }
    // The same model, its elements summed in another order: measured 2.6e-13 (camber, lateral force).
    assert!(worst <= 1e-12, "{worst:e}");
}

#[test]
fn a_coupled_fields_right_corner_is_the_mirror_image_of_the_left() {
    let mut file = macpherson_general();
    as_field(&mut file, 0.3);
    let report = kc::run(Analysis::Roll, &file, &Settings::default()).unwrap();
    let t = &report.table;
    let col = |name: &str| -> Vec<f64> {
        let c = t.columns.iter().position(|x| x == name).unwrap();
        t.rows.iter().map(|r| r[c].number().unwrap()).collect()
    };
    let (left, right, travel) = (col("left_toe_deg"), col("right_toe_deg"), col("left_travel_m"));
    let n = left.len() - 1;
    let mut worst = 0.0f64;
    for k in 0..=n {
        assert!((travel[k] + travel[n - k]).abs() < 1e-15, "rows symmetric about design");
        worst = worst.max((left[k] - right[n - k]).abs());
    }
    // The left wheel at +φ is the right one at −φ: measured 5.6e-14 deg, where the coupling moves the rows
    // by 2.8e-3 of their size (a wrong mirror would show it).
    assert!(worst < 5e-12, "{worst:e} deg");
    let mut uncoupled = macpherson_general();
    as_field(&mut uncoupled, 0.0);
    let plain = kc::run(Analysis::Roll, &uncoupled, &Settings::default()).unwrap();
    let coupled_effect = table_difference(&plain.table, &report.table);
    assert!(coupled_effect > 1e-6, "the coupling changes the roll rows: {coupled_effect:e}");
    let lateral = report.figure("roll_centre_lateral").unwrap().value.unwrap();
    assert!(lateral.abs() < 1e-9, "roll centre on the centre plane: {lateral} mm");
}

#[test]
fn one_body_on_a_coupled_field_moves_as_the_inverse_of_its_matrix() {
    // A body held to the ground by a field alone, its frame turned, a force and no moment at the field's
    // point: to first order the deflection in the frame is K⁻¹ (F; 0), the rotation too.
    let frame = *nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.7).matrix();
    let mut k = Matrix6::from_diagonal(&Vector6::new(2e6, 1e6, 3e6, 2000.0, 1500.0, 800.0));
    for (r, c, v) in [(0, 4, 20_000.0), (1, 3, -15_000.0), (2, 5, 10_000.0), (0, 1, 3e5)] {
        k[(r, c)] = v;
        k[(c, r)] = v;
    }
    let point = Vec3::new(0.1, 0.5, -0.2);
    let mut model = Model::new();
    let body = model.add_body("knuckle", Pose::at(point + Vec3::new(0.05, 0.0, 0.0))).unwrap();
    let spec = FieldSpec {
        name: "mount".into(),
        body_i: BodyRef::Ground,
        body_j: BodyRef::Body(body),
        point,
        frame,
        stiffness: k,
        preload_force: Vec3::zeros(),
        preload_torque: Vec3::zeros(),
    };
    model.add_element(Field::from_spec(spec).unwrap()).unwrap();
    let force = Vec3::new(3.0, -2.0, 5.0);
    model.add_element(PointForce::new("load", BodyRef::Body(body), point, force).unwrap()).unwrap();
    let mut solver = StaticSolver::new(&model, SolverOptions::default()).unwrap();
    let mut state = solver.design_state(1.0);
    let step = solver.equilibrium(&mut state).unwrap();
    let report = model.elements()[0].report(&Pose::IDENTITY, &step.poses[body.0], 1.0);
    let q = Vector6::new(
        report.deflection.x,
        report.deflection.y,
        report.deflection.z,
        report.rotation.x,
        report.rotation.y,
        report.rotation.z,
    );
    let local = frame.transpose() * force;
    let expected = k.try_inverse().unwrap() * Vector6::new(local.x, local.y, local.z, 0.0, 0.0, 0.0);
    let error = (q - expected).amax() / expected.amax();
    // Second order in a deflection of micrometres and a rotation of 24 µrad: measured 3.7e-12 relative.
    assert!(error < 3e-10, "{error:e}: {q:?} against {expected:?}");
    // The coupling matters: the diagonal alone would leave the rotation at zero; here it is the largest.
    assert!(expected.fixed_rows::<3>(3).amax() >= expected.amax());
}

#[test]
fn a_field_is_its_own_item_of_the_build_map() {
    use elastokin_suspensions::{BuildMap, Rig, Side};
    let mut file = macpherson_general();
    as_field(&mut file, 0.2);
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap();
    let map = BuildMap::of(general(&mut file), &corner.model, &[(Side::Left, "")]);
    let item = map.find("fields[0]").next().expect("the field's entry is mapped");
    assert_eq!(item.name, "lower arm front bushing");
    assert_eq!(item.elements.len(), 1);
    assert_eq!(corner.model.elements()[item.elements[0].0].name(), "lower arm front bushing");
    assert!(map.find("bushings[0]").all(|b| b.name != "lower arm front bushing"));
}

#[test]
fn a_field_matrix_no_elastic_element_has_is_refused_by_its_key() {
    let mut file = macpherson_general();
    as_field(&mut file, 0.0);
    general(&mut file).fields[0].stiffness[0][4] = 1.0;
    let e =
        file.suspension.build(elastokin_suspensions::Side::Left, elastokin_suspensions::Rig::WheelTravel).unwrap_err();
    let said = e.to_string();
    assert!(said.contains("fields[0] (lower arm front bushing).stiffness") && said.contains("not symmetric"), "{said}");
}

/// A bushing's or a field's y axis that leans along its x axis gives no frame: refused by the entry's key and
/// name, saying why, in the left corner's build and the right's.
#[test]
fn a_frame_whose_y_axis_leans_along_its_x_axis_is_refused_by_its_key() {
    use elastokin_suspensions::description::Axis;
    use elastokin_suspensions::{Rig, Side};
    let parallel = |axis: &mut Option<Axis>, y: &mut Option<Axis>| {
        *axis = Some(Axis::Vector(Vec3::new(0.3, 1.0, 0.0)));
        *y = Some(Axis::Vector(Vec3::new(-0.6, -2.0, 0.0)));
    };
    let mut file = macpherson_general();
    let g = general(&mut file);
    let k = g.bushings.iter().position(|b| b.name == "lower arm front bushing").unwrap();
    let b = &mut g.bushings[k];
    parallel(&mut b.axis, &mut b.y_axis);
    for side in [Side::Left, Side::Right] {
        let said = file.suspension.build(side, Rig::WheelTravel).unwrap_err().to_string();
        let key = format!("bushings[{k}] (lower arm front bushing)");
        assert!(said.contains(&key) && said.contains("y_axis is parallel to the bushing's axis"), "{said}");
    }
    let mut file = macpherson_general();
    as_field(&mut file, 0.0);
    let f = &mut general(&mut file).fields[0];
    parallel(&mut f.axis, &mut f.y_axis);
    let said = file.suspension.build(Side::Left, Rig::WheelTravel).unwrap_err().to_string();
    assert!(said.contains("fields[0]") && said.contains("y_axis is parallel"), "{said}");
}
