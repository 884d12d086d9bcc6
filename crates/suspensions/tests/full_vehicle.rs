//! The whole car's budget: each term against a hand calculation of a simple car (the formulas of
//! docs/vehicle.md written out with its numbers), the roll moment balanced by the load transfer, a car
//! whose axles are alike front and rear balanced to zero, and what cannot be a car refused by key.

use elastokin_suspensions::full_vehicle::{
    budget, run_vehicle, AxleCharacteristics, AxleName, Car, CarError, Tyre, VehicleFile, VehicleFileError,
};
use elastokin_suspensions::kc::Settings;
use elastokin_suspensions::SuspensionFile;
use std::path::Path;

const G: f64 = 9.80665;

fn car() -> Car {
    Car { mass: 1000.0, cg_height: 0.5, wheelbase: 2.5, front_weight_share: 0.6, steering_ratio: 16.0 }
}

fn tyre(c: f64) -> Tyre {
    Tyre { cornering_stiffness: c, camber_stiffness: 0.1 * c, vertical_rate: 200_000.0, pneumatic_trail: 0.03 }
}

fn axle(rc: f64, roll_steer: f64, roll_camber: f64) -> AxleCharacteristics {
    AxleCharacteristics {
        roll_stiffness: 60_000.0,
        roll_centre_height: rc,
        track: 1.5,
        roll_steer,
        roll_camber,
        // 0.2 and 0.1 deg/kN, −0.3 deg/kN·m, held in SI.
        lateral_steer: 0.2e-3_f64.to_radians(),
        lateral_camber: 0.1e-3_f64.to_radians(),
        aligning_torque_steer: -0.3e-3_f64.to_radians(),
    }
}

fn term(b: &elastokin_suspensions::full_vehicle::Budget, effect: &str, axle: AxleName) -> f64 {
    b.contributions.iter().find(|c| c.effect == effect && c.axle == axle).unwrap().value
}

#[test]
fn every_term_is_the_hand_calculation_of_a_simple_car() {
    let (front, rear) = (axle(0.05, -0.10, -0.70), axle(0.10, 0.05, -0.80));
    let b = budget(&car(), [tyre(1000.0), tyre(1200.0)], &front, &rear);
    // The car: 9806.65 N, 60 % front: axle loads 5883.99 and 3922.66 N; CG 1.0 m behind the front axle.
    let w = 1000.0 * G;
    let (wf, wr) = (0.6 * w, 0.4 * w);
    // Roll stiffness with the tyres in series: 200 kN/m × 1.5² / 2 = 225 000 N·m/rad against 60 000.
    let k: f64 = 60_000.0 * 225_000.0 / 285_000.0;
    assert!((b.roll_stiffness[0] - k.to_radians()).abs() < 1e-9 * k);
    // Roll axis under the CG: 0.05 + 0.05 × 1.0 / 2.5 = 0.07 m; the CG 0.43 m above it.
    let h1 = 0.5 - 0.07;
    assert!((b.cg_above_roll_axis - h1).abs() < 1e-15);
    let phi = (w * h1 / (2.0 * k - w * h1)).to_degrees();
    assert!((b.roll_gradient - phi).abs() < 1e-12 * phi, "{} against {phi}", b.roll_gradient);
    // Each term, deg/g (tyres per axle: two of them).
    let hand = [
        ("tyre", AxleName::Front, wf / 2000.0),
        ("tyre", AxleName::Rear, -wr / 2400.0),
        ("roll steer", AxleName::Front, -0.10 * phi),
        ("roll steer", AxleName::Rear, -0.05 * phi),
        ("roll camber", AxleName::Front, -0.1 * -0.70 * phi),
        ("roll camber", AxleName::Rear, 0.1 * -0.80 * phi),
        ("lateral-force compliance steer", AxleName::Front, -0.2e-3 * wf / 2.0),
        ("lateral-force compliance steer", AxleName::Rear, 0.2e-3 * wr / 2.0),
        ("lateral-force compliance camber", AxleName::Front, 0.1 * 0.1e-3 * wf / 2.0),
        ("lateral-force compliance camber", AxleName::Rear, -0.1 * 0.1e-3 * wr / 2.0),
        ("aligning-torque compliance steer", AxleName::Front, 0.3e-3 * 0.03 * wf / 2.0),
        ("aligning-torque compliance steer", AxleName::Rear, -0.3e-3 * 0.03 * wr / 2.0),
    ];
    let mut sum = 0.0;
    for (effect, axle, expected) in hand {
        let got = term(&b, effect, axle);
        assert!(
            (got - expected).abs() <= 1e-12 * expected.abs().max(1e-3),
            "{effect} {axle:?}: {got} against {expected}"
        );
        sum += expected;
    }
    assert_eq!(b.contributions.len(), hand.len());
    assert!((b.understeer_gradient - sum).abs() < 1e-12);
    assert!((b.steering_wheel_gradient - 16.0 * sum).abs() < 1e-11);
    // Characteristic speed: √(L g / K), K in rad/g.
    let vch = (2.5 * G / sum.to_radians()).sqrt() * 3.6;
    assert!((b.characteristic_speed.unwrap() - vch).abs() < 1e-9 * vch);
}

#[test]
fn the_load_transfer_balances_the_rolling_moment() {
    let (front, rear) =
        (axle(0.03, 0.0, 0.0), AxleCharacteristics { track: 1.6, roll_stiffness: 30_000.0, ..axle(0.12, 0.0, 0.0) });
    let c = car();
    let b = budget(&c, [tyre(1000.0), tyre(1000.0)], &front, &rear);
    // Per g: the weight's lateral force at the CG and its lever as the body rolls, against the wheels'
    // vertical force differences across each track.
    let w = c.mass * G;
    let moment = w * (c.cg_height + b.cg_above_roll_axis * b.roll_gradient.to_radians());
    let held = b.load_transfer[0] * 1.5 + b.load_transfer[1] * 1.6;
    assert!((held - moment).abs() < 1e-12 * moment, "{held} against {moment}");
    assert!(
        (b.load_transfer_front_share - b.load_transfer[0] / (b.load_transfer[0] + b.load_transfer[1])).abs() < 1e-15
    );
}

#[test]
fn a_car_alike_front_and_rear_is_neutral() {
    let a = axle(0.08, 0.07, -0.6);
    let c = Car { front_weight_share: 0.5, ..car() };
    let b = budget(&c, [tyre(1100.0), tyre(1100.0)], &a, &a);
    assert!(b.understeer_gradient.abs() < 1e-12, "{}", b.understeer_gradient);
    assert!((b.roll_stiffness_front_share - 0.5).abs() < 1e-15 && (b.load_transfer_front_share - 0.5).abs() < 1e-15);
    assert_eq!(b.characteristic_speed, None);
}

fn example(name: &str) -> SuspensionFile {
    SuspensionFile::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)).unwrap()
}

fn vehicle_file(front: &str, rear: &str) -> VehicleFile {
    let text = format!(
        r#"{{ "name": "test car", "front": "{front}", "rear": "{rear}",
             "car": {{ "mass": 1400, "cg_height": 0.55, "wheelbase": 2.6, "front_weight_share": 0.6, "steering_ratio": 15 }},
             "tyres": {{ "cornering_stiffness": 1300, "camber_stiffness": 100, "vertical_rate": 250000, "pneumatic_trail": 0.03 }} }}"#
    );
    VehicleFile::from_json(&text, "car.json").unwrap()
}

#[test]
fn a_car_of_the_shipped_axles_runs_and_what_is_no_car_is_refused_by_key() {
    let s = Settings { steps: 8, ..Settings::default() };
    let (mac, five) = (example("macpherson.json"), example("five_link.json"));
    let r = run_vehicle(&vehicle_file("macpherson.json", "five_link.json"), &mac, &five, &s).unwrap();
    assert!(r.budget.understeer_gradient.is_finite() && r.budget.roll_gradient > 0.0);
    assert_eq!(r.budget.contributions.len(), 12);
    assert_eq!(r.table().rows.len(), 12 + 10 + usize::from(r.budget.characteristic_speed.is_some()));
    // The rear as the front: its model says rear, and it does not steer.
    let e = run_vehicle(&vehicle_file("five_link.json", "macpherson.json"), &five, &mac, &s).unwrap_err();
    assert!(matches!(&e, CarError::AxleSaysOther { key: "front", said: "rear", .. }), "{e:?}");
    assert!(e.to_string().contains("`front`") && e.to_string().contains("vehicle.axle"), "{e}");
    let e = run_vehicle(&vehicle_file("macpherson.json", "macpherson.json"), &mac, &mac, &s).unwrap_err();
    assert_eq!(e, CarError::SameModel { model: "macpherson.json".into() });
    assert!(e.to_string().starts_with("`front` and `rear` are both macpherson.json"), "{e}");
    let (mut unsteered, mut rear) = (five.clone(), mac.clone());
    unsteered.vehicle = None;
    rear.vehicle = None;
    let e = run_vehicle(&vehicle_file("five_link.json", "macpherson.json"), &unsteered, &rear, &s).unwrap_err();
    assert!(matches!(&e, CarError::FrontDoesNotSteer { model } if *model == five.name), "{e:?}");
    assert!(e.to_string().contains("does not steer"), "{e}");
    let mut steered_rear = five.clone();
    if let Some(v) = &mut steered_rear.vehicle {
        v.rack_travel_per_revolution = Some(0.05);
    }
    let e = run_vehicle(&vehicle_file("macpherson.json", "five_link.json"), &mac, &steered_rear, &s).unwrap_err();
    assert!(matches!(&e, CarError::RearSteers { .. }), "{e:?}");
    assert!(e.to_string().contains("`rear`") && e.to_string().contains("rack_travel_per_revolution"), "{e}");
    for (text, key, got) in [
        (r#""mass": 1400"#, r#""mass": -1"#, -1.0),
        (r#""front_weight_share": 0.6"#, r#""front_weight_share": 1.0"#, 1.0),
        (r#""pneumatic_trail": 0.03"#, r#""pneumatic_trail": 2"#, 2.0),
    ] {
        let good = r#"{ "name": "c", "front": "a", "rear": "b",
             "car": { "mass": 1400, "cg_height": 0.55, "wheelbase": 2.6, "front_weight_share": 0.6, "steering_ratio": 15 },
             "tyres": { "cornering_stiffness": 1300, "camber_stiffness": 100, "vertical_rate": 250000, "pneumatic_trail": 0.03 } }"#;
        let e = VehicleFile::from_json(&good.replace(text, key), "car.json").unwrap_err();
        let name = key.split('"').nth(1).unwrap();
        let VehicleFileError::OutOfRange { key, got: given, .. } = &e else { panic!("{e:?}") };
        assert!(key.ends_with(name) && *given == got, "{e:?}");
        assert!(e.to_string().starts_with(&format!("car.json: `{key}` must lie ")), "{e}");
    }
}

/// The budget is the car's, whatever units the caller shows its K&C reports in: under every `Units`
/// choice the same to the bit (`DegPer10Mm` scaled the aligning-torque compliance steer it read by 0.1).
#[test]
fn the_budget_is_the_same_to_the_bit_under_every_units_choice() {
    let (mac, five) = (example("macpherson.json"), example("five_link.json"));
    let car = vehicle_file("macpherson.json", "five_link.json");
    let run = |units| run_vehicle(&car, &mac, &five, &Settings { steps: 8, units, ..Settings::default() }).unwrap();
    let base = run(elastokin_suspensions::kc::Units::DegPerM);
    for (units, name) in elastokin_suspensions::kc::Units::ALL {
        assert_eq!(run(units), base, "{name}");
    }
}
