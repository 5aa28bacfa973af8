//! `ronray lsp` driven over standard input and output by a scripted client:
//! located diagnostics for a scene with mistakes, updated after an edit;
//! hover, completion and go-to-definition answers.

use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

struct Client {
    child: Child,
    stdin: ChildStdin,
    incoming: Receiver<Value>,
    /// Notifications received while waiting for something else.
    backlog: Vec<Value>,
    next_id: i64,
}

impl Client {
    fn start() -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ronray"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("ronray lsp starts");
        let stdin = child.stdin.take().expect("stdin");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, incoming) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            loop {
                let mut len = 0;
                loop {
                    let mut line = String::new();
                    if r.read_line(&mut line).unwrap_or(0) == 0 {
                        return;
                    }
                    let line = line.trim();
                    if line.is_empty() {
                        break;
                    }
                    if let Some(n) = line.strip_prefix("Content-Length: ") {
                        len = n.parse().expect("length");
                    }
                }
                let mut body = vec![0; len];
                if r.read_exact(&mut body).is_err() {
                    return;
                }
                let v: Value = serde_json::from_slice(&body).expect("JSON message");
                if tx.send(v).is_err() {
                    return;
                }
            }
        });
        let mut c = Client {
            child,
            stdin,
            incoming,
            backlog: Vec::new(),
            next_id: 1,
        };
        let init = c.request(
            "initialize",
            json!({"capabilities": {}, "processId": null, "rootUri": null}),
        );
        assert!(
            init["capabilities"]["hoverProvider"].as_bool().unwrap_or(false),
            "{init}"
        );
        c.notify("initialized", json!({}));
        c
    }

    fn send(&mut self, v: Value) {
        let body = v.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("write");
        self.stdin.flush().expect("flush");
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    fn recv(&mut self) -> Value {
        self.incoming
            .recv_timeout(Duration::from_secs(60))
            .expect("the server answers within a minute")
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        loop {
            let v = self.recv();
            if v["id"] == json!(id) {
                assert!(v.get("error").is_none(), "{method} failed: {v}");
                return v["result"].clone();
            }
            self.backlog.push(v);
        }
    }

    /// The next diagnostics published for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            if let Some(i) = self
                .backlog
                .iter()
                .position(|v| v["method"] == "textDocument/publishDiagnostics" && v["params"]["uri"] == uri)
            {
                let v = self.backlog.remove(i);
                return v["params"]["diagnostics"].as_array().cloned().unwrap_or_default();
            }
            assert!(Instant::now() < deadline, "no diagnostics for {uri}");
            let v = self.recv();
            self.backlog.push(v);
        }
    }

    fn at(&mut self, method: &str, uri: &str, (line, character): (usize, usize)) -> Value {
        self.request(
            method,
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}),
        )
    }
}

/// Line and column (0-based; the texts are ASCII) of the `n`-th `needle`,
/// plus `delta` columns.
fn pos(text: &str, needle: &str, n: usize, delta: usize) -> (usize, usize) {
    let off = text
        .match_indices(needle)
        .nth(n)
        .unwrap_or_else(|| panic!("no {needle} #{n}"))
        .0
        + delta;
    let line = text[..off].matches('\n').count();
    let col = off - text[..off].rfind('\n').map_or(0, |i| i + 1);
    (line, col)
}

fn uri(p: &Path) -> String {
    format!("file://{}", p.display())
}

const BROKEN: &str = r#"Scene(
    include: ["lib.ron"],
    camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
    integrator: Direct(light_samples: 2),
    materials: {
        "white": Lambert(albedo: (0.8, 0.8, 0.8)),
    },
    lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))],
    objects: [
        Sphere(center: (0, 0, 0), radius: -1, material: "whte"),
        Sphere(center: (2, 0, 0), radius: 1, material: "brick"),
    ],
)
"#;

const LIB: &str = "// A material library.\nInclude(\n    materials: {\n        \"brick\": Lambert(albedo: (0.6, 0.3, 0.2)),\n    },\n)\n";

#[test]
fn lsp_client_gets_diagnostics_hover_completion_and_definitions() {
    let dir = tempfile::tempdir().expect("tmp");
    let scene = dir.path().join("scene.ron");
    let lib = dir.path().join("lib.ron");
    std::fs::write(&lib, LIB).expect("write");
    std::fs::write(&scene, BROKEN).expect("write");
    let (s_uri, lib_uri) = (uri(&scene), uri(&lib));
    let mut c = Client::start();

    // Open with two mistakes: both located, with their help.
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": s_uri, "languageId": "ron", "version": 1, "text": BROKEN}}),
    );
    let d = c.diagnostics(&s_uri);
    assert_eq!(d.len(), 2, "two mistakes, two diagnostics: {d:#?}");
    let whte = d
        .iter()
        .find(|x| x["message"].as_str().unwrap_or("").contains("whte"))
        .expect("unknown material");
    let (line, col) = pos(BROKEN, "\"whte\"", 0, 0);
    assert_eq!(
        whte["range"]["start"],
        json!({"line": line, "character": col}),
        "{whte}"
    );
    assert_eq!(whte["severity"], 1, "an error");
    assert!(
        whte["message"]
            .as_str()
            .unwrap_or("")
            .contains("did you mean `white`?"),
        "help line: {whte}"
    );
    let radius = d
        .iter()
        .find(|x| x["message"].as_str().unwrap_or("").contains("radius"))
        .expect("radius");
    assert_eq!(
        radius["range"]["start"]["line"],
        pos(BROKEN, "-1", 0, 0).0,
        "{radius}"
    );

    // Edit: both fixed, the diagnostics clear.
    let fixed = BROKEN
        .replace("radius: -1", "radius: 1")
        .replace("\"whte\"", "\"white\"");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": s_uri, "version": 2}, "contentChanges": [{"text": fixed}]}),
    );
    let d = c.diagnostics(&s_uri);
    assert!(d.is_empty(), "fixed: {d:#?}");
    // Edit: a syntax error is located too.
    let broken = fixed.replace("fov_y_degrees: 40", "fov_y_degree: 40");
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": s_uri, "version": 3}, "contentChanges": [{"text": broken}]}),
    );
    let d = c.diagnostics(&s_uri);
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(d[0]["range"]["start"]["line"], 2);
    assert!(
        d[0]["message"]
            .as_str()
            .unwrap_or("")
            .contains("did you mean `fov_y_degrees`"),
        "{d:#?}"
    );
    c.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": s_uri, "version": 4}, "contentChanges": [{"text": fixed}]}),
    );
    assert!(c.diagnostics(&s_uri).is_empty());
    let text = fixed;

    // Hover: documentation, type, default and range of a field.
    let h = c.at("textDocument/hover", &s_uri, pos(&text, "fov_y_degrees", 0, 2));
    let md = h["contents"]["value"].as_str().unwrap_or("").to_string();
    assert!(md.contains("Full vertical field of view"), "{md}");
    assert!(md.contains("range: ≥ 0, ≤ 180"), "{md}");
    // Only perspective cameras need a field of view; every sphere a
    // radius. (`eye` is required unless a glTF camera is taken: the
    // checks say so, the schema cannot.)
    assert!(!md.contains("(required)"), "{md}");
    let h = c.at("textDocument/hover", &s_uri, pos(&text, "radius", 0, 1));
    let md = h["contents"]["value"].as_str().unwrap_or("").to_string();
    assert!(md.contains("(required)"), "{md}");
    let h = c.at("textDocument/hover", &s_uri, pos(&text, "eye", 0, 1));
    let md = h["contents"]["value"].as_str().unwrap_or("").to_string();
    assert!(md.contains("unless `gltf` takes"), "{md}");
    let h = c.at("textDocument/hover", &s_uri, pos(&text, "light_samples", 0, 1));
    let md = h["contents"]["value"].as_str().unwrap_or("").to_string();
    assert!(md.contains("default: `1`") && md.contains("integer"), "{md}");
    let h = c.at("textDocument/hover", &s_uri, pos(&text, "Lambert", 0, 1));
    assert!(
        h["contents"]["value"].as_str().unwrap_or("").contains("albedo"),
        "{h}"
    );

    // Completion: missing fields, variants, the scene's material names.
    let labels = |v: &Value| -> Vec<String> {
        v.as_array()
            .into_iter()
            .flatten()
            .filter_map(|i| i["label"].as_str().map(String::from))
            .collect()
    };
    let items = labels(&c.at("textDocument/completion", &s_uri, pos(&text, "eye", 0, 0)));
    assert!(
        items.contains(&"up".into()) && items.contains(&"aperture_radius".into()),
        "{items:?}"
    );
    assert!(
        !items.contains(&"eye".into()),
        "fields already written are not offered: {items:?}"
    );
    let items = labels(&c.at("textDocument/completion", &s_uri, pos(&text, "Direct", 0, 0)));
    for v in ["Direct", "Whitted", "Path"] {
        assert!(items.contains(&v.into()), "{items:?}");
    }
    let items = labels(&c.at("textDocument/completion", &s_uri, pos(&text, "\"brick\"", 0, 1)));
    assert_eq!(items, ["brick", "white"], "own and included material names");

    // Go to definition: a material to its entry, here or in the included
    // file; an include to its file.
    let d = c.at("textDocument/definition", &s_uri, pos(&text, "\"white\"", 1, 2));
    assert_eq!(d["uri"], s_uri.as_str());
    assert_eq!(d["range"]["start"], json!({"line": 5, "character": 8}), "{d}");
    let d = c.at("textDocument/definition", &s_uri, pos(&text, "\"brick\"", 0, 2));
    assert_eq!(d["uri"], lib_uri.as_str(), "{d}");
    assert_eq!(d["range"]["start"], json!({"line": 3, "character": 8}), "{d}");
    let d = c.at("textDocument/definition", &s_uri, pos(&text, "lib.ron", 0, 1));
    assert_eq!(d["uri"], lib_uri.as_str(), "{d}");

    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    let status = c.child.wait().expect("exits");
    assert!(status.success(), "ronray lsp exits cleanly: {status}");
}

/// CPU time (user + system, in clock ticks) `pid` has used so far.
fn cpu_ticks(pid: u32) -> u64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).expect("/proc/PID/stat");
    // Fields after the command name (in parentheses, which may hold spaces):
    // state is field 3, utime 14, stime 15.
    let rest = &stat[stat.rfind(')').expect("comm") + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    f[11].parse::<u64>().expect("utime") + f[12].parse::<u64>().expect("stime")
}

/// A valid scene but for `n` spheres each naming a material that does not
/// exist: `n` located errors.
fn scene_with_errors(n: usize) -> String {
    let objects: String = (0..n)
        .map(|i| format!("        Sphere(center: ({i}, 0, 0), radius: 0.5, material: \"nope{i}\"),\n"))
        .collect();
    format!(
        "Scene(\n    camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n    lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],\n    objects: [\n{objects}    ],\n)\n"
    )
}

/// The server's CPU ticks to publish the diagnostics of a scene with `n`
/// errors, and how many it published.
fn diagnostics_work(n: usize) -> (u64, usize) {
    let dir = tempfile::tempdir().expect("tmp");
    let scene = dir.path().join("big.ron");
    let text = scene_with_errors(n);
    std::fs::write(&scene, &text).expect("write");
    let mut c = Client::start();
    let u = uri(&scene);
    // A round trip first: the server is past its start-up work.
    c.at("textDocument/hover", &u, (0, 0));
    let before = cpu_ticks(c.child.id());
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": u, "languageId": "ron", "version": 1, "text": text}}),
    );
    // Minutes of patience: the quadratic server took that long.
    let published = loop {
        let v = c
            .incoming
            .recv_timeout(Duration::from_secs(900))
            .expect("diagnostics within 15 minutes");
        if v["method"] == "textDocument/publishDiagnostics" && v["params"]["uri"] == u.as_str() {
            break v["params"]["diagnostics"].as_array().map_or(0, Vec::len);
        }
    };
    let work = cpu_ticks(c.child.id()) - before;
    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    let _ = c.child.wait();
    (work, published)
}

/// Publishing diagnostics is linear in the document: 4× the errors in a
/// 4× larger document cost about 4× the server's CPU time, not 16× (it
/// located and converted each diagnostic by scanning the text from its
/// start: 80 s frozen on a 5.6 MB scene). CPU time of the server process,
/// not the wall clock; the bound, 8×, sits halfway between.
#[test]
fn lsp_diagnostics_work_is_linear_in_the_document() {
    let (n, m) = (4_000, 16_000);
    let (small, got_small) = diagnostics_work(n);
    let (large, got_large) = diagnostics_work(m);
    assert_eq!((got_small, got_large), (n, m), "every error published");
    let ratio = large as f64 / small.max(1) as f64;
    assert!(
        ratio < 8.0,
        "{m} errors took {large} CPU ticks, {n} took {small}: {ratio:.1}× for 4× the errors (linear is 4×, quadratic 16×)"
    );
}

/// The exit status the protocol asks for: 0 after `shutdown` then `exit`,
/// 1 on `exit` alone (it was 0 both ways).
#[test]
fn lsp_exit_status_says_whether_shutdown_came_first() {
    let mut c = Client::start();
    c.request("shutdown", Value::Null);
    c.notify("exit", Value::Null);
    let status = c.child.wait().expect("exits");
    assert_eq!(status.code(), Some(0), "exit after shutdown: {status}");

    let mut c = Client::start();
    c.notify("exit", Value::Null);
    let status = c.child.wait().expect("exits");
    assert_eq!(status.code(), Some(1), "exit without shutdown: {status}");
}

/// Issue 39: one header line, `Content-Length: 100000000000`, made the
/// server size a 100 GB buffer before any body byte arrived, and abort on
/// the failed allocation (SIGABRT). The server now refuses it, naming the
/// limit (`MAX_MESSAGE_BYTES`), and exits with status 1 at once: with its
/// input still open, a server that waited for the body would hang, and one
/// that allocated it would abort. Bounded by a deadline either way.
#[test]
fn lsp_refuses_a_content_length_past_the_limit_without_allocating_it() {
    // In 4 GiB of address space (`ulimit -v`): a regression that sizes the
    // buffer from the header aborts at once instead of taking the shared
    // machine's memory.
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {} && exec \"$0\" lsp", 4u64 << 20))
        .arg(env!("CARGO_BIN_EXE_ronray"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("ronray lsp starts");
    let mut stdin = child.stdin.take().expect("stdin");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("stdout")));
    let err = drain(Box::new(child.stderr.take().expect("stderr")));
    let frame = |v: Value| {
        let body = v.to_string();
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    };
    let init = json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"capabilities": {}, "processId": null, "rootUri": null}});
    let initialized = json!({"jsonrpc": "2.0", "method": "initialized", "params": {}});
    let text = format!(
        "{}{}Content-Length: 100000000000\r\n\r\n{{\"jsonrpc\":",
        frame(init),
        frame(initialized)
    );
    stdin.write_all(text.as_bytes()).expect("write");
    stdin.flush().expect("flush");
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("the server neither refused nor ended within a minute of a 100 GB Content-Length");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    drop(stdin);
    let err = String::from_utf8_lossy(&err.join().unwrap_or_default()).into_owned();
    let out = String::from_utf8_lossy(&out.join().unwrap_or_default()).into_owned();
    assert_eq!(
        status.code(),
        Some(1),
        "expected exit status 1, got {status} (a signal is an abort)\n{err}"
    );
    assert!(
        err.contains("a message of 100000000000 bytes is above the limit of"),
        "stderr: {err}"
    );
    assert!(
        out.contains("\"id\":1"),
        "the server never answered `initialize`: {out}"
    );
}
