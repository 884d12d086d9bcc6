//! `elastokin live`'s server as plain functions from a request to its response: who may be served (the
//! token, the Host and the Origin), the routes, and the design they edit (`design::live`). The command
//! (`src/command/live.rs`) carries requests between a socket and [`Live::handle`]; everything here is
//! testable without one.
//!
//! Safe by default: every request names the server's token, 128 random bits in hex, as the first segment of
//! its path, compared in constant time; its Host must be the address the server is bound to (or
//! `localhost` at its port), which keeps a name that a foreign page rebinds to this machine away; an
//! Origin, when the browser sends one, must be the server's own, so that no other page open in the browser
//! can drive it. Anything else is refused with 403, and a body over [`BODY_LIMIT`] with 413.
//!
//! Routes, each under `/TOKEN`: `GET /` the page (`html::live_html`); `GET /state` the current design ([`State`]); `POST /edit` with
//! `{"pointer": "/json/pointer", "value": number}` (SI, as the model file stores it) a new design;
//! `POST /undo`, `POST /redo`; `POST /save` the model file written where it was read; `POST /guidance`
//! with `{"point": "/…/hardpoints/NAME"}` every figure's derivatives to that hardpoint's x, y and z;
//! `POST /tune` the TARGETS file's free numbers tuned from the current design, one design more. A design
//! refused comes back with the reason and the design kept.

use crate::html::{live_chart_data, live_html};
use elastokin_suspensions::design::live::{LiveDesign, LiveError};
use serde_json::{json, Value};
use std::net::{IpAddr, SocketAddr};
use std::path::{Path, PathBuf};
use subtle::ConstantTimeEq;

/// The largest request body served: an edit is some hundred bytes.
pub const BODY_LIMIT: usize = 1 << 20;

/// The server's token: 128 random bits, in hex.
#[derive(Debug, Clone)]
pub struct Token(String);

impl Token {
    /// A token from the operating system's random source.
    pub fn random() -> Result<Token, String> {
        let mut bytes = [0u8; 16];
        getrandom::fill(&mut bytes).map_err(|e| format!("no random numbers for the server's token: {e}"))?;
        Ok(Token(bytes.iter().map(|b| format!("{b:02x}")).collect()))
    }

    /// The token as written in the address.
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// Whether `given` is the token, compared in constant time (a length differing is no secret).
    fn is(&self, given: &str) -> bool {
        bool::from(self.0.as_bytes().ct_eq(given.as_bytes()))
    }
}

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
    fn json(status: u16, body: &Value) -> Response {
        Response { status, content_type: "application/json", body: body.to_string().into_bytes() }
    }

    fn refused(status: u16, why: &str) -> Response {
        Response::json(status, &json!({ "error": why }))
    }

    /// 413: a body over [`BODY_LIMIT`].
    pub fn too_large() -> Response {
        Response::refused(413, &format!("the request's body is over {BODY_LIMIT} bytes: an edit is one number"))
    }
}

/// The server: the design, the token, the address it is bound to and the file a save writes.
#[derive(Debug)]
pub struct Live {
    design: LiveDesign,
    token: Token,
    bound: SocketAddr,
    model: PathBuf,
    /// The model file's text as the server last read or wrote it: a save refuses to write over other
    /// changes.
    on_disk: String,
}

impl Live {
    /// The server of `design`, read from the file at `model` whose text was `text`, with `token`, bound to
    /// `bound`. A save writes to `model` and nowhere else.
    pub fn new(design: LiveDesign, text: String, model: &Path, token: Token, bound: SocketAddr) -> Live {
        Live { design, token, bound, model: model.to_path_buf(), on_disk: text }
    }

    /// The page's address, token included.
    pub fn address(&self) -> String {
        let host = match self.bound.ip() {
            ip if ip.is_unspecified() && ip.is_ipv4() => "127.0.0.1".to_string(),
            ip if ip.is_unspecified() => "[::1]".to_string(),
            IpAddr::V6(ip) => format!("[{ip}]"),
            IpAddr::V4(ip) => ip.to_string(),
        };
        format!("http://{host}:{}/{}/", self.bound.port(), self.token.as_str())
    }

    /// The design served.
    pub fn design(&self) -> &LiveDesign {
        &self.design
    }

    /// Whether the design differs from the file as last read or written.
    pub fn unsaved(&self) -> bool {
        self.design.text().map_or(true, |text| text != self.on_disk)
    }

    /// Whether a request with `head` is served at all: refused with 403 unless its path starts with the
    /// token, its Host is this server's and its Origin, when sent, is this server's; with 413 when it says
    /// its body is over [`BODY_LIMIT`]. Decided before the body is read.
    pub fn admit(&self, head: &Head) -> Result<(), Response> {
        let path = head.url.split(['?', '#']).next().unwrap_or("");
        let first = path.strip_prefix('/').and_then(|p| p.split('/').next()).unwrap_or("");
        if !self.token.is(first) {
            return Err(Response::refused(403, "the address lacks the server's token: use the address it printed"));
        }
        let Some(host) = head.host.filter(|h| self.is_own_host(h)) else {
            return Err(Response::refused(403, "the request's Host is not this server's address"));
        };
        if let Some(origin) = head.origin {
            if !origin.eq_ignore_ascii_case(&format!("http://{host}")) {
                return Err(Response::refused(403, "the request comes from another page than the server's own"));
            }
        }
        if head.content_length.is_some_and(|n| n > BODY_LIMIT) {
            return Err(Response::too_large());
        }
        Ok(())
    }

    /// Whether `host` (a Host header: a name or address and the port) names this server: its port, and
    /// `localhost`, or the address it is bound to (any literal address of this machine when bound to all of
    /// them). A name other than `localhost` is refused: a foreign page could have it point here.
    fn is_own_host(&self, host: &str) -> bool {
        let Some((name, port)) = host.rsplit_once(':') else { return false };
        if port != self.bound.port().to_string() {
            return false;
        }
        if name.eq_ignore_ascii_case("localhost") {
            return self.bound.ip().is_loopback() || self.bound.ip().is_unspecified();
        }
        let literal = name.strip_prefix('[').and_then(|n| n.strip_suffix(']')).unwrap_or(name);
        match literal.parse::<IpAddr>() {
            Ok(ip) if self.bound.ip().is_unspecified() => ip.is_ipv4() == self.bound.ip().is_ipv4(),
            Ok(ip) => ip == self.bound.ip(),
            Err(_) => false,
        }
    }

    /// The response to a request with `head` and `body`: admitted ([`Live::admit`]) and routed.
    pub fn handle(&mut self, head: &Head, body: &[u8]) -> Response {
        if let Err(refused) = self.admit(head) {
            return refused;
        }
        if body.len() > BODY_LIMIT {
            return Response::too_large();
        }
        let path = head.url.split(['?', '#']).next().unwrap_or("");
        let route = path.strip_prefix('/').and_then(|p| p.split_once('/')).map_or("", |(_, r)| r);
        match (head.method, route) {
            ("GET", "") => Response {
                status: 200,
                content_type: "text/html; charset=utf-8",
                body: live_html(&self.design.current().report.model).into_bytes(),
            },
            ("GET", "state") => self.state(200, None),
            ("POST", "edit") => self.edit(body),
            ("POST", "undo") => {
                let done = self.design.undo().map(|_| ());
                self.after(done, 409)
            }
            ("POST", "redo") => {
                let done = self.design.redo().map(|_| ());
                self.after(done, 409)
            }
            ("POST", "save") => self.save(),
            ("POST", "guidance") => self.guidance(body),
            ("POST", "tune") => match self.design.tune() {
                Ok(said) => self.state_noted(200, None, Some(said)),
                Err(e) => self.state(422, Some(e.to_string())),
            },
            (_, "" | "state" | "edit" | "undo" | "redo" | "save" | "guidance" | "tune") => Response::refused(
                405,
                &format!("{} /{route} is not served: state is read with GET, every change is a POST", head.method),
            ),
            _ => Response::refused(
                404,
                &format!("nothing at /{route}: the routes are state, edit, undo, redo, save, guidance, tune"),
            ),
        }
    }

    /// The current design with `status`, and the error when a change was refused; each chart as the page
    /// draws it, and, when the analyses recorded the parts' poses, the geometry's three projections as SVG
    /// with where each puts a point (the page's hardpoints and arrows go there) and the 3D view's data.
    fn state(&self, status: u16, error: Option<String>) -> Response {
        self.state_noted(status, error, None)
    }

    /// [`Self::state`], with what the change did in words (`tuned`: how a tune ended), when said.
    fn state_noted(&self, status: u16, error: Option<String>, tuned: Option<String>) -> Response {
        match self.design.state() {
            Ok(state) => {
                let mut body = json!({ "state": state });
                let report = &self.design.current().report;
                for (k, a) in report.analyses.iter().enumerate() {
                    body["state"]["analyses"][k]["charts"] = a.charts.iter().map(live_chart_data).collect();
                }
                let mut projections = String::new();
                if crate::view::write_projections(&mut projections, report).is_ok() {
                    body["state"]["projections"] = Value::String(projections);
                    body["state"]["projection_frames"] =
                        crate::view::projection_frames(report).iter().map(|f| f.json()).collect();
                }
                body["state"]["view3d"] = crate::view::viewer_data(report);
                if let Some(error) = error {
                    body["error"] = Value::String(error);
                }
                if let Some(tuned) = tuned {
                    body["tuned"] = Value::String(tuned);
                }
                Response::json(status, &body)
            }
            Err(e) => Response::refused(500, &e.to_string()),
        }
    }

    /// The state after a change, or the reason it was refused (with `refused`) and the design kept.
    fn after(&self, done: Result<(), LiveError>, refused: u16) -> Response {
        match done {
            Ok(()) => self.state(200, None),
            Err(e) => self.state(refused, Some(e.to_string())),
        }
    }

    /// `POST /edit`: `{"pointer": …, "value": …}`.
    fn edit(&mut self, body: &[u8]) -> Response {
        let asked: Value = match serde_json::from_slice(body) {
            Ok(v) => v,
            Err(e) => return Response::refused(400, &format!("the edit is no JSON: {e}")),
        };
        let (Some(pointer), Some(value)) = (asked["pointer"].as_str(), asked["value"].as_f64()) else {
            return Response::refused(
                400,
                "give the edit as {\"pointer\": \"/suspension/…/hardpoints/NAME/2\", \"value\": 0.1} (SI units, as \
                 the model file stores them)",
            );
        };
        let done = self.design.edit(pointer, value).map(|_| ());
        self.after(done, 422)
    }

    /// `POST /guidance`: `{"point": …}`, a hardpoint's pointer: how every figure of the current design
    /// moves with its x, y and z.
    fn guidance(&self, body: &[u8]) -> Response {
        let asked: Value = serde_json::from_slice(body).unwrap_or(Value::Null);
        let Some(point) = asked["point"].as_str() else {
            return Response::refused(
                400,
                "give the hardpoint as {\"point\": \"/suspension/…/hardpoints/NAME\"} (its pointer, without a coordinate)",
            );
        };
        match self.design.guidance(point) {
            Ok(guidance) => Response::json(200, &json!({ "guidance": guidance })),
            Err(e) => Response::refused(422, &e.to_string()),
        }
    }

    /// `POST /save`: the model file written where it was read, through a file beside it renamed over it
    /// (a reader sees the old file or the new one); refused when the file changed on disk since the server
    /// last read or wrote it.
    fn save(&mut self) -> Response {
        let text = match self.design.text() {
            Ok(text) => text,
            Err(e) => return Response::refused(500, &e.to_string()),
        };
        let shown = self.model.display().to_string();
        match std::fs::read_to_string(&self.model) {
            Ok(now) if now == self.on_disk => {}
            Ok(_) => {
                return self.state(
                    409,
                    Some(format!(
                        "{shown} changed on disk since it was read: nothing saved (save the other changes elsewhere, \
                         or start again from the file as it is)"
                    )),
                )
            }
            Err(e) => return self.state(500, Some(format!("{shown}: {e}: nothing saved"))),
        }
        let name = self.model.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let beside = self.model.with_file_name(format!(".{name}.live-{}.tmp", std::process::id()));
        let written = std::fs::write(&beside, &text).and_then(|()| std::fs::rename(&beside, &self.model));
        if let Err(e) = written {
            let _ = std::fs::remove_file(&beside);
            return self.state(500, Some(format!("{shown}: {e}: nothing saved")));
        }
        self.on_disk = text;
        let mut response = self.state(200, None);
        if let Ok(mut body) = serde_json::from_slice::<Value>(&response.body) {
            body["saved"] = Value::String(shown);
            response.body = body.to_string().into_bytes();
        }
        response
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use elastokin_suspensions::kc::{Analysis, Settings};

    fn served(bound: &str) -> Live {
        let text = include_str!("../examples/macpherson.json");
        let settings = Settings { steps: 4, ..Settings::default() };
        let design = LiveDesign::open(text, "macpherson.json", &[Analysis::ParallelTravel], settings).unwrap();
        Live::new(
            design,
            text.into(),
            Path::new("/nowhere/macpherson.json"),
            Token::random().unwrap(),
            bound.parse().unwrap(),
        )
    }

    fn head<'a>(url: &'a str, host: &'a str, origin: Option<&'a str>) -> Head<'a> {
        Head { method: "GET", url, host: Some(host), origin, content_length: None }
    }

    #[test]
    fn a_token_is_128_random_bits_in_hex() {
        let (a, b) = (Token::random().unwrap(), Token::random().unwrap());
        assert_eq!(a.as_str().len(), 32);
        assert!(a.as_str().bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a.as_str(), b.as_str());
        assert!(a.is(a.as_str()) && !a.is(b.as_str()) && !a.is(&a.as_str()[..31]) && !a.is(""));
    }

    #[test]
    fn only_the_servers_own_host_and_origin_are_served() {
        let live = served("127.0.0.1:4000");
        let url = format!("/{}/state", live.token.as_str());
        let status = |host: &str, origin: Option<&str>| live.admit(&head(&url, host, origin)).err().map(|r| r.status);
        assert_eq!(status("127.0.0.1:4000", None), None);
        assert_eq!(status("localhost:4000", Some("http://localhost:4000")), None);
        assert_eq!(status("127.0.0.1:4000", Some("http://127.0.0.1:4000")), None);
        assert_eq!(status("127.0.0.1:4001", None), Some(403));
        assert_eq!(status("evil.example:4000", None), Some(403));
        assert_eq!(status("127.0.0.2:4000", None), Some(403));
        assert_eq!(status("127.0.0.1:4000", Some("http://evil.example")), Some(403));
        assert_eq!(status("127.0.0.1:4000", Some("null")), Some(403));
        assert_eq!(status("127.0.0.1:4000", Some("http://localhost:4000")), Some(403));

        // Bound to every address: any literal address of the family at the port, never a name but localhost.
        let all = served("0.0.0.0:4000");
        let url = format!("/{}/state", all.token.as_str());
        let status = |host: &str| all.admit(&head(&url, host, None)).err().map(|r| r.status);
        assert_eq!(status("192.0.2.7:4000"), None);
        assert_eq!(status("localhost:4000"), None);
        assert_eq!(status("rebound.example:4000"), Some(403));
        assert_eq!(status("[::1]:4000"), Some(403));
        assert_eq!(all.address(), format!("http://127.0.0.1:4000/{}/", all.token.as_str()));
    }

    #[test]
    fn routes_answer_and_an_oversize_body_is_refused() {
        let mut live = served("127.0.0.1:4000");
        let token = live.token.as_str().to_string();
        let url = |route: &str| format!("/{token}/{route}");
        let ask = |live: &mut Live, method: &str, route: &str, body: &[u8]| {
            let url = url(route);
            let head = Head { method, url: &url, host: Some("127.0.0.1:4000"), origin: None, content_length: None };
            live.handle(&head, body)
        };
        assert_eq!(ask(&mut live, "GET", "state", b"").status, 200);
        assert_eq!(ask(&mut live, "GET", "edit", b"").status, 405);
        assert_eq!(ask(&mut live, "GET", "nothing", b"").status, 404);
        assert_eq!(ask(&mut live, "POST", "edit", b"{").status, 400);
        assert_eq!(ask(&mut live, "POST", "undo", b"").status, 409);
        // No TARGETS file: nothing to tune to, said, the design kept.
        let tune = ask(&mut live, "POST", "tune", b"");
        assert_eq!(tune.status, 422);
        assert!(String::from_utf8_lossy(&tune.body).contains("nothing to tune to: start the server with --targets"));
        assert_eq!(ask(&mut live, "GET", "tune", b"").status, 405);
        assert_eq!(ask(&mut live, "POST", "edit", &vec![b' '; BODY_LIMIT + 1]).status, 413);
        let edit = br#"{"pointer": "/suspension/macpherson/spring/rate", "value": 27000}"#;
        let done = ask(&mut live, "POST", "edit", edit);
        let body: Value = serde_json::from_slice(&done.body).unwrap();
        assert_eq!((done.status, body["state"]["version"].as_u64()), (200, Some(2)));
        assert!(live.unsaved());
        // The file is nowhere: the save says so and the design stays.
        let failed = ask(&mut live, "POST", "save", b"");
        let body: Value = serde_json::from_slice(&failed.body).unwrap();
        assert_eq!(failed.status, 500);
        assert!(body["error"].as_str().unwrap().contains("/nowhere/macpherson.json"), "{body}");
        assert_eq!(body["state"]["version"].as_u64(), Some(2));
    }
}
