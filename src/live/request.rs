//! What the server reads of a request before its body, and what it answers: no HTTP library's types, so
//! that who is served and what they are answered can be tested without a socket.

use serde_json::{json, Value};

/// The largest request body served: an edit is some hundred bytes.
pub const BODY_LIMIT: usize = 1 << 20;

/// What the server reads of a request before its body: whether it is served at all is decided on it.
#[derive(Debug, Clone, Copy)]
pub struct Head<'a> {
    /// `GET`, `POST`, …
    pub method: &'a str,
    /// The path and query, as sent.
    pub url: &'a str,
    /// The Host header.
    pub host: Option<&'a str>,
    /// The Origin header.
    pub origin: Option<&'a str>,
    /// The Content-Length header, when given.
    pub content_length: Option<usize>,
}

impl Head<'_> {
    /// The path without its query or fragment.
    pub fn path(&self) -> &str {
        self.url.split(['?', '#']).next().unwrap_or("")
    }
}

/// A response: its status, its content type and its body.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// The HTTP status.
    pub status: u16,
    /// The content type.
    pub content_type: &'static str,
    /// The body.
    pub body: Vec<u8>,
}

impl Response {
    /// `body` as JSON with `status`.
    pub fn json(status: u16, body: &Value) -> Response {
        Response { status, content_type: "application/json", body: body.to_string().into_bytes() }
    }

    /// A request refused with `status`, and why in words: `{"error": why}`.
    pub fn refused(status: u16, why: &str) -> Response {
        Response::json(status, &json!({ "error": why }))
    }

    /// 413: a body over [`BODY_LIMIT`].
    pub fn too_large() -> Response {
        Response::refused(413, &format!("the request's body is over {BODY_LIMIT} bytes: an edit is one number"))
    }

    /// 503: a request that came in as the server was stopping.
    pub fn stopped() -> Response {
        Response::refused(503, "the server has stopped: start it again to go on editing")
    }
}
