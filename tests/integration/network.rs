//! One network simulation: `simulate` and a one-drone `swarm` are the same event loop, more
//! gateways never deliver less, the network server keeps one copy of each packet, ADR runs in
//! swarms with its downlinks counted and tracking ADR reads a crowd's collisions as collisions,
//! and every drone reports its radio's charge.

use loratrack::api::{simulate, swarm};
use loratrack::{Scenario, Simulator};
use serde_json::{json, Value};

/// Compared as JSON: an empty sample's statistics are NaN in Rust (never equal), null in JSON.
fn json<T: serde::Serialize>(v: &T) -> Value {
    serde_json::to_value(v).unwrap()
}

fn scenario(settings: Value) -> Scenario {
    Scenario::default().with(&settings).unwrap()
}

#[test]
fn a_one_drone_swarm_is_simulate_with_the_same_flight() {
    for (flight, extra) in [
        (json!(1), json!({})),
        (
            json!(7),
            json!({"sf": 9, "bw": 125, "distance": 3000, "prediction": "bounded"}),
        ),
        (
            json!(3),
            json!({"sender": "error", "threshold": 1.5, "dutyCycleMode": "budget"}),
        ),
        (
            json!("all"),
            json!({"adr": "tracking", "sf": 9, "bw": 125, "distance": 4000}),
        ),
    ] {
        let mut settings = json!({"synthetic": flight, "model": "3d-ctra"});
        settings
            .as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        let one = simulate(&mut Simulator::new(), &scenario(settings.clone())).unwrap();
        // With the paper's exact timing: a swarm's drones otherwise drift and jitter.
        settings.as_object_mut().unwrap().extend([
            ("drones".into(), json!(1)),
            ("channels".into(), json!(1)),
            ("sfPlan".into(), json!("fixed")),
            ("jitter".into(), json!(0)),
            ("clockDrift".into(), json!(0)),
        ]);
        let sw = swarm(&scenario(settings.clone())).unwrap();
        let r = &one.results[0];
        assert_eq!(
            sw.delivery.packets_sent, r.delivery.packets_sent,
            "{settings}"
        );
        assert_eq!(
            sw.delivery.packets_received, r.delivery.packets_received,
            "{settings}"
        );
        assert_eq!(sw.airtime, r.airtime, "{settings}");
        assert_eq!(json(&sw.error3d), json(&r.error3d), "{settings}");
        assert_eq!(sw.energy, r.energy, "{settings}");
        // The same gateway, named in each command's frame (swarm: the centre; simulate: the
        // flight's first point), heard the same packets.
        let counts = |g: &[loratrack::GatewayReport]| {
            g.iter()
                .map(|x| (x.heard, x.only_heard, x.downlinks_sent, x.downlinks_dropped))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            counts(&sw.delivery.gateways),
            counts(&r.delivery.gateways),
            "{settings}"
        );
        assert!(r.delivery.packets_sent > 2, "{settings}");
    }
}

#[test]
fn a_second_gateway_delivers_at_least_as_many_packets_and_tracks_no_worse() {
    let far = json!({"synthetic": 1, "distance": 5000});
    let alone = simulate(
        &mut Simulator::new(),
        &scenario(json!({"synthetic": 1, "gateways": [{"east": 5000, "north": 0}]})),
    )
    .unwrap();
    let default = simulate(&mut Simulator::new(), &scenario(far)).unwrap();
    assert_eq!(
        json(&alone.results),
        json(&default.results),
        "the default gateway is (distance, 0)"
    );
    let both = simulate(
        &mut Simulator::new(),
        &scenario(json!({"synthetic": 1, "gateways": [{"east": 5000, "north": 0}, {"east": 0, "north": 0}]})),
    )
    .unwrap();
    for (a, b) in alone.results.iter().zip(&both.results) {
        assert!(b.delivery.packets_received >= a.delivery.packets_received);
        assert!(b.error3d.count >= a.error3d.count);
        // What the first gateway hears does not depend on the second being there.
        assert_eq!(b.delivery.gateways[0].heard, a.delivery.gateways[0].heard);
        if a.error3d.count > 0 {
            assert!(
                b.error3d.p75 <= a.error3d.p75,
                "{:?}: {} vs {}",
                b.model,
                b.error3d.p75,
                a.error3d.p75
            );
        }
    }
    assert!(both.delivery.packets_received > alone.delivery.packets_received);
    let g = &both.delivery.gateways;
    let heard: usize = g.iter().map(|x| x.heard).sum();
    assert_eq!(
        heard - both.delivery.duplicates,
        both.delivery.packets_received
    );
}

#[test]
fn three_gateways_serve_a_72_drone_swarm_better_and_the_copies_are_removed() {
    let base = json!({"drones": 72, "duration": 120, "distance": 2500, "bw": 125, "model": "dr"});
    let one = swarm(&scenario(base.clone())).unwrap();
    let mut three = base;
    three["gateways"] = json!([{"east": 0, "north": 0}, {"east": 3000, "north": 0}, {"east": -1500, "north": 2600}]);
    let three = swarm(&scenario(three)).unwrap();
    assert_eq!(three.delivery.packets_sent, one.delivery.packets_sent);
    assert!(three.delivery.packets_received > one.delivery.packets_received);
    assert!(three.delivery.duplicates > 0);
    let heard: usize = three.delivery.gateways.iter().map(|g| g.heard).sum();
    assert_eq!(
        heard,
        three.delivery.packets_received + three.delivery.duplicates
    );
    let only: usize = three.delivery.gateways.iter().map(|g| g.only_heard).sum();
    assert!(only <= three.delivery.packets_received);
    assert_eq!(
        three.delivery.gateways[0].heard,
        one.delivery.gateways[0].heard
    );
}

#[test]
fn adr_runs_in_a_swarm_and_its_downlinks_are_counted() {
    // A gateway at 1 % (RX1) and 10 % (RX2) cannot answer sixty drones' ADR: it sends what its
    // duty cycle allows and drops the rest; LoRaWAN's server holds none back for a later uplink.
    let busy = swarm(&scenario(
        json!({"drones": 60, "duration": 600, "adr": "lorawan", "sfPlan": "fixed", "sf": 7, "bw": 125}),
    ))
    .unwrap();
    let g = &busy.delivery.gateways[0];
    assert!(g.downlinks_sent > 0 && g.downlinks_dropped > 0, "{g:?}");
    assert_eq!(g.downlinks_held_back, 0, "{g:?}");
}

#[test]
fn a_tracking_network_reads_a_crowds_collisions_as_collisions_and_keeps_its_drones_fast() {
    // 36 drones on one SF7 channel at 3 km: a third of their frames collide. Read as a weak
    // link, those losses slowed the drones to 0.69-0.81x the frames the fixed rate sends (seeds
    // 1-3); read as collisions, 0.86-0.87x, for a lower median drone's p75 than the fixed rate.
    let crowd = |adr: &str| {
        swarm(&scenario(json!({
            "drones": 36, "duration": 600, "model": "3d-ctra", "sfPlan": "fixed", "sf": 7,
            "bw": 250, "distance": 3000, "channels": 1, "adr": adr, "seed": 1
        })))
        .unwrap()
    };
    let (fixed, tracking) = (crowd("off"), crowd("tracking"));
    // Every packet is counted at the SF it went at: all at SF7 without ADR, some elsewhere with.
    let at_sf7 = |d: &loratrack::DroneReport| -> usize {
        let at = d.data_rate_use.iter().filter(|u| u.sf == 7);
        at.map(|u| u.packets).sum()
    };
    for d in fixed.drones.iter().chain(&tracking.drones) {
        let counted: usize = d.data_rate_use.iter().map(|u| u.packets).sum();
        assert_eq!(counted, d.packets_sent);
    }
    assert!(fixed.drones.iter().all(|d| at_sf7(d) == d.packets_sent));
    assert!(tracking.drones.iter().any(|d| at_sf7(d) < d.packets_sent));
    let sent = tracking.delivery.packets_sent as f64 / fixed.delivery.packets_sent as f64;
    assert!(sent > 0.84, "{sent}");
    assert!(
        tracking.median_drone_p75 < fixed.median_drone_p75,
        "{} vs {}",
        tracking.median_drone_p75,
        fixed.median_drone_p75
    );
}

#[test]
fn the_radio_charge_grows_with_the_spreading_factor_and_the_power() {
    let charge = |s: Value| {
        simulate(&mut Simulator::new(), &scenario(s))
            .unwrap()
            .results[0]
            .energy
            .charge_per_uplink
    };
    let sf7 = charge(json!({"synthetic": 1, "model": "dr"}));
    let sf10 = charge(json!({"synthetic": 1, "model": "dr", "sf": 10, "bw": 125}));
    let loud = charge(json!({"synthetic": 1, "model": "dr", "txPower": 20}));
    assert!(sf10 > 4.0 * sf7, "{sf10} vs {sf7}");
    assert!(loud > sf7);
    // Raw LoRa (the paper's preset) opens no receive window: less charge per uplink.
    assert!(charge(json!({"synthetic": 1, "model": "dr", "overhead": 0})) < sf7);
}

#[test]
fn settings_are_checked_before_any_work_with_the_key_and_the_limit() {
    for (settings, expected) in [
        (
            json!({"synthetic": 1, "gateways": [{"east": 200000, "north": 0}]}),
            "gateway must be -100000..100000 m",
        ),
        (
            json!({"synthetic": 1, "gateways": (0..17).map(|i| json!({"east": i, "north": 0})).collect::<Vec<_>>()}),
            "gateways must be 1..16",
        ),
        (
            json!({"synthetic": 1, "drones": 5}),
            "`drones` is a swarm setting: simulate flies one drone over its flight",
        ),
        (
            json!({"synthetic": 1, "duration": 120}),
            "`duration` is a swarm setting",
        ),
        (
            json!({"synthetic": 1, "sfPlan": "fixed"}),
            "`sfPlan` is a swarm setting",
        ),
        (
            json!({"synthetic": 1, "spreadingFactor": 9}),
            "unknown setting 'spreadingFactor'",
        ),
        (
            json!({"synthetic": 1, "channels": 2}),
            "channels must be 1 or EU868's 3",
        ),
    ] {
        let e = simulate(&mut Simulator::new(), &scenario(settings.clone()))
            .unwrap_err()
            .to_string();
        assert!(e.contains(expected), "{settings}: {e}");
    }
}

#[test]
fn simulate_keeps_the_papers_timing_unless_given_a_jitter_and_never_sends_sooner_than_the_rule() {
    let arrivals = |extra: Value| {
        let mut settings = json!({"synthetic": 1, "model": "dr", "series": true});
        settings
            .as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        let r = simulate(&mut Simulator::new(), &scenario(settings)).unwrap();
        let toa = r.results[0].time_on_air;
        let interval = r.results[0].interval;
        (r.series.unwrap().models[0].arrivals.clone(), toa, interval)
    };
    let (exact, toa, interval) = arrivals(json!({}));
    // The paper's timing: every uplink starts on a 10 Hz sensor step.
    for a in &exact {
        let start = (a - toa) * 10.0;
        assert!((start - start.round()).abs() < 1e-6, "{a}");
    }
    let (jittered, ..) = arrivals(json!({"jitter": 1.0, "clockDrift": 20}));
    assert_ne!(exact, jittered);
    assert!(jittered.iter().any(|a| {
        let start = (a - toa) * 10.0;
        (start - start.round()).abs() > 1e-3
    }));
    for w in jittered.windows(2) {
        // At most 20 ppm early, at most 1 s late on each interval.
        assert!(w[1] - w[0] >= interval * (1.0 - 2e-5) - 1e-9, "{w:?}");
        assert!(w[1] - w[0] <= interval + 1.0 + 0.1 + 1e-9, "{w:?}");
    }
}
