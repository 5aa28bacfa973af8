//! `--serve`: a small local web page that follows the render.
//!
//! Plain HTTP/1.1 on std's `TcpListener`, one thread per connection and
//! `Connection: close`, which is all a page on loopback needs; a framework
//! would dwarf the rest of watch mode. Endpoints: `/` (the page), `/image.png`
//! (the latest pass; `?exposure=STOPS` re-encodes it that many stops
//! brighter than the scene's exposure, for the page's exposure control), `/events` (server-sent events: `pass`, `diagnostics`,
//! `progress`, each JSON) and `/state` (the same, as one JSON object).

use super::hub::{Hub, KINDS, Snapshot};
use super::progressive::encode_png;
use crate::imageio::Display;
use std::io::{self, BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream, ToSocketAddrs};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

const PAGE: &str = include_str!("page.html");
/// The default address and how many ports after it to try when it is taken.
const DEFAULT_HOST: &str = "127.0.0.1";
const DEFAULT_PORT: u16 = 8765;
const DEFAULT_TRIES: u16 = 10;
/// Threads are cheap, not free: a runaway client gets 503s.
const MAX_CONNECTIONS: usize = 64;
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

/// Binds `addr` (`HOST:PORT`, or a bare port on loopback; empty for the
/// default, moving to the next port while one is taken) and serves in the
/// background. Returns the bound address (port 0 becomes a real port).
pub fn start(addr: &str, hub: Arc<Hub>) -> io::Result<SocketAddr> {
    let listener = bind(addr)?;
    let local = listener.local_addr()?;
    let open = Arc::new(AtomicUsize::new(0));
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let (hub, open) = (hub.clone(), open.clone());
            if open.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
                open.fetch_sub(1, Ordering::SeqCst);
                let mut s = stream;
                let _ = respond(&mut s, "503 Service Unavailable", "text/plain", b"busy");
                continue;
            }
            std::thread::spawn(move || {
                let _ = handle(stream, &hub);
                open.fetch_sub(1, Ordering::SeqCst);
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

fn handle(mut stream: TcpStream, hub: &Hub) -> io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(5)))?;
    let (method, target, host) = read_request(&stream)?;
    let path = target.split(['?', '#']).next().unwrap_or("/");
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

/// The request line's method and target, and the `Host` header; other
/// headers are read and ignored.
fn read_request(stream: &TcpStream) -> io::Result<(String, String, Option<String>)> {
    let mut reader = BufReader::new(stream).take(16 * 1024);
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
    /// connections within a poll, not after 15 s of 503s.
    #[test]
    fn server_frees_closed_event_streams_promptly() {
        let addr = start("0", Arc::new(Hub::default())).expect("start");
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
        assert!(
            get(addr, "/state", &host).starts_with("HTTP/1.1 503"),
            "all slots taken"
        );
        drop(streams);
        let t = Instant::now();
        loop {
            if get(addr, "/state", &host).starts_with("HTTP/1.1 200") {
                break;
            }
            assert!(
                t.elapsed() < Duration::from_secs(5),
                "still busy after {:?}",
                t.elapsed()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}
