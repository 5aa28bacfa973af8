//! Turning a burst of filesystem events into one reload.
//!
//! One save is often several events (truncate, write, close; or create temp,
//! write, rename), and a script may save many times in a row. A reload waits
//! until the files have been quiet for [`QUIET`], but never more than
//! [`MAX_WAIT`] after the first event, so a file written continuously still
//! shows up.

use std::time::{Duration, Instant};

/// Long enough to cover the events of one save, short enough not to be felt.
pub const QUIET: Duration = Duration::from_millis(75);
pub const MAX_WAIT: Duration = Duration::from_millis(500);

/// The events seen since the last reload.
#[derive(Clone, Copy, Debug, Default)]
pub struct Debounce {
    first: Option<Instant>,
    last: Option<Instant>,
}

impl Debounce {
    pub fn note(&mut self, now: Instant) {
        self.first.get_or_insert(now);
        self.last = Some(now);
    }

    /// When to reload, if anything changed.
    pub fn deadline(&self) -> Option<Instant> {
        match (self.first, self.last) {
            (Some(first), Some(last)) => Some((last + QUIET).min(first + MAX_WAIT)),
            _ => None,
        }
    }

    /// The time of the batch's first event, once the batch is due; the
    /// batch is then cleared.
    pub fn take_due(&mut self, now: Instant) -> Option<Instant> {
        let due = self.deadline()? <= now;
        if due {
            let first = self.first;
            *self = Debounce::default();
            first
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn debounce_waits_for_quiet() {
        let t0 = Instant::now();
        let mut d = Debounce::default();
        assert_eq!(d.take_due(t0), None);
        d.note(t0);
        d.note(t0 + 50 * MS);
        assert_eq!(
            d.take_due(t0 + 100 * MS),
            None,
            "50 ms after the last event is not quiet"
        );
        assert_eq!(d.take_due(t0 + 125 * MS), Some(t0));
        assert_eq!(d.deadline(), None, "a taken batch is cleared");
    }

    #[test]
    fn debounce_gives_up_waiting_after_max_wait() {
        let t0 = Instant::now();
        let mut d = Debounce::default();
        let mut t = t0;
        while t < t0 + MAX_WAIT {
            d.note(t);
            t += 20 * MS;
        }
        assert_eq!(d.deadline(), Some(t0 + MAX_WAIT));
        assert_eq!(d.take_due(t0 + MAX_WAIT), Some(t0));
    }
}
