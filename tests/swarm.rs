//! Swarms (issue "many drones, one gateway"): the simulated collision rate agrees with the ALOHA
//! formula where its assumptions hold, the paper's "72 drones below 10 %" claim, and every
//! drone's error reported.
#![cfg(not(target_arch = "wasm32"))]

use loratrack::api::swarm;
use loratrack::{SfPlan, SwarmParams, SwarmReport};

fn aloha(drones: usize, channels: u8, seed: u64) -> SwarmParams {
    SwarmParams {
        drones,
        channels,
        duration: 300.0,
        model: "dr".into(),
        sf_plan: SfPlan::Spread,
        capture: false,
        inter_sf: false,
        shadowing: 0.0,
        seed,
        ..SwarmParams::default()
    }
}

#[test]
fn without_capture_or_inter_sf_the_collision_rate_is_the_aloha_formula() {
    for channels in [1, 3] {
        for drones in [12, 72, 300] {
            let runs: Vec<SwarmReport> = (1..=3)
                .map(|s| swarm(&aloha(drones, channels, s)).unwrap())
                .collect();
            let sim = runs.iter().map(|r| r.collision_rate).sum::<f64>() / 3.0;
            let theory = runs.iter().map(|r| r.collision_rate_theory).sum::<f64>() / 3.0;
            let close = (sim - theory).abs() <= 0.03 || (sim - theory).abs() <= 0.25 * theory;
            assert!(
                close,
                "{drones} drones, {channels} channels: simulated {sim:.4}, theory {theory:.4}"
            );
            for r in &runs {
                assert_eq!(
                    r.packets_below_sensitivity, 0,
                    "1 km, no shadowing: every packet is audible"
                );
            }
        }
    }
}

#[test]
fn seventy_two_drones_on_three_channels_with_spread_sfs_collide_below_ten_percent() {
    let r = swarm(&SwarmParams {
        drones: 72,
        channels: 3,
        sf_plan: SfPlan::Spread,
        ..SwarmParams::default()
    })
    .unwrap();
    assert!(
        r.collision_rate < 0.10,
        "collision rate {}",
        r.collision_rate
    );
    // Everyone on SF7 and one channel collides far more: the SF plan is what makes 72 possible.
    let crowded = swarm(&SwarmParams {
        drones: 72,
        channels: 1,
        sf_plan: SfPlan::Fixed,
        duration: 300.0,
        ..SwarmParams::default()
    })
    .unwrap();
    assert!(
        crowded.collision_rate > 2.0 * r.collision_rate,
        "{} vs {}",
        crowded.collision_rate,
        r.collision_rate
    );
}

#[test]
fn every_drone_is_reported_and_the_counts_add_up() {
    let r = swarm(&SwarmParams {
        drones: 20,
        duration: 120.0,
        ..SwarmParams::default()
    })
    .unwrap();
    assert_eq!(r.drones.len(), 20);
    assert_eq!(
        r.drones.iter().map(|d| d.packets_sent).sum::<usize>(),
        r.packets_sent
    );
    assert_eq!(
        r.drones.iter().map(|d| d.packets_received).sum::<usize>(),
        r.packets_received
    );
    assert_eq!(
        r.drones.iter().map(|d| d.packets_collided).sum::<usize>(),
        r.packets_collided
    );
    for d in &r.drones {
        assert_eq!(d.channel_use.iter().sum::<usize>(), d.packets_sent);
        assert_eq!(d.channel_use.len(), 3);
        assert_eq!(usize::from(d.sf - 7), d.id % 6, "spread plan");
    }
    let lost = r.packets_collided + r.packets_below_sensitivity + r.packets_no_demodulator;
    assert_eq!(r.packets_received + lost, r.packets_sent);
}

#[test]
fn a_drone_that_receives_nothing_says_so() {
    let r = swarm(&SwarmParams {
        drones: 3,
        duration: 60.0,
        distance: 20_000.0,
        sf_plan: SfPlan::Fixed,
        ..SwarmParams::default()
    })
    .unwrap();
    for d in &r.drones {
        assert_eq!((d.packets_received, d.error3d.count), (0, 0));
    }
    let json = serde_json::to_value(&r).unwrap();
    assert!(json["drones"][0]["error3d"]["p75"].is_null());
    assert_eq!(r.packets_below_sensitivity, r.packets_sent);
}

#[test]
fn the_numbers_do_not_depend_on_the_number_of_threads() {
    let p = SwarmParams {
        drones: 40,
        duration: 60.0,
        ..SwarmParams::default()
    };
    let parallel = swarm(&p).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let serial = one.install(|| swarm(&p).unwrap());
    // Compared as JSON: empty statistics are NaN, which is never equal to itself.
    assert_eq!(
        serde_json::to_string(&parallel).unwrap(),
        serde_json::to_string(&serial).unwrap()
    );
}

#[test]
fn invalid_swarms_are_refused() {
    for (p, expected) in [
        (
            SwarmParams {
                drones: 0,
                ..SwarmParams::default()
            },
            "drones must be 1..500",
        ),
        (
            SwarmParams {
                drones: 501,
                ..SwarmParams::default()
            },
            "drones must be 1..500",
        ),
        (
            SwarmParams {
                channels: 2,
                ..SwarmParams::default()
            },
            "channels must be 1 or 3",
        ),
        (
            SwarmParams {
                model: "kalman".into(),
                ..SwarmParams::default()
            },
            "unknown model 'kalman'",
        ),
    ] {
        let e = swarm(&p).unwrap_err().to_string();
        assert!(e.contains(expected), "{e:?} should contain {expected:?}");
    }
}
