//! `elastokin live MODEL`: the design served over HTTP on this machine, its numbers moved from a browser
//! and its analyses run again on each move (`elastokin::live` holds the routes and who may be served;
//! this module carries requests between the socket and them).
//!
//! The server is tiny_http: synchronous, as the engine is (each request is served in turn on this thread,
//! the analyses on rayon as everywhere else), six crates in all. Measured against axum on tokio, each
//! serving one small POST on this machine's loopback (release builds): a request on a fresh connection took
//! 0.11 ms (median) against axum's 0.08 ms, both far inside an analysis's run; tiny_http built from
//! nothing in 11 s with 6 crates against axum's 66 s with 45, and the stripped test program was 0.7 MB against
//! 1.3 MB.

use super::input::{read_input, read_targets_file};
use super::sweeps::{AnalysisName, LoadSteps};
use crate::output::{note, on_interrupt_stop, Failure, Stdout};
use clap::Args;
use elastokin::live::{Head, Live, Response, Token, BODY_LIMIT};
use elastokin::suspensions::design::live::LiveDesign;
use elastokin::suspensions::design::targets::Reading;
use elastokin::suspensions::kc::Settings;
use std::io::Read;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(Debug, Args)]
pub struct LiveArgs {
    /// The model file (JSON; see examples/*.json): the design served, and the one file a save writes
    pub model: PathBuf,
    /// An analysis to run on every design, as often as wanted (default: the suite)
    #[arg(long = "analysis", value_enum, value_name = "NAME")]
    pub analyses: Vec<AnalysisName>,
    #[command(flatten)]
    pub load: LoadSteps,
    /// A TARGETS file (as `tune` reads, `free` optional) every design is judged against: each figure and
    /// curve target and packaging constraint met or not
    #[arg(long, value_name = "FILE")]
    pub targets: Option<PathBuf>,
    /// The address to listen on (default 127.0.0.1, this machine alone); any other is reachable from
    /// elsewhere, and the command warns
    #[arg(long, value_name = "ADDR")]
    pub bind: Option<IpAddr>,
    /// The port to listen on (default: any free one)
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub port: u16,
    /// Print the address without opening it in a browser
    #[arg(long)]
    pub no_open: bool,
}

/// `live`: the design served until Ctrl-C.
pub fn run(args: LiveArgs, out: &Stdout) -> Result<(), Failure> {
    let which: Vec<_> = args.analyses.iter().map(|a| a.analysis()).collect();
    // The parts' poses at every row, for the page's projections of the geometry.
    let settings = Settings { steps: args.load.steps, motion: true, ..Settings::default() };
    super::sweeps::check_each(&which, &settings)?;
    let (_, text) = read_input(&args.model, "MODEL")?;
    let origin = args.model.display().to_string();
    let mut design = LiveDesign::open(&text, &origin, &which, settings).map_err(|e| Failure::Input(e.to_string()))?;
    if let Some(path) = &args.targets {
        let document = design.document().map_err(|e| Failure::Input(e.to_string()))?;
        let (_, targets) = read_targets_file(path, &document, Reading::ToJudge)?;
        design = design.judged_against(targets);
    }
    let ip = args.bind.unwrap_or(IpAddr::V4(Ipv4Addr::LOCALHOST));
    if !ip.is_loopback() {
        note(format!(
            "warning: listening on {ip}, reachable from other machines: anyone who learns the address with its \
             token can edit and save {origin}"
        ));
    }
    let server = tiny_http::Server::http(SocketAddr::new(ip, args.port)).map_err(|e| {
        Failure::Input(format!("cannot listen on {ip} port {}: {e} (choose another with --port)", args.port))
    })?;
    let bound =
        server.server_addr().to_ip().ok_or_else(|| Failure::Run("the server is listening on no IP address".into()))?;
    let token = Token::random().map_err(Failure::Run)?;
    let mut live = Live::new(design, text, &args.model, token, bound);
    let server = Arc::new(server);
    let stop = Arc::new(AtomicBool::new(false));
    {
        let (server, stop) = (Arc::clone(&server), Arc::clone(&stop));
        on_interrupt_stop(move || {
            stop.store(true, Ordering::SeqCst);
            server.unblock();
        });
    }
    out.line(format!("{} — serving {origin} at", live.design().current().report.model))?;
    // The address is what the command gives: printed even under --quiet.
    println!("{}", live.address());
    out.line("Ctrl-C stops the server")?;
    if !args.no_open {
        open_in_browser(&live.address());
    }
    while !stop.load(Ordering::SeqCst) {
        let Ok(request) = server.recv() else { continue };
        serve(&mut live, request);
    }
    if live.unsaved() {
        note(format!("stopped: the edits since the last save are not in {origin}"));
    } else {
        note("stopped");
    }
    Ok(())
}

/// One request answered: refused on its head alone when it may not be served, its body read to at most
/// [`BODY_LIMIT`] bytes, and routed.
fn serve(live: &mut Live, mut request: tiny_http::Request) {
    let header = |name: &'static str| {
        request.headers().iter().find(|h| h.field.equiv(name)).map(|h| h.value.as_str().to_string())
    };
    let (host, origin) = (header("Host"), header("Origin"));
    let method = request.method().as_str().to_string();
    let url = request.url().to_string();
    let head = Head {
        method: &method,
        url: &url,
        host: host.as_deref(),
        origin: origin.as_deref(),
        content_length: request.body_length(),
    };
    let response = match live.admit(&head) {
        Err(refused) => refused,
        Ok(()) => {
            let mut body = Vec::new();
            let limit = u64::try_from(BODY_LIMIT).unwrap_or(u64::MAX).saturating_add(1);
            match request.as_reader().take(limit).read_to_end(&mut body) {
                Ok(_) if body.len() > BODY_LIMIT => Response::too_large(),
                Ok(_) => live.handle(&head, &body),
                Err(e) => {
                    note(format!("a request's body could not be read: {e}"));
                    return;
                }
            }
        }
    };
    let content_type = tiny_http::Header::from_bytes(&b"Content-Type"[..], response.content_type.as_bytes());
    // Sent whole with its length, never in chunks: the answer is in memory already.
    let mut answer = tiny_http::Response::from_data(response.body)
        .with_status_code(response.status)
        .with_chunked_threshold(usize::MAX);
    if let Ok(h) = content_type {
        answer.add_header(h);
    }
    // Nothing the server sends may be kept by a cache or framed by another page.
    for (name, value) in [("Cache-Control", "no-store"), ("X-Frame-Options", "SAMEORIGIN")] {
        if let Ok(h) = tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes()) {
            answer.add_header(h);
        }
    }
    if let Err(e) = request.respond(answer) {
        note(format!("a response could not be sent: {e}"));
    }
}

/// Opens `address` in the desktop's browser, or says how to.
fn open_in_browser(address: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    let opened = std::process::Command::new(opener)
        .arg(address)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    match opened {
        // Waited for on a thread of its own, so that the opener leaves no process behind.
        Ok(mut child) => drop(std::thread::spawn(move || child.wait())),
        Err(_) => note(format!("no browser opened ({opener} is not there): open the address above in one")),
    }
}
