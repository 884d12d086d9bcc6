//! The section of the model's hardpoints: each point's name and position in mm, in ISO 8855 axes.

use crate::markup::text;
use crate::suspensions::kc::fixed;
use crate::suspensions::SuspensionFile;
use std::fmt::Write;

/// The hardpoints of a model file: its template's name (`macpherson`, `double_wishbone`, `general`) and
/// each point's name and position (m).
struct Hardpoints {
    template: String,
    points: Vec<(String, [f64; 3])>,
}

fn hardpoints(model: &SuspensionFile) -> Result<Hardpoints, String> {
    let points = model.suspension.hardpoints().into_iter().map(|(name, p)| (name, [p.x, p.y, p.z])).collect();
    Ok(Hardpoints { template: model.suspension.kind().to_string(), points })
}

/// The section "Hardpoints": the template's name and a table of the points, or why they could not be read.
pub(super) fn write_hardpoints(out: &mut String, model: &SuspensionFile) -> std::fmt::Result {
    writeln!(out, "<section id=\"hardpoints\">")?;
    match hardpoints(model) {
        Ok(Hardpoints { template, points }) => {
            writeln!(out, "<h2>Hardpoints <span class=\"quiet\">({}, left corner)</span></h2>", text(&template))?;
            writeln!(out, "<table class=\"numbers\">")?;
            writeln!(out, "<thead><tr><th>hardpoint</th><th>x [mm]</th><th>y [mm]</th><th>z [mm]</th></tr></thead>")?;
            writeln!(out, "<tbody>")?;
            for (name, p) in points {
                write!(out, "<tr><td><code>{}</code></td>", text(&name))?;
                for v in p {
                    write!(out, "<td>{}</td>", fixed(v * 1e3, 2))?;
                }
                writeln!(out, "</tr>")?;
            }
            writeln!(out, "</tbody></table>")?;
            writeln!(out, "<p class=\"note\">ISO 8855: x forward, y left, z up.</p>")?;
        }
        Err(e) => {
            writeln!(out, "<h2>Hardpoints</h2>")?;
            writeln!(out, "<p class=\"error\">the hardpoints could not be read: {}</p>", text(&e))?;
        }
    }
    writeln!(out, "</section>")
}
