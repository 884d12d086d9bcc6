//! Designs compared: the figures side by side are each model's own figures and their differences, each
//! overlaid curve is the model's own curve, a measured file's points are drawn as given, and what cannot
//! be compared is refused by name.

use elastokin_suspensions::compare::{compare, CompareError, Design};
use elastokin_suspensions::design::targets::read_measured;
use elastokin_suspensions::kc::{self, Analysis, AnalysisReport, Cell, KcReport, Settings};
use elastokin_suspensions::SuspensionFile;
use std::path::Path;

fn example(name: &str) -> SuspensionFile {
    SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)).unwrap()
}

fn suite(file: &SuspensionFile, which: &[Analysis]) -> KcReport {
    kc::run_suite(file, which, &Settings { steps: 8, ..Settings::default() }, |_| {})
}

fn number(c: &Cell) -> Option<f64> {
    c.number()
}

#[test]
fn figures_side_by_side_are_each_models_own_and_their_differences() {
    let (a, b) = (example("macpherson.json"), example("double_wishbone.json"));
    let (ra, rb) = (suite(&a, &[]), suite(&b, &[]));
    let c = compare(&[Design::model(&a, ra.clone()), Design::model(&b, rb.clone())]).unwrap();
    assert_eq!(c.names, [a.name.clone(), b.name.clone()]);
    let table = c.table();
    assert_eq!(table.rows.len(), c.figures.len());
    let col = |name: &str| table.columns.iter().position(|x| x == name).unwrap();
    let (va, vb) = (col(&a.name), col(&b.name));
    let diff = col(&format!("{} − {}", b.name, a.name));
    let (mut checked, mut worst) = (0, 0.0f64);
    for row in &table.rows {
        let (Cell::Text(analysis), Cell::Text(key)) = (&row[0], &row[1]) else { panic!("{row:?}") };
        // Written as each report writes it: the figure in SI times its unit's factor.
        let of = |r: &KcReport| {
            let a = r.analyses.iter().find(|x| x.analysis.name() == analysis.as_str())?;
            a.figure(key)?.written(a.units).value
        };
        assert_eq!(number(&row[va]), of(&ra), "{analysis} {key}");
        assert_eq!(number(&row[vb]), of(&rb), "{analysis} {key}");
        if let (Some(x), Some(y)) = (of(&ra), of(&rb)) {
            // Taken in SI, then written: the written values' difference to rounding (measured 2.6e-16
            // relative).
            let d = number(&row[diff]).unwrap();
            worst = worst.max((d - (y - x)).abs() / x.abs().max(y.abs()));
            checked += 1;
        }
    }
    assert!(worst < 1e-14, "{worst:e}");
    assert!(checked > 40, "{checked} differences");
    // Every curve of every chart of an analysis both ran is overlaid: one chart per curve, one curve per
    // model, each the model's (the MacPherson's wheel envelope, of its packaging, has no counterpart).
    let both = |x: &&AnalysisReport| rb.analyses.iter().any(|y| y.analysis == x.analysis);
    assert!(ra.analyses.iter().any(|x| !both(&x)));
    let curves: usize = ra
        .analyses
        .iter()
        .filter(both)
        .flat_map(|x| &x.charts)
        .map(|ch| ch.left.series.len() + ch.right.as_ref().map_or(0, |r| r.series.len()))
        .sum();
    assert_eq!(c.charts.len(), curves);
    let toe = c.charts.iter().find(|ch| ch.name == "compare_parallel_travel_toe_camber_toe_in").unwrap();
    let own = |r: &KcReport| {
        r.analyses[0].charts.iter().find(|ch| ch.name == "parallel_travel_toe_camber").unwrap().left.series[0].clone()
    };
    assert_eq!(toe.left.series.len(), 2);
    assert_eq!(toe.left.series[0].points, own(&ra).points);
    assert_eq!(toe.left.series[1].points, own(&rb).points);
    assert_eq!(toe.left.series[1].name, b.name);
}

#[test]
fn a_model_against_itself_differs_by_nothing_and_its_repeated_name_is_numbered() {
    let a = example("macpherson.json");
    let r = suite(&a, &[Analysis::ParallelTravel]);
    let c = compare(&[Design::model(&a, r.clone()), Design::model(&a, r)]).unwrap();
    assert_eq!(c.names[1], format!("{} (2)", a.name));
    let table = c.table();
    let diff = table.columns.len() - 1;
    let zeros = table.rows.iter().filter_map(|row| number(&row[diff])).filter(|d| *d == 0.0).count();
    let values = table.rows.iter().filter(|row| number(&row[3]).is_some()).count();
    assert_eq!(zeros, values);
}

#[test]
fn a_measured_file_is_drawn_as_given_beside_the_models_rows() {
    let a = example("macpherson.json");
    let r = suite(&a, &[Analysis::ParallelTravel]);
    let text = "# analysis: parallel-travel\n# a rig's wheel held by the hub\ntravel_m,toe_deg\n\
                -0.05,0.8\n0.0,0.0\n0.05,-0.9\n";
    let measured = read_measured(text, "rig.csv").unwrap();
    let designs = [Design::model(&a, r.clone()), Design::Measured { name: "rig.csv".into(), measured }];
    let c = compare(&designs).unwrap();
    let chart = c.charts.iter().find(|ch| ch.name.starts_with("compare_measured_")).unwrap();
    assert_eq!(chart.left.series.len(), 2);
    assert_eq!(chart.left.series[1].points, vec![(-0.05, 0.8), (0.0, 0.0), (0.05, -0.9)]);
    let table = &r.analyses[0].table;
    assert_eq!(chart.left.series[0].points.len(), table.rows.len());
    assert_eq!(c.charts.iter().filter(|ch| ch.name.starts_with("compare_measured_")).count(), 1);

    let refused = |text: &str| {
        let measured = read_measured(text, "rig.csv").unwrap();
        compare(&[Design::model(&a, r.clone()), Design::Measured { name: "rig.csv".into(), measured }]).unwrap_err()
    };
    let e = refused("# analysis: parallel-travel\ntravel_m,spring_rate\n0,1\n");
    assert!(matches!(&e, CompareError::UnknownColumn { column, .. } if column == "spring_rate"), "{e:?}");
    let e = e.to_string();
    assert!(e.contains("no column 'spring_rate'") && e.contains("toe_deg"), "{e}");
    let e = refused("# analysis: parallel-travel\nload_n,toe_deg\n0,1\n");
    assert!(
        matches!(&e, CompareError::FirstColumn { first, parameter, .. } if first == "load_n" && parameter == "travel_m")
    );
    let e = e.to_string();
    assert!(e.contains("'load_n'") && e.contains("'travel_m'"), "{e}");
    let e = refused("# analysis: roll\nleft_travel_m,roll_angle_deg\n0,1\n");
    assert!(matches!(&e, CompareError::AnalysisNotRun { analysis, .. } if analysis == "roll"), "{e:?}");
    assert!(e.to_string().contains("roll, which no model ran"), "{e}");
    let e = refused("travel_m,toe_deg\n0,1\n");
    assert_eq!(e, CompareError::NoAnalysisNamed { name: "rig.csv".into() });
    assert!(e.to_string().contains("# analysis: NAME"), "{e}");
}

/// A measured column the analysis's table lacks, beside one it has, was left out of the comparison
/// unseen; a column named twice, unnamed, or with a NUL in its name was read as given. Each is refused,
/// naming the column.
#[test]
fn a_measured_column_that_is_unknown_duplicated_or_not_plain_text_is_refused_by_name() {
    let a = example("macpherson.json");
    let r = suite(&a, &[Analysis::ParallelTravel]);
    let measured = read_measured("# analysis: parallel-travel\ntravel_m,toe_deg,toe_dge\n0,0,0\n", "rig.csv").unwrap();
    let e = compare(&[Design::model(&a, r), Design::Measured { name: "rig.csv".into(), measured }]).unwrap_err();
    assert!(matches!(&e, CompareError::UnknownColumn { column, .. } if column == "toe_dge"), "{e:?}");
    let e = e.to_string();
    assert!(e.contains("no column 'toe_dge'") && e.contains("camber_deg"), "{e}");
    for (header, says) in [
        ("travel_m,toe_deg,toe_deg", "rig.csv:2: the column 'toe_deg' is named twice"),
        ("travel_m,,toe_deg", "rig.csv:2: column 2 has no name"),
        ("travel_m,toe\0_deg", "rig.csv:2: the name of column 2 holds a control character (toe\\u{0}_deg)"),
    ] {
        let e = read_measured(&format!("# analysis: parallel-travel\n{header}\n0,0,0\n"), "rig.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains(says), "{header:?}: {e}");
    }
}

#[test]
fn what_cannot_be_compared_is_refused_by_name() {
    let (a, axle) = (example("macpherson.json"), example("four_link_axle.json"));
    let ra = suite(&a, &[Analysis::ParallelTravel]);
    let e = compare(&[Design::model(&a, ra.clone())]).unwrap_err();
    assert_eq!(e, CompareError::TooFew);
    assert!(e.to_string().contains("two designs at least"), "{e}");
    let e = compare(&[Design::model(&a, ra.clone()), Design::model(&axle, suite(&axle, &[Analysis::ParallelTravel]))])
        .unwrap_err();
    assert!(matches!(&e, CompareError::MixedKinds { first_solid: false, .. }), "{e:?}");
    let e = e.to_string();
    assert!(e.contains(&a.name) && e.contains(&axle.name) && e.contains("solid axle"), "{e}");
    let m = || read_measured("# analysis: parallel-travel\ntravel_m,toe_deg\n0,1\n", "rig.csv").unwrap();
    let e = compare(&[
        Design::Measured { name: "one.csv".into(), measured: m() },
        Design::Measured { name: "two.csv".into(), measured: m() },
    ])
    .unwrap_err();
    assert_eq!(e, CompareError::NoModel);
    assert!(e.to_string().contains("a model among the designs"), "{e}");
    let rb = suite(&example("double_wishbone.json"), &[Analysis::Roll]);
    let e = compare(&[Design::model(&a, ra), Design::model(&example("double_wishbone.json"), rb)]).unwrap_err();
    assert_eq!(e, CompareError::NothingInCommon { first: a.name.clone() });
    assert!(e.to_string().contains("no analysis in common"), "{e}");
}

/// A measured row shorter than its header: `MeasuredError::RowLength`, naming the file, the line and both
/// counts.
#[test]
fn a_measured_row_shorter_than_its_header_is_refused_by_its_line() {
    use elastokin_suspensions::design::targets::MeasuredError;
    let e = read_measured("# analysis: parallel-travel\ntravel_m,toe_deg,camber_deg\n0,0,0\n0.01,0.1\n", "rig.csv")
        .unwrap_err();
    assert!(matches!(e, MeasuredError::RowLength { line: 4, .. }), "{e:?}");
    assert_eq!(e.to_string(), "rig.csv:4: 2 values where the header names 3 columns");
}
