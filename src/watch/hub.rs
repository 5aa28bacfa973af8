//! The latest state of a watch session, shared between the render worker
//! (which publishes) and the web page's event streams (which wait for news).
//!
//! Only the latest event of each kind is kept: a browser that falls behind
//! skips straight to the newest pass instead of replaying every one.

use crate::imageio::{Display, Image};
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
    /// The latest pass, whatever format the output file is.
    pub frame: Option<Arc<Frame>>,
}

/// A pass as the page shows it: the PNG at the scene's own display
/// settings, and the linear image to encode again at another exposure.
#[derive(Debug)]
pub struct Frame {
    /// PNG bytes at the scene's exposure and tone map (8-bit).
    pub png: Vec<u8>,
    /// The pass's linear pixels.
    pub image: Image,
    /// The scene's exposure and tone map.
    pub display: Display,
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

    pub fn publish(&self, kind: Kind, json: String, frame: Option<Frame>) {
        let mut s = self.lock();
        s.seq += 1;
        let seq = s.seq;
        s.events[kind as usize] = (seq, json);
        if let Some(frame) = frame {
            s.frame = Some(Arc::new(frame));
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
