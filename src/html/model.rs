//! The K&C report's last section: the model file as run, so that whoever receives the report can run it
//! again.

use crate::markup::text;
use crate::suspensions::SuspensionFile;
use std::fmt::Write;

/// The model file itself, so that the colleague who receives the report can run it again.
pub(super) fn write_model(out: &mut String, model: &SuspensionFile) -> std::fmt::Result {
    writeln!(out, "<section id=\"model\">")?;
    writeln!(out, "<h2>Model file</h2>")?;
    match serde_json::to_string_pretty(model) {
        Ok(json) => {
            writeln!(out, "<details>")?;
            writeln!(out, "<summary>the model as run (JSON, SI units)</summary>")?;
            writeln!(out, "<pre>{}</pre>", text(&json))?;
            writeln!(out, "</details>")?;
        }
        Err(e) => writeln!(out, "<p class=\"error\">the model could not be written out: {}</p>", text(&e.to_string()))?,
    }
    writeln!(out, "</section>")
}
