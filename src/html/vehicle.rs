//! The whole car's page: the understeer budget as a bar chart, the roll and load-transfer figures, and each
//! axle's characteristics read off its K&C runs.

use super::charts::write_bars;
use super::tables::write_open_table;
use super::{write_foot, write_head, NAME_SHOWN};
use crate::markup::text;
use crate::suspensions::kc::{figures, significant};
use serde_json::Value;
use std::fmt::Write;

/// The whole car's page: the understeer budget as a bar chart (each term per axle, understeer to the
/// right), the roll and load-transfer figures, each axle's characteristics read off its K&C runs, and
/// how it was made.
pub fn vehicle_html(report: &crate::suspensions::full_vehicle::VehicleReport, provenance: &Value) -> String {
    let mut page = String::new();
    // Writing into a String cannot fail.
    let _ = write_vehicle_page(&mut page, report, provenance);
    page
}

fn write_vehicle_page(
    out: &mut String,
    report: &crate::suspensions::full_vehicle::VehicleReport,
    provenance: &Value,
) -> std::fmt::Result {
    let b = &report.budget;
    let name = crate::plot::shown(&report.name, NAME_SHOWN);
    let character = if b.understeer_gradient > crate::suspensions::full_vehicle::NEUTRAL {
        "understeers"
    } else if b.understeer_gradient < -crate::suspensions::full_vehicle::NEUTRAL {
        "oversteers"
    } else {
        "is neutral"
    };
    let lede = format!(
        "The car {character}: {} deg/g of road-wheel steer ({} deg/g at the steering wheel); the body rolls {} deg/g.",
        significant(b.understeer_gradient, 3),
        significant(b.steering_wheel_gradient, 3),
        significant(b.roll_gradient, 3)
    );
    write_head(out, &format!("Vehicle: {name}"), &lede)?;
    if !report.warnings.is_empty() {
        writeln!(out, "<ul class=\"warnings\">")?;
        for w in &report.warnings {
            writeln!(out, "<li>{}</li>", text(w))?;
        }
        writeln!(out, "</ul>")?;
    }
    writeln!(out, "<section id=\"budget\">")?;
    writeln!(out, "<h2>Understeer budget</h2>")?;
    writeln!(
        out,
        "<p class=\"note\">each term's share of the understeer gradient, deg/g of road-wheel steer: understeer \
         to the right, oversteer to the left; docs/vehicle.md gives every formula</p>"
    )?;
    let mut bars: Vec<(String, f64)> =
        b.contributions.iter().map(|c| (format!("{}, {}", c.effect, c.axle.name()), c.value)).collect();
    bars.push(("understeer gradient (the sum)".into(), b.understeer_gradient));
    write_bars(out, &bars, "deg/g")?;
    writeln!(out, "</section>")?;
    writeln!(out, "<section id=\"figures\">")?;
    writeln!(out, "<h2>Roll and load transfer</h2>")?;
    write_open_table(out, &report.table())?;
    writeln!(out, "</section>")?;
    write_axles(out, report)?;
    write_foot(out, provenance)
}

/// The section of the axles: each figure of the front and the rear read off their K&C runs.
fn write_axles(out: &mut String, report: &crate::suspensions::full_vehicle::VehicleReport) -> std::fmt::Result {
    writeln!(out, "<section id=\"axles\">")?;
    writeln!(out, "<h2>The axles, from their K&amp;C runs</h2>")?;
    writeln!(
        out,
        "<table class=\"numbers\"><thead><tr><th>figure</th><th>unit</th><th>front</th><th>rear</th></tr></thead><tbody>"
    )?;
    let [f, r] = &report.axles;
    for (kind, x, y) in [
        (&figures::ROLL_STIFFNESS, f.roll_stiffness, r.roll_stiffness),
        (&figures::ROLL_CENTRE_HEIGHT, f.roll_centre_height, r.roll_centre_height),
        (&figures::TRACK, f.track, r.track),
        (&figures::ROLL_STEER, f.roll_steer, r.roll_steer),
        (&figures::ROLL_CAMBER, f.roll_camber, r.roll_camber),
        (&figures::LATERAL_STEER, f.lateral_steer, r.lateral_steer),
        (&figures::LATERAL_CAMBER, f.lateral_camber, r.lateral_camber),
        (&figures::ALIGNING_TORQUE_STEER, f.aligning_torque_steer, r.aligning_torque_steer),
    ] {
        let unit = kind.unit.shown();
        writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            text(kind.label),
            text(unit.symbol),
            text(&significant(x * unit.factor, 4)),
            text(&significant(y * unit.factor, 4))
        )?;
    }
    writeln!(out, "</tbody></table>")?;
    writeln!(out, "</section>")
}
