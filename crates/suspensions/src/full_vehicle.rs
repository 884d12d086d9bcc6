//! The whole car from its two axles' K&C results: roll stiffness of each axle and its distribution, roll
//! gradient, lateral load-transfer distribution, and the understeer budget — how many degrees of steer per
//! g of lateral acceleration each effect asks for (the tyres, roll steer, roll camber, lateral-force
//! compliance steer and camber, aligning-torque compliance steer), per axle. `docs/vehicle.md` derives
//! every formula; [`budget`] is them, from an [`AxleCharacteristics`] of each axle read off its K&C
//! report ([`AxleCharacteristics::from_reports`]).
//!
//! Signs: ISO 8855. A left turn has `a_y > 0`; the body rolls out of it (`φ > 0`, left side up); an
//! axle's steer `δ` is positive to the left. The understeer gradient `K` is the steer the driver adds per g
//! beyond the kinematic `L/R` (`δ = L/R + K·a_y`): a positive contribution is understeer.

use crate::kc::{figures, plain, Analysis, AnalysisError, AnalysisReport, FigureKind, NoFigure};
use serde::{Deserialize, Serialize};

/// Standard gravity (m/s²): lateral acceleration is counted in g.
pub const G: f64 = 9.80665;

/// A tyre as the budget needs it (per tyre, SI but the stiffnesses per degree, as tyre data sheets give
/// them).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tyre {
    /// Cornering stiffness `C_α` (N/deg): lateral force per degree of slip at the axle's load.
    pub cornering_stiffness: f64,
    /// Camber stiffness `C_γ` (N/deg): lateral force per degree of inclination toward the force.
    pub camber_stiffness: f64,
    /// Vertical rate (N/m), in series with the suspension's roll stiffness.
    pub vertical_rate: f64,
    /// Pneumatic trail (m): the lateral force acts this far behind the contact patch, making the aligning
    /// torque.
    pub pneumatic_trail: f64,
}

/// The car around the two axles (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Car {
    /// Mass (kg).
    pub mass: f64,
    /// Height of the centre of gravity above the ground (m).
    pub cg_height: f64,
    /// Wheelbase (m).
    pub wheelbase: f64,
    /// Share of the weight on the front axle, 0 to 1.
    pub front_weight_share: f64,
    /// Steering ratio: hand-wheel angle per road-wheel angle.
    pub steering_ratio: f64,
}

/// A vehicle file: the two axles' model files (paths relative to the vehicle file), the car and its
/// tyres (the same front and rear unless `rear_tyres` is given).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleFile {
    /// What the car is.
    pub name: String,
    /// The front axle's model file.
    pub front: String,
    /// The rear axle's model file.
    pub rear: String,
    /// The car.
    pub car: Car,
    /// The tyres (front, and rear unless `rear_tyres` says otherwise).
    pub tyres: Tyre,
    /// Other tyres on the rear axle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rear_tyres: Option<Tyre>,
}

impl VehicleFile {
    /// Reads a vehicle file's text; `origin` names it in errors. Every value out of range is refused by
    /// its key with the range.
    pub fn from_json(text: &str, origin: &str) -> Result<VehicleFile, VehicleFileError> {
        let file: VehicleFile = serde_json::from_str(text)
            .map_err(|error| VehicleFileError::Json { origin: origin.to_string(), error: error.to_string() })?;
        let c = &file.car;
        let mut checks: Vec<(String, f64, f64, f64, &str)> = vec![
            ("car.mass".into(), c.mass, 1.0, 1e6, "kg"),
            ("car.cg_height".into(), c.cg_height, 1e-3, 20.0, "m"),
            ("car.wheelbase".into(), c.wheelbase, 0.1, 50.0, "m"),
            ("car.front_weight_share".into(), c.front_weight_share, 0.0, 1.0, "(a share)"),
            ("car.steering_ratio".into(), c.steering_ratio, 1.0, 100.0, "(hand wheel : road wheel)"),
        ];
        for (key, t) in [("tyres", Some(file.tyres)), ("rear_tyres", file.rear_tyres)] {
            let Some(t) = t else { continue };
            checks.extend([
                (format!("{key}.cornering_stiffness"), t.cornering_stiffness, 1.0, 1e6, "N/deg"),
                (format!("{key}.camber_stiffness"), t.camber_stiffness, 0.0, 1e6, "N/deg"),
                (format!("{key}.vertical_rate"), t.vertical_rate, 1e3, 1e10, "N/m"),
                (format!("{key}.pneumatic_trail"), t.pneumatic_trail, 0.0, 0.5, "m"),
            ]);
        }
        for (key, v, lo, hi, unit) in checks {
            let open_low = key.ends_with("front_weight_share");
            let inside = if open_low { v > lo && v < hi } else { v >= lo && v <= hi };
            if !(v.is_finite() && inside) {
                let range = Range { low: lo, high: hi, open: open_low, unit };
                return Err(VehicleFileError::OutOfRange { origin: origin.to_string(), key, range, got: v });
            }
        }
        Ok(file)
    }

    /// The rear tyres.
    pub fn rear_tyres(&self) -> Tyre {
        self.rear_tyres.unwrap_or(self.tyres)
    }
}

/// Why a vehicle file is not read ([`VehicleFile::from_json`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VehicleFileError {
    /// The text is no vehicle file: bad JSON, a key missing, unknown or of the wrong type.
    #[error("{origin}: {error}")]
    Json {
        /// The file.
        origin: String,
        /// What the JSON reader says, with its line and column.
        error: String,
    },
    /// A value outside its range.
    #[error("{origin}: `{key}` must lie {range}, got {}", plain(*got))]
    OutOfRange {
        /// The file.
        origin: String,
        /// The key, as the file writes it (`car.mass`).
        key: String,
        /// Its range.
        range: Range,
        /// The value given.
        got: f64,
    },
}

/// The range a vehicle file's value must lie in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Its low end.
    pub low: f64,
    /// Its high end.
    pub high: f64,
    /// Whether both ends are excluded (a share strictly between 0 and 1), else both are included.
    pub open: bool,
    /// The unit, or what the number is.
    pub unit: &'static str,
}

impl std::fmt::Display for Range {
    /// `from 1 to 1000000 kg`, `between 0 and 1 (a share)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (a, b) = if self.open { ("between", "and") } else { ("from", "to") };
        write!(f, "{a} {} {b} {} {}", plain(self.low), plain(self.high), self.unit)
    }
}

/// Why an axle's K&C reports give no characteristics for the budget ([`AxleCharacteristics::from_reports`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AxleError {
    /// A figure the budget reads has no value.
    #[error("{axle}: {figure}")]
    Figure {
        /// The axle, as the vehicle file names it and its model.
        axle: String,
        /// Which figure, and why.
        figure: NoFigure,
    },
    /// The wheels stand nowhere apart.
    #[error("{axle}: its track at design is {track:.4} m: an axle's wheels stand apart")]
    NoTrack {
        /// The axle.
        axle: String,
        /// Its track at design, m.
        track: f64,
    },
    /// The axle does not resist roll.
    #[error("{axle}: its roll stiffness is {stiffness:e} N·m/rad: the axle does not resist roll")]
    NoRollStiffness {
        /// The axle.
        axle: String,
        /// Its roll stiffness, N·m/rad.
        stiffness: f64,
    },
}

/// Why two models make no car ([`check_axles`], [`run_vehicle`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CarError {
    /// One model file for both ends.
    #[error("`front` and `rear` are both {model}: give each axle its own model file")]
    SameModel {
        /// The model file named twice.
        model: String,
    },
    /// A model whose own `vehicle.axle` names the other end.
    #[error("`{key}` ({model}): its own `vehicle.axle` says {said}: swap `front` and `rear`, or correct the model")]
    AxleSaysOther {
        /// `front` or `rear`: where the vehicle file puts it.
        key: &'static str,
        /// The model's name.
        model: String,
        /// Where the model says it belongs.
        said: &'static str,
    },
    /// A front axle that does not steer.
    #[error("`front` ({model}): it has no tie rod or steering link, so it does not steer: the front axle steers")]
    FrontDoesNotSteer {
        /// The model's name.
        model: String,
    },
    /// A rear axle with a steering gear.
    #[error(
        "`rear` ({model}): it has a steering gear (`vehicle.rack_travel_per_revolution`): the rear axle does not \
         steer here; remove it from the rear model"
    )]
    RearSteers {
        /// The model's name.
        model: String,
    },
    /// An axle's analysis failed.
    #[error("`{key}` ({model}): {error}")]
    Analysis {
        /// `front` or `rear`.
        key: &'static str,
        /// The model's name.
        model: String,
        /// What stopped it.
        error: AnalysisError,
    },
    /// An axle's reports give no characteristics.
    #[error(transparent)]
    Axle(#[from] AxleError),
}

/// What the budget needs of one axle, read off its K&C figures (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxleCharacteristics {
    /// Roll stiffness of the suspension (springs, bushings, bars), tyres not included (N·m/rad).
    pub roll_stiffness: f64,
    /// Roll centre height at design (m).
    pub roll_centre_height: f64,
    /// Track at design (m).
    pub track: f64,
    /// Roll steer: the left wheel's toe-in per roll angle (rad/rad).
    pub roll_steer: f64,
    /// Roll camber: the left wheel's camber to the ground per roll angle (rad/rad).
    pub roll_camber: f64,
    /// Lateral-force compliance steer: toe-in per inboard force at the patch (rad/N).
    pub lateral_steer: f64,
    /// Lateral-force compliance camber: camber per inboard force at the patch (rad/N).
    pub lateral_camber: f64,
    /// Aligning-torque compliance steer: toe-in per torque about the vertical (rad/(N·m)).
    pub aligning_torque_steer: f64,
}

impl AxleCharacteristics {
    /// An axle's characteristics from its roll and parallel-travel reports; `axle` names it in errors
    /// (a figure the reports do not have is refused by its key, with the report's reason).
    pub fn from_reports(axle: &str, roll: &AnalysisReport, travel: &AnalysisReport) -> Result<Self, AxleError> {
        let value = |r: &AnalysisReport, kind: &FigureKind| {
            r.value_of(kind).map_err(|figure| AxleError::Figure { axle: axle.to_string(), figure })
        };
        let a = AxleCharacteristics {
            roll_stiffness: value(roll, &figures::ROLL_STIFFNESS)?,
            roll_centre_height: value(roll, &figures::ROLL_CENTRE_HEIGHT)?,
            track: value(roll, &figures::TRACK)?,
            roll_steer: value(roll, &figures::ROLL_STEER)?,
            roll_camber: value(roll, &figures::ROLL_CAMBER)?,
            lateral_steer: value(travel, &figures::LATERAL_STEER)?,
            lateral_camber: value(travel, &figures::LATERAL_CAMBER)?,
            aligning_torque_steer: value(travel, &figures::ALIGNING_TORQUE_STEER)?,
        };
        if !(a.track.is_finite() && a.track > 0.0) {
            return Err(AxleError::NoTrack { axle: axle.to_string(), track: a.track });
        }
        if !(a.roll_stiffness.is_finite() && a.roll_stiffness > 0.0) {
            return Err(AxleError::NoRollStiffness { axle: axle.to_string(), stiffness: a.roll_stiffness });
        }
        Ok(a)
    }
}

/// Front or rear.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AxleName {
    /// The front axle.
    Front,
    /// The rear axle.
    Rear,
}

impl AxleName {
    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            AxleName::Front => "front",
            AxleName::Rear => "rear",
        }
    }
}

/// One term of the understeer budget.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Contribution {
    /// Which effect (`tyre`, `roll steer`, …).
    pub effect: &'static str,
    /// Which axle.
    pub axle: AxleName,
    /// Its share of the understeer gradient (deg/g; positive: understeer).
    pub value: f64,
}

/// The whole car's static characteristics.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Budget {
    /// Each axle's roll stiffness with its tyres in series (N·m/deg): front, rear.
    pub roll_stiffness: [f64; 2],
    /// The front axle's share of the roll stiffness (0 to 1).
    pub roll_stiffness_front_share: f64,
    /// Height of the CG above the roll axis (m).
    pub cg_above_roll_axis: f64,
    /// Roll gradient (deg/g; the body rolls out of the turn).
    pub roll_gradient: f64,
    /// Lateral load transfer of each axle per g (N): front, rear.
    pub load_transfer: [f64; 2],
    /// The front axle's share of the lateral load transfer (0 to 1).
    pub load_transfer_front_share: f64,
    /// The understeer budget, term by term.
    pub contributions: Vec<Contribution>,
    /// The understeer gradient: the sum (deg/g of road-wheel steer).
    pub understeer_gradient: f64,
    /// The same at the steering wheel (deg/g).
    pub steering_wheel_gradient: f64,
    /// The characteristic speed (km/h) of an understeering car, `√(L g / K)`; `None` for a neutral or
    /// oversteering one (`K` at most [`NEUTRAL`]).
    pub characteristic_speed: Option<f64>,
}

/// The budget of `car` on `tyres` (front, rear) with its axles `front` and `rear` (see the module's
/// documentation and `docs/vehicle.md`).
pub fn budget(car: &Car, tyres: [Tyre; 2], front: &AxleCharacteristics, rear: &AxleCharacteristics) -> Budget {
    let weight = car.mass * G;
    let axle_load = [weight * car.front_weight_share, weight * (1.0 - car.front_weight_share)];
    let axles = [front, rear];
    // Each axle's roll stiffness with its two tyres in series: a tyre's rate k at half the track t gives
    // k t²/2 per radian of roll.
    let k = [0, 1].map(|i| {
        let tyre = tyres[i].vertical_rate * axles[i].track.powi(2) / 2.0;
        axles[i].roll_stiffness * tyre / (axles[i].roll_stiffness + tyre)
    });
    let b = car.wheelbase * car.front_weight_share; // CG to the rear axle
    let a = car.wheelbase - b; // CG to the front axle
    let roll_axis = front.roll_centre_height + (rear.roll_centre_height - front.roll_centre_height) * a / car.wheelbase;
    let h1 = car.cg_height - roll_axis;
    // rad per g: the sprung weight's moment about the roll axis, and its own lever as the body rolls.
    let phi = weight * h1 / (k[0] + k[1] - weight * h1);
    let roll_gradient = phi.to_degrees();
    // N per g: each axle's share of the rolling moment through its springs, and its roll centre's share of
    // the lateral force.
    let transfer = [
        weight / front.track * (h1 * k[0] / (k[0] + k[1] - weight * h1) + b / car.wheelbase * front.roll_centre_height),
        weight / rear.track * (h1 * k[1] / (k[0] + k[1] - weight * h1) + a / car.wheelbase * rear.roll_centre_height),
    ];
    let mut contributions = Vec::new();
    for (i, axle) in [AxleName::Front, AxleName::Rear].into_iter().enumerate() {
        let (x, t) = (axles[i], tyres[i]);
        // A front term counts as it is, a rear one with its sign turned: the front's slip adds to the
        // steer asked for, the rear's takes from it.
        let sign = if i == 0 { 1.0 } else { -1.0 };
        let c_alpha = 2.0 * t.cornering_stiffness; // N/deg, the axle's two tyres
        let per_wheel = axle_load[i] / 2.0; // N per g on each tyre
        let camber_ratio = t.camber_stiffness / t.cornering_stiffness;
        let terms = [
            ("tyre", axle_load[i] / c_alpha),
            ("roll steer", x.roll_steer * roll_gradient),
            ("roll camber", -camber_ratio * x.roll_camber * roll_gradient),
            ("lateral-force compliance steer", -x.lateral_steer.to_degrees() * per_wheel),
            ("lateral-force compliance camber", camber_ratio * x.lateral_camber.to_degrees() * per_wheel),
            ("aligning-torque compliance steer", -x.aligning_torque_steer.to_degrees() * t.pneumatic_trail * per_wheel),
        ];
        contributions.extend(terms.map(|(effect, v)| Contribution { effect, axle, value: sign * v }));
    }
    let understeer_gradient: f64 = contributions.iter().map(|c| c.value).sum();
    let characteristic_speed =
        (understeer_gradient > NEUTRAL).then(|| (car.wheelbase * G / understeer_gradient.to_radians()).sqrt() * 3.6);
    Budget {
        roll_stiffness: k.map(f64::to_radians),
        roll_stiffness_front_share: k[0] / (k[0] + k[1]),
        cg_above_roll_axis: h1,
        roll_gradient,
        load_transfer: transfer,
        load_transfer_front_share: transfer[0] / (transfer[0] + transfer[1]),
        understeer_gradient,
        steering_wheel_gradient: understeer_gradient * car.steering_ratio,
        characteristic_speed,
        contributions,
    }
}

/// An understeer gradient at most this (deg/g) is neutral: the sum of terms that cancel leaves rounding.
pub const NEUTRAL: f64 = 1e-9;

/// A vehicle's budget and what it was made from.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleReport {
    /// The vehicle file's name.
    pub name: String,
    /// The axles' characteristics: front, rear.
    pub axles: [AxleCharacteristics; 2],
    /// The budget.
    pub budget: Budget,
    /// What a reader should know (a model's design wheel load far from the car's).
    pub warnings: Vec<String>,
}

/// How far (a share) a model's design wheel load may be from the car's axle load over two before it is
/// said: the K&C figures were taken at the model's own load.
const LOAD_MISMATCH: f64 = 0.1;

/// The budget of the vehicle `file` with its `front` and `rear` models: each axle's roll and parallel
/// travel run with `settings`. Refused by key: a front that does not steer, a rear with a steering gear,
/// a model whose own `vehicle.axle` says the other end, one model for both ends, a track of zero, an
/// analysis that fails.
pub fn run_vehicle(
    file: &VehicleFile,
    front: &crate::file::SuspensionFile,
    rear: &crate::file::SuspensionFile,
    settings: &crate::kc::Settings,
) -> Result<VehicleReport, CarError> {
    check_axles(file, front, rear)?;
    let mut axles = Vec::with_capacity(2);
    let mut warnings = Vec::new();
    let weight = file.car.mass * G;
    for (key, model, share) in
        [("front", front, file.car.front_weight_share), ("rear", rear, 1.0 - file.car.front_weight_share)]
    {
        let models = crate::kc::Models::new(model);
        let run = |a: Analysis| {
            crate::kc::run_on(a, &models, settings).map_err(|error| CarError::Analysis {
                key,
                model: model.name.clone(),
                error,
            })
        };
        let (roll, travel) = (run(Analysis::Roll)?, run(Analysis::ParallelTravel)?);
        axles.push(AxleCharacteristics::from_reports(&format!("`{key}` ({})", model.name), &roll, &travel)?);
        let own = travel.figure_of(&figures::WHEEL_LOAD_AT_DESIGN).and_then(|f| f.value);
        let car = weight * share / 2.0;
        if let Some(own) = own.filter(|own| ((own - car) / car).abs() > LOAD_MISMATCH) {
            warnings.push(format!(
                "{key}: the model carries {own:.0} N per wheel at design, the car {car:.0} N: its K&C figures are \
                 taken at its own load"
            ));
        }
    }
    let axles = [axles[0], axles[1]];
    let budget = budget(&file.car, [file.tyres, file.rear_tyres()], &axles[0], &axles[1]);
    Ok(VehicleReport { name: file.name.clone(), axles, budget, warnings })
}

/// What [`run_vehicle`] refuses before anything runs: `front` and `rear` must be able to be the car's
/// front and rear.
pub fn check_axles(
    file: &VehicleFile,
    front: &crate::file::SuspensionFile,
    rear: &crate::file::SuspensionFile,
) -> Result<(), CarError> {
    use crate::description::vehicle::AxlePosition;
    if file.front == file.rear {
        return Err(CarError::SameModel { model: file.front.clone() });
    }
    for (key, model, other) in [("front", front, AxlePosition::Rear), ("rear", rear, AxlePosition::Front)] {
        if model.vehicle.as_ref().is_some_and(|v| v.axle == other) {
            let said = if other == AxlePosition::Rear { "rear" } else { "front" };
            return Err(CarError::AxleSaysOther { key, model: model.name.clone(), said });
        }
    }
    if !front.suspension.expand().is_steered() {
        return Err(CarError::FrontDoesNotSteer { model: front.name.clone() });
    }
    if rear.vehicle.as_ref().is_some_and(|v| v.rack_travel_per_revolution.is_some()) {
        return Err(CarError::RearSteers { model: rear.name.clone() });
    }
    Ok(())
}

impl VehicleReport {
    /// `vehicle.csv`: the understeer budget term by term, then the totals and the roll figures, each with
    /// its unit.
    pub fn table(&self) -> crate::kc::Table {
        use crate::kc::Cell;
        let b = &self.budget;
        let mut rows: Vec<Vec<Cell>> = b
            .contributions
            .iter()
            .map(|c| {
                vec![
                    Cell::Text(c.effect.into()),
                    Cell::Text(c.axle.name().into()),
                    Cell::from(Some(c.value)),
                    Cell::Text("deg/g".into()),
                ]
            })
            .collect();
        let total = |what: &str, v: f64, unit: &str| {
            vec![Cell::Text(what.into()), Cell::Text("car".into()), Cell::from(Some(v)), Cell::Text(unit.into())]
        };
        rows.extend([
            total("understeer gradient", b.understeer_gradient, "deg/g"),
            total("at the steering wheel", b.steering_wheel_gradient, "deg/g"),
            total("roll gradient", b.roll_gradient, "deg/g"),
            total("front roll stiffness", b.roll_stiffness[0], "N·m/deg"),
            total("rear roll stiffness", b.roll_stiffness[1], "N·m/deg"),
            total("roll stiffness, front share", 100.0 * b.roll_stiffness_front_share, "%"),
            total("lateral load transfer, front", b.load_transfer[0], "N/g"),
            total("lateral load transfer, rear", b.load_transfer[1], "N/g"),
            total("lateral load transfer, front share", 100.0 * b.load_transfer_front_share, "%"),
            total("CG above the roll axis", b.cg_above_roll_axis * 1e3, "mm"),
        ]);
        if let Some(v) = b.characteristic_speed {
            rows.push(total("characteristic speed", v, "km/h"));
        }
        crate::kc::Table {
            name: "vehicle".into(),
            columns: ["what", "axle", "value", "unit"].map(String::from).to_vec(),
            rows,
        }
    }
}
