//! `elastokin live` over real HTTP on the loopback: who is refused (no token, a wrong one, a foreign Origin
//! or Host, a body over the limit), an edit's figures against `elastokin run` on the file edited by hand,
//! undo, two clients seeing one design, a save writing the file with the moved number alone rewritten, and
//! Ctrl-C stopping the server with nothing left behind.

use serde_json::Value;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const RATE: &str = "/suspension/macpherson/spring/rate";
const TIE_ROD_INNER_Z: &str = "/suspension/macpherson/hardpoints/tie_rod_inner/2";

/// A server started on a copy of the MacPherson example in a directory of its own.
struct Server {
    child: Child,
    dir: PathBuf,
    model: PathBuf,
    port: u16,
    token: String,
}

impl Server {
    fn start(name: &str, more: &[&str]) -> Server {
        let dir = std::env::temp_dir().join(format!("elastokin-live-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let model = dir.join("macpherson.json");
        std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/macpherson.json"), &model).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_elastokin"))
            .args(["live", "--no-open", "--analysis", "parallel-travel", "--steps", "8"])
            .args(more)
            .arg(&model)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let address = lines.find_map(|l| l.ok().filter(|l| l.starts_with("http://"))).expect("the address printed");
        // http://127.0.0.1:PORT/TOKEN/
        let rest = address.strip_prefix("http://127.0.0.1:").unwrap();
        let (port, token) = rest.split_once('/').unwrap();
        let token = token.trim_end_matches('/').to_string();
        assert_eq!(token.len(), 32, "{address}");
        Server { child, dir, model, port: port.parse().unwrap(), token }
    }

    fn host(&self) -> String {
        format!("127.0.0.1:{}", self.port)
    }

    /// A request with the server's own Host and no Origin.
    fn ask(&self, method: &str, path: &str, body: &str) -> (u16, Value) {
        self.raw(method, path, &[("Host", &self.host())], body.as_bytes())
    }

    /// A request under the token.
    fn call(&self, method: &str, route: &str, body: &str) -> (u16, Value) {
        self.ask(method, &format!("/{}/{route}", self.token), body)
    }

    /// A request as written: `headers` and `body` (its Content-Length added), on a connection of its own.
    fn raw(&self, method: &str, path: &str, headers: &[(&str, &str)], body: &[u8]) -> (u16, Value) {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        let mut head = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\nContent-Length: {}\r\n", body.len());
        for (name, value) in headers {
            head.push_str(&format!("{name}: {value}\r\n"));
        }
        head.push_str("\r\n");
        stream.write_all(head.as_bytes()).unwrap();
        // A refused body may be cut off by the server: what matters is its answer.
        let _ = stream.write_all(body);
        read_response(stream)
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The status and JSON body of a response read to the end of the connection.
fn read_response(mut stream: TcpStream) -> (u16, Value) {
    let mut bytes = Vec::new();
    let _ = stream.read_to_end(&mut bytes);
    let text = String::from_utf8_lossy(&bytes);
    let status = text.split(' ').nth(1).and_then(|s| s.parse().ok()).unwrap_or_else(|| panic!("no status: {text}"));
    let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or_else(|e| panic!("{e}: {text}")))
}

/// The SI value of figure `key` of parallel travel in a state.
fn figure(state: &Value, key: &str) -> f64 {
    let analysis = state["analyses"].as_array().unwrap().iter().find(|a| a["name"] == "parallel-travel").unwrap();
    let figures = analysis["figures"].as_array().unwrap();
    figures.iter().find(|f| f["key"] == key).unwrap()["value"].as_f64().unwrap()
}

/// A request refused or served: what it is, its path, its headers and the status expected.
type Case<'a> = (&'a str, &'a str, Vec<(&'a str, &'a str)>, u16);

#[test]
fn every_request_without_the_token_or_from_elsewhere_is_refused() {
    let server = Server::start("refusals", &["--targets", "examples/targets/macpherson.json"]);
    let host = server.host();
    let state = format!("/{}/state", server.token);
    let wrong = format!("/{}/state", "0".repeat(32));
    let own = format!("http://{host}");
    let cases: [Case; 8] = [
        ("the token's own request", &state, vec![("Host", &host)], 200),
        ("no token", "/state", vec![("Host", &host)], 403),
        ("the root", "/", vec![("Host", &host)], 403),
        ("a wrong token", &wrong, vec![("Host", &host)], 403),
        ("a foreign Origin", &state, vec![("Host", &host), ("Origin", "http://evil.example")], 403),
        ("a foreign Host", &state, vec![("Host", "evil.example")], 403),
        ("another port", &state, vec![("Host", "127.0.0.1:1")], 403),
        ("its own Origin", &state, vec![("Host", &host), ("Origin", &own)], 200),
    ];
    for (what, path, headers, expected) in cases {
        let (status, body) = server.raw("GET", path, &headers, b"");
        assert_eq!(status, expected, "{what}: {body}");
        if expected == 403 {
            assert!(body["error"].is_string() && body.get("state").is_none(), "{what}: {body}");
        }
    }
    // A body over the limit, said by its length or sent in chunks.
    let edit = format!("/{}/edit", server.token);
    let (status, _) = server.raw("POST", &edit, &[("Host", &host)], &vec![b' '; (1 << 20) + 1]);
    assert_eq!(status, 413);
    let mut stream = TcpStream::connect(("127.0.0.1", server.port)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let head =
        format!("POST {edit} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\nTransfer-Encoding: chunked\r\n\r\n");
    stream.write_all(head.as_bytes()).unwrap();
    let chunk = format!("{:x}\r\n{}\r\n", 1 << 16, " ".repeat(1 << 16));
    for _ in 0..17 {
        if stream.write_all(chunk.as_bytes()).is_err() {
            break;
        }
    }
    let _ = stream.write_all(b"0\r\n\r\n");
    assert_eq!(read_response(stream).0, 413);
    // Still serving, the design untouched; judged against the targets given.
    let (status, body) = server.call("GET", "state", "");
    assert_eq!((status, body["state"]["version"].as_u64()), (200, Some(1)));
    let targets = body["state"]["targets"].as_array().unwrap();
    let judged: Vec<(&str, bool)> =
        targets.iter().map(|t| (t["figure"].as_str().unwrap(), t["met"].as_bool().unwrap())).collect();
    assert_eq!(judged, [("bump_steer", true), ("wheel_rate", true)], "the shipped example meets its targets");
}

#[test]
fn an_edit_answers_as_the_file_edited_by_hand_runs_and_a_save_writes_that_file() {
    let server = Server::start("edit", &[]);
    let original = std::fs::read_to_string(&server.model).unwrap();
    let (status, first) = server.call("GET", "state", "");
    assert_eq!(status, 200);
    let first_bump = figure(&first["state"], "bump_steer");

    let edit = format!(r#"{{"pointer": "{TIE_ROD_INNER_Z}", "value": -0.0394}}"#);
    let (status, edited) = server.call("POST", "edit", &edit);
    assert_eq!(status, 200, "{edited}");
    assert_eq!(edited["state"]["version"].as_u64(), Some(2));

    // The file edited by hand, run by `elastokin run`.
    let by_hand = original.replacen("[-0.150, 0.370, -0.0374]", "[-0.150, 0.370, -0.0394]", 1);
    assert_ne!(by_hand, original);
    let hand = server.dir.join("by_hand.json");
    std::fs::write(&hand, &by_hand).unwrap();
    let out = server.dir.join("out");
    let ran = Command::new(env!("CARGO_BIN_EXE_elastokin"))
        .args(["run", "--quiet", "--analysis", "parallel-travel", "--steps", "8", "--out"])
        .args([&out, &hand])
        .output()
        .unwrap();
    assert!(ran.status.success(), "{}", String::from_utf8_lossy(&ran.stderr));
    let summary: Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let ran_figures = summary["analyses"]["parallel-travel"]["figures"].as_object().unwrap();
    for key in ["bump_steer", "camber_gain", "wheel_rate", "caster", "scrub_radius"] {
        let (live, run) = (figure(&edited["state"], key), ran_figures[key]["si_value"].as_f64().unwrap());
        // The same file read the same way: equal to the bit (the issue asks 1e-9).
        assert_eq!(live.to_bits(), run.to_bits(), "{key}: live {live}, run {run}");
    }
    assert!((figure(&edited["state"], "bump_steer") - first_bump).abs() > 1e-3, "the edit moved bump steer");

    // A second client sees the same design.
    let (_, seen) = server.call("GET", "state", "");
    assert_eq!(seen["state"]["version"].as_u64(), Some(2));
    assert_eq!(seen["state"]["moved"][0]["pointer"], TIE_ROD_INNER_Z);

    // A refused edit keeps the design and says why.
    let (status, refused) = server.call("POST", "edit", &format!(r#"{{"pointer": "{RATE}", "value": -1}}"#));
    assert_eq!(status, 422);
    assert!(refused["error"].as_str().unwrap().contains("rate"), "{refused}");
    assert_eq!(refused["state"]["version"].as_u64(), Some(2));

    // Undo, redo, save: the file is the one edited by hand, byte for byte.
    let (status, undone) = server.call("POST", "undo", "");
    assert_eq!((status, figure(&undone["state"], "bump_steer")), (200, first_bump));
    let (status, _) = server.call("POST", "redo", "");
    assert_eq!(status, 200);
    let (status, saved) = server.call("POST", "save", "");
    assert_eq!(status, 200, "{saved}");
    assert_eq!(std::fs::read_to_string(&server.model).unwrap(), by_hand);
    let mut left: Vec<String> =
        std::fs::read_dir(&server.dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    left.sort();
    assert_eq!(left, ["by_hand.json", "macpherson.json", "out"], "a save leaves no file beside the model");

    // A file changed on disk since is not written over.
    std::fs::write(&server.model, &original).unwrap();
    let (status, refused) = server.call("POST", "save", "");
    assert_eq!(status, 409, "{refused}");
    assert_eq!(std::fs::read_to_string(&server.model).unwrap(), original);
}

#[test]
fn ctrl_c_stops_the_server_and_leaves_nothing_behind() {
    let mut server = Server::start("interrupt", &[]);
    let (status, _) = server.call("POST", "edit", &format!(r#"{{"pointer": "{RATE}", "value": 26000}}"#));
    assert_eq!(status, 200);
    let interrupted = Command::new("kill").args(["-INT", &server.child.id().to_string()]).status().unwrap();
    assert!(interrupted.success());
    let start = Instant::now();
    let status = loop {
        if let Some(status) = server.child.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "the server did not stop");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "{status}");
    let mut said = String::new();
    server.child.stderr.take().unwrap().read_to_string(&mut said).unwrap();
    assert!(said.contains("not in") && said.contains("macpherson.json"), "unsaved edits are told: {said}");
    let left: Vec<_> = std::fs::read_dir(&server.dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["macpherson.json"]);
    assert!(TcpStream::connect(("127.0.0.1", server.port)).is_err(), "the port is closed");
}
