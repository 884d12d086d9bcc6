//! Who the server serves and who may frame its page: the token every request names, the Host and Origin
//! it must come with, the body it may send, and the headers every answer carries.

use super::request::{Head, Response, BODY_LIMIT};
use std::net::{IpAddr, SocketAddr};
use subtle::ConstantTimeEq;

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

/// The origins, besides the page's own, whose pages may show it in a frame: a notebook's, which shows the
/// page in an `<iframe>` from an origin of its own (`http://localhost:8888`). Each is a source of a
/// Content-Security-Policy's `frame-ancestors`: `http` or `https`, a host (a name, a literal address, or
/// `*.` and a name), and a port or `*` for any (`http://localhost:*`).
///
/// Allowing a frame lets that origin's pages show the page; it lets none of them drive the server. A page
/// that frames it must know the address with its token, which only the program that started the server
/// has; every request of the framed page is its own, from its own origin, with the token, and a request
/// of the framing page (another Origin) is still refused. What framing could still be used for is
/// clickjacking, which needs the token too. With none given the page may be framed by its own origin
/// alone (`frame-ancestors 'self'` and `X-Frame-Options: SAMEORIGIN`, for browsers that read only that).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct FrameAncestors(Vec<String>);

impl FrameAncestors {
    /// The page's own origin alone.
    pub fn none() -> FrameAncestors {
        FrameAncestors(Vec::new())
    }

    /// `sources`, each checked to be an origin as a Content-Security-Policy writes one.
    pub fn new<S: AsRef<str>>(sources: impl IntoIterator<Item = S>) -> Result<FrameAncestors, FramingError> {
        let mut out = Vec::new();
        for source in sources {
            let source = source.as_ref().trim();
            if let Err(why) = check_source(source) {
                return Err(FramingError { given: source.to_string(), why });
            }
            out.push(source.to_string());
        }
        Ok(FrameAncestors(out))
    }

    /// The origins, as given.
    pub fn sources(&self) -> &[String] {
        &self.0
    }
}

/// Why a frame ancestor is refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("frame ancestor '{given}': {why}")]
pub struct FramingError {
    /// The source as given.
    pub given: String,
    /// What is wrong with it, and what to give.
    pub why: &'static str,
}

/// Whether `source` is a scheme, a host and an optional port as `frame-ancestors` takes it; why not.
fn check_source(source: &str) -> Result<(), &'static str> {
    let shape = "give an origin such as http://localhost:* or http://127.0.0.1:8888 (http or https, a host, a \
                 port or * for any)";
    let Some((scheme, rest)) = source.split_once("://") else { return Err(shape) };
    if !scheme.eq_ignore_ascii_case("http") && !scheme.eq_ignore_ascii_case("https") {
        return Err(shape);
    }
    // The port: the digits or `*` after the last colon outside an IPv6 literal's brackets.
    let (host, port) = match rest.rfind(':') {
        Some(at) if !rest[at..].contains(']') => (&rest[..at], Some(&rest[at + 1..])),
        _ => (rest, None),
    };
    if let Some(port) = port {
        let digits = !port.is_empty() && port.len() <= 5 && port.bytes().all(|b| b.is_ascii_digit());
        if port != "*" && !(digits && port.parse::<u16>().is_ok()) {
            return Err(shape);
        }
    }
    if host == "*" {
        return Err("any host at all could frame the page: name the notebook's host (http://localhost:*)");
    }
    if let Some(literal) = host.strip_prefix('[').and_then(|h| h.strip_suffix(']')) {
        return literal.parse::<std::net::Ipv6Addr>().map(|_| ()).map_err(|_| shape);
    }
    let name = host.strip_prefix("*.").unwrap_or(host);
    let label = |l: &str| !l.is_empty() && l.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'-');
    if name.split('.').all(label) {
        Ok(())
    } else {
        Err(shape)
    }
}

/// Who is served and who may frame the page: the token, the address the server is bound to and the
/// origins that may frame it.
#[derive(Debug, Clone)]
pub struct Admission {
    token: Token,
    bound: SocketAddr,
    frame_ancestors: FrameAncestors,
}

impl Admission {
    /// A server's admission: `token`, bound to `bound`, its page framed by its own origin and
    /// `frame_ancestors`.
    pub fn new(token: Token, bound: SocketAddr, frame_ancestors: FrameAncestors) -> Admission {
        Admission { token, bound, frame_ancestors }
    }

    /// The token.
    pub fn token(&self) -> &Token {
        &self.token
    }

    /// The address the server is bound to.
    pub fn bound(&self) -> SocketAddr {
        self.bound
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

    /// Whether a request with `head` is served at all: refused with 403 unless its path starts with the
    /// token, its Host is this server's and its Origin, when sent, is this server's; with 413 when it says
    /// its body is over [`BODY_LIMIT`]. Decided before the body is read.
    pub fn admit(&self, head: &Head) -> Result<(), Response> {
        let first = head.path().strip_prefix('/').and_then(|p| p.split('/').next()).unwrap_or("");
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

    /// The headers every answer carries, each its name and value: nothing may be kept by a cache, and only
    /// the page's own origin and the frame ancestors may frame it.
    pub fn headers(&self) -> Vec<(&'static str, String)> {
        let mut ancestors = "frame-ancestors 'self'".to_string();
        for source in self.frame_ancestors.sources() {
            ancestors.push(' ');
            ancestors.push_str(source);
        }
        let mut headers = vec![("Cache-Control", "no-store".to_string()), ("Content-Security-Policy", ancestors)];
        // A browser that reads a policy's frame-ancestors ignores X-Frame-Options; one that does not would
        // refuse a notebook's frame by it, so it is sent only when no other origin may frame the page.
        if self.frame_ancestors.sources().is_empty() {
            headers.push(("X-Frame-Options", "SAMEORIGIN".to_string()));
        }
        headers
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn admission(bound: &str) -> Admission {
        Admission::new(Token::random().unwrap(), bound.parse().unwrap(), FrameAncestors::none())
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
        let live = admission("127.0.0.1:4000");
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
        let all = admission("0.0.0.0:4000");
        let url = format!("/{}/state", all.token.as_str());
        let status = |host: &str| all.admit(&head(&url, host, None)).err().map(|r| r.status);
        assert_eq!(status("192.0.2.7:4000"), None);
        assert_eq!(status("localhost:4000"), None);
        assert_eq!(status("rebound.example:4000"), Some(403));
        assert_eq!(status("[::1]:4000"), Some(403));
        assert_eq!(all.address(), format!("http://127.0.0.1:4000/{}/", all.token.as_str()));
    }

    #[test]
    fn frame_ancestors_are_origins_and_the_page_is_framed_by_its_own_alone_without_them() {
        let header = |a: &Admission, name: &str| a.headers().into_iter().find(|(n, _)| *n == name).map(|(_, v)| v);
        let own = admission("127.0.0.1:4000");
        assert_eq!(header(&own, "Content-Security-Policy").as_deref(), Some("frame-ancestors 'self'"));
        assert_eq!(header(&own, "X-Frame-Options").as_deref(), Some("SAMEORIGIN"));
        assert_eq!(header(&own, "Cache-Control").as_deref(), Some("no-store"));

        let notebook = FrameAncestors::new(["http://localhost:*", " http://127.0.0.1:8888", "https://*.example.org"]);
        let framed = Admission::new(Token::random().unwrap(), "127.0.0.1:4000".parse().unwrap(), notebook.unwrap());
        assert_eq!(
            header(&framed, "Content-Security-Policy").as_deref(),
            Some("frame-ancestors 'self' http://localhost:* http://127.0.0.1:8888 https://*.example.org")
        );
        assert_eq!(header(&framed, "X-Frame-Options"), None);
        assert!(FrameAncestors::new(["http://[::1]:8888", "http://jupyter.local"]).is_ok());

        // Nothing that would widen the policy, add to it or break the header.
        for bad in [
            "*",
            "http://*",
            "http://*:*",
            "'none'",
            "localhost:8888",
            "ftp://localhost",
            "http://localhost:8888/tree",
            "http://localhost:8888; script-src *",
            "http://localhost:8888 http://evil.example",
            "http://local\r\nhost",
            "http://localhost:99999",
            "http://localhost:",
            "http://[::g]:1",
            "http://",
        ] {
            let refused = FrameAncestors::new([bad]).expect_err(bad);
            assert_eq!(refused.given, bad.trim(), "{bad}");
            assert!(refused.to_string().contains("frame ancestor"), "{refused}");
        }
    }
}
