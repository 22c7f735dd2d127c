//! A drone's clock as its radio stack sees it: a crystal that runs a few parts per million fast
//! or slow, and the random delay a LoRaWAN stack adds before each uplink. Both decide *when* a
//! packet leaves; neither changes what it carries. `docs/reference.md` §13.
//!
//! Why it matters: senders that wait exactly the duty-cycle off-time on a shared sensor grid
//! keep their starting phases forever, so whether two drones collide is fixed by luck at the
//! start (12 drones on one SF7 channel never collided, 36 collided at 0.45). Real clocks drift
//! (crystals are specified at ±10–20 ppm) and stacks randomise (LoRaMac-node's periodic
//! uplink example adds up to `APP_TX_DUTYCYCLE_RND` = 1 s), so the phases wander and collisions
//! follow the ALOHA formula.

use crate::rng::Rng;

/// A run's timing settings, resolved: every drone's clock drift is drawn from
/// ±`clock_drift_ppm` and its uplinks wait up to `jitter` s more.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// The largest clock error, parts per million.
    pub clock_drift_ppm: f64,
    /// The longest random delay before each uplink, s.
    pub jitter: f64,
}

impl Timing {
    /// The paper's timing: no drift, no delay.
    pub const EXACT: Timing = Timing {
        clock_drift_ppm: 0.0,
        jitter: 0.0,
    };

    /// Whether uplinks keep the paper's exact timing.
    pub fn is_exact(&self) -> bool {
        self.clock_drift_ppm == 0.0 && self.jitter == 0.0
    }
}

/// The timing of one drone's uplinks.
#[derive(Clone, Debug)]
pub struct Clock {
    /// Relative clock error (fraction; +2e-5 runs 20 ppm fast).
    drift: f64,
    /// The longest random delay before each uplink, s.
    jitter: f64,
    rng: Rng,
    /// A slot on GPS time: its offset from time 0 and the frame it repeats in, s.
    slot: Option<(f64, f64)>,
}

impl Clock {
    /// The paper's timing: packets leave on the drone's sensor steps as soon as the duty-cycle
    /// rule allows, with no delay and a perfect clock.
    pub fn exact() -> Self {
        Clock {
            drift: 0.0,
            jitter: 0.0,
            rng: Rng::new(0),
            slot: None,
        }
    }

    /// A drone that keeps a slot of a schedule: it sends only at `offset` + m·`frame` s, on GPS
    /// time (which a drone's GPS receiver gives to within a microsecond, so neither drift nor
    /// random delays apply).
    pub fn slotted(offset: f64, frame: f64) -> Self {
        Clock {
            slot: Some((offset, frame)),
            ..Clock::exact()
        }
    }

    /// The first slot start at or after `t` s, for a slotted clock; `t` otherwise.
    pub fn slot_at_or_after(&self, t: f64) -> f64 {
        match self.slot {
            Some((offset, frame)) => {
                let m = ((t - offset) / frame - 1e-9).ceil().max(0.0);
                offset + m * frame
            }
            None => t,
        }
    }

    /// The slot after the one starting at `t` s, for a slotted clock.
    pub fn slot_after(&self, t: f64) -> Option<f64> {
        self.slot
            .map(|(_, frame)| self.slot_at_or_after(t + frame / 2.0))
    }

    /// A clock whose drift is drawn uniformly from ±`max_drift_ppm` parts per million and which
    /// delays each uplink by a uniform draw from [0, `jitter`] s, both from `rng`.
    pub fn new(max_drift_ppm: f64, jitter: f64, mut rng: Rng) -> Self {
        let drift = (2.0 * rng.uniform() - 1.0) * max_drift_ppm * 1e-6;
        Clock {
            drift,
            jitter,
            rng,
            slot: None,
        }
    }

    /// Whether this is [`Clock::exact`]: uplinks then start on sensor steps, as the paper's do.
    pub fn is_exact(&self) -> bool {
        self.drift == 0.0 && self.jitter == 0.0 && self.slot.is_none()
    }

    /// The drift, as a fraction.
    pub fn drift(&self) -> f64 {
        self.drift
    }

    /// When the drone plans its next uplink after one that left at `sent` s, if the duty-cycle
    /// rule (in true time) allows the next at `earliest` s: the wait as the drone's own clock
    /// measures it (a fast clock ends it early, by `drift` of the wait), then the random delay.
    /// A slotted clock waits for the first slot at or after `earliest`.
    pub fn next_start(&mut self, sent: f64, earliest: f64) -> f64 {
        if self.slot.is_some() {
            // The schedule's frame is at least the duty-cycle interval; a rounding error must
            // not cost a whole frame.
            return self.slot_at_or_after(earliest - 1e-6);
        }
        let wait = (earliest - sent).max(0.0);
        sent + wait * (1.0 - self.drift) + self.delay()
    }

    /// One random delay before an uplink, s.
    pub fn delay(&mut self) -> f64 {
        if self.jitter > 0.0 {
            self.jitter * self.rng.uniform()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_clock_waits_exactly_the_off_time() {
        let mut c = Clock::exact();
        assert!(c.is_exact());
        assert_eq!(c.next_start(10.0, 16.17), 16.17);
    }

    #[test]
    fn drift_stays_within_its_bound_and_shortens_or_lengthens_the_wait() {
        for seed in 0..200 {
            let mut c = Clock::new(20.0, 0.0, Rng::new(seed));
            assert!(c.drift().abs() <= 20e-6);
            let next = c.next_start(0.0, 1000.0);
            assert!((next - 1000.0 * (1.0 - c.drift())).abs() < 1e-9);
        }
    }

    #[test]
    fn a_slotted_clock_sends_only_in_its_slot() {
        let mut c = Clock::slotted(0.25, 6.5);
        assert!(!c.is_exact());
        assert_eq!(c.slot_at_or_after(0.0), 0.25);
        assert_eq!(c.slot_at_or_after(0.25), 0.25);
        assert!((c.slot_at_or_after(0.3) - 6.75).abs() < 1e-12);
        assert!((c.next_start(0.25, 0.25 + 6.5) - 6.75).abs() < 1e-12);
        assert!((c.slot_after(6.75).unwrap() - 13.25).abs() < 1e-12);
    }

    #[test]
    fn jitter_delays_by_up_to_its_bound_and_spreads_the_delays() {
        let mut c = Clock::new(0.0, 1.0, Rng::new(3));
        let delays: Vec<f64> = (0..1000).map(|_| c.next_start(0.0, 5.0) - 5.0).collect();
        assert!(delays.iter().all(|d| (0.0..=1.0).contains(d)));
        let mean = delays.iter().sum::<f64>() / 1000.0;
        assert!((mean - 0.5).abs() < 0.05, "{mean}");
    }
}
