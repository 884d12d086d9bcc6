//! `elastokin live`'s server: a design edited from a browser over HTTP on this machine. What a request is
//! read as and answered with ([`request`]), who may be served and who may frame the page ([`admission`]),
//! the routes on the design (`design::live`) as plain functions from a request to its response
//! ([`routes`]), and the server that carries requests between a socket and them on a thread of its own
//! ([`server`]: started on an address, stopped on request or when dropped). Only [`server`] knows the
//! HTTP library; everything else is testable without a socket. The command (`src/command/live.rs`) and
//! Python's `Model.live` start the same [`LiveServer`].
//!
//! Safe by default: every request names the server's token, 128 random bits in hex, as the first segment of
//! its path, compared in constant time; its Host must be the address the server is bound to (or
//! `localhost` at its port), which keeps a name that a foreign page rebinds to this machine away; an
//! Origin, when the browser sends one, must be the server's own, so that no other page open in the browser
//! can drive it. Anything else is refused with 403, and a body over [`BODY_LIMIT`] with 413. The page may
//! be framed by its own origin alone unless the server is given the origins that may frame it
//! ([`FrameAncestors`]: a notebook's).
//!
//! Routes, each under `/TOKEN`: `GET /` the page (`html::live_html`); `GET /state` the current design
//! (`design::live::State`); `POST /edit` with `{"pointer": "/json/pointer", "value": number}` (SI, as the
//! model file stores it) a new design; `POST /undo`, `POST /redo`; `POST /save` the model file written
//! where it was read; `POST /guidance` with `{"point": "/…/hardpoints/NAME"}` every figure's derivatives
//! to that hardpoint's x, y and z; `POST /tune` the TARGETS file's free numbers tuned from the current
//! design, one design more. A design refused comes back with the reason and the design kept.

pub mod admission;
pub mod request;
pub mod routes;
pub mod server;

pub use admission::{Admission, FrameAncestors, FramingError, Token};
pub use request::{Head, Response, BODY_LIMIT};
pub use routes::{Live, OpenError, Served};
pub use server::{reachable_from_elsewhere, LiveServer, ServeError, Stopper};
