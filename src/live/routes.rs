//! The routes on a design: each request admitted ([`Admission`]) and answered from the design it edits
//! (`design::live`), the model file read where it was and saved there.

use super::admission::Admission;
use super::request::{Head, Response, BODY_LIMIT};
use crate::html::{live_chart_data, live_estimate_words, live_html};
use elastokin_suspensions::design::live::{LiveDesign, LiveError};
use elastokin_suspensions::file::{read_input, InputError};
use elastokin_suspensions::kc::{self, Analysis, Settings};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// The routes under the page's address, as a refusal names them: state is read with GET, every change
/// is a POST (`routes_answer_and_an_oversize_body_is_refused` asks each with the other method).
const ROUTES: [&str; 8] = ["state", "edit", "undo", "redo", "save", "guidance", "tune", "estimate"];

/// What a server serves: the design of the model file at `model`, whose text was `text`.
#[derive(Debug)]
pub struct Served {
    /// The design, as edited.
    pub design: LiveDesign,
    /// The model file's text as read.
    pub text: String,
    /// The model file: the one file a save writes.
    pub model: PathBuf,
}

/// Why a model file's design is not served: settings an analysis cannot take, a file that cannot be read,
/// or a model that does not read or build.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// Settings an analysis cannot take.
    #[error(transparent)]
    Settings(#[from] kc::AnalysisError),
    /// A file that cannot be read.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A model that does not read or build.
    #[error(transparent)]
    Design(#[from] LiveError),
}

impl Served {
    /// The design of the model file at `model` (named as given in messages): its analyses `which` (the
    /// suite when empty) walked in `steps` load steps on every design, each with the parts' poses at every
    /// row for the page's projections of the geometry. Settings an analysis cannot take are refused before
    /// the file is read.
    pub fn open(model: &Path, which: &[Analysis], steps: usize) -> Result<Served, OpenError> {
        let settings = Settings { steps, motion: true, ..Settings::default() };
        for &a in if which.is_empty() { &kc::ALL[..] } else { which } {
            kc::check_settings(a, &settings)?;
        }
        let (_, text) = read_input(model, "MODEL")?;
        let design = LiveDesign::open(&text, &model.display().to_string(), which, settings)?;
        Ok(Served { design, text, model: model.to_path_buf() })
    }
}

/// The server's state: the design, who is served, and the file a save writes.
#[derive(Debug)]
pub struct Live {
    design: LiveDesign,
    admission: Admission,
    model: PathBuf,
    /// The model file's text as the server last read or wrote it: a save refuses to write over other
    /// changes.
    on_disk: String,
}

impl Live {
    /// The server of `served`, admitting as `admission` says. A save writes to the model file and nowhere
    /// else.
    pub fn new(served: Served, admission: Admission) -> Live {
        Live { design: served.design, admission, model: served.model, on_disk: served.text }
    }

    /// Who is served.
    pub fn admission(&self) -> &Admission {
        &self.admission
    }

    /// The design served.
    pub fn design(&self) -> &LiveDesign {
        &self.design
    }

    /// Whether the design differs from the file as last read or written.
    pub fn unsaved(&self) -> bool {
        self.design.text().map_or(true, |text| text != self.on_disk)
    }

    /// The response to a request with `head` and `body`: admitted ([`Admission::admit`]) and routed.
    pub fn handle(&mut self, head: &Head, body: &[u8]) -> Response {
        if let Err(refused) = self.admission.admit(head) {
            return refused;
        }
        if body.len() > BODY_LIMIT {
            return Response::too_large();
        }
        let route = head.path().strip_prefix('/').and_then(|p| p.split_once('/')).map_or("", |(_, r)| r);
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
            ("POST", "estimate") => self.estimate(body),
            ("POST", "tune") => match self.design.tune() {
                Ok(said) => self.state_noted(200, None, Some(said)),
                Err(e) => self.state(422, Some(e.to_string())),
            },
            _ if route.is_empty() || ROUTES.contains(&route) => Response::refused(
                405,
                &format!("{} /{route} is not served: state is read with GET, every change is a POST", head.method),
            ),
            _ => Response::refused(404, &format!("nothing at /{route}: the routes are {}", ROUTES.join(", "))),
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
                    for (j, f) in a.figures.iter().enumerate() {
                        if let Some(words) = live_estimate_words(f, a.units) {
                            body["state"]["analyses"][k]["figures"][j]["estimate"] = Value::String(words);
                        }
                    }
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

    /// `POST /estimate`: `{"version": …}`, the version the page shows: every figure's error estimate of the
    /// current design, walked with them now if an edit made it without ([`LiveDesign::estimate`]); refused
    /// when the design is no longer that version (the page asks again for the one it then shows).
    fn estimate(&mut self, body: &[u8]) -> Response {
        let asked: Value = serde_json::from_slice(body).unwrap_or(Value::Null);
        let Some(version) = asked["version"].as_u64() else {
            return Response::refused(400, "give the version shown as {\"version\": 3}");
        };
        if version != self.design.version() {
            return Response::refused(
                409,
                &format!("the design is at version {}, not {version}: ask for its estimates", self.design.version()),
            );
        }
        match self.design.estimate() {
            Ok(design) => {
                let analyses: Vec<Value> = design
                    .report
                    .analyses
                    .iter()
                    .map(|a| {
                        let figures: Vec<Value> = a
                            .figures
                            .iter()
                            .map(|f| json!({ "key": f.key, "error": f.error, "estimate": live_estimate_words(f, a.units) }))
                            .collect();
                        json!({ "name": a.analysis.name(), "figures": figures })
                    })
                    .collect();
                Response::json(200, &json!({ "version": version, "analyses": analyses }))
            }
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
    use super::super::admission::{FrameAncestors, Token};
    use super::*;

    fn served(bound: &str) -> Live {
        let text = include_str!("../../examples/macpherson.json");
        let settings = Settings { steps: 4, ..Settings::default() };
        let design = LiveDesign::open(text, "macpherson.json", &[Analysis::ParallelTravel], settings).unwrap();
        let served = Served { design, text: text.into(), model: PathBuf::from("/nowhere/macpherson.json") };
        let admission = Admission::new(Token::random().unwrap(), bound.parse().unwrap(), FrameAncestors::none());
        Live::new(served, admission)
    }

    #[test]
    fn routes_answer_and_an_oversize_body_is_refused() {
        let mut live = served("127.0.0.1:4000");
        let token = live.admission().token().as_str().to_string();
        let url = |route: &str| format!("/{token}/{route}");
        let ask = |live: &mut Live, method: &str, route: &str, body: &[u8]| {
            let url = url(route);
            let head = Head { method, url: &url, host: Some("127.0.0.1:4000"), origin: None, content_length: None };
            live.handle(&head, body)
        };
        assert_eq!(ask(&mut live, "GET", "state", b"").status, 200);
        // Each route asked with the method it does not take is refused as such, not as unknown.
        for route in ROUTES {
            let other = if route == "state" { "POST" } else { "GET" };
            assert_eq!(ask(&mut live, other, route, b"").status, 405, "{other} /{route}");
        }
        assert_eq!(ask(&mut live, "GET", "nothing", b"").status, 404);
        assert_eq!(ask(&mut live, "POST", "edit", b"{").status, 400);
        assert_eq!(ask(&mut live, "POST", "undo", b"").status, 409);
        // No TARGETS file: nothing to tune to, said, the design kept.
        let tune = ask(&mut live, "POST", "tune", b"");
        assert_eq!(tune.status, 422);
        assert!(
            String::from_utf8_lossy(&tune.body).contains("nothing to tune to: start the server with a TARGETS file")
        );
        assert_eq!(ask(&mut live, "GET", "tune", b"").status, 405);
        assert_eq!(ask(&mut live, "POST", "edit", &vec![b' '; BODY_LIMIT + 1]).status, 413);
        let edit = br#"{"pointer": "/suspension/macpherson/spring/rate", "value": 27000}"#;
        let done = ask(&mut live, "POST", "edit", edit);
        let body: Value = serde_json::from_slice(&done.body).unwrap();
        assert_eq!((done.status, body["state"]["version"].as_u64()), (200, Some(2)));
        assert!(live.unsaved());
        // The edit's figures come without their estimates; asked for the version shown, they follow (an
        // older version is refused, the page asks for the one it shows).
        let bump = |body: &Value, field: &str| body["state"]["analyses"][0]["figures"][0][field].clone();
        assert_eq!((body["state"]["estimated"].as_bool(), bump(&body, "error")), (Some(false), Value::Null));
        assert_eq!(ask(&mut live, "POST", "estimate", br#"{"version": 1}"#).status, 409);
        assert_eq!(ask(&mut live, "POST", "estimate", b"{}").status, 400);
        let estimated = ask(&mut live, "POST", "estimate", br#"{"version": 2}"#);
        let answer: Value = serde_json::from_slice(&estimated.body).unwrap();
        let figure = &answer["analyses"][0]["figures"][0];
        let state: Value = serde_json::from_slice(&ask(&mut live, "GET", "state", b"").body).unwrap();
        assert_eq!(state["state"]["estimated"].as_bool(), Some(true));
        assert_eq!(
            (estimated.status, &figure["key"], &figure["error"]),
            (200, &bump(&state, "key"), &bump(&state, "error"))
        );
        assert!(figure["error"].as_f64().is_some_and(|e| e > 0.0) && figure["estimate"].is_string(), "{figure}");
        assert_eq!(bump(&state, "value"), bump(&body, "value"), "the same figure, to the bit");
        // The file is nowhere: the save says so and the design stays.
        let failed = ask(&mut live, "POST", "save", b"");
        let body: Value = serde_json::from_slice(&failed.body).unwrap();
        assert_eq!(failed.status, 500);
        assert!(body["error"].as_str().unwrap().contains("/nowhere/macpherson.json"), "{body}");
        assert_eq!(body["state"]["version"].as_u64(), Some(2));
    }
}
