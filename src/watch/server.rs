//! `--serve`: a small local web page that follows the render.
//!
//! Plain HTTP/1.1 on std's `TcpListener`, one thread per connection and
//! `Connection: close`, which is all a page on loopback needs; a framework
//! would dwarf the rest of watch mode. Endpoints: `/` (the page), `/image.png`
//! (the latest pass), `/events` (server-sent events: `pass`, `diagnostics`,
//! `progress`, each JSON) and `/state` (the same, as one JSON object).

use super::hub::{Hub, KINDS, Snapshot};
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
    let (method, target) = read_request(&stream)?;
    let path = target.split(['?', '#']).next().unwrap_or("/");
    if method != "GET" {
        return respond(&mut stream, "405 Method Not Allowed", "text/plain", b"GET only");
    }
    match path {
        "/" | "/index.html" => respond(&mut stream, "200 OK", "text/html; charset=utf-8", PAGE.as_bytes()),
        "/image.png" => match hub.snapshot().png {
            Some(png) => respond(&mut stream, "200 OK", "image/png", &png),
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

/// The request line's method and target; headers are read and ignored.
fn read_request(stream: &TcpStream) -> io::Result<(String, String)> {
    let mut reader = BufReader::new(stream).take(16 * 1024);
    let mut first = String::new();
    reader.read_line(&mut first)?;
    let mut line = String::new();
    loop {
        line.clear();
        if reader.read_line(&mut line)? == 0 || line == "\r\n" || line == "\n" {
            break;
        }
    }
    let mut parts = first.split_whitespace();
    match (parts.next(), parts.next()) {
        (Some(m), Some(t)) => Ok((m.to_string(), t.to_string())),
        _ => Err(io::Error::new(io::ErrorKind::InvalidData, "bad request line")),
    }
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
    loop {
        let snap = hub.wait_newer(seen, KEEPALIVE);
        if snap.seq == seen {
            stream.write_all(b": keepalive\n\n")?;
            continue;
        }
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
