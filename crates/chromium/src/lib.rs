//! Headless Chromium (Debian's `chromium` package) driven through its DevTools protocol on a pipe
//! (`--remote-debugging-pipe`: commands on its descriptor 3, answers and events on 4, each a JSON message
//! ended by a NUL byte), with every page's console kept: what the tests of `elastokin live` and its
//! benchmark drive the page with, as a user's pointer and keys do.
//!
//! Each browser gets a fresh profile, removed when it is dropped with the browser's process.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

/// Chromium on `PATH`, or why not.
pub fn find() -> Result<PathBuf, String> {
    std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default())
        .map(|d| d.join("chromium"))
        .find(|p| p.is_file())
        .ok_or_else(|| "chromium is not on PATH: install Debian's chromium package (apt-get install chromium)".into())
}

/// A headless Chromium and the pages it was asked to open.
#[derive(Debug)]
pub struct Browser {
    child: Child,
    to: ChildStdin,
    from: BufReader<ChildStdout>,
    profile: PathBuf,
    next: u64,
    /// What each page logged as an error or warning, and every exception it threw: its session, and what.
    pub console: Vec<(String, String)>,
    /// The frames of another origin attached to a page ([`Browser::open_with_frames`]): the page's session,
    /// the frame's session and its address.
    pub frames: Vec<(String, String, String)>,
}

impl Browser {
    /// `chromium` started headless with a fresh profile at `profile` (whatever was there is removed).
    pub fn start(chromium: &Path, profile: PathBuf) -> Result<Browser, String> {
        let _ = std::fs::remove_dir_all(&profile);
        std::fs::create_dir_all(&profile).map_err(|e| format!("{}: {e}", profile.display()))?;
        // The shell hands the pipes over as descriptors 3 and 4.
        let script = r#"exec "$0" --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking \
            --disable-component-update --disable-sync --remote-debugging-pipe --user-data-dir="$1" \
            3<&0 4>&1 0</dev/null 1>/dev/null 2>/dev/null"#;
        let mut child = Command::new("sh")
            .args(["-c", script])
            .arg(chromium)
            .arg(&profile)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| format!("{}: {e}", chromium.display()))?;
        let (Some(to), Some(from)) = (child.stdin.take(), child.stdout.take()) else {
            let _ = child.kill();
            return Err("chromium's pipes were not given".into());
        };
        Ok(Browser { child, to, from: BufReader::new(from), profile, next: 0, console: Vec::new(), frames: Vec::new() })
    }

    /// Sends `method` with `params` (to the page of `session`, or to the browser) and returns its result;
    /// the console events and attached frames read meanwhile are kept.
    pub fn send(&mut self, session: Option<&str>, method: &str, params: Value) -> Result<Value, String> {
        self.next += 1;
        let mut message = json!({ "id": self.next, "method": method, "params": params });
        if let Some(s) = session {
            message["sessionId"] = Value::String(s.into());
        }
        let broken = |e: std::io::Error| format!("chromium's pipe: {e}");
        self.to.write_all(message.to_string().as_bytes()).map_err(broken)?;
        self.to.write_all(b"\0").map_err(broken)?;
        self.to.flush().map_err(broken)?;
        loop {
            let mut bytes = Vec::new();
            self.from.read_until(0, &mut bytes).map_err(broken)?;
            if !bytes.ends_with(b"\0") {
                return Err(format!("{method}: chromium closed its pipe"));
            }
            let answer: Value =
                serde_json::from_slice(&bytes[..bytes.len() - 1]).map_err(|e| format!("{method}: {e}"))?;
            if answer["id"].as_u64() == Some(self.next) {
                return match answer.get("error") {
                    Some(error) => Err(format!("{method}: {error}")),
                    None => Ok(answer["result"].clone()),
                };
            }
            self.keep(&answer);
        }
    }

    /// The console events and attached frames of an event the browser sent.
    fn keep(&mut self, event: &Value) {
        let from = event["sessionId"].as_str().unwrap_or("").to_string();
        let params = &event["params"];
        if event["method"] == "Target.attachedToTarget" {
            let (session, url) = (&params["sessionId"], &params["targetInfo"]["url"]);
            self.frames.push((from.clone(), session.as_str().unwrap_or("").into(), url.as_str().unwrap_or("").into()));
        }
        let said = match event["method"].as_str() {
            Some("Runtime.consoleAPICalled") if matches!(params["type"].as_str(), Some("error" | "warning")) => {
                Some(params["args"].to_string())
            }
            Some("Runtime.exceptionThrown") => Some(params["exceptionDetails"].to_string()),
            Some("Log.entryAdded") if params["entry"]["level"] != "info" => Some(params["entry"].to_string()),
            _ => None,
        };
        if let Some(said) = said {
            self.console.push((from, said));
        }
    }

    /// A new page at `url`, attached: its session.
    pub fn open(&mut self, url: &str) -> Result<String, String> {
        self.open_with_frames(url, false)
    }

    /// A new page at `url`, attached, and with `frames` each frame of another origin it shows attached too
    /// (listed in [`Browser::frames`] once loaded): the page's session.
    pub fn open_with_frames(&mut self, url: &str, frames: bool) -> Result<String, String> {
        let target = self.send(None, "Target.createTarget", json!({ "url": "about:blank" }))?;
        let attached =
            self.send(None, "Target.attachToTarget", json!({ "targetId": target["targetId"], "flatten": true }))?;
        let session = attached["sessionId"].as_str().ok_or("Target.attachToTarget: no session")?.to_string();
        for domain in ["Runtime.enable", "Log.enable", "Page.enable"] {
            self.send(Some(&session), domain, json!({}))?;
        }
        if frames {
            let attach = json!({ "autoAttach": true, "waitForDebuggerOnStart": false, "flatten": true });
            self.send(Some(&session), "Target.setAutoAttach", attach)?;
        }
        self.send(Some(&session), "Page.navigate", json!({ "url": url }))?;
        Ok(session)
    }

    /// The value of the script `expression` in the page of `session` (awaited when it is a promise); with
    /// `command_line`, the DevTools console's own functions (`getEventListeners`) are in scope.
    pub fn evaluate_with(&mut self, session: &str, expression: &str, command_line: bool) -> Result<Value, String> {
        let params = json!({ "expression": expression, "returnByValue": true, "awaitPromise": true,
                             "includeCommandLineAPI": command_line });
        let result = self.send(Some(session), "Runtime.evaluate", params)?;
        match result.get("exceptionDetails") {
            Some(thrown) => Err(format!("{expression}: {thrown}")),
            None => Ok(result["result"]["value"].clone()),
        }
    }

    /// The value of the script `expression` in the page of `session` (awaited when it is a promise).
    pub fn evaluate(&mut self, session: &str, expression: &str) -> Result<Value, String> {
        self.evaluate_with(session, expression, false)
    }

    /// The JSON a page's script keeps in its `<output id="ID">` (as `elastokin live`'s page keeps what it
    /// did in `live-state`) once `ready` holds of it, read every 20 ms for at most `limit`.
    pub fn output_when(
        &mut self,
        session: &str,
        id: &str,
        ready: impl Fn(&Value) -> bool,
        limit: std::time::Duration,
    ) -> Result<Value, String> {
        let start = std::time::Instant::now();
        let read = format!("(document.getElementById('{id}') || {{}}).textContent || ''");
        loop {
            let text = self.evaluate(session, &read)?;
            let kept = text.as_str().and_then(|t| serde_json::from_str::<Value>(t).ok());
            if let Some(kept) = kept.filter(|k| ready(k)) {
                return Ok(kept);
            }
            if start.elapsed() > limit {
                return Err(format!("the page's {id} did not get there within {limit:?}: {text}"));
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }

    /// The mouse's `kind` of event (`mousePressed`, `mouseMoved`, `mouseReleased`) at `at` (CSS pixels of
    /// the page's viewport), its left button held while `held`, as a user's mouse gives it.
    pub fn mouse(&mut self, session: &str, kind: &str, at: (f64, f64), held: bool) -> Result<(), String> {
        let params = json!({ "type": kind, "x": at.0, "y": at.1, "button": "left",
                             "buttons": u8::from(held), "clickCount": 1 });
        self.send(Some(session), "Input.dispatchMouseEvent", params).map(drop)
    }

    /// The key `key` (its DOM name, code and Windows key code) pressed and released.
    pub fn key(&mut self, session: &str, key: &str, code: u32) -> Result<(), String> {
        for kind in ["keyDown", "keyUp"] {
            let params = json!({ "type": kind, "key": key, "code": key, "windowsVirtualKeyCode": code });
            self.send(Some(session), "Input.dispatchKeyEvent", params)?;
        }
        Ok(())
    }

    /// The page of `session` laid out in a window of `size` CSS pixels (one device pixel each).
    pub fn window(&mut self, session: &str, size: (u32, u32)) -> Result<(), String> {
        let metrics = json!({ "width": size.0, "height": size.1, "deviceScaleFactor": 1, "mobile": false });
        self.send(Some(session), "Emulation.setDeviceMetricsOverride", metrics).map(drop)
    }

    /// The part of the page of `session` at `top` (CSS pixels from the page's top) of `size` (width and
    /// height) as a PNG picture, drawn whether or not it is in the window.
    pub fn picture(&mut self, session: &str, top: f64, size: (u32, u32)) -> Result<Vec<u8>, String> {
        use base64::Engine;
        let clip = json!({ "x": 0, "y": top, "width": size.0, "height": size.1, "scale": 1 });
        let params = json!({ "format": "png", "clip": clip, "captureBeyondViewport": true });
        let shot = self.send(Some(session), "Page.captureScreenshot", params)?;
        let data = shot["data"].as_str().ok_or("Page.captureScreenshot: no picture")?;
        base64::engine::general_purpose::STANDARD.decode(data).map_err(|e| format!("the page's picture: {e}"))
    }

    /// A press at `from`, the mouse moved by each of `path` (from where it was pressed) in turn, then,
    /// with `escape`, the Escape key pressed, and the button released where the path ends.
    pub fn drag(&mut self, session: &str, from: (f64, f64), path: &[(f64, f64)], escape: bool) -> Result<(), String> {
        self.mouse(session, "mousePressed", from, true)?;
        let mut at = from;
        for (dx, dy) in path {
            at = (from.0 + dx, from.1 + dy);
            self.mouse(session, "mouseMoved", at, true)?;
        }
        if escape {
            self.key(session, "Escape", 27)?;
        }
        self.mouse(session, "mouseReleased", at, false)
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}
