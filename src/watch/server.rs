//! `--serve`: a small local web page that follows the render.
//!
//! Plain HTTP/1.1 on std's `TcpListener`, one thread per connection and
//! `Connection: close`, which is all a page on loopback needs; a framework
//! would dwarf the rest of watch mode. Connections are bounded (in all and
//! per peer) and timed (the request head, each write); a client that sends
//! or reads nothing gives its slot to the next one ([`MAX_CONNECTIONS`]).
//! The render loop only publishes to the hub and never waits on a client. Endpoints: `/` (the page), `/image.png`
//! (the latest pass; `?exposure=STOPS` re-encodes it that many stops
//! brighter than the scene's exposure, for the page's exposure control), `/events` (server-sent events: `pass`, `diagnostics`,
//! `progress`, each JSON) and `/state` (the same, as one JSON object).

use super::hub::{Hub, KINDS, Snapshot};
use super::progressive::encode_png;
use crate::imageio::Display;
use std::io::{self, BufRead, BufReader, Read, Write};
use std::net::{IpAddr, Shutdown, SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

const PAGE: &str = include_str!("page.html");
/// The default address and how many ports after it to try when it is taken.
const DEFAULT_HOST: &str = "127.0.0.1";
const DEFAULT_PORT: u16 = 8765;
const DEFAULT_TRIES: u16 = 10;
/// Connections served at once (one thread each). When all are taken, a new
/// one takes the place of the oldest that is idle (see [`Slots::admit`]);
/// only when none is does it get a 503.
pub const MAX_CONNECTIONS: usize = 64;
/// Connections one remote peer address may hold at once: past it, the
/// peer's own oldest idle connection makes room, so one remote client
/// cannot take every slot. Not applied on loopback, where every local
/// client (each browser tab) shares one address.
pub const MAX_PER_PEER: usize = 16;
/// Time a client has to send its whole request head once connected (a
/// browser sends it at once). The read timeout alone was per read: a byte
/// every few seconds held a connection for ever.
pub const REQUEST_TIMEOUT: Duration = Duration::from_secs(5);
/// Time a write may wait on a client that reads nothing.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// A response this old may be cut short to make room for a new client: a
/// page on loopback takes milliseconds to fetch, a client reading nothing
/// would otherwise keep its slot until [`WRITE_TIMEOUT`].
const RESPONSE_GRACE: Duration = Duration::from_secs(2);
const KEEPALIVE: Duration = Duration::from_secs(15);
/// How often an idle event stream checks that its page is still there.
const POLL: Duration = Duration::from_millis(250);

/// Whether the client has closed its end (a read would return end of file).
/// Pages send nothing after their request, so any byte would also do; the
/// peek is non-blocking, then the socket goes back to blocking.
fn peer_closed(stream: &TcpStream) -> bool {
    if stream.set_nonblocking(true).is_err() {
        return false;
    }
    let mut b = [0u8; 1];
    let closed = matches!(stream.peek(&mut b), Ok(0));
    let _ = stream.set_nonblocking(false);
    closed
}

/// What a connection is doing, from most to least willing to give up its
/// slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Stage {
    /// Waiting for the request head: a client that sends nothing.
    Request,
    /// An event stream: the page reconnects by itself (`retry: 1000`).
    Events,
    /// Sending a response: cut only after [`RESPONSE_GRACE`].
    Response,
}

struct Slot {
    id: u64,
    peer: IpAddr,
    since: Instant,
    stage: Stage,
    /// A handle on the socket, to shut it down when the slot is taken: the
    /// thread blocked on it then returns at once.
    stream: TcpStream,
}

/// The connections being served, so that slow or idle clients cannot lock
/// everyone out: the accept loop never waits on a client, and a new client
/// takes the place of the oldest idle one instead of being refused.
#[derive(Default)]
struct Slots {
    open: Mutex<Vec<Slot>>,
    next: AtomicU64,
}

impl Slots {
    fn lock(&self) -> MutexGuard<'_, Vec<Slot>> {
        self.open.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// A slot for `stream` from `peer`, making room within the peer's share
    /// and then within the total by closing the oldest connection that may
    /// give way (waiting for its request, then an event stream, then a
    /// response older than [`RESPONSE_GRACE`]); `None` when none may.
    fn admit(&self, stream: &TcpStream, peer: IpAddr) -> Option<u64> {
        let handle = stream.try_clone().ok()?;
        let mut open = self.lock();
        let now = Instant::now();
        if !peer.is_loopback() && open.iter().filter(|s| s.peer == peer).count() >= MAX_PER_PEER {
            evict(&mut open, now, |s| s.peer == peer)?;
        }
        if open.len() >= MAX_CONNECTIONS {
            evict(&mut open, now, |_| true)?;
        }
        let id = self.next.fetch_add(1, Ordering::Relaxed);
        open.push(Slot {
            id,
            peer,
            since: now,
            stage: Stage::Request,
            stream: handle,
        });
        Some(id)
    }

    fn set_stage(&self, id: u64, stage: Stage) {
        if let Some(s) = self.lock().iter_mut().find(|s| s.id == id) {
            s.stage = stage;
            s.since = Instant::now();
        }
    }

    fn leave(&self, id: u64) {
        self.lock().retain(|s| s.id != id);
    }
}

/// Closes the connection among `open` (those `which` picks) that gives way
/// first; `None` when none may.
fn evict(open: &mut Vec<Slot>, now: Instant, which: impl Fn(&Slot) -> bool) -> Option<()> {
    let (i, _) = open
        .iter()
        .enumerate()
        .filter(|(_, s)| which(s) && (s.stage != Stage::Response || now - s.since >= RESPONSE_GRACE))
        .min_by_key(|(_, s)| (s.stage, s.since))?;
    let s = open.swap_remove(i);
    let _ = s.stream.shutdown(Shutdown::Both);
    Some(())
}

/// Binds `addr` (`HOST:PORT`, or a bare port on loopback; empty for the
/// default, moving to the next port while one is taken) and serves in the
/// background. Returns the bound address (port 0 becomes a real port).
pub fn start(addr: &str, hub: Arc<Hub>) -> io::Result<SocketAddr> {
    start_with(addr, hub, Arc::new(Slots::default()))
}

fn start_with(addr: &str, hub: Arc<Hub>, slots: Arc<Slots>) -> io::Result<SocketAddr> {
    let listener = bind(addr)?;
    let local = listener.local_addr()?;
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let peer = match stream.peer_addr() {
                Ok(a) => a.ip(),
                Err(_) => continue,
            };
            let Some(id) = slots.admit(&stream, peer) else {
                // Every slot is busy sending: a short answer that fits in the
                // socket's buffer, so the accept loop never waits.
                let mut s = stream;
                let _ = s.set_write_timeout(Some(Duration::from_millis(100)));
                let _ = respond(&mut s, "503 Service Unavailable", "text/plain", b"busy");
                continue;
            };
            let (hub, slots) = (hub.clone(), slots.clone());
            std::thread::spawn(move || {
                let _ = handle(stream, &hub, &slots, id);
                slots.leave(id);
            });
        }
    });
    Ok(local)
}

fn bind(addr: &str) -> io::Result<TcpListener> {
    if addr.is_empty() {
        let mut last = None;
        for port in DEFAULT_PORT..DEFAULT_PORT + DEFAULT_TRIES {
            match TcpListener::bind((DEFAULT_HOST, port)) {
                Ok(l) => return Ok(l),
                Err(e) => last = Some(e),
            }
        }
        return Err(last.unwrap_or_else(|| io::Error::other("no port to try")));
    }
    if let Ok(port) = addr.parse::<u16>() {
        return TcpListener::bind((DEFAULT_HOST, port));
    }
    let addrs: Vec<SocketAddr> = addr.to_socket_addrs()?.collect();
    TcpListener::bind(&addrs[..])
}

fn handle(mut stream: TcpStream, hub: &Hub, slots: &Slots, id: u64) -> io::Result<()> {
    stream.set_write_timeout(Some(WRITE_TIMEOUT))?;
    let head = Deadline {
        stream: &stream,
        until: Instant::now() + REQUEST_TIMEOUT,
    };
    let (method, target, host) = read_request(head)?;
    let path = target.split(['?', '#']).next().unwrap_or("/");
    slots.set_stage(
        id,
        if path == "/events" {
            Stage::Events
        } else {
            Stage::Response
        },
    );
    if !host_allowed(host.as_deref()) {
        return respond(&mut stream, "403 Forbidden", "text/plain", b"unknown Host");
    }
    if method != "GET" {
        return respond(&mut stream, "405 Method Not Allowed", "text/plain", b"GET only");
    }
    match path {
        "/" | "/index.html" => respond(&mut stream, "200 OK", "text/html; charset=utf-8", PAGE.as_bytes()),
        "/image.png" => match hub.snapshot().frame {
            Some(frame) => match exposure_of(&target) {
                // The page's exposure control: stops added to the scene's.
                Some(stops) if stops != 0.0 => {
                    let display = Display {
                        exposure: frame.display.exposure + stops,
                        ..frame.display
                    };
                    let png = encode_png(&frame.image, &display);
                    respond(&mut stream, "200 OK", "image/png", &png)
                }
                _ => respond(&mut stream, "200 OK", "image/png", &frame.png),
            },
            None => respond(&mut stream, "404 Not Found", "text/plain", b"no image yet"),
        },
        "/state" => respond(
            &mut stream,
            "200 OK",
            "application/json",
            state_json(&hub.snapshot()).as_bytes(),
        ),
        "/events" => events(stream, hub),
        _ => respond(&mut stream, "404 Not Found", "text/plain", b"not found"),
    }
}

/// Largest exposure offset the page may ask for, in stops.
const MAX_PAGE_STOPS: f32 = 20.0;

/// The `exposure=STOPS` query parameter of `target`, clamped to
/// ±[`MAX_PAGE_STOPS`]; `None` when absent or not a number.
fn exposure_of(target: &str) -> Option<f32> {
    let query = target.split_once('?')?.1.split('#').next()?;
    let value = query
        .split('&')
        .find_map(|kv| kv.strip_prefix("exposure="))?
        .parse::<f32>()
        .ok()
        .filter(|x| x.is_finite())?;
    Some(value.clamp(-MAX_PAGE_STOPS, MAX_PAGE_STOPS))
}

/// A socket read against a deadline for all the reads together.
struct Deadline<'a> {
    stream: &'a TcpStream,
    until: Instant,
}

impl Read for Deadline<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let left = self.until.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(io::Error::new(io::ErrorKind::TimedOut, "request head too slow"));
        }
        self.stream.set_read_timeout(Some(left))?;
        let mut stream: &TcpStream = self.stream;
        stream.read(buf)
    }
}

/// The request line's method and target, and the `Host` header; other
/// headers are read and ignored.
fn read_request(head: Deadline) -> io::Result<(String, String, Option<String>)> {
    let mut reader = BufReader::new(head).take(16 * 1024);
    let mut first = String::new();
    reader.read_line(&mut first)?;
    let mut line = String::new();
    let mut host = None;
    loop {
        line.clear();
        if reader.read_line(&mut line)? == 0 || line == "\r\n" || line == "\n" {
            break;
        }
        if let Some((name, value)) = line.split_once(':')
            && name.trim().eq_ignore_ascii_case("host")
        {
            host = Some(value.trim().to_string());
        }
    }
    let mut parts = first.split_whitespace();
    match (parts.next(), parts.next()) {
        (Some(m), Some(t)) => Ok((m.to_string(), t.to_string(), host)),
        _ => Err(io::Error::new(io::ErrorKind::InvalidData, "bad request line")),
    }
}

/// Whether a request's `Host` may be served: `localhost` or an IP address
/// (any port). A DNS name that resolves to this machine is how a web page
/// elsewhere would reach the server (DNS rebinding), so names are refused;
/// a request without `Host` (HTTP/1.0 tools) is served.
fn host_allowed(host: Option<&str>) -> bool {
    let Some(host) = host else {
        return true;
    };
    let name = if let Some(rest) = host.strip_prefix('[') {
        // `[::1]:8765`
        rest.split(']').next().unwrap_or("")
    } else {
        host.rsplit_once(':').map_or(host, |(n, _)| n)
    };
    name.eq_ignore_ascii_case("localhost") || name.parse::<std::net::IpAddr>().is_ok()
}

fn respond(stream: &mut TcpStream, status: &str, content_type: &str, body: &[u8]) -> io::Result<()> {
    write!(
        stream,
        "HTTP/1.1 {status}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\n\
         Cache-Control: no-store\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(body)?;
    stream.flush()
}

/// Streams every event newer than the last one sent, oldest first; a comment
/// line now and then notices a closed page.
fn events(mut stream: TcpStream, hub: &Hub) -> io::Result<()> {
    stream.write_all(
        b"HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n\
          Connection: keep-alive\r\n\r\nretry: 1000\n\n",
    )?;
    let mut seen = 0;
    let mut quiet = Duration::ZERO;
    loop {
        // Short waits, so a page that closed frees its connection within a
        // poll instead of at the next keep-alive write (64 closed pages kept
        // the server answering 503 for 15 s).
        let snap = hub.wait_newer(seen, POLL);
        if snap.seq == seen {
            if peer_closed(&stream) {
                return Ok(());
            }
            quiet += POLL;
            if quiet >= KEEPALIVE {
                stream.write_all(b": keepalive\n\n")?;
                quiet = Duration::ZERO;
            }
            continue;
        }
        quiet = Duration::ZERO;
        let mut news: Vec<_> = KINDS
            .iter()
            .map(|&k| (&snap.events[k as usize], k))
            .filter(|((seq, _), _)| *seq > seen)
            .collect();
        news.sort_by_key(|((seq, _), _)| *seq);
        let mut text = String::new();
        for ((_, json), kind) in news {
            text.push_str(&format!("event: {}\ndata: {json}\n\n", kind.name()));
        }
        stream.write_all(text.as_bytes())?;
        stream.flush()?;
        seen = snap.seq;
    }
}

fn state_json(snap: &Snapshot) -> String {
    let fields: Vec<String> = KINDS
        .iter()
        .map(|&k| {
            let (seq, json) = &snap.events[k as usize];
            let value = if *seq == 0 { "null" } else { json.as_str() };
            format!("\"{}\":{value}", k.name())
        })
        .collect();
    format!("{{{}}}", fields.join(","))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    fn get(addr: SocketAddr, path: &str, host: &str) -> String {
        let mut s = TcpStream::connect(addr).expect("connect");
        s.set_read_timeout(Some(Duration::from_secs(5))).expect("timeout");
        // A busy server answers 503 without reading: the write may fail.
        let _ = write!(s, "GET {path} HTTP/1.1\r\nHost: {host}\r\n\r\n");
        let mut out = String::new();
        let _ = s.read_to_string(&mut out);
        out
    }

    #[test]
    fn server_refuses_hosts_that_are_dns_names() {
        let addr = start("0", Arc::new(Hub::default())).expect("start");
        assert!(get(addr, "/state", &format!("127.0.0.1:{}", addr.port())).starts_with("HTTP/1.1 200"));
        assert!(get(addr, "/state", "localhost:8765").starts_with("HTTP/1.1 200"));
        assert!(get(addr, "/state", "[::1]:8765").starts_with("HTTP/1.1 200"));
        assert!(get(addr, "/state", "evil.example:8765").starts_with("HTTP/1.1 403"));
    }

    /// The page's exposure control: `?exposure=1` serves the pass one stop
    /// brighter (linear values doubled before the sRGB encoding).
    #[test]
    fn image_exposure_parameter_re_exposes_the_latest_pass() {
        use crate::imageio::{Image, srgb_decode};
        let hub = Arc::new(Hub::default());
        let mut image = Image::new(2, 1);
        image.pixels[0] = crate::math::Rgb::splat(0.1);
        image.pixels[1] = crate::math::Rgb::splat(0.3);
        let display = Display::default();
        let frame = super::super::hub::Frame {
            png: encode_png(&image, &display),
            image,
            display,
        };
        hub.publish(super::super::hub::Kind::Pass, "{}".into(), Some(frame));
        let addr = start("0", hub).expect("start");
        let fetch = |path: &str| {
            let mut s = TcpStream::connect(addr).expect("connect");
            write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").expect("send");
            let mut out = Vec::new();
            s.read_to_end(&mut out).expect("read");
            let body = out
                .windows(4)
                .position(|w| w == b"\r\n\r\n")
                .expect("headers end")
                + 4;
            let img = image::load_from_memory(&out[body..]).expect("a PNG").to_rgb8();
            [0, 1].map(|x| srgb_decode(f32::from(img.get_pixel(x, 0)[0]) / 255.0))
        };
        let plain = fetch("/image.png?v=1");
        let brighter = fetch("/image.png?v=1&exposure=1");
        let darker = fetch("/image.png?v=1&exposure=-1");
        for (i, x) in [0.1f32, 0.3].into_iter().enumerate() {
            assert!((plain[i] - x).abs() < 0.01, "plain {plain:?}");
            assert!(
                (brighter[i] - 2.0 * x).abs() < 0.01,
                "+1 stop: {brighter:?}, expected {}",
                2.0 * x
            );
            assert!(
                (darker[i] - 0.5 * x).abs() < 0.01,
                "−1 stop: {darker:?}, expected {}",
                0.5 * x
            );
        }
        assert_eq!(exposure_of("/image.png?v=3&exposure=nan"), None);
        assert_eq!(exposure_of("/image.png?exposure=99"), Some(MAX_PAGE_STOPS));
    }

    /// 64 pages open `/events` and close: the server frees their
    /// connections within a poll, not at the next keep-alive write 15 s
    /// later.
    #[test]
    fn server_frees_closed_event_streams_promptly() {
        let slots = Arc::new(Slots::default());
        let addr = start_with("0", Arc::new(Hub::default()), slots.clone()).expect("start");
        let host = format!("127.0.0.1:{}", addr.port());
        let streams: Vec<TcpStream> = (0..MAX_CONNECTIONS)
            .map(|_| {
                let mut s = TcpStream::connect(addr).expect("connect");
                write!(s, "GET /events HTTP/1.1\r\nHost: {host}\r\n\r\n").expect("send");
                let mut b = [0u8; 16];
                s.read_exact(&mut b).expect("headers start");
                s
            })
            .collect();
        assert_eq!(slots.lock().len(), MAX_CONNECTIONS, "all slots taken");
        drop(streams);
        let t = Instant::now();
        while !slots.lock().is_empty() {
            assert!(
                t.elapsed() < Duration::from_secs(5),
                "{} streams still open after {:?}",
                slots.lock().len(),
                t.elapsed()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// A request of `path` that reads the whole answer (hang guard 60 s).
    fn fetch(addr: SocketAddr, path: &str) -> Vec<u8> {
        let mut s = TcpStream::connect(addr).expect("connect");
        s.set_read_timeout(Some(Duration::from_secs(60)))
            .expect("timeout");
        let _ = write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
        let mut out = Vec::new();
        let _ = s.read_to_end(&mut out);
        out
    }

    /// Every slot held by clients that send nothing or read nothing (a
    /// large image requested and never read): a new client still gets the
    /// page and the whole image at once (it got 503 until they let go,
    /// and a client that never reads never did).
    #[test]
    fn server_serves_a_new_client_while_slow_ones_hold_every_slot() {
        use crate::imageio::Image;
        let hub = Arc::new(Hub::default());
        // Noise does not compress: 25 MB, more than socket buffers hold.
        let (w, h) = (4096, 2048);
        let mut image = Image::new(w, h);
        let mut rng = crate::math::Pcg32::new(7, 1);
        for p in image.pixels.iter_mut() {
            *p = crate::math::Rgb::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        }
        let display = Display::default();
        let png = encode_png(&image, &display);
        let png_len = png.len();
        hub.publish(
            super::super::hub::Kind::Pass,
            "{}".into(),
            Some(super::super::hub::Frame { png, image, display }),
        );
        let slots = Arc::new(Slots::default());
        let addr = start_with("0", hub, slots.clone()).expect("start");
        let mut slow = Vec::new();
        for i in 0..MAX_CONNECTIONS {
            let mut s = TcpStream::connect(addr).expect("connect");
            if i % 2 == 0 {
                write!(s, "GET /image.png HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n").expect("send");
            }
            slow.push(s);
        }
        // Until the server holds them all.
        let t = Instant::now();
        while slots.lock().len() < MAX_CONNECTIONS && t.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(20));
        }
        let page = fetch(addr, "/");
        assert!(
            page.starts_with(b"HTTP/1.1 200") && page.ends_with(PAGE.as_bytes()),
            "the page: {}",
            String::from_utf8_lossy(&page[..page.len().min(200)])
        );
        let img = fetch(addr, "/image.png");
        assert!(
            img.starts_with(b"HTTP/1.1 200") && img.len() > png_len,
            "the image: {} bytes of {png_len}: {}",
            img.len(),
            String::from_utf8_lossy(&img[..img.len().min(200)])
        );
        drop(slow);
    }

    /// A request head sent a byte at a time, each well within any per-read
    /// timeout, is cut off once [`REQUEST_TIMEOUT`] has passed in all (it
    /// held its connection for as long as it kept dribbling).
    #[test]
    fn server_cuts_off_a_request_head_that_dribbles() {
        let addr = start("0", Arc::new(Hub::default())).expect("start");
        let mut s = TcpStream::connect(addr).expect("connect");
        s.set_read_timeout(Some(Duration::from_millis(200)))
            .expect("timeout");
        let t = Instant::now();
        let guard = REQUEST_TIMEOUT * 12;
        let mut b = [0u8; 64];
        loop {
            if s.write_all(b"X").is_err() {
                break;
            }
            match s.read(&mut b) {
                Ok(_) => break,
                Err(e) if matches!(e.kind(), io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut) => {}
                Err(_) => break,
            }
            assert!(t.elapsed() < guard, "still open after {:?}", t.elapsed());
        }
    }
}
