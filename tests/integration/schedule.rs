//! Slotted schedules (reference §13): over random swarms, no two drones on one channel are
//! ever on air together, and no drone sends more often than its duty cycle allows.

use loratrack::sim::schedule::{assign, guard_s, Airtime};
use proptest::prelude::*;

fn swarm() -> impl Strategy<Value = Vec<(u8, f64)>> {
    prop::collection::vec((7u8..=12, 0.02f64..0.2), 1..160).prop_map(|v| {
        v.into_iter()
            .map(|(sf, base)| {
                // Longer packets at higher SFs, as LoRa's are, but not exactly doubling.
                let time_on_air =
                    base * f64::from(1u32 << (sf - 7)) * 1.1f64.powi(i32::from(sf) - 7);
                (sf, time_on_air)
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn no_two_slots_on_one_channel_overlap(
        drones in swarm(),
        channels in prop::sample::select(vec![1u8, 3, 8]),
        duty_cycle in prop::sample::select(vec![0.001, 0.01, 0.1]),
        drift in 0.0f64..100.0,
    ) {
        let drones: Vec<Airtime> = drones
            .into_iter()
            .map(|(sf, time_on_air)| Airtime { sf, time_on_air, interval: time_on_air / duty_cycle })
            .collect();
        let slots = assign(&drones, channels, drift);
        let horizon = 2.0 * slots.iter().map(|s| s.frame).fold(0.0, f64::max);
        for ch in 0..channels {
            let mut on_air: Vec<(f64, f64)> = Vec::new();
            for (d, s) in drones.iter().zip(&slots) {
                prop_assert!(s.frame >= d.interval * (1.0 - 1e-12));
                prop_assert!(s.offset >= 0.0 && s.offset + d.time_on_air <= s.frame + 1e-9);
                if s.channel != ch {
                    continue;
                }
                let mut t = s.offset;
                while t < horizon {
                    on_air.push((t, t + d.time_on_air));
                    t += s.frame;
                }
            }
            on_air.sort_by(|a, b| a.0.total_cmp(&b.0));
            for w in on_air.windows(2) {
                // Each packet ends a guard before the next starts.
                prop_assert!(
                    w[0].1 + guard_s(drift) <= w[1].0 + 1e-6,
                    "channel {}: {:?} then {:?}", ch, w[0], w[1]
                );
            }
        }
    }
}
