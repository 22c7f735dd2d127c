//! A progress line on standard error for the runs a person waits for (a swarm of 500 drones
//! flying an hour, a whole set over many seeds, a sweep of hundreds of runs): shown only on a
//! terminal, so that scripts, pipes and the tests read stderr as before, and only once a run has
//! taken longer than [`DELAY`].

use loratrack::Simulator;
use std::io::{IsTerminal, Write};
use std::sync::{Arc, Mutex};
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
    /// When the line was last written, and what it said after the name.
    shown: Option<(Instant, String)>,
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
        let percent = 100 * done.min(total) / total.max(1);
        self.show(|| format!("{percent} %"));
    }

    /// `runs` runs are done, of a number not known in advance (a sweep's).
    pub fn count(&mut self, runs: usize) {
        let seconds = self.started.elapsed().as_secs();
        self.show(|| format!("{runs} runs done, {seconds} s"));
    }

    /// Writes `text()` after the name, when the line is due and says something new.
    fn show(&mut self, text: impl FnOnce() -> String) {
        let Some(out) = &mut self.out else {
            return;
        };
        let now = Instant::now();
        let due = match &self.shown {
            None => now - self.started >= self.delay,
            Some((at, _)) => now - *at >= INTERVAL,
        };
        if !due {
            return;
        }
        let text = text();
        if self.shown.as_ref().is_some_and(|(_, shown)| *shown == text) {
            return;
        }
        // A terminal that cannot be written to only loses the line; the rest of an older,
        // longer text is cleared.
        let _ = write!(out, "\rloratrack {}: {text}\x1b[K", self.what).and_then(|_| out.flush());
        self.shown = Some((now, text));
    }
}

/// A sweep's runs, counted on one progress line whichever simulator or swarm batch ran them:
/// cheap to clone and shareable between threads.
#[derive(Clone)]
pub struct RunCount {
    /// The line, and the runs done.
    line: Arc<Mutex<(Progress<std::io::Stderr>, usize)>>,
}

impl RunCount {
    /// A count of `what`'s runs on standard error, when standard error is a terminal; the line
    /// is erased when the last clone is dropped.
    pub fn on_stderr(what: &'static str) -> Self {
        RunCount {
            line: Arc::new(Mutex::new((Progress::on_stderr(what), 0))),
        }
    }

    /// One more run is done.
    pub fn done(&self) {
        // A poisoned line (a run panicked while counting) only stops counting.
        if let Ok(mut line) = self.line.lock() {
            line.1 += 1;
            let runs = line.1;
            line.0.count(runs);
        }
    }

    /// A simulator whose every run is counted here.
    pub fn simulator(&self) -> Simulator {
        let mut sim = Simulator::new();
        let runs = self.clone();
        sim.on_each_run(move || runs.done());
        sim
    }
}

impl<W: Write> Drop for Progress<W> {
    /// Erases the line, so that the report or an error starts on a clean one.
    fn drop(&mut self) {
        if let (Some(out), Some(_)) = (&mut self.out, &self.shown) {
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
            "\rloratrack swarm: 0 %\x1b[K\rloratrack swarm: 37 %\x1b[K\rloratrack swarm: 100 %\x1b[K\r\x1b[K"
        );
    }

    #[test]
    fn a_sweep_counts_its_runs_with_the_time_taken() {
        let mut buffer = Vec::new();
        {
            let mut p = Progress::to(Some(&mut buffer), "sweep", Duration::ZERO);
            for runs in 1..=3 {
                p.count(runs);
                std::thread::sleep(INTERVAL);
            }
        }
        let text = String::from_utf8(buffer).unwrap();
        let lines: Vec<&str> = text.split('\r').skip(1).collect();
        assert_eq!(lines.len(), 4, "three counts and the erasure: {text:?}");
        for (runs, line) in (1..=3).zip(&lines) {
            assert!(
                line.starts_with(&format!("loratrack sweep: {runs} runs done, "))
                    && line.ends_with(" s\x1b[K"),
                "{line:?}"
            );
        }
        assert_eq!(lines[3], "\x1b[K");
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
