//! The units figures are shown in. A figure's value is held in SI (rad/m, N/m, rad/N); its [`Unit`] says
//! how it is written, and [`Units`] the choice of units for the slopes K&C rigs print their own way. Only
//! the writers (terminal, CSV, JSON, HTML) convert: every layer that computes with a figure reads SI.

use serde::Serialize;

/// How a figure is written: its unit on the page, the SI unit its value is held in, and the factor between.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Unit {
    /// mm, of a length in m.
    Millimetre,
    /// deg, of an angle in rad.
    Degree,
    /// N.
    Newton,
    /// N/mm, of a stiffness in N/m.
    NewtonPerMillimetre,
    /// N·m/deg, of a torsional stiffness in N·m/rad.
    NewtonMetrePerDegree,
    /// deg/m, of an angle per travel in rad/m (a rig's own units under [`Units`]).
    DegreePerMetre,
    /// deg/mm, of an angle per travel in rad/m.
    DegreePerMillimetre,
    /// deg/kN, of an angle per force in rad/N.
    DegreePerKilonewton,
    /// deg/kN·m, of an angle per torque in rad/(N·m) (a rig's own units under [`Units`]).
    DegreePerKilonewtonMetre,
    /// deg per load case, of an angle per fraction of the model's load case in rad.
    DegreePerLoadCase,
    /// deg/deg, of an angle per angle.
    DegreePerDegree,
    /// A ratio of like quantities, shown as a bare number.
    Ratio,
    /// %, of a fraction.
    Percent,
    /// `:1`, a ratio written as a gear ratio.
    ToOne,
}

/// A unit as written: its symbol, and the factor its SI value is multiplied by.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shown {
    /// The unit's symbol (`deg/m`; `-` for a bare number).
    pub symbol: &'static str,
    /// Written value per SI value.
    pub factor: f64,
    /// Decimals shown more than the figure's own.
    pub more_decimals: usize,
}

const DEG: f64 = 180.0 / std::f64::consts::PI;

impl Unit {
    /// Every unit, for tests and docs that list them.
    pub const ALL: [Unit; 14] = [
        Unit::Millimetre,
        Unit::Degree,
        Unit::Newton,
        Unit::NewtonPerMillimetre,
        Unit::NewtonMetrePerDegree,
        Unit::DegreePerMetre,
        Unit::DegreePerMillimetre,
        Unit::DegreePerKilonewton,
        Unit::DegreePerKilonewtonMetre,
        Unit::DegreePerLoadCase,
        Unit::DegreePerDegree,
        Unit::Ratio,
        Unit::Percent,
        Unit::ToOne,
    ];

    /// The unit written (with the default [`Units`]) and the factor from SI.
    pub fn shown(self) -> Shown {
        let (symbol, factor) = match self {
            Unit::Millimetre => ("mm", 1e3),
            Unit::Degree => ("deg", DEG),
            Unit::Newton => ("N", 1.0),
            Unit::NewtonPerMillimetre => ("N/mm", 1e-3),
            Unit::NewtonMetrePerDegree => ("N·m/deg", 1.0 / DEG),
            Unit::DegreePerMetre => ("deg/m", DEG),
            Unit::DegreePerMillimetre => ("deg/mm", DEG * 1e-3),
            Unit::DegreePerKilonewton => ("deg/kN", DEG * 1e3),
            Unit::DegreePerKilonewtonMetre => ("deg/kN·m", DEG * 1e3),
            Unit::DegreePerLoadCase => ("deg per load case", DEG),
            Unit::DegreePerDegree => ("deg/deg", 1.0),
            Unit::Ratio => ("-", 1.0),
            Unit::Percent => ("%", 100.0),
            Unit::ToOne => (":1", 1.0),
        };
        Shown { symbol, factor, more_decimals: 0 }
    }

    /// The unit written under `units`.
    pub fn shown_in(self, units: Units) -> Shown {
        let base = self.shown();
        let (symbol, scale, more_decimals) = match (units, self) {
            (Units::DegPerM, _) => return base,
            (Units::DegPer10Mm, Unit::DegreePerMetre) => ("deg/10 mm", 1e-2, 2),
            (Units::ArcminPerMm, Unit::DegreePerMetre) => ("arcmin/mm", 60.0 * 1e-3, 1),
            (_, Unit::DegreePerKilonewtonMetre) => ("deg/100 N·m", 0.1, 1),
            _ => return base,
        };
        Shown { symbol, factor: base.factor * scale, more_decimals }
    }

    /// The SI unit the value is held in.
    pub fn si(self) -> &'static str {
        match self {
            Unit::Millimetre => "m",
            Unit::Degree => "rad",
            Unit::Newton => "N",
            Unit::NewtonPerMillimetre => "N/m",
            Unit::NewtonMetrePerDegree => "N·m/rad",
            Unit::DegreePerMetre | Unit::DegreePerMillimetre => "rad/m",
            Unit::DegreePerKilonewton => "rad/N",
            Unit::DegreePerKilonewtonMetre => "rad/(N·m)",
            Unit::DegreePerLoadCase => "rad",
            Unit::DegreePerDegree => "rad/rad",
            Unit::Ratio | Unit::Percent | Unit::ToOne => "1",
        }
    }
}

/// How the figures that are slopes against wheel travel (bump steer, camber gain) and the aligning-torque
/// compliances are written: in SI multiples, or as K&C rigs print them. A choice of the writers only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum Units {
    /// deg/m and deg/kN·m.
    #[default]
    #[serde(rename = "deg-per-m")]
    DegPerM,
    /// deg/10 mm and deg/100 N·m.
    #[serde(rename = "deg-per-10mm")]
    DegPer10Mm,
    /// arc minutes per mm (′/mm) and deg/100 N·m.
    #[serde(rename = "arcmin-per-mm")]
    ArcminPerMm,
}

impl Units {
    /// Every choice, with its name on the command line.
    pub const ALL: [(Units, &'static str); 3] =
        [(Units::DegPerM, "deg-per-m"), (Units::DegPer10Mm, "deg-per-10mm"), (Units::ArcminPerMm, "arcmin-per-mm")];
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each factor against the unit's definition, written out independently.
    #[test]
    fn each_unit_is_its_si_unit_scaled_by_its_definition() {
        let pi = std::f64::consts::PI;
        let expected = [
            (Unit::Millimetre, 1.0 / 0.001),
            (Unit::Degree, 180.0 / pi),
            (Unit::Newton, 1.0),
            (Unit::NewtonPerMillimetre, 0.001),
            (Unit::NewtonMetrePerDegree, pi / 180.0),
            (Unit::DegreePerMetre, 180.0 / pi),
            (Unit::DegreePerMillimetre, (180.0 / pi) / 1000.0),
            (Unit::DegreePerKilonewton, (180.0 / pi) * 1000.0),
            (Unit::DegreePerKilonewtonMetre, (180.0 / pi) * 1000.0),
            (Unit::DegreePerLoadCase, 180.0 / pi),
            (Unit::DegreePerDegree, 1.0),
            (Unit::Ratio, 1.0),
            (Unit::Percent, 100.0),
            (Unit::ToOne, 1.0),
        ];
        assert_eq!(expected.len(), Unit::ALL.len());
        for ((unit, factor), listed) in expected.into_iter().zip(Unit::ALL) {
            assert_eq!(unit, listed);
            let got = unit.shown().factor;
            assert!((got - factor).abs() <= 4.0 * f64::EPSILON * factor, "{unit:?}: {got} for {factor}");
        }
        // A rig's units: 1 rad/m is 0.5729… deg/10 mm and 3.437… arcmin/mm; 1 rad/(N·m) is 5729.6 deg/100 N·m.
        let per_10mm = Unit::DegreePerMetre.shown_in(Units::DegPer10Mm);
        assert_eq!(per_10mm.symbol, "deg/10 mm");
        assert!((per_10mm.factor - 180.0 / pi / 100.0).abs() < 1e-15);
        let arcmin = Unit::DegreePerMetre.shown_in(Units::ArcminPerMm);
        assert!((arcmin.factor - 180.0 / pi * 60.0 / 1000.0).abs() < 1e-14);
        let per_100nm = Unit::DegreePerKilonewtonMetre.shown_in(Units::ArcminPerMm);
        assert_eq!(per_100nm.symbol, "deg/100 N·m");
        assert!((per_100nm.factor - 180.0 / pi * 100.0).abs() < 1e-11);
        assert_eq!(Unit::Millimetre.shown_in(Units::DegPer10Mm), Unit::Millimetre.shown());
    }
}
