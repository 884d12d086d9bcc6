//! `elastokin live MODEL`: the design served over HTTP on this machine, its numbers moved from a browser
//! and its analyses run again on each move, until Ctrl-C. The server is the library's
//! (`elastokin::live::LiveServer`, which tells its choice of HTTP library); this module reads the
//! arguments, starts it, opens the browser and stops it on Ctrl-C.

use super::input::read_targets_file;
use super::sweeps::{AnalysisName, LoadSteps};
use crate::output::{note, on_interrupt_stop, Failure, Stdout};
use clap::Args;
use elastokin::live::{reachable_from_elsewhere, FrameAncestors, LiveServer, ServeError, Served};
use elastokin::suspensions::design::targets::Reading;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;

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
    let mut served = Served::open(&args.model, &which, args.load.steps).map_err(|e| Failure::Input(e.to_string()))?;
    if let Some(path) = &args.targets {
        let document = served.design.document().map_err(|e| Failure::Input(e.to_string()))?;
        let (_, targets) = read_targets_file(path, &document, Reading::ToJudge)?;
        served.design = served.design.judged_against(targets);
    }
    let origin = args.model.display().to_string();
    let model = served.design.current().report.model.clone();
    let ip = args.bind.unwrap_or(IpAddr::V4(Ipv4Addr::LOCALHOST));
    if let Some(warning) = reachable_from_elsewhere(ip, &origin) {
        note(format!("warning: {warning}"));
    }
    // Framed by its own origin alone: a browser tab needs no other.
    let mut server =
        LiveServer::start(served, SocketAddr::new(ip, args.port), FrameAncestors::none()).map_err(|e| match e {
            e @ ServeError::Listen { .. } => Failure::Input(format!("{e} (choose another with --port)")),
            e => Failure::Run(e.to_string()),
        })?;
    let stopper = server.stopper();
    on_interrupt_stop(move || stopper.stop());
    out.line(format!("{model} — serving {origin} at"))?;
    // The address is what the command gives: printed even under --quiet.
    println!("{}", server.address());
    out.line("Ctrl-C stops the server")?;
    if !args.no_open {
        open_in_browser(server.address());
    }
    match server.wait() {
        Some(live) if live.unsaved() => note(format!("stopped: the edits since the last save are not in {origin}")),
        Some(_) => note("stopped"),
        None => return Err(Failure::Run("the server stopped on an error of its own (said above)".into())),
    }
    Ok(())
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
