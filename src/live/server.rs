//! The server: a socket on an address, and a thread of its own that carries each request between it and
//! [`Live::handle`] in turn, until it is asked to stop.
//!
//! The socket is tiny_http's: synchronous, as the engine is (each request is served in turn on the
//! server's thread, the analyses on rayon as everywhere else), six crates in all. Measured against axum on
//! tokio, each serving one small POST on this machine's loopback (release builds): a request on a fresh
//! connection took 0.11 ms (median) against axum's 0.08 ms, both far inside an analysis's run; tiny_http
//! built from nothing in 11 s with 6 crates against axum's 66 s with 45, and the stripped test program was
//! 0.7 MB against 1.3 MB.
//!
//! Every answer says `Connection: close`, so that a browser closes the connection once it has read the
//! answer (by its length): tiny_http keeps a thread reading each open connection and closes one itself only
//! when the request asked it to, and a connection a browser kept open would outlive a stopped server, its
//! next request waiting on a server that is gone. Closed after each answer, a page's next request to a
//! stopped server is refused at once; on the loopback a new connection costs a tenth of a millisecond.

use super::admission::{Admission, FrameAncestors, Token};
use super::request::{Head, Response, BODY_LIMIT};
use super::routes::{Live, Served};
use std::io::{Read, Write};
use std::net::{IpAddr, SocketAddr, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Weak};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a stop waits for the listening socket to close once the server's thread has ended.
const CLOSING: Duration = Duration::from_secs(5);

/// Why a server did not start.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The address and port could not be listened on.
    #[error("cannot listen on {ip} port {port}: {why}")]
    Listen {
        /// The address asked for.
        ip: IpAddr,
        /// The port asked for.
        port: u16,
        /// The operating system's reason.
        why: String,
    },
    /// No token could be made.
    #[error("{0}")]
    Token(String),
    /// The server's thread could not be started.
    #[error("the server's thread did not start: {0}")]
    Thread(String),
}

/// A design served on a thread of its own: started on an address ([`LiveServer::start`]), stopped by
/// [`LiveServer::stop`], by a [`Stopper`] and [`LiveServer::wait`], or when dropped. Stopped, its thread
/// has ended and its port is free.
#[derive(Debug)]
pub struct LiveServer {
    address: String,
    bound: SocketAddr,
    stopper: Stopper,
    serving: Option<JoinHandle<Live>>,
}

/// What asks a server to stop, from any thread (a Ctrl-C handler's): the server finishes the request it
/// is serving, answers those already received that the server has stopped, and its thread ends.
#[derive(Clone)]
pub struct Stopper {
    stop: Arc<AtomicBool>,
    /// The socket, held by the server's thread alone: a stopper kept after the server has stopped keeps
    /// no port open.
    server: Weak<tiny_http::Server>,
}

impl std::fmt::Debug for Stopper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stopper").field("stopped", &self.stop.load(Ordering::SeqCst)).finish()
    }
}

impl Stopper {
    /// Asks the server to stop; returns at once.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(server) = self.server.upgrade() {
            server.unblock();
        }
    }
}

impl LiveServer {
    /// `served` on `bind` (port 0: any free one), its page framed by its own origin and `frame_ancestors`,
    /// with a new token; serving on its own thread when this returns.
    pub fn start(served: Served, bind: SocketAddr, frame_ancestors: FrameAncestors) -> Result<LiveServer, ServeError> {
        let listen = |why: String| ServeError::Listen { ip: bind.ip(), port: bind.port(), why };
        let server = tiny_http::Server::http(bind).map_err(|e| listen(e.to_string()))?;
        let bound = server.server_addr().to_ip().ok_or_else(|| listen("not an IP address".into()))?;
        let admission = Admission::new(Token::random().map_err(ServeError::Token)?, bound, frame_ancestors);
        let address = admission.address();
        let server = Arc::new(server);
        let stop = Arc::new(AtomicBool::new(false));
        let stopper = Stopper { stop: Arc::clone(&stop), server: Arc::downgrade(&server) };
        let live = Live::new(served, admission);
        let serving = std::thread::Builder::new()
            .name("elastokin live".into())
            .spawn(move || serve(server, &stop, live))
            .map_err(|e| ServeError::Thread(e.to_string()))?;
        Ok(LiveServer { address, bound, stopper, serving: Some(serving) })
    }

    /// The page's address, token included: `http://127.0.0.1:PORT/TOKEN/`.
    pub fn address(&self) -> &str {
        &self.address
    }

    /// The address and port listened on.
    pub fn bound(&self) -> SocketAddr {
        self.bound
    }

    /// What asks this server to stop from another thread.
    pub fn stopper(&self) -> Stopper {
        self.stopper.clone()
    }

    /// Stops the server and waits until it has stopped ([`LiveServer::wait`]).
    pub fn stop(&mut self) -> Option<Live> {
        self.stopper.stop();
        self.wait()
    }

    /// Waits until the server has been stopped (by a [`Stopper`]), its thread has ended and its port is
    /// free; the design as it was left, or `None` when the server's thread has ended already or panicked
    /// (the panic said on standard error).
    pub fn wait(&mut self) -> Option<Live> {
        let live = self.serving.take()?.join().ok();
        closed(self.bound);
        live
    }
}

impl Drop for LiveServer {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The server's thread: each request received answered in turn until a stop is asked, then the requests
/// already received answered that the server has stopped. The socket is dropped with the last reference
/// to it, here.
fn serve(server: Arc<tiny_http::Server>, stop: &AtomicBool, mut live: Live) -> Live {
    while !stop.load(Ordering::SeqCst) {
        // An error is a wake-up by a stopper (or a failed accept, after which nothing more arrives).
        if let Ok(request) = server.recv() {
            answer(&mut live, request);
        }
    }
    while let Ok(Some(request)) = server.try_recv() {
        let headers = live.admission().headers();
        respond(request, &Response::stopped(), &headers);
    }
    live
}

/// Waits until nothing listens at `bound` any more, for at most [`CLOSING`]: tiny_http closes its
/// listening socket on a thread of its own once its server is dropped, and gives no handle to wait for it.
fn closed(bound: SocketAddr) {
    let at = match bound.ip() {
        ip if ip.is_unspecified() && ip.is_ipv4() => SocketAddr::new(IpAddr::from([127, 0, 0, 1]), bound.port()),
        ip if ip.is_unspecified() => SocketAddr::new(IpAddr::from(std::net::Ipv6Addr::LOCALHOST), bound.port()),
        _ => bound,
    };
    let started = Instant::now();
    while started.elapsed() < CLOSING && TcpStream::connect_timeout(&at, Duration::from_millis(200)).is_ok() {
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// One request answered: refused on its head alone when it may not be served, its body read to at most
/// [`BODY_LIMIT`] bytes, and routed.
fn answer(live: &mut Live, mut request: tiny_http::Request) {
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
    let response = match live.admission().admit(&head) {
        Err(refused) => refused,
        Ok(()) => {
            let mut body = Vec::new();
            let limit = u64::try_from(BODY_LIMIT).unwrap_or(u64::MAX).saturating_add(1);
            match request.as_reader().take(limit).read_to_end(&mut body) {
                Ok(_) if body.len() > BODY_LIMIT => Response::too_large(),
                Ok(_) => live.handle(&head, &body),
                // The client went away while sending: there is no one to answer.
                Err(_) => return,
            }
        }
    };
    respond(request, &response, &live.admission().headers());
}

/// Writes `response` with `headers` as the answer to `request`, whole with its length, and closes the
/// connection. A client that has gone away is not answered.
fn respond(request: tiny_http::Request, response: &Response, headers: &[(&'static str, String)]) {
    let reason = tiny_http::StatusCode(response.status).default_reason_phrase();
    let mut out = format!(
        "HTTP/1.1 {} {reason}\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n",
        response.status,
        response.content_type,
        response.body.len()
    );
    for (name, value) in headers {
        out.push_str(&format!("{name}: {value}\r\n"));
    }
    out.push_str("\r\n");
    let mut writer = request.into_writer();
    let _ =
        writer.write_all(out.as_bytes()).and_then(|()| writer.write_all(&response.body)).and_then(|()| writer.flush());
}

/// What a server bound to `ip` warns of, serving the model file `model`: when the address is not this
/// machine's own, anyone who learns the address can edit and save the file.
pub fn reachable_from_elsewhere(ip: IpAddr, model: &str) -> Option<String> {
    (!ip.is_loopback()).then(|| {
        format!(
            "listening on {ip}, reachable from other machines: anyone who learns the address with its token can \
             edit and save {model}"
        )
    })
}
