//! EU868 duty-cycle limits (ETSI EN 300 220-2 §7.2.3; LoRaWAN RP002 §2.4; reference §6).

use super::LoraError;
use serde::{Deserialize, Serialize};

/// EU868 sub-bands with their duty-cycle limit. The limit is per sub-band: hopping among
/// 868.1/868.3/868.5 MHz (all in [`SubBand::G1`]) does not raise it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SubBand {
    /// 868.0–868.6 MHz, 1 % (the three default LoRaWAN channels).
    G1,
    /// 868.7–869.2 MHz, 0.1 %.
    G2,
    /// 869.4–869.65 MHz, 10 % (also used for the RX2 downlink).
    G3,
}

impl SubBand {
    /// The band's duty-cycle limit as a fraction.
    pub fn duty_cycle(self) -> f64 {
        match self {
            SubBand::G1 => 0.01,
            SubBand::G2 => 0.001,
            SubBand::G3 => 0.1,
        }
    }
    /// Band edges in MHz.
    pub fn range_mhz(self) -> (f64, f64) {
        match self {
            SubBand::G1 => (868.0, 868.6),
            SubBand::G2 => (868.7, 869.2),
            SubBand::G3 => (869.4, 869.65),
        }
    }
}

/// The Things Network's fair-use policy: at most 30 s of uplink airtime per device per day.
/// Enforced with `fairUse: "ttn"` ([`FairUse`]); otherwise shown as information.
pub const TTN_FAIR_USE_SECONDS_PER_DAY: f64 = 30.0;

/// A network's fair-use policy on top of the plan's rule (`--fair-use`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum FairUse {
    /// None: only the plan's rule.
    #[default]
    Off,
    /// The Things Network's: 30 s of airtime per day, spread evenly over the day (a duty cycle
    /// of 30 / 86 400 ≈ 0.035 %). A drone that flies only part of the day could send faster
    /// while it flies and still keep the daily total; the even spread is the conservative reading.
    Ttn,
}

impl FairUse {
    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            FairUse::Off => "off",
            FairUse::Ttn => "ttn",
        }
    }

    /// The largest duty cycle the policy leaves, as a fraction.
    pub fn duty_cycle(self) -> f64 {
        match self {
            FairUse::Off => 1.0,
            FairUse::Ttn => TTN_FAIR_USE_SECONDS_PER_DAY / 86_400.0,
        }
    }
}

/// The smallest duty-cycle fraction a rule enforces, 10⁻⁶: small enough for a packet of 20 ms
/// sent once an hour (a plan without duty cycle at its longest `interval`, or TTN's fair use),
/// large enough that every interval stays finite. The `dutyCycle` setting itself stops at 10⁻⁴
/// (`options::DUTY_CYCLE`).
pub const MIN_DUTY_CYCLE: f64 = 1e-6;

/// Minimum interval between transmissions (s) that keeps a device within `duty_cycle`:
/// the radio may be on air for at most that fraction of the time, so
/// `interval = time_on_air / duty_cycle`.
///
/// ```
/// use loratrack::min_interval;
/// assert!((min_interval(0.0412, 0.01).unwrap() - 4.12).abs() < 1e-12);
/// ```
pub fn min_interval(time_on_air: f64, duty_cycle: f64) -> Result<f64, LoraError> {
    if !(MIN_DUTY_CYCLE..=1.0).contains(&duty_cycle) {
        return Err(LoraError::DutyCycle(duty_cycle));
    }
    Ok(time_on_air / duty_cycle)
}

/// How a device keeps within its duty cycle (`--duty-cycle-mode`).
///
/// ETSI EN 300 220-2 counts the duty cycle over an observation period of one hour; LoRaWAN
/// stacks enforce it either as an off-time after every packet (LoRaMac-node before 4.5, and the
/// paper's reading) or as a budget of airtime credits (LoRaMac-node 4.5 and later).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum DutyCycleMode {
    /// After a packet of time on air T the next may start T / duty cycle later.
    #[default]
    PerPacket,
    /// A token bucket: airtime credit accrues at duty cycle × elapsed time, holds at most
    /// `burst` packets' airtime and starts with one; a packet needs its time on air in credit.
    Budget,
}

impl DutyCycleMode {
    /// The CLI/JS name: `per-packet` or `budget`.
    pub fn name(self) -> &'static str {
        match self {
            DutyCycleMode::PerPacket => "per-packet",
            DutyCycleMode::Budget => "budget",
        }
    }
}

/// The largest `burst` accepted: a budget of 3600 packets is an hour of airtime at 100 %.
pub const MAX_BURST: u32 = 3600;

/// The duty-cycle rule of one device: when may it send, and what does a packet cost? The one
/// place both senders ask.
///
/// ```
/// use loratrack::{DutyCycle, DutyCycleMode};
/// // 20 ms packets at 1 %: one every 2 s, or a burst of up to 5 after 10 s of silence.
/// let mut per_packet = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, 0.02, 1, 0.0).unwrap();
/// per_packet.spend(0.0);
/// assert!((per_packet.earliest(0.0) - 2.0).abs() < 1e-12);
/// let mut budget = DutyCycle::new(DutyCycleMode::Budget, 0.01, 0.02, 5, 0.0).unwrap();
/// budget.spend(10.0); // credit 5 packets' worth (capped) before, 4 after
/// assert_eq!(budget.earliest(10.0), 10.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DutyCycle {
    duty_cycle: f64,
    time_on_air: f64,
    /// Packets the credit may hold.
    packets: f64,
    capacity: f64,
    /// Credit (s of airtime) at `at`.
    credit: f64,
    at: f64,
}

impl DutyCycle {
    /// The rule for packets of `time_on_air` s at `duty_cycle`, starting at time `start` (s)
    /// with one packet's credit. `PerPacket` is a budget of exactly one packet.
    pub fn new(
        mode: DutyCycleMode,
        duty_cycle: f64,
        time_on_air: f64,
        burst: u32,
        start: f64,
    ) -> Result<Self, LoraError> {
        if !(MIN_DUTY_CYCLE..=1.0).contains(&duty_cycle) {
            return Err(LoraError::DutyCycle(duty_cycle));
        }
        if !(1..=MAX_BURST).contains(&burst) {
            return Err(LoraError::Parameter(
                "burst",
                f64::from(burst),
                "1..3600 packets",
            ));
        }
        if !(time_on_air > 0.0 && time_on_air.is_finite()) {
            return Err(LoraError::Parameter(
                "timeOnAir",
                time_on_air,
                "a positive number of seconds",
            ));
        }
        let packets = match mode {
            DutyCycleMode::PerPacket => 1.0,
            DutyCycleMode::Budget => f64::from(burst),
        };
        Ok(DutyCycle {
            duty_cycle,
            time_on_air,
            packets,
            capacity: packets * time_on_air,
            credit: time_on_air,
            at: start,
        })
    }

    fn credit_at(&self, t: f64) -> f64 {
        (self.credit + self.duty_cycle * (t - self.at)).min(self.capacity)
    }

    /// The earliest time at or after `t` (s) when a packet may start.
    pub fn earliest(&self, t: f64) -> f64 {
        let missing = self.time_on_air - self.credit_at(t);
        if missing <= 0.0 {
            t
        } else {
            t + missing / self.duty_cycle
        }
    }

    /// Later packets take `time_on_air` s (an ADR data-rate change), and the credit holds at most
    /// `burst` of them.
    ///
    /// Per packet, the credit shifts by the difference, so the off-time the last packet imposed
    /// stays what it was (LoRaMac-node before 4.5 waits out the packet sent). A budget's credit
    /// is airtime and stays what it is: a packet costs its own airtime whatever the rate of the
    /// one before it (LoRaMac-node 4.5's time credits; ETSI EN 300 220 counts airtime over an
    /// hour; docs/reference.md §6.1). Shifted there too, a drone moved from DR0 to DR6 after its
    /// first DR0 frame waited out that frame's whole off-time (115 s at 12 bytes), and one moved
    /// the other way was given the difference as credit it had not earned.
    pub fn set_time_on_air(&mut self, time_on_air: f64) {
        if time_on_air == self.time_on_air || !(time_on_air > 0.0 && time_on_air.is_finite()) {
            return;
        }
        if self.packets == 1.0 {
            self.credit += time_on_air - self.time_on_air;
        }
        self.time_on_air = time_on_air;
        self.capacity = self.packets * time_on_air;
        self.credit = self.credit.min(self.capacity);
    }

    /// The same rule for a device that starts at `t` (s): one packet's credit then, as
    /// [`new`](Self::new) gives. Credit accrues from when a device starts, not from a time all
    /// devices share: a budget started at the flight's first instant by a drone whose first
    /// packet waits a random offset would hold that offset's credit, and its second packet,
    /// like every other drone's, would fall one interval after the shared start.
    pub fn starting_at(self, t: f64) -> Self {
        DutyCycle {
            credit: self.time_on_air,
            at: t,
            ..self
        }
    }

    /// Records a packet that starts at `t` (s): its time on air is taken from the credit. The
    /// caller sends only at or after [`earliest`](Self::earliest).
    pub fn spend(&mut self, t: f64) {
        self.spend_airtime(t, self.time_on_air);
    }

    /// Records a packet that starts at `t` (s) and takes `time_on_air` s, shorter than the
    /// rule's packets (a [lean payload](crate::LeanPayload)): only its own airtime is taken, so
    /// the off-time follows the packet sent, while later packets are planned at the rule's
    /// length (the drone chooses a packet's payload when it sends it).
    pub fn spend_airtime(&mut self, t: f64, time_on_air: f64) {
        self.credit = self.credit_at(t) - time_on_air;
        self.at = t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shorter_packet_imposes_its_own_off_time() {
        let (full, short) = (0.04, 0.03);
        let mut rule = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, full, 1, 0.0).unwrap();
        rule.spend_airtime(5.0, short);
        let next = rule.earliest(5.0);
        assert!((next - (5.0 + short / 0.01)).abs() < 1e-9);
        rule.spend(next);
        assert!((rule.earliest(next) - (next + full / 0.01)).abs() < 1e-9);
    }

    #[test]
    fn one_packet_budget_is_the_per_packet_off_time() {
        let toa = 0.041216;
        let mut a = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, toa, 10, 0.0).unwrap();
        let mut b = DutyCycle::new(DutyCycleMode::Budget, 0.01, toa, 1, 0.0).unwrap();
        let mut t = 0.3;
        for _ in 0..50 {
            assert_eq!(a.earliest(t), b.earliest(t));
            t = a.earliest(t);
            a.spend(t);
            b.spend(t);
            t += 0.05;
        }
        let interval = min_interval(toa, 0.01).unwrap();
        let later = t + 100.0;
        a.spend(later);
        assert!((a.earliest(later) - (later + interval)).abs() < 1e-9);
    }

    #[test]
    fn a_rule_started_later_holds_one_packet_then_and_accrues_from_there() {
        // 20 ms at 1 %: one packet every 2 s. Started at 0, by 3 s the credit holds 2.5 packets;
        // started at 3 s, one: the next packet waits the whole interval.
        let rule = DutyCycle::new(DutyCycleMode::Budget, 0.01, 0.02, 10, 0.0).unwrap();
        let mut from_zero = rule.clone();
        from_zero.spend(3.0);
        assert_eq!(from_zero.earliest(3.0), 3.0);
        let mut late = rule.starting_at(3.0);
        late.spend(3.0);
        assert!((late.earliest(3.0) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_budget_saves_for_a_burst_and_never_exceeds_the_duty_cycle() {
        let toa = 0.02;
        let mut b = DutyCycle::new(DutyCycleMode::Budget, 0.01, toa, 10, 0.0).unwrap();
        // Quiet for a minute: the credit is full (10 packets), so 10 go at once.
        for _ in 0..10 {
            assert_eq!(b.earliest(60.0), 60.0);
            b.spend(60.0);
        }
        assert!(b.earliest(60.0) > 60.0 + 1.99);
    }

    #[test]
    fn a_longer_airtime_keeps_the_last_packets_off_time_and_costs_more_after() {
        let mut r = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, 0.05, 1, 0.0).unwrap();
        r.spend(0.0);
        r.set_time_on_air(0.2);
        assert!((r.earliest(0.0) - 5.0).abs() < 1e-9, "{}", r.earliest(0.0));
        r.spend(5.0);
        assert!((r.earliest(5.0) - 25.0).abs() < 1e-9, "{}", r.earliest(5.0));
    }

    #[test]
    fn a_budget_keeps_its_airtime_credit_when_the_rate_changes() {
        // A 1 s frame at 1 % from a budget of 10 leaves no credit; 10 ms frames then wait only
        // for their own 10 ms (1 s), not for the 1 s frame's 100 s off-time.
        let mut b = DutyCycle::new(DutyCycleMode::Budget, 0.01, 1.0, 10, 0.0).unwrap();
        b.spend(0.0);
        b.set_time_on_air(0.01);
        assert!((b.earliest(0.0) - 1.0).abs() < 1e-9, "{}", b.earliest(0.0));
        // Quiet until the credit is full (10 frames, 0.1 s), one more frame leaves 0.09 s; moved
        // back to 1 s frames right after it, the next waits to earn the other 0.91 s (91 s),
        // not at once on credit the change would have given.
        b.spend(100.0);
        b.set_time_on_air(1.0);
        assert!(
            (b.earliest(100.0) - 191.0).abs() < 1e-9,
            "{}",
            b.earliest(100.0)
        );
    }

    #[test]
    fn refuses_a_burst_of_zero() {
        assert!(DutyCycle::new(DutyCycleMode::Budget, 0.01, 0.02, 0, 0.0).is_err());
        assert!(DutyCycle::new(DutyCycleMode::Budget, 0.0, 0.02, 1, 0.0).is_err());
    }

    #[test]
    fn interval_is_airtime_over_duty_cycle() {
        assert!((min_interval(0.1, 0.01).unwrap() - 10.0).abs() < 1e-12);
        assert!((min_interval(0.1, SubBand::G3.duty_cycle()).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_impossible_duty_cycles() {
        assert!(min_interval(0.1, 0.0).is_err());
        assert!(min_interval(0.1, 1.5).is_err());
        assert!(min_interval(0.1, f64::NAN).is_err());
        assert!(min_interval(0.1, 5e-324).is_err(), "an infinite interval");
    }
}
