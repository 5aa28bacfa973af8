//! The latest state of a watch session, shared between the render worker
//! (which publishes) and the web page's event streams (which wait for news).
//!
//! Only the latest event of each kind is kept: a browser that falls behind
//! skips straight to the newest pass instead of replaying every one.

use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

/// The server-sent event kinds. `diagnostics` is not called `error`:
/// `EventSource` already fires `error` for connection failures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Pass,
    Diagnostics,
    Progress,
}

pub const KINDS: [Kind; 3] = [Kind::Pass, Kind::Diagnostics, Kind::Progress];

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Pass => "pass",
            Kind::Diagnostics => "diagnostics",
            Kind::Progress => "progress",
        }
    }
}

/// The newest event of each kind, numbered so a reader can tell what it has
/// not sent yet; `seq` 0 means none yet.
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    pub seq: u64,
    pub events: [(u64, String); 3],
    /// The latest pass as PNG, whatever format the output file is.
    pub png: Option<Arc<Vec<u8>>>,
}

#[derive(Default)]
pub struct Hub {
    state: Mutex<Snapshot>,
    changed: Condvar,
}

impl Hub {
    fn lock(&self) -> MutexGuard<'_, Snapshot> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub fn publish(&self, kind: Kind, json: String, png: Option<Vec<u8>>) {
        let mut s = self.lock();
        s.seq += 1;
        let seq = s.seq;
        s.events[kind as usize] = (seq, json);
        if let Some(png) = png {
            s.png = Some(Arc::new(png));
        }
        drop(s);
        self.changed.notify_all();
    }

    pub fn snapshot(&self) -> Snapshot {
        self.lock().clone()
    }

    /// Waits until something newer than `seen` is published, or `timeout`.
    pub fn wait_newer(&self, seen: u64, timeout: Duration) -> Snapshot {
        let guard = self.lock();
        let (guard, _) = self
            .changed
            .wait_timeout_while(guard, timeout, |s| s.seq <= seen)
            .unwrap_or_else(PoisonError::into_inner);
        guard.clone()
    }
}

/// A JSON string literal.
pub fn json_str(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_str_escapes_quotes_newlines_and_controls() {
        assert_eq!(json_str("a\"b\\c\nd\u{1b}"), r#""a\"b\\c\nd\u001b""#);
    }

    #[test]
    fn hub_wakes_readers_with_the_newest_event() {
        let hub = Arc::new(Hub::default());
        let h = hub.clone();
        let reader = std::thread::spawn(move || h.wait_newer(0, Duration::from_secs(10)));
        hub.publish(Kind::Progress, "{}".into(), None);
        let s = reader.join().expect("reader");
        assert_eq!(s.seq, 1);
        assert_eq!(s.events[Kind::Progress as usize], (1, "{}".to_string()));
    }
}
