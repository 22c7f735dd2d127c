//! The canonical synthetic flight set, imitating the paper's Mid-Air flights (reference §11).

use super::Trajectory;
use crate::math::{cos, sin};
use crate::rng::Rng;

/// Number of flights in the set (the paper: 30 Mid-Air trajectories).
pub const SYNTHETIC_FLIGHTS: usize = 30;
/// Total flight time of the set, s (the paper: 44 minutes).
pub const SYNTHETIC_TOTAL_SECONDS: f64 = 44.0 * 60.0;
/// The seed that fixes the canonical set; it never changes with the simulation seed.
pub const SYNTHETIC_SEED: u64 = 0x4D49_4441_4952; // "MIDAIR"
/// Sample rate, Hz.
const RATE_HZ: f64 = 100.0;
/// Natural frequency of the velocity loop, rad/s: how briskly the airframe follows a command.
const OMEGA_N: f64 = 2.0;

/// Manoeuvres a quadcopter flies; each sets targets for the commanded speed, turn rate and
/// vertical speed.
#[derive(Clone, Copy, Debug)]
enum Manoeuvre {
    Hover,
    Cruise,
    Brake,
    Turn,
    Climb,
    Dive,
    Helix,
}

const MANOEUVRES: [Manoeuvre; 7] = [
    Manoeuvre::Hover,
    Manoeuvre::Cruise,
    Manoeuvre::Brake,
    Manoeuvre::Turn,
    Manoeuvre::Climb,
    Manoeuvre::Dive,
    Manoeuvre::Helix,
];

/// Commanded (horizontal speed m/s, turn rate rad/s, vertical speed m/s) for a manoeuvre.
fn targets(m: Manoeuvre, speed: f64, rng: &mut Rng) -> (f64, f64, f64) {
    let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
    match m {
        Manoeuvre::Hover => (0.0, 0.0, 0.0),
        Manoeuvre::Cruise => (rng.range(4.0, 15.0), 0.0, 0.0),
        Manoeuvre::Brake => (rng.range(0.0, 2.0), 0.0, 0.0),
        Manoeuvre::Turn => (speed.max(3.0), sign * rng.range(0.15, 0.9), 0.0),
        Manoeuvre::Climb => (rng.range(0.0, 8.0), 0.0, rng.range(1.0, 4.0)),
        Manoeuvre::Dive => (rng.range(2.0, 10.0), 0.0, -rng.range(1.0, 4.0)),
        Manoeuvre::Helix => (
            rng.range(3.0, 8.0),
            sign * rng.range(0.3, 0.9),
            if rng.uniform() < 0.5 { 2.0 } else { -2.0 },
        ),
    }
}

/// Moves `x` toward `target` by at most `rate * dt`: the rate limit that makes every command
/// continuous and, through the second-order velocity loop, the motion jerk-limited.
fn approach(x: f64, target: f64, rate: f64, dt: f64) -> f64 {
    x + (target - x).clamp(-rate * dt, rate * dt)
}

/// Synthetic flight `index` (1..=30) of the canonical set.
///
/// Each flight is a seeded sequence of 4–14 s manoeuvres (hover, cruise, brake, banked turns of
/// 0.15–0.9 rad/s, climbs and dives of 1–4 m/s, helices), commanded through rate limits
/// (3 m/s², 0.6 rad/s², 2 m/s²) and followed by a critically damped second-order velocity loop
/// (natural frequency 2 rad/s), so velocity and acceleration are continuous and jerk bounded.
/// Altitude stays within 10–120 m. Returns `None` outside 1..=30.
pub fn synthetic_flight(index: usize) -> Option<Trajectory> {
    if !(1..=SYNTHETIC_FLIGHTS).contains(&index) {
        return None;
    }
    let durations = durations();
    let mut rng = Rng::derive(SYNTHETIC_SEED, index as u64);
    let n = (durations[index - 1] * RATE_HZ).round() as usize + 1;
    let dt = 1.0 / RATE_HZ;
    let mut p = [
        rng.range(-50.0, 50.0),
        rng.range(-50.0, 50.0),
        rng.range(20.0, 60.0),
    ];
    let (mut v, mut a) = ([0.0f64; 3], [0.0f64; 3]);
    let mut heading = rng.range(-core::f64::consts::PI, core::f64::consts::PI);
    let (mut speed_cmd, mut turn_cmd, mut climb_cmd) = (0.0, 0.0, 0.0);
    let (mut target, mut until) = ((0.0, 0.0, 0.0), 0.0);
    let (mut t_out, mut pos, mut vel, mut acc) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for k in 0..n {
        let t = k as f64 * dt;
        if t >= until {
            let m =
                MANOEUVRES[(rng.uniform() * MANOEUVRES.len() as f64) as usize % MANOEUVRES.len()];
            target = targets(m, speed_cmd, &mut rng);
            until = t + rng.range(4.0, 14.0);
        }
        // Altitude envelope: turn a climb or dive around before leaving 10–120 m.
        if (p[2] < 10.0 && target.2 < 0.0) || (p[2] > 120.0 && target.2 > 0.0) {
            target.2 = -target.2;
        }
        t_out.push(t);
        pos.push(p);
        vel.push(v);
        acc.push(a);
        speed_cmd = approach(speed_cmd, target.0, 3.0, dt);
        turn_cmd = approach(turn_cmd, target.1, 0.6, dt);
        climb_cmd = approach(climb_cmd, target.2, 2.0, dt);
        heading += turn_cmd * dt;
        let command = [
            speed_cmd * cos(heading),
            speed_cmd * sin(heading),
            climb_cmd,
        ];
        for i in 0..3 {
            // Critically damped: a' = wn² (c − v) − 2 wn a; semi-implicit Euler at 100 Hz.
            let jerk = OMEGA_N * OMEGA_N * (command[i] - v[i]) - 2.0 * OMEGA_N * a[i];
            a[i] += jerk * dt;
            v[i] += a[i] * dt;
            p[i] += v[i] * dt;
        }
    }
    // Always valid: over 6000 finite samples at increasing times.
    Trajectory::new(format!("synthetic {index}"), t_out, pos, vel, acc).ok()
}

/// Flight durations (s): 60–120 s each, scaled so the set totals [`SYNTHETIC_TOTAL_SECONDS`].
fn durations() -> Vec<f64> {
    let mut rng = Rng::new(SYNTHETIC_SEED);
    let raw: Vec<f64> = (0..SYNTHETIC_FLIGHTS)
        .map(|_| rng.range(60.0, 120.0))
        .collect();
    let scale = SYNTHETIC_TOTAL_SECONDS / raw.iter().sum::<f64>();
    raw.iter()
        .map(|d| (d * scale * RATE_HZ).round() / RATE_HZ)
        .collect()
}

/// All 30 flights of the canonical set.
pub fn synthetic_set() -> Vec<Trajectory> {
    (1..=SYNTHETIC_FLIGHTS)
        .filter_map(synthetic_flight)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_set_has_30_flights_of_about_44_minutes() {
        let total: f64 = durations().iter().sum();
        assert!((total - SYNTHETIC_TOTAL_SECONDS).abs() < 1.0, "{total}");
        assert!(synthetic_flight(0).is_none() && synthetic_flight(31).is_none());
    }

    #[test]
    fn flights_are_deterministic_smooth_and_within_the_envelope() {
        let a = synthetic_flight(3).unwrap();
        assert_eq!(a, synthetic_flight(3).unwrap());
        let dt = 0.01;
        for w in a.acc.windows(2) {
            for (now, next) in w[0].iter().zip(&w[1]) {
                let jerk = (next - now) / dt;
                assert!(jerk.abs() < 30.0, "jerk {jerk}");
            }
        }
        let vmax = (0..a.len()).map(|i| a.state(i)[5]).fold(0.0, f64::max);
        assert!(vmax < 17.0, "{vmax}");
        assert!(a.pos.iter().all(|p| p[2] > 0.0));
    }
}
