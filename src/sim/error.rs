use crate::lora::LoraError;
use crate::options::{as_given, OutOfRange, MAX_FILTER_STEPS, MAX_SWARM_FILTER_STEPS, SEED};
use crate::trajectory::{PlanError, TrajectoryError};
use core::fmt;

/// Why a simulation could not run.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// The flight could not be read.
    Trajectory(TrajectoryError),
    /// The mission plan could not be read (reference §16).
    Plan(PlanError),
    /// A LoRa setting is invalid.
    Lora(LoraError),
    /// A setting outside its declared limits ([`crate::options`]).
    OutOfRange(OutOfRange),
    /// A simulation parameter is out of range (name, value, what is allowed).
    Parameter(&'static str, f64, &'static str),
    /// No flight was chosen, or more than one.
    Source(String),
    /// A seed above 2^53 − 1.
    Seed(u64),
    /// Repeats whose seeds (`first`, `first` + 1, …, `count` of them) run past 2^53 − 1.
    Seeds {
        /// The first seed.
        first: u64,
        /// How many seeds.
        count: u32,
    },
    /// ADR asked for with a start (SF, bandwidth in kHz) that is no EU868 data rate.
    AdrStart(u8, f64),
    /// Error-triggered sending's heartbeat shorter than a drone's duty-cycle interval: it could
    /// never be kept.
    Heartbeat {
        /// The heartbeat (`maxInterval`), s.
        max_interval: f64,
        /// The spreading factor and bandwidth (kHz) whose interval it misses.
        sf: u8,
        /// See `sf`.
        bw_khz: f64,
        /// That data rate's duty-cycle interval, s.
        interval: f64,
    },
    /// More filter steps than one run may take (flight time × (sensor rate + 1 / T)).
    TooLong {
        /// Seconds of flight, every seed's or every drone's.
        flight_time: f64,
        /// Filter steps it would take: per model for `simulate`, over every drone for a swarm.
        steps: f64,
        /// Which run, with what its remedy names.
        run: LongRun,
    },
    /// A setting changed from its default where it changes nothing (a `threshold` while sending
    /// periodically): refused, as `dutyCycle` is without a duty cycle, so that no run goes ahead
    /// on other settings than those it was given.
    Unused {
        /// The setting's key (`threshold`).
        setting: &'static str,
        /// Whose setting it is ("error-triggered sending's").
        whose: &'static str,
        /// What makes it apply ("set `sender` to error").
        remedy: &'static str,
    },
    /// The run's progress callback asked it to stop ([`Simulator::run_stoppable`]).
    ///
    /// [`Simulator::run_stoppable`]: super::Simulator::run_stoppable
    Stopped,
}

/// A count rounded to a whole number, its thousands grouped as the docs write them (SI: "36 000
/// 000"), with no-break spaces, so that a message wrapped on a phone never splits a number.
fn grouped(x: f64) -> String {
    let digits = format!("{:.0}", x.abs());
    if digits.len() <= 4 || !x.is_finite() {
        return format!("{x:.0}");
    }
    let mut out = String::from(if x < 0.0 { "-" } else { "" });
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push('\u{a0}');
        }
        out.push(d);
    }
    out
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Trajectory(e) => e.fmt(f),
            SimError::Plan(e) => e.fmt(f),
            SimError::Lora(e) => e.fmt(f),
            SimError::OutOfRange(e) => e.fmt(f),
            SimError::Parameter(name, v, allowed) => {
                write!(f, "{name} must be {allowed}, got {}", as_given(*v))
            }
            SimError::Heartbeat {
                max_interval,
                sf,
                bw_khz,
                interval,
            } => write!(
                f,
                "maxInterval must be at least the duty-cycle interval of every drone's data rate (SF{sf} at {bw_khz} kHz: {} s), got {}",
                as_given(tenths_up(*interval)),
                as_given(*max_interval)
            ),
            SimError::Source(msg) => f.write_str(msg),
            SimError::Unused {
                setting,
                whose,
                remedy,
            } => write!(f, "`{setting}` is {whose}: {remedy}"),
            SimError::Stopped => f.write_str("the run was stopped by its progress callback"),
            SimError::Seed(seed) => write!(
                f,
                "seed must be 0..{} (2^53 - 1, the largest integer JavaScript holds exactly), got {seed}",
                SEED.max
            ),
            SimError::Seeds { first, count } => write!(
                f,
                "seeds {first}..{} run past the largest seed, {} (2^53 - 1); with {count} seeds the seed can be at most {}",
                first.saturating_add(u64::from(*count) - 1),
                SEED.max,
                SEED.max as u64 + 1 - u64::from(*count)
            ),
            SimError::AdrStart(sf, bw) => write!(
                f,
                "`adr` starts at an EU868 data rate (SF7..12 at 125 kHz or SF7 at 250 kHz), got SF{sf} at {bw} kHz"
            ),
            SimError::TooLong {
                flight_time,
                steps,
                run: LongRun::Simulate { .. },
            } => {
                write!(
                    f,
                    "the run is too long: {} s of flight at these rates is {} filter steps per model; \
                     the limit is {} (",
                    grouped(*flight_time),
                    grouped(*steps),
                    grouped(MAX_FILTER_STEPS as f64)
                )?;
                if let Some(("seeds", room)) = self.fewer_that_fit() {
                    write!(f, "at most {}, or ", counted(room, "seed"))?;
                }
                f.write_str("shorten the flight, lower the sensor rate or lengthen the step T)")
            }
            SimError::TooLong {
                flight_time,
                steps,
                run: LongRun::Swarm { .. },
            } => {
                write!(
                    f,
                    "the swarm is too long: its drones fly {} s in all, {} filter steps at these rates; \
                     the limit is {} (",
                    grouped(*flight_time),
                    grouped(*steps),
                    grouped(MAX_SWARM_FILTER_STEPS as f64)
                )?;
                // Where one drone's flights are already too long, fewer drones would not do.
                if let Some(("drones", room)) = self.fewer_that_fit() {
                    write!(f, "at most {}, or ", counted(room, "drone"))?;
                }
                f.write_str("shorter flights, a lower sensor rate or a longer step T)")
            }
        }
    }
}

/// `n` and the noun `one` names one of, in the plural unless `n` is 1: "1 seed", "18 seeds".
fn counted(n: u32, one: &str) -> String {
    if n == 1 {
        format!("1 {one}")
    } else {
        format!("{n} {one}s")
    }
}

/// The run [`SimError::TooLong`] refuses, for its remedy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LongRun {
    /// `simulate`: one drone over its flights, once per seed.
    Simulate {
        /// The seeds each flight is flown with.
        seeds: u64,
        /// How many of them fit at these rates (the report's `maxSeeds`).
        fit: u32,
    },
    /// `swarm`: every drone's flights.
    Swarm {
        /// The swarm's drones.
        drones: usize,
        /// How many of them fit at these rates, each flying what it flies in this swarm (0
        /// where one drone's flights are already too long).
        fit: u32,
    },
}

impl std::error::Error for SimError {}

impl SimError {
    /// [`SimError::Unused`] for the first of `settings` (each its key and whether it was changed
    /// from its default) that was changed, unless they apply; `whose` they are and the `remedy`
    /// that makes them apply as that variant words them.
    pub(crate) fn unless_read(
        applies: bool,
        settings: &[(&'static str, bool)],
        whose: &'static str,
        remedy: &'static str,
    ) -> Result<(), SimError> {
        match settings.iter().find(|(_, changed)| *changed) {
            Some(&(setting, _)) if !applies => Err(SimError::Unused {
                setting,
                whose,
                remedy,
            }),
            _ => Ok(()),
        }
    }

    /// For a run too long only for how many times it flies, the setting that counts them and how
    /// many would fit: a `simulate` run's seeds (the whole synthetic set at the default rates:
    /// 18), a swarm's drones. `None` for any other error, or where one is already too long.
    fn fewer_that_fit(&self) -> Option<(&'static str, u32)> {
        match self {
            SimError::TooLong {
                run: LongRun::Simulate { seeds, fit },
                ..
            } if *seeds > 1 && *fit >= 1 => Some(("seeds", *fit)),
            SimError::TooLong {
                run: LongRun::Swarm { drones, fit },
                ..
            } if *drones > 1 && *fit >= 1 => Some(("drones", *fit)),
            _ => None,
        }
    }

    /// The value of the setting this error names ([`Self::setting`]) with which the run would go
    /// ahead, every other setting as it is, where the error knows one: for a `simulate` run too
    /// long only for its several seeds, how many fit, and for a swarm too long only for its many
    /// drones, how many fit; for error-triggered sending's heartbeat (`maxInterval`), the slowest
    /// drone's duty-cycle interval rounded up to 0.1 s, as the message gives it. `None` for any
    /// other error.
    pub fn value_that_fits(&self) -> Option<f64> {
        match self {
            SimError::Heartbeat { interval, .. } => Some(tenths_up(*interval)),
            _ => self.fewer_that_fit().map(|(_, n)| f64::from(n)),
        }
    }

    /// The setting this error refuses, by its key in the JS API and the page's form (as
    /// [`LoraError::setting`]); `None` where no one setting is at fault (a choice of flight that
    /// conflicts with another setting, a run too long for its several settings together; one
    /// too long only for its seeds names `seeds`, a swarm too long only for its drones `drones`).
    pub fn setting(&self) -> Option<&'static str> {
        match self {
            SimError::Trajectory(e) => Some(e.setting()),
            SimError::Plan(_) => Some("plan"),
            SimError::Lora(e) => e.setting(),
            SimError::OutOfRange(e) => Some(e.option.key),
            SimError::Parameter(name, ..) => Some(name),
            SimError::Heartbeat { .. } => Some("maxInterval"),
            SimError::Unused { setting, .. } => Some(setting),
            SimError::Seed(_) => Some("seed"),
            SimError::Seeds { .. } => Some("seeds"),
            SimError::AdrStart(..) => Some("adr"),
            SimError::TooLong { .. } => self.fewer_that_fit().map(|(setting, _)| setting),
            SimError::Source(_) | SimError::Stopped => None,
        }
    }
}

/// `x` rounded up to the next tenth, never below `x`: a limit quoted to 0.1 that a reader may type
/// back (a duty-cycle interval of 10.34 s is quoted as 10.4 s, not as 10.3 s, which falls short).
fn tenths_up(x: f64) -> f64 {
    let tenths = (x * 10.0).ceil();
    // k / 10 is the float nearest the decimal, so it prints as one; where x · 10 rounded down
    // onto k, that k / 10 may fall an ulp short of x, and the next tenth is taken.
    if tenths / 10.0 < x {
        (tenths + 1.0) / 10.0
    } else {
        tenths / 10.0
    }
}

impl From<TrajectoryError> for SimError {
    fn from(e: TrajectoryError) -> Self {
        SimError::Trajectory(e)
    }
}

impl From<PlanError> for SimError {
    fn from(e: PlanError) -> Self {
        SimError::Plan(e)
    }
}

impl From<OutOfRange> for SimError {
    fn from(e: OutOfRange) -> Self {
        SimError::OutOfRange(e)
    }
}

impl From<LoraError> for SimError {
    fn from(e: LoraError) -> Self {
        SimError::Lora(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_interval_is_quoted_rounded_up_so_that_the_quoted_value_suffices() {
        assert_eq!(tenths_up(10.34), 10.4);
        assert_eq!(tenths_up(10.3), 10.3);
        assert_eq!(tenths_up(148.27), 148.3);
        for k in 1..20_000 {
            let x = f64::from(k) * 0.0137;
            let q = tenths_up(x);
            assert!(q >= x && q < x + 0.1 + 1e-9, "{x} -> {q}");
            // Printed as the decimal it is, one digit after the point.
            assert_eq!(
                format!("{q:?}").split('.').nth(1).map(str::len),
                Some(1),
                "{q:?}"
            );
        }
    }

    #[test]
    fn large_counts_are_grouped_in_thousands_that_never_break_apart() {
        assert_eq!(grouped(242_400_000.0), "242\u{a0}400\u{a0}000");
        assert_eq!(grouped(36_000_000.0), "36\u{a0}000\u{a0}000");
        assert_eq!(grouped(162_000.4), "162\u{a0}000");
        assert_eq!(grouped(99_999.6), "100\u{a0}000");
        assert_eq!(grouped(1000.0), "1000");
        assert_eq!(grouped(-12_345.0), "-12\u{a0}345");
        assert_eq!(grouped(f64::INFINITY), "inf");
    }

    #[test]
    fn a_too_long_swarm_gives_its_counts_grouped() {
        let e = SimError::TooLong {
            flight_time: 240_000.0,
            steps: 242_400_000.0,
            run: LongRun::Swarm {
                drones: 200,
                fit: 29,
            },
        };
        assert!(
            e.to_string().starts_with(
                "the swarm is too long: its drones fly 240\u{a0}000 s in all, 242\u{a0}400\u{a0}000 filter steps \
                 at these rates; the limit is 36\u{a0}000\u{a0}000 (at most 29 drones, or shorter"
            ),
            "{e}"
        );
    }

    #[test]
    fn room_for_one_seed_or_one_drone_is_named_in_the_singular() {
        let run = |run| SimError::TooLong {
            flight_time: 5280.0,
            steps: 1_636_806.0,
            run,
        };
        let one_seed = run(LongRun::Simulate { seeds: 2, fit: 1 }).to_string();
        assert!(
            one_seed.contains("(at most 1 seed, or shorten"),
            "{one_seed}"
        );
        let seeds = run(LongRun::Simulate { seeds: 20, fit: 2 }).to_string();
        assert!(seeds.contains("(at most 2 seeds, or shorten"), "{seeds}");
        let one_drone = run(LongRun::Swarm { drones: 2, fit: 1 }).to_string();
        assert!(
            one_drone.contains("(at most 1 drone, or shorter"),
            "{one_drone}"
        );
    }

    #[test]
    fn a_heartbeat_refusal_names_maxinterval_and_the_value_that_fits() {
        let e = SimError::Heartbeat {
            max_interval: 10.0,
            sf: 9,
            bw_khz: 250.0,
            interval: 10.34,
        };
        assert_eq!(e.setting(), Some("maxInterval"));
        assert_eq!(e.value_that_fits(), Some(10.4));
        assert!(
            e.to_string().contains("(SF9 at 250 kHz: 10.4 s), got 10"),
            "{e}"
        );
    }
}
