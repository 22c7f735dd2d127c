//! How much direct process noise a bounded station puts on heading and pitch: fixed, or chosen
//! per flight from its own forecasts of the packets (docs/beyond-the-paper.md, "Which hedge,
//! chosen per flight"; reference §4).

use serde::{Deserialize, Serialize};

/// The station's direct process noise on heading θ and pitch φ (`--heading-noise`; the adaptive
/// choice: [`HedgeChoice`]).
///
/// That noise does more than widen the 95 % region: the unscented mean of cos θ over a heading
/// spread σ² is about cos θ̄·e^(−σ²/2), so it shrinks the extrapolated velocity as a packet
/// ages, a hedge against turns the station cannot see. On straight legs the hedge costs, on a
/// loitering multicopter it pays, and which a flight is shows in how well each hedge would have
/// forecast the packets that arrived.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum HeadingNoise {
    /// q per second on θ and φ, as on every other component (the drone's q): the default.
    #[default]
    Fixed,
    /// 0, 1 or 3 × q on θ and φ, whichever has forecast the flight's packets best so far;
    /// bounded prediction only.
    Adaptive,
}

/// The factors on q for θ and φ that [`HeadingNoise::Adaptive`] chooses between: none (the
/// model's own heading, no hedge), q as for [`HeadingNoise::Fixed`], and three times as much.
pub const HEDGE_LEVELS: [f64; 3] = [0.0, 1.0, 3.0];

/// The level flown until enough packets have been scored: q, as with a fixed noise.
const START_LEVEL: usize = 1;

/// The weight a level's earlier misses keep at each packet: a flight's last ~10 packets decide.
pub const HEDGE_MEMORY: f64 = 0.9;

/// Packets scored before the choice leaves q. Without a minimum, one or two packets a flight
/// (SF9 and slower) decided it: DR's p95 at SF9 rose 13 %, DR's and the IMM's p75 at SF10
/// 8–9 %; with ten, SF7/250 kHz kept most of its gain, SF7/125 kHz half to three quarters
/// and SF8 little (a temporary build, 2026-11-29).
pub const HEDGE_MIN_SCORED: u32 = 5;

/// The most one packet's squared miss counts, m²: (1 km)², so that one wild forecast (a packet
/// after a long loss) does not decide the rest of a flight.
pub const HEDGE_MISS_CAP: f64 = 1e6;

/// The step of the forecasts that score the levels, s: coarser than the station's own T, since
/// they only rank the levels (in steps of T = 0.1 s the synthetic set's p75 at SF7–SF8 came
/// within 0.13 m of the same, for ten times the forecasts' cost).
pub const HEDGE_FORECAST_STEP: f64 = 1.0;

/// The per-flight choice of [`HeadingNoise::Adaptive`]: each level's squared forecast misses,
/// forgotten by [`HEDGE_MEMORY`] a packet, and the level with the least once
/// [`HEDGE_MIN_SCORED`] packets have been scored.
///
/// ```
/// use loratrack::HedgeChoice;
/// let mut c = HedgeChoice::default();
/// assert_eq!(c.factor(), 1.0);
/// for _ in 0..5 {
///     c.score([0.5, 4.0, 9.0]); // the hedge-free forecasts missed least
/// }
/// assert_eq!(c.factor(), 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HedgeChoice {
    misses: [f64; 3],
    scored: u32,
    level: usize,
}

impl Default for HedgeChoice {
    fn default() -> Self {
        HedgeChoice {
            misses: [0.0; 3],
            scored: 0,
            level: START_LEVEL,
        }
    }
}

impl HedgeChoice {
    /// The factor on q for θ and φ now.
    pub fn factor(&self) -> f64 {
        HEDGE_LEVELS[self.level]
    }

    /// A packet has arrived: `squared_misses[i]` m² is how far the forecast under
    /// [`HEDGE_LEVELS`]`[i]` from the packet before put the drone from where this one says it
    /// was, counted up to [`HEDGE_MISS_CAP`]; a forecast that is not finite counts as missing
    /// by that much.
    pub fn score(&mut self, squared_misses: [f64; 3]) {
        for (total, miss) in self.misses.iter_mut().zip(squared_misses) {
            let miss = if miss.is_finite() {
                miss.min(HEDGE_MISS_CAP)
            } else {
                HEDGE_MISS_CAP
            };
            *total = HEDGE_MEMORY * *total + miss;
        }
        self.scored += 1;
        if self.scored >= HEDGE_MIN_SCORED {
            // The first of equals: the order of HEDGE_LEVELS breaks ties toward less hedge.
            self.level = (0..HEDGE_LEVELS.len()).fold(0, |best, i| {
                if self.misses[i] < self.misses[best] {
                    i
                } else {
                    best
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flight_flies_q_until_five_packets_are_scored() {
        let mut c = HedgeChoice::default();
        for _ in 0..HEDGE_MIN_SCORED - 1 {
            c.score([0.0, 10.0, 20.0]);
            assert_eq!(c.factor(), 1.0);
        }
        c.score([0.0, 10.0, 20.0]);
        assert_eq!(c.factor(), 0.0);
    }

    #[test]
    fn recent_misses_outweigh_old_ones() {
        let mut c = HedgeChoice::default();
        for _ in 0..10 {
            c.score([1.0, 5.0, 9.0]);
        }
        assert_eq!(c.factor(), 0.0);
        // The flight starts to loiter: the most hedge forecasts best from now on.
        for _ in 0..10 {
            c.score([30.0, 20.0, 2.0]);
        }
        assert_eq!(c.factor(), 3.0);
    }

    #[test]
    fn a_forecast_that_is_not_finite_loses_and_the_scores_stay_finite() {
        let mut c = HedgeChoice::default();
        for _ in 0..6 {
            c.score([f64::NAN, 4.0, f64::INFINITY]);
        }
        assert_eq!(c.factor(), 1.0);
        assert!(c.misses.iter().all(|m| m.is_finite()));
    }

    #[test]
    fn the_names_are_the_cli_and_js_names() {
        let name = |n: HeadingNoise| serde_json::to_string(&n).unwrap();
        assert_eq!(name(HeadingNoise::Fixed), "\"fixed\"");
        assert_eq!(name(HeadingNoise::Adaptive), "\"adaptive\"");
        assert_eq!(HeadingNoise::default(), HeadingNoise::Fixed);
    }
}
