//! Text written into the HTML report and its views: escaped, with every character no text may hold shown
//! as its escape, so a name a user gave cannot break the page.

use crate::suspensions::file::key_path::printable;

/// `s` as HTML text: escaped, each character no text is written with shown as its escape.
pub(crate) fn text(s: &str) -> String {
    html_escape::encode_text(&printable(s)).into_owned()
}

/// `s` as a double-quoted HTML attribute value, as [`text`] is written.
pub(crate) fn attr(s: &str) -> String {
    html_escape::encode_double_quoted_attribute(&printable(s)).into_owned()
}
