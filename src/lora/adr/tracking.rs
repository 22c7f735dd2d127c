//! A tracking-aware ADR: choose the data rate that keeps the station's newest packet youngest,
//! over the link's long run and, within that, for the next frame through a fade.

use super::{AckLimits, AdrNetwork, LinkAdrReq, UplinkReport};
use crate::lora::{Channel, DataRate};
use crate::math::normal_cdf;
use std::collections::VecDeque;

/// Uplinks (by frame counter, received or lost) the delivery estimate looks back over.
pub const TRACKING_WINDOW: usize = 96;
/// A better rate must promise a cost this fraction below the current rate's before the network
/// switches: the margin that keeps estimation noise (shadowing is correlated over ~100 m, so a
/// window holds few independent samples) from flipping the rate back and forth. Chosen with
/// the window on `sweep --distances` (docs/adr.md).
pub const TRACKING_HYSTERESIS: f64 = 0.5;
/// The least shadowing spread assumed, dB, so that a channel without shadowing still gives a
/// smooth delivery curve.
const MIN_SIGMA_DB: f64 = 1.0;
/// The shortest decorrelation distance assumed, m (the channel accepts 1 m and up).
const MIN_DECORRELATION_M: f64 = 1.0;
/// The least spread of the next frame's shadowing given this frame's, dB: a drone that hovers
/// keeps its shadowing (ρ = 1), and the forecast should still not be a step.
const MIN_NEXT_SIGMA_DB: f64 = 0.5;

/// How the station's error grows with the age of its newest packet: error ∝ age^g. Between
/// packets the paper's stations extrapolate a constant acceleration and turn rate, so the
/// unmodelled manoeuvre's error grows about quadratically (g = 2).
pub const ERROR_GROWTH: i32 = 2;

/// The time average of age^(2g) ([`ERROR_GROWTH`] g), s^(2g), of the station's newest packet,
/// for packets sent every `interval` s, each arriving with probability `delivery`
/// independently, `time_on_air` s old when they arrive: a station's mean squared error up to a
/// constant.
///
/// With K ~ Geometric(`delivery`) intervals between arrivals the age runs from a =
/// `time_on_air` to a + K·`interval`, so the average is
/// E[((a + K T)^(m+1) − a^(m+1)) / (m+1)] / E[K T] with m = 2g, summed over K.
///
/// ```
/// use loratrack::expected_age_cost;
/// // Every packet arrives, error ∝ age²: the mean of u⁴ over [0, T] is T⁴/5.
/// assert!((expected_age_cost(2.0, 1.0, 0.0) - 16.0 / 5.0).abs() < 1e-9);
/// assert!(expected_age_cost(2.0, 0.5, 0.0) > 16.0 / 5.0);
/// ```
pub fn expected_age_cost(interval: f64, delivery: f64, time_on_air: f64) -> f64 {
    if delivery < 1e-6 {
        return f64::INFINITY;
    }
    let (p, t, a) = (delivery.min(1.0), interval, time_on_air);
    let m = (2 * ERROR_GROWTH + 1) as usize;
    // E[(a + K T)^m] by the binomial theorem.
    let mut binomial = 1.0;
    let mut e = 0.0;
    for j in 0..=m {
        e += binomial
            * crate::math::powi(a, (m - j) as i32)
            * crate::math::powi(t, j as i32)
            * geometric_moment(j, p);
        binomial = binomial * (m - j) as f64 / (j + 1) as f64;
    }
    (e - crate::math::powi(a, m as i32)) / m as f64 / (t / p)
}

/// E[K^n] for K ~ Geometric(p) on 1, 2, …: A_n(1 − p) / p^n with A_n the Eulerian polynomial.
fn geometric_moment(n: usize, p: f64) -> f64 {
    if n == 0 {
        return 1.0;
    }
    // Row n of the Eulerian numbers A(n, k), k = 0..n−1.
    let mut row = vec![1.0];
    for len in 2..=n {
        let prev = row.clone();
        row = (0..len)
            .map(|k| {
                let a = if k < prev.len() {
                    (k + 1) as f64 * prev[k]
                } else {
                    0.0
                };
                let b = if k > 0 {
                    (len - k) as f64 * prev[k - 1]
                } else {
                    0.0
                };
                a + b
            })
            .collect();
    }
    let q = 1.0 - p;
    let poly = row.iter().rev().fold(0.0, |acc, c| acc * q + c);
    poly / crate::math::powi(p, n as i32)
}

/// Standard normal density.
fn phi(z: f64) -> f64 {
    crate::math::exp(-0.5 * z * z) / (2.0 * core::f64::consts::PI).sqrt()
}

/// φ(z)/Φ(z), the inverse Mills ratio, stable in the far left tail where it tends to −z.
fn mills(z: f64) -> f64 {
    if z < -30.0 {
        -z
    } else {
        phi(z) / normal_cdf(z)
    }
}

/// A lost frame's score (the derivative of its log-likelihood in μ, times σ) at z = (its
/// sensitivity − μ) / σ, when it met another device's frame with probability `crowd`: lost
/// with probability c + (1 − c) Φ(z), so −(1 − c) φ(z) / (c + (1 − c) Φ(z)); −φ(z)/Φ(z) alone.
/// A crowd explains part of the losses, and the rest no longer reads as a weak link.
fn lost_score(z: f64, crowd: f64) -> f64 {
    if crowd <= 0.0 {
        return -mills(z);
    }
    -(1.0 - crowd) * phi(z) / (crowd + (1.0 - crowd) * normal_cdf(z))
}

#[derive(Clone, Copy, Debug)]
struct Frame {
    dr: DataRate,
    power_reduction_db: f64,
    rssi_dbm: Option<f64>,
    /// The chance it met another device's frame ([`UplinkReport::crowd_loss`]).
    crowd_loss: f64,
}

/// A window's frames as [`TrackingAdr::mean_rssi`]'s score reads them: a heard frame by its
/// full-power RSSI, dBm; a lost one by its kind, an index into `lost_kinds`, the distinct
/// (full-power sensitivity, dBm; crowd loss) pairs.
struct ScoreTerms {
    frames: Vec<Term>,
    lost_kinds: Vec<(f64, f64)>,
}

#[derive(Clone, Copy)]
enum Term {
    Heard(f64),
    Lost(usize),
}

impl ScoreTerms {
    fn of<'a>(frames: impl IntoIterator<Item = &'a Frame>) -> Self {
        let mut lost_kinds: Vec<(f64, f64)> = Vec::new();
        let frames = frames
            .into_iter()
            .map(|f| match f.rssi_dbm {
                Some(r) => Term::Heard(r + f.power_reduction_db),
                None => {
                    let kind = (
                        Channel::sensitivity_dbm(f.dr.sf(), f.dr.bw()) + f.power_reduction_db,
                        f.crowd_loss,
                    );
                    let same = |k: &(f64, f64)| {
                        k.0.to_bits() == kind.0.to_bits() && k.1.to_bits() == kind.1.to_bits()
                    };
                    Term::Lost(lost_kinds.iter().position(same).unwrap_or_else(|| {
                        lost_kinds.push(kind);
                        lost_kinds.len() - 1
                    }))
                }
            })
            .collect();
        ScoreTerms { frames, lost_kinds }
    }
}

/// The tracking-aware network ADR.
///
/// **The long run.** From the last [`TRACKING_WINDOW`] frames, received ones with their RSSI and
/// lost ones known from gaps in the frame counter (assumed sent at the settings of the frame
/// before), it estimates the mean full-power received power μ by maximum likelihood of a
/// censored normal (a lost frame's power lay below its rate's sensitivity; the spread σ is the
/// configured shadowing, at least 1 dB). Each rate's delivery is then Φ((μ − sensitivity)/σ) and
/// its cost [`expected_age_cost`] of its own interval. The cheapest rate becomes the *base* rate
/// when it beats the base by [`TRACKING_HYSTERESIS`].
///
/// **The crowd** (reference §6.5). Among other devices a frame is also lost when it meets
/// another's, with the chance c the server reports for its rate
/// ([`UplinkReport::crowd_loss`]): a lost frame is then a collision or a weak link, c + (1 − c)
/// Φ((sensitivity − μ)/σ), and each rate's delivery (1 − c) Φ((μ − sensitivity)/σ). Read as a
/// weak link alone, a crowd's collisions slowed every drone, which only made its frames longer
/// and rarer: 72 drones on one SF7 channel at 3 km sent 14 000 frames in 20 minutes where a fixed
/// SF7 sent 24 000. For a lone drone c = 0 and nothing changes.
///
/// **The next frame** (docs/adr.md). Shadowing is correlated along the path (Gudmundson 1991:
/// ρ = exp(−d / d₀) over d metres, d₀ the channel's decorrelation distance), so a received frame
/// says where the link is now, not only on average: its shadowing s = RSSI − μ decays toward 0
/// as ρ = exp(−v T / d₀) over one interval T of a rate at the speed v its payload reports, and
/// the next frame's delivery at that rate is Φ((μ + ρ s − sensitivity) / (σ √(1 − ρ²))). The
/// network asks for the rate, no faster than the base, whose [`expected_age_cost`] under that
/// delivery is least: a weak frame at the base rate (a fade coming) slows the next frames, and a
/// strong one brings them back to the base. Never faster than the base, because the device
/// cannot come back from a rate whose frames are lost (no frame heard, no command), and a fade
/// holds many frames; the forecast treats the frames ahead as one draw each.
///
/// Commands go at full power in the downlink after a received uplink, as LoRaWAN's ADR does; it
/// may slow the rate as well as speed it up.
#[derive(Clone, Debug)]
pub struct TrackingAdr {
    time_on_air: [f64; 7],
    interval: [f64; 7],
    sigma_db: f64,
    decorrelation_m: f64,
    frames: VecDeque<Frame>,
    next_fcnt: u32,
    settings: Option<(DataRate, f64)>,
    /// The settings last asked for, until a frame shows whether they were applied.
    commanded: Option<(DataRate, f64)>,
    /// The frame counter of the last uplink the network answered with a downlink: the device's
    /// back-off counts from the one after it.
    answered: Option<u32>,
    /// `answered` before the last downlink, restored when a frame shows that downlink was lost.
    answered_before: Option<u32>,
    /// The long-run choice (from the first frame heard on): the fastest rate a command may ask for.
    base: Option<DataRate>,
    /// The device's back-off, which the network set ([`tracking_ack_limits`]).
    limits: AckLimits,
    /// Each rate's chance of meeting another device's frame, from the last report.
    crowd_loss: [f64; 7],
}

/// The back-off a tracking network sets its devices to, when `devices` share `gateways`
/// (LoRaWAN 1.1 `ADRParamSetupReq`, §5.12: both limits as powers of two): `ADR_ACK_LIMIT` and
/// `ADR_ACK_DELAY` both the least power of two ≥ 2 × the devices per gateway, at least 2 and never
/// past the regional 64 and 32.
///
/// A drone that hears nothing cannot tell a lost uplink from a quiet network, so it learns its
/// link is gone only by asking (`ADRACKReq`) and backing off unanswered. With the regional
/// defaults that takes 96 uplinks, over three minutes at SF7 / 250 kHz: at 5 km from DR6 a
/// tenth of the synthetic set's flight time went by before the network heard the drone at all,
/// and in every fade deep enough to lose the commands the drone waited as long (docs/adr.md).
/// Each request costs the gateway a downlink, though, and a gateway may answer only within its
/// own duty cycle: a device on a good link forces one answer per `limit + 1` uplinks, a
/// downlink about as long as its uplink (RX1 at the uplink's rate) once per `limit + 1` duty-cycle
/// intervals, so n devices per gateway with limits ≥ 2n take under half of the gateway's 1 %
/// in RX1. Smaller limits in a swarm starve the gateway's answers, and drones that hear none
/// back off to rates where they collide and wait (72 drones at 3 km with 2 and 2: median
/// drone's p75 43 m → 7.8 km), so a shared gateway keeps the regional back-off.
pub fn tracking_ack_limits(devices: usize, gateways: usize) -> AckLimits {
    let per_gateway = devices.div_ceil(gateways.max(1)).max(1);
    let power = (2 * per_gateway).next_power_of_two() as u32;
    AckLimits {
        limit: power.min(AckLimits::LORAWAN.limit),
        delay: power.min(AckLimits::LORAWAN.delay),
    }
}

impl TrackingAdr {
    /// For packets of `time_on_air[dr]` s sent every `interval[dr]` s at each data rate, over a
    /// channel with `sigma_db` of shadowing that decorrelates over `decorrelation_m` metres flown.
    pub fn new(
        time_on_air: [f64; 7],
        interval: [f64; 7],
        sigma_db: f64,
        decorrelation_m: f64,
    ) -> Self {
        TrackingAdr {
            time_on_air,
            interval,
            sigma_db: sigma_db.max(MIN_SIGMA_DB),
            decorrelation_m: decorrelation_m.max(MIN_DECORRELATION_M),
            frames: VecDeque::new(),
            next_fcnt: 0,
            settings: None,
            commanded: None,
            answered: None,
            answered_before: None,
            base: None,
            limits: AckLimits::LORAWAN,
            crowd_loss: [0.0; 7],
        }
    }

    /// The same network, with its devices set to back off after `limits`
    /// ([`tracking_ack_limits`]): it counts a gap's lost frames by their back-off.
    pub fn with_ack_limits(mut self, limits: AckLimits) -> Self {
        self.limits = limits;
        self
    }

    fn record(&mut self, up: &UplinkReport) {
        let now = (up.dr, up.power_reduction_db);
        // Frames lost in a gap went at the settings the device used after the last frame heard:
        // the old ones if it still uses them, else mostly what the network last asked for.
        // Before the first frame the network knows nothing; the fastest rate is the guess that
        // claims least (a frame lost there says little about a slower rate's link).
        let start = match (self.settings, self.commanded.take()) {
            (None, _) => (DataRate::DR6, 0.0),
            (Some(before), _) if before == now => before,
            // A device that obeyed is at the commanded rate or, backing off, slower; one that
            // arrives faster never heard the command (its downlink was lost): the gap went at
            // the old settings, and its back-off counts from the downlink before.
            (Some(_), Some(asked)) if up.dr <= asked.0 => asked,
            (Some(before), Some(_)) => {
                self.answered = self.answered_before;
                before
            }
            (Some(before), None) => before,
        };
        for fcnt in self.next_fcnt..up.fcnt {
            let (dr, power_reduction_db) = if up.dr < start.0 {
                (self.backed_off(start.0, up, fcnt), 0.0)
            } else {
                start
            };
            let frame = Frame {
                dr,
                power_reduction_db,
                rssi_dbm: None,
                crowd_loss: up.crowd_loss[usize::from(dr.index())],
            };
            self.frames.push_back(frame);
        }
        self.frames.push_back(Frame {
            dr: up.dr,
            power_reduction_db: up.power_reduction_db,
            rssi_dbm: Some(up.rssi_dbm),
            crowd_loss: up.crowd_loss[usize::from(up.dr.index())],
        });
        self.crowd_loss = up.crowd_loss;
        while self.frames.len() > TRACKING_WINDOW {
            self.frames.pop_front();
        }
        self.settings = Some(now);
        self.next_fcnt = up.fcnt.wrapping_add(1);
    }

    /// The data rate lost frame `fcnt` most likely went at when the device arrives slower than
    /// `start` without being told to: it backed off on its own ([`AdrDevice::no_downlink`]), one
    /// rate per `delay` frames once `limit + delay` went unanswered since the last downlink the
    /// network sent (the [`AckLimits`] it set). Counting back from `up` puts the frames just before it
    /// at its rate and earlier ones faster, never faster than `start`. Without this the whole gap
    /// counted as lost at the slow rate it ended on (at 7 km from DR6, 166 frames "lost at DR3"
    /// for one heard), and the estimate sank ~8 dB below the link.
    ///
    /// [`AdrDevice::no_downlink`]: super::AdrDevice::no_downlink
    fn backed_off(&self, start: DataRate, up: &UplinkReport, fcnt: u32) -> DataRate {
        let reset = self.answered.map_or(0, |a| a.wrapping_add(1));
        let steps = |f: u32| self.limits.steps(f.wrapping_sub(reset));
        let faster_by = steps(up.fcnt).saturating_sub(steps(fcnt));
        let index = (u32::from(up.dr.index()) + faster_by).min(u32::from(start.index()));
        DataRate::ALL[index as usize]
    }

    /// The maximum-likelihood mean full-power RSSI, dBm, of the frames in the window.
    fn mean_rssi(&self) -> f64 {
        let s = self.sigma_db;
        let terms = ScoreTerms::of(&self.frames);
        let mut lost = vec![0.0; terms.lost_kinds.len()];
        let mut score = |mu: f64| -> f64 {
            // A window's lost frames share a few (sensitivity, crowd) pairs, so each pair's
            // exp and erfc are computed once; the frames are still added one by one in their
            // order, so the sum, and the root, are the same bits as term by term.
            for (value, &(c, crowd)) in lost.iter_mut().zip(&terms.lost_kinds) {
                *value = lost_score((c - mu) / s, crowd) / s;
            }
            terms
                .frames
                .iter()
                .map(|t| match *t {
                    Term::Heard(r) => (r - mu) / (s * s),
                    Term::Lost(k) => lost[k],
                })
                .sum()
        };
        // The score falls with μ (a censored normal is log-concave): bisect its root. With a
        // crowd a lost frame's pull fades far above its sensitivity, where a collision explains
        // it, so the score may turn and have more than one root; bisection still ends on one
        // (the score is positive at the bottom of the range and negative at the top), and where
        // frames are heard their linear pull makes it the only one.
        let (mut lo, mut hi) = (-300.0, 100.0);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            // Adjacent floats (after ~55 halvings of 400 dB): every further step leaves
            // 0.5·(lo + hi) at this mid, so the score's exps and erfcs would be spent for nothing.
            if mid == lo || mid == hi {
                break;
            }
            if score(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The estimated delivery ratio of each data rate at full power.
    pub fn delivery(&self) -> [f64; 7] {
        self.delivery_around(self.mean_rssi())
    }

    fn delivery_around(&self, mu: f64) -> [f64; 7] {
        DataRate::ALL.map(|dr| {
            let heard =
                normal_cdf((mu - Channel::sensitivity_dbm(dr.sf(), dr.bw())) / self.sigma_db);
            self.uncollided(dr) * heard
        })
    }

    /// The chance a frame at `dr` meets no other device's frame, as the last report said.
    fn uncollided(&self, dr: DataRate) -> f64 {
        1.0 - self.crowd_loss[usize::from(dr.index())]
    }

    /// Each rate's delivery for the next frame after `up`, received: its shadowing over the mean
    /// `mu`, carried forward one interval of that rate at the payload's speed (type docs).
    fn next_delivery(&self, up: &UplinkReport, mu: f64) -> [f64; 7] {
        let shadow = up.rssi_dbm + up.power_reduction_db - mu;
        let speed = if up.speed_mps.is_finite() {
            up.speed_mps.abs()
        } else {
            0.0
        };
        DataRate::ALL.map(|dr| {
            let k = usize::from(dr.index());
            let rho = crate::math::exp(-speed * self.interval[k] / self.decorrelation_m);
            let spread = (self.sigma_db * (1.0 - rho * rho).sqrt()).max(MIN_NEXT_SIGMA_DB);
            let margin = mu + rho * shadow - Channel::sensitivity_dbm(dr.sf(), dr.bw());
            self.uncollided(dr) * normal_cdf(margin / spread)
        })
    }

    /// The long-run choice after this frame: the cheapest rate when it beats the base by the
    /// hysteresis, else the base (the first frame's rate until then).
    fn update_base(&mut self, up: &UplinkReport, delivery: &[f64; 7]) -> Option<DataRate> {
        let base = self.base.unwrap_or(up.dr);
        let best = DataRate::ALL
            .into_iter()
            .min_by(|a, b| self.cost(*a, delivery).total_cmp(&self.cost(*b, delivery)))?;
        let better =
            self.cost(best, delivery) < (1.0 - TRACKING_HYSTERESIS) * self.cost(base, delivery);
        self.base = Some(if better { best } else { base });
        self.base
    }

    fn cost(&self, dr: DataRate, delivery: &[f64; 7]) -> f64 {
        let k = usize::from(dr.index());
        expected_age_cost(self.interval[k], delivery[k], self.time_on_air[k])
    }
}

impl AdrNetwork for TrackingAdr {
    /// Answering in RX2 as LoRaWAN does, a swarm of 12 drones on one SF7/250 kHz channel at 3 km
    /// missed 3.5 % of the frames that reached the gateway while it sent, and its median drone's
    /// p75 was 1.15× the fixed rate's; sparing the gateway, 0.9 % and 1.09× (32 seeds;
    /// docs/beyond-the-paper.md, "Half-duplex gateways").
    fn spares_the_gateway(&self) -> bool {
        true
    }

    fn on_uplink(&mut self, up: &UplinkReport) -> Option<LinkAdrReq> {
        // The long-run choice is judged on every uplink: the window already holds the frames at
        // the old settings (censored where lost), and the hysteresis stops it flipping (the
        // command below moves with each fade on purpose, only below it). Waiting for four frames
        // at the new settings, as it once did, cost minutes at DR0-DR1 (116 s a frame) and
        // kept a bad choice for as long: pooled over 8 seeds, p75 / best fixed from DR0 at
        // 3 km was 2.39 with the wait and 1.19 without.
        self.record(up);
        let mu = self.mean_rssi();
        let base = self.update_base(up, &self.delivery_around(mu))?;
        let next = self.next_delivery(up, mu);
        let best = DataRate::ALL
            .into_iter()
            .filter(|dr| *dr <= base)
            .min_by(|a, b| self.cost(*a, &next).total_cmp(&self.cost(*b, &next)))?;
        let better = best != up.dr;
        let full_power = up.power_reduction_db == 0.0;
        let command = match (better, full_power) {
            (true, _) => Some(best),
            (false, false) => Some(up.dr),
            (false, true) => None,
        }
        .map(|dr| LinkAdrReq {
            dr,
            power_reduction_db: 0.0,
        });
        self.commanded = command.map(|c| (c.dr, c.power_reduction_db));
        if command.is_some() || up.adr_ack_req {
            self.answered_before = self.answered;
            self.answered = Some(up.fcnt);
        }
        command
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> ([f64; 7], [f64; 7]) {
        // 25-byte packets at 1 %: DR0 1.48 s … DR6 0.031 s.
        let toa = [1.4828, 0.8233, 0.3707, 0.2058, 0.1132, 0.0617, 0.0308];
        (toa, toa.map(|t| t / 0.01))
    }

    fn up(fcnt: u32, dr: u8, rssi: f64) -> UplinkReport {
        UplinkReport {
            fcnt,
            dr: DataRate::new(dr).unwrap(),
            power_reduction_db: 0.0,
            rssi_dbm: rssi,
            snr_db: rssi + 114.0,
            adr_ack_req: false,
            speed_mps: 8.0,
            crowd_loss: [0.0; 7],
        }
    }

    #[test]
    fn a_lone_drone_backs_off_after_four_silent_uplinks_and_a_crowd_as_lorawan_does() {
        let limits = |d, g| {
            let l = tracking_ack_limits(d, g);
            (l.limit, l.delay)
        };
        assert_eq!(limits(1, 1), (2, 2));
        assert_eq!(limits(1, 3), (2, 2));
        assert_eq!(limits(6, 1), (16, 16));
        assert_eq!(limits(6, 3), (4, 4));
        assert_eq!(limits(16, 1), (32, 32));
        assert_eq!(limits(17, 1), (64, 32));
        assert_eq!(tracking_ack_limits(500, 1), AckLimits::LORAWAN);
    }

    #[test]
    fn a_gap_after_a_short_back_off_is_counted_at_the_rates_the_device_passed() {
        // With 2 + 2: frames 4, 6 and 8 of a silence step DR6 down to DR3.
        let (toa, interval) = table();
        let mut adr = TrackingAdr::new(toa, interval, 4.0, 110.0)
            .with_ack_limits(AckLimits { limit: 2, delay: 2 });
        adr.on_uplink(&up(9, 3, -125.0));
        let lost: Vec<u8> = adr.frames.iter().take(9).map(|f| f.dr.index()).collect();
        assert_eq!(lost, vec![6, 6, 6, 6, 5, 5, 4, 4, 3]);
    }

    #[test]
    fn a_gap_that_ends_at_a_slower_rate_is_counted_as_the_devices_own_back_off() {
        // At 7 km from DR6 nothing is heard until the device, unanswered, has backed off to DR3:
        // 64 + 32 silent frames, then one rate per 32 more (frame 160 is its first at DR3).
        let (toa, interval) = table();
        let mut adr = TrackingAdr::new(toa, interval, 4.0, 110.0);
        adr.on_uplink(&up(166, 3, -125.0));
        // The window keeps the last TRACKING_WINDOW frames: lost frames 71..=165 and the one heard.
        assert_eq!(adr.frames.len(), TRACKING_WINDOW);
        let lost: Vec<u8> = adr.frames.iter().take(95).map(|f| f.dr.index()).collect();
        assert!(adr.frames.iter().take(95).all(|f| f.rssi_dbm.is_none()));
        // Counted back from the frame heard: DR3 from 160, DR4 from 128, DR5 from 96, DR6 before.
        let at = |dr: u8| lost.iter().filter(|&&d| d == dr).count();
        assert_eq!((at(6), at(5), at(4), at(3)), (25, 32, 32, 6), "{lost:?}");
        // A gap at the rate the device already had stays at that rate.
        let mut steady = TrackingAdr::new(toa, interval, 4.0, 110.0);
        steady.on_uplink(&up(0, 3, -120.0));
        steady.on_uplink(&up(10, 3, -121.0));
        assert!(steady.frames.iter().all(|f| f.dr.index() == 3));
    }

    #[test]
    fn a_frame_faster_than_the_command_shows_the_command_was_lost() {
        let (toa, iv) = table();
        // One frame in ten heard at DR6: the network asks for a slower rate.
        let slowed = |adr: &mut TrackingAdr| {
            (0..4)
                .find_map(|k| {
                    adr.on_uplink(&up(10 * k + 9, 6, -126.0))
                        .map(|c| (10 * k + 9, c))
                })
                .expect("a command")
        };
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        let (fcnt, cmd) = slowed(&mut adr);
        assert!(cmd.dr < DataRate::DR5, "{cmd:?}");
        // The downlink was lost: the device stayed at DR6 until, unanswered for 64 + 32
        // frames, it backed off to DR5 on its own, and is heard there. Its lost frames went
        // at DR6, then DR5, never at the rate asked for.
        adr.on_uplink(&up(fcnt + 100, 5, -120.0));
        let gap: Vec<u8> = adr
            .frames
            .iter()
            .rev()
            .skip(1)
            .take(60)
            .map(|f| f.dr.index())
            .collect();
        assert!(gap.iter().all(|&d| d == 5 || d == 6), "{gap:?}");
        assert!(gap.contains(&6), "{gap:?}");
        // A device that obeyed is counted at the rate it was asked for.
        let mut obeyed = TrackingAdr::new(toa, iv, 4.0, 110.0);
        let (fcnt, cmd) = slowed(&mut obeyed);
        obeyed.on_uplink(&up(fcnt + 10, cmd.dr.index(), -120.0));
        let gap: Vec<u8> = obeyed
            .frames
            .iter()
            .rev()
            .skip(1)
            .take(9)
            .map(|f| f.dr.index())
            .collect();
        assert_eq!(gap, vec![cmd.dr.index(); 9]);
    }

    #[test]
    fn the_cost_grows_as_delivery_falls_and_as_the_interval_grows() {
        let a = expected_age_cost(4.0, 0.9, 0.05);
        assert!(expected_age_cost(4.0, 0.5, 0.05) > a);
        assert!(expected_age_cost(8.0, 0.9, 0.05) > a);
        assert_eq!(expected_age_cost(4.0, 0.0, 0.05), f64::INFINITY);
    }

    #[test]
    fn geometric_moments_match_their_series() {
        for p in [0.1, 0.5, 0.9] {
            for n in 1..=5 {
                let series: f64 = (1..4000)
                    .map(|k: i32| p * (1.0_f64 - p).powi(k - 1) * f64::from(k).powi(n as i32))
                    .sum();
                let closed = geometric_moment(n, p);
                assert!((closed - series).abs() < 1e-9 * series, "n {n} p {p}");
            }
        }
    }

    #[test]
    fn a_strong_link_keeps_the_fastest_rate() {
        let (toa, iv) = table();
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        for k in 0..10 {
            assert_eq!(adr.on_uplink(&up(k, 6, -100.0)), None);
        }
    }

    #[test]
    fn losses_seen_in_the_frame_counter_slow_the_rate() {
        let (toa, iv) = table();
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        // One frame in ten arrives at DR6, just above the sensitivity (−127 dBm).
        let cmd = (0..4)
            .filter_map(|k| adr.on_uplink(&up(10 * k + 9, 6, -126.0)))
            .next()
            .expect("a command");
        assert!(cmd.dr < DataRate::DR6, "{cmd:?}");
        let delivery = adr.delivery();
        assert!(delivery[6] < 0.3 && delivery[2] > 0.8, "{delivery:?}");
    }

    #[test]
    fn losses_a_crowd_explains_do_not_slow_the_rate_but_an_uncrowded_sf_draws_it() {
        // Every frame that arrives is 4 dB above DR6's sensitivity (−127 dBm), yet three in
        // four are lost: alone that reads as a link past its edge.
        let (toa, iv) = table();
        let crowded = |loss: [f64; 7]| {
            let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
            let mut commands = Vec::new();
            for k in 0..30u32 {
                let report = UplinkReport {
                    crowd_loss: loss,
                    ..up(4 * k, 6, -123.0)
                };
                commands.extend(adr.on_uplink(&report));
            }
            (commands, adr.mean_rssi(), adr.delivery())
        };
        let (alone, mu_alone, _) = crowded([0.0; 7]);
        assert!(alone.iter().any(|c| c.dr < DataRate::DR6), "{alone:?}");
        // A crowd that collides three frames in four at every rate: the losses are its, the
        // link is strong, and DR6 sends most often.
        let (crowd, mu, delivery) = crowded([0.75; 7]);
        assert!(crowd.is_empty(), "{crowd:?}");
        assert!(mu > -124.5 && mu > mu_alone + 2.0, "{mu} vs {mu_alone}");
        // DR6's delivery: the crowd's quarter, times the link's own three quarters or more.
        assert!(
            delivery[6] <= 0.25 && delivery[6] > 0.75 * 0.25,
            "{delivery:?}"
        );
        // The same crowd at SF7 alone (DR5 and DR6): SF8 meets no one and is worth its
        // longer interval.
        let (spread, ..) = crowded([0.0, 0.0, 0.0, 0.0, 0.0, 0.75, 0.75]);
        assert!(
            spread.iter().all(|c| c.dr == DataRate::new(4).unwrap()),
            "{spread:?}"
        );
    }

    #[test]
    fn the_censored_estimate_finds_the_mean_behind_the_losses() {
        let (toa, iv) = table();
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        // Half the frames lost at DR6 (sensitivity −127): the mean sits near −127, below the
        // received frames' average.
        for k in 0..8 {
            adr.on_uplink(&up(2 * k + 1, 6, -124.0));
        }
        let mu = adr.mean_rssi();
        assert!(mu < -124.0 && mu > -129.0, "{mu}");
    }

    /// The window's score summed term by term, each lost frame's exp and erfc its own (the
    /// estimate as first written): the oracle for [`TrackingAdr::mean_rssi`]'s shared terms.
    fn mean_rssi_term_by_term(adr: &TrackingAdr) -> f64 {
        let s = adr.sigma_db;
        let score = |mu: f64| -> f64 {
            adr.frames
                .iter()
                .map(|f| match f.rssi_dbm {
                    Some(r) => (r + f.power_reduction_db - mu) / (s * s),
                    None => {
                        let c =
                            Channel::sensitivity_dbm(f.dr.sf(), f.dr.bw()) + f.power_reduction_db;
                        lost_score((c - mu) / s, f.crowd_loss) / s
                    }
                })
                .sum()
        };
        let (mut lo, mut hi) = (-300.0_f64, 100.0_f64);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if score(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn lost_frames_of_one_kind_share_their_score_and_the_estimate_keeps_every_bit() {
        let (toa, iv) = table();
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        // Frames at three rates and two powers, a crowd that changes from report to report,
        // and gaps of one to three lost frames: several kinds of lost frame, mixed with heard ones.
        let mut fcnt = 0;
        for k in 0..60u32 {
            fcnt += 1 + k % 3;
            let crowd = [0.0, 0.1, 0.2, 0.3, 0.4, 0.05 * f64::from(k % 4), 0.5];
            adr.on_uplink(&UplinkReport {
                power_reduction_db: if k % 5 == 0 { 2.0 } else { 0.0 },
                crowd_loss: crowd,
                ..up(fcnt, 4 + (k % 3) as u8, -125.0 + f64::from(k % 7))
            });
            assert_eq!(
                adr.mean_rssi().to_bits(),
                mean_rssi_term_by_term(&adr).to_bits(),
                "after uplink {k}"
            );
        }
        let terms = ScoreTerms::of(&adr.frames);
        let lost = terms
            .frames
            .iter()
            .filter(|t| matches!(t, Term::Lost(_)))
            .count();
        assert!(
            terms.lost_kinds.len() > 1 && terms.lost_kinds.len() < lost,
            "{lost}"
        );
    }

    /// `up` at `speed` m/s.
    fn moving(fcnt: u32, dr: u8, rssi: f64, speed: f64) -> UplinkReport {
        UplinkReport {
            speed_mps: speed,
            ..up(fcnt, dr, rssi)
        }
    }

    /// A network that has settled on DR5 over a link whose mean lies 4 dB above DR5's
    /// sensitivity (−130 dBm): forty frames heard around −126 dBm.
    fn settled_at_dr5() -> TrackingAdr {
        let (toa, iv) = table();
        let mut adr = TrackingAdr::new(toa, iv, 4.0, 110.0);
        for k in 0..40 {
            let wobble = if k % 2 == 0 { 1.0 } else { -1.0 };
            adr.on_uplink(&moving(k, 5, -126.0 + wobble, 8.0));
        }
        assert_eq!(adr.base, Some(DataRate::DR5), "{:?}", adr.delivery());
        adr
    }

    #[test]
    fn a_weak_frame_on_a_correlated_link_slows_the_next_frames_and_a_strong_one_restores_the_base()
    {
        let mut adr = settled_at_dr5();
        // A frame 0.1 dB above the sensitivity: the fade it sits in outlasts the next interval.
        let weak = moving(40, 5, -129.9, 8.0);
        let next = adr.next_delivery(&weak, adr.mean_rssi());
        let slowed = adr.on_uplink(&weak).expect("a command");
        assert!(slowed.dr < DataRate::DR5, "{slowed:?}");
        assert!(
            next[5] < 0.75 && next[usize::from(slowed.dr.index())] > 0.85,
            "{next:?}"
        );
        // Heard at the slower rate, well above DR5's sensitivity again: back to the base.
        let back = adr.on_uplink(&moving(41, slowed.dr.index(), -122.0, 8.0));
        assert_eq!(back.map(|c| c.dr), Some(DataRate::DR5));
    }

    #[test]
    fn where_the_drone_stands_still_its_shadowing_holds_and_where_it_flies_far_it_is_forgotten() {
        let adr = settled_at_dr5();
        let mu = adr.mean_rssi();
        let weak = |speed| adr.next_delivery(&moving(40, 5, -129.9, speed), mu)[5];
        // Hovering, the next frame meets the link where this one did, 0.1 dB above DR5's
        // sensitivity (within the least spread assumed, 0.5 dB); flying a kilometre between
        // frames, the forecast is the long-run delivery.
        assert!(
            (weak(0.0) - normal_cdf(0.1 / MIN_NEXT_SIGMA_DB)).abs() < 1e-9,
            "{}",
            weak(0.0)
        );
        assert!((weak(300.0) - adr.delivery()[5]).abs() < 1e-3);
        assert!(weak(8.0) < weak(300.0));
    }

    #[test]
    fn a_strong_frame_never_asks_for_a_rate_faster_than_the_long_run_choice() {
        let mut adr = settled_at_dr5();
        // 15 dB above DR6's sensitivity for one frame: DR6 would arrive next time, but a frame
        // lost there could not bring the drone back (no frame heard, no command).
        assert_eq!(adr.on_uplink(&moving(40, 5, -112.0, 8.0)), None);
        assert_eq!(adr.base, Some(DataRate::DR5));
    }
}
