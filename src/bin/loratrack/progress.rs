//! A progress line on standard error for the runs a person waits for (a swarm of 500 drones
//! flying an hour, a whole set over many seeds): shown only on a terminal, so that scripts, pipes
//! and the tests read stderr as before, and only once a run has taken longer than [`DELAY`].

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// How long a run goes before its progress is shown: a quick run prints nothing.
const DELAY: Duration = Duration::from_millis(500);
/// The least time between two updates of the line.
const INTERVAL: Duration = Duration::from_millis(100);

/// One run's progress line: `loratrack swarm: 37 %` rewritten in place, erased when the run
/// ends (or fails, before its `error: ...` line).
pub struct Progress<W: Write> {
    /// Where the line goes; `None` prints nothing.
    out: Option<W>,
    /// What runs: `swarm`, `simulate`.
    what: &'static str,
    started: Instant,
    delay: Duration,
    /// When the line was last written, and its percentage.
    shown: Option<(Instant, u32)>,
}

impl Progress<std::io::Stderr> {
    /// Progress of `what` on standard error, when standard error is a terminal.
    pub fn on_stderr(what: &'static str) -> Self {
        let err = std::io::stderr();
        let out = err.is_terminal().then_some(err);
        Progress::to(out, what, DELAY)
    }
}

impl<W: Write> Progress<W> {
    /// Progress of `what` to `out`, shown once `delay` has passed.
    pub fn to(out: Option<W>, what: &'static str, delay: Duration) -> Self {
        Progress {
            out,
            what,
            started: Instant::now(),
            delay,
            shown: None,
        }
    }

    /// `done` of `total` units of work are done.
    pub fn update(&mut self, done: usize, total: usize) {
        let Some(out) = &mut self.out else {
            return;
        };
        let now = Instant::now();
        let percent = (100 * done.min(total) / total.max(1)) as u32;
        let due = match self.shown {
            None => now - self.started >= self.delay,
            Some((at, shown)) => percent != shown && now - at >= INTERVAL,
        };
        if due {
            // A terminal that cannot be written to only loses the line.
            let _ = write!(out, "\rloratrack {}: {percent} %", self.what).and_then(|_| out.flush());
            self.shown = Some((now, percent));
        }
    }
}

impl<W: Write> Drop for Progress<W> {
    /// Erases the line, so that the report or an error starts on a clean one.
    fn drop(&mut self) {
        if let (Some(out), Some(_)) = (&mut self.out, self.shown) {
            let _ = write!(out, "\r\x1b[K").and_then(|_| out.flush());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The text a progress line wrote to a buffer, by `steps` of a run of 100 units.
    fn written(delay: Duration, steps: &[usize]) -> String {
        let mut buffer = Vec::new();
        {
            let mut p = Progress::to(Some(&mut buffer), "swarm", delay);
            for &done in steps {
                p.update(done, 100);
                std::thread::sleep(INTERVAL);
            }
        }
        String::from_utf8(buffer).unwrap()
    }

    #[test]
    fn a_long_run_shows_its_percentage_and_erases_the_line_at_the_end() {
        let text = written(Duration::ZERO, &[0, 37, 37, 100]);
        assert_eq!(
            text,
            "\rloratrack swarm: 0 %\rloratrack swarm: 37 %\rloratrack swarm: 100 %\r\x1b[K"
        );
    }

    #[test]
    fn a_quick_run_prints_nothing() {
        assert_eq!(written(Duration::from_secs(60), &[0, 50, 100]), "");
    }

    #[test]
    fn without_a_terminal_nothing_is_written() {
        let mut p = Progress::<Vec<u8>>::to(None, "swarm", Duration::ZERO);
        p.update(1, 2);
        assert!(p.out.is_none());
    }
}
