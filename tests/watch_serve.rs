//! `ronray watch --serve` in a real headless Chromium: the page shows the
//! image, follows an edit without being reloaded, and shows the diagnostics
//! of a broken edit. The browser is driven over the DevTools protocol and
//! the page's DOM is read with `Runtime.evaluate`, pixels included.
//!
//! Chromium is required: CI installs it (`.ci/run`), and a missing browser
//! fails this test rather than skipping it.

use crate::common;

use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;

use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

const DEADLINE: Duration = Duration::from_secs(60);
const TRIANGLE: &str = "v -0.6 -0.6 0\nv 0.4 -0.6 0\nv -0.1 0.4 0\nf 1 2 3\n";

fn scene(material: &str, albedo: &str) -> String {
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
    film: (width: 48, height: 48, spp: 8, seed: 3),
    materials: {{ "ball": Lambert(albedo: ({albedo})), "grey": Lambert(albedo: (0.6, 0.6, 0.6)) }},
    lights: [ Point(position: (0, 2, 3), intensity: (6, 6, 6)) ],
    objects: [
        Sphere(center: (0.5, 0.2, 0), radius: 0.4, material: "{material}"),
        Mesh(file: "tri.obj", material: "grey"),
    ],
)
"#
    )
}

/// A child process whose output lines are collected; killed when dropped.
struct Proc {
    child: Child,
    log: Arc<Mutex<Vec<String>>>,
}

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Proc {
    fn spawn(cmd: &mut Command) -> Proc {
        let mut child = cmd
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {cmd:?}: {e}"));
        let log = Arc::new(Mutex::new(Vec::new()));
        let streams: [Box<dyn Read + Send>; 2] = [
            Box::new(child.stdout.take().expect("stdout")),
            Box::new(child.stderr.take().expect("stderr")),
        ];
        for s in streams {
            let log = log.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(s).lines().map_while(Result::ok) {
                    log.lock().expect("log").push(line);
                }
            });
        }
        Proc { child, log }
    }

    /// The first output line's text after `prefix`, waiting for it.
    fn wait_for(&self, prefix: &str) -> String {
        let start = Instant::now();
        loop {
            let log = self.log.lock().expect("log").clone();
            if let Some(rest) = log
                .iter()
                .find_map(|l| l.split_once(prefix).map(|(_, r)| r.to_string()))
            {
                return rest;
            }
            assert!(
                start.elapsed() < DEADLINE,
                "no `{prefix}` in the output:\n{}",
                log.join("\n")
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// A GET to the DevTools HTTP endpoint, which keeps the connection open:
/// the body is read by its `Content-Length`.
fn http_get(port: u16, path: &str) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port)).expect("connect to DevTools");
    s.set_read_timeout(Some(Duration::from_secs(10)))
        .expect("timeout");
    write!(s, "GET {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n").expect("send");
    let mut reader = BufReader::new(s);
    let mut length = 0;
    let mut line = String::new();
    while reader.read_line(&mut line).expect("read header") > 0 && line.trim() != "" {
        if let Some((k, v)) = line.split_once(':')
            && k.eq_ignore_ascii_case("content-length")
        {
            length = v.trim().parse().expect("content length");
        }
        line.clear();
    }
    let mut body = vec![0; length];
    reader.read_exact(&mut body).expect("read body");
    String::from_utf8_lossy(&body).into_owned()
}

/// One page of the browser, over the DevTools protocol.
struct Page {
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    next_id: u64,
}

impl Page {
    fn open(devtools_port: u16, url: &str) -> Page {
        let start = Instant::now();
        let ws_url = loop {
            let list: Value =
                serde_json::from_str(&http_get(devtools_port, "/json/list")).unwrap_or(json!([]));
            let found = list
                .as_array()
                .into_iter()
                .flatten()
                .find(|t| t["type"] == "page" && t["url"].as_str().is_some_and(|u| u.starts_with(url)));
            if let Some(ws) = found.and_then(|t| t["webSocketDebuggerUrl"].as_str()) {
                break ws.to_string();
            }
            assert!(start.elapsed() < DEADLINE, "no page for {url} in {list}");
            std::thread::sleep(Duration::from_millis(100));
        };
        let (ws, _) = tungstenite::connect(ws_url.as_str()).expect("DevTools websocket");
        if let MaybeTlsStream::Plain(s) = ws.get_ref() {
            s.set_read_timeout(Some(Duration::from_secs(20)))
                .expect("timeout");
        }
        Page { ws, next_id: 1 }
    }

    /// Evaluates `expr` in the page and returns its (JSON) value.
    fn eval(&mut self, expr: &str) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let msg = json!({"id": id, "method": "Runtime.evaluate",
                         "params": {"expression": expr, "returnByValue": true}});
        self.ws.send(Message::Text(msg.to_string().into())).expect("send");
        loop {
            let reply = self.ws.read().expect("DevTools reply");
            let Ok(text) = reply.to_text() else { continue };
            let v: Value = serde_json::from_str(text).expect("JSON reply");
            if v["id"] == id {
                return v["result"]["result"]["value"].clone();
            }
        }
    }

    /// The page state as the DOM shows it, plus the colour of a pixel on the
    /// sphere read back through a canvas.
    fn state(&mut self) -> Value {
        const STATE: &str = r#"(() => {
            const $ = id => document.getElementById(id);
            const img = $('image');
            let px = null;
            if (img.complete && img.naturalWidth > 0) {
                const c = document.createElement('canvas');
                c.width = img.naturalWidth; c.height = img.naturalHeight;
                const g = c.getContext('2d');
                g.drawImage(img, 0, 0);
                px = Array.from(g.getImageData(35, 20, 1, 1).data.slice(0, 3));
            }
            return JSON.stringify({
                version: Number(img.dataset.version), pass: $('pass').textContent,
                width: img.naturalWidth, px, state: $('state').dataset.state,
                error: $('error').hidden ? null : $('error').textContent,
            });
        })()"#;
        let text = self.eval(STATE);
        serde_json::from_str(text.as_str().unwrap_or("null")).expect("state JSON")
    }

    fn wait(&mut self, what: &str, done: impl Fn(&Value) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let s = self.state();
            if done(&s) {
                return s;
            }
            assert!(
                start.elapsed() < DEADLINE,
                "page never showed {what}; it shows {s}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

fn red(s: &Value) -> bool {
    s["px"][0].as_i64() > s["px"][2].as_i64().map(|b| b + 40)
}

fn blue(s: &Value) -> bool {
    s["px"][2].as_i64() > s["px"][0].as_i64().map(|r| r + 40)
}

#[test]
fn watch_serve_page_follows_edits_in_a_real_browser() {
    let Some(browser) = common::tool_or_skip(
        "chromium",
        "watch_serve_page_follows_edits_in_a_real_browser",
        "`apt-get install chromium`; .ci/run installs it",
    ) else {
        return;
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let write = |text: String| std::fs::write(dir.path().join("scene.ron"), text).expect("write scene");
    std::fs::write(dir.path().join("tri.obj"), TRIANGLE).expect("write obj");
    write(scene("ball", "0.9, 0.1, 0.1"));
    let watch = Proc::spawn(
        Command::new(env!("CARGO_BIN_EXE_ronray"))
            .current_dir(dir.path())
            .args(["watch", "scene.ron", "-o", "out.png", "--serve", "127.0.0.1:0"]),
    );
    let url = format!("http://{}", watch.wait_for("serving http://").trim());
    watch.wait_for("pass 4/4:");

    let profile = tempfile::tempdir().expect("profile dir");
    let chrome = Proc::spawn(
        Command::new(browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--remote-debugging-port=0",
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg(&url),
    );
    let devtools = chrome.wait_for("DevTools listening on ws://");
    let port: u16 = devtools
        .split(['/', ':'])
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no port in `{devtools}`"));
    let mut page = Page::open(port, &url);

    let first = page.wait("the complete red image", |s| {
        s["pass"] == "4/4" && s["width"] == 48 && s["version"].as_u64() >= Some(4) && red(s)
    });
    assert!(first["error"].is_null(), "an error on a valid scene: {first}");

    write(scene("ball", "0.1, 0.1, 0.9"));
    let second = page.wait("the edit, without a reload", |s| {
        s["pass"] == "4/4" && blue(s) && s["version"].as_u64() > first["version"].as_u64()
    });
    // The labels describe the image on screen: the edit's fourth pass is the
    // fourth image written after the first render's last. (The page once
    // changed the label when a pass was announced, before its image loaded,
    // and this test then caught the second pass under a "4/4" label.)
    assert!(
        second["version"].as_u64() >= first["version"].as_u64().map(|v| v + 4),
        "the pass label is ahead of the image: {first} then {second}"
    );

    write(scene("bal", "0.1, 0.1, 0.9"));
    let broken = page.wait("the diagnostics", |s| {
        s["error"].as_str().is_some_and(|e| !e.is_empty())
    });
    let error = broken["error"].as_str().unwrap_or_default();
    assert!(error.contains("unknown material `bal`"), "diagnostics: {error}");
    assert!(error.contains("did you mean `ball`?"), "diagnostics: {error}");
    assert_eq!(
        broken["version"], second["version"],
        "a broken edit changed the image"
    );
    assert!(blue(&broken), "the last good image is gone: {broken}");

    write(scene("ball", "0.9, 0.1, 0.1"));
    page.wait("the fix", |s| {
        s["error"].is_null()
            && s["pass"] == "4/4"
            && red(s)
            && s["version"].as_u64() > second["version"].as_u64()
    });
}
