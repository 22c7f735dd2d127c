//! The end-to-end simulation: reproducibility, the drone-run cache, link effects and the JSON
//! contract of reference §9.

use loratrack::api::{simulate, simulate_stoppable, sweep_paper, ApiError};
use loratrack::{ModelChoice, ModelKind, Prediction, Scenario, Simulator, MAX_SEED};
use serde_json::{json, Value};

/// `base` with the flat JSON settings of `changes` applied.
fn set(base: &Scenario, changes: Value) -> Scenario {
    base.with(&changes).unwrap()
}

fn one_flight(n: usize) -> Scenario {
    set(&Scenario::default(), json!({"synthetic": n}))
}

#[test]
fn the_same_seed_gives_the_same_numbers_and_another_seed_does_not() {
    let a = simulate(&mut Simulator::new(), &one_flight(2)).unwrap();
    let b = simulate(&mut Simulator::new(), &one_flight(2)).unwrap();
    assert_eq!(a, b);
    let c = simulate(
        &mut Simulator::new(),
        &set(&one_flight(2), json!({"seed": 2})),
    )
    .unwrap();
    assert_ne!(a.results[0].error3d, c.results[0].error3d);
}

#[test]
fn a_random_seed_is_drawn_reported_and_repeats_the_run() {
    let draw = || -> Scenario {
        serde_json::from_str(r#"{"synthetic": 2, "model": "dr", "seed": "random"}"#).unwrap()
    };
    let (a, b) = (draw(), draw());
    assert_ne!(a.run.seed, b.run.seed, "two draws gave the same seed");
    assert!(a.run.seed <= MAX_SEED);
    let first = simulate(&mut Simulator::new(), &a).unwrap();
    assert_eq!(first.config.settings.run.seed, a.run.seed);
    let again = set(&a.clone(), json!({"seed": first.config.settings.run.seed}));
    assert_eq!(simulate(&mut Simulator::new(), &again).unwrap(), first);
    let bad = serde_json::from_str::<Scenario>(r#"{"synthetic": 2, "seed": "often"}"#);
    assert!(bad.unwrap_err().to_string().contains("random"));
}

#[test]
fn changing_only_the_link_does_not_rerun_the_drone_filters() {
    let mut sim = Simulator::new();
    let base = simulate(&mut sim, &one_flight(4)).unwrap();
    let runs = sim.drone_runs();
    assert_eq!(runs, 3, "one drone run per model");
    let far = simulate(
        &mut sim,
        &set(
            &one_flight(4),
            json!({"sf": 9, "bw": 125.0, "distance": 4000.0, "overhead": 0}),
        ),
    )
    .unwrap();
    assert_eq!(
        sim.drone_runs(),
        runs,
        "link changes must reuse the drone runs"
    );
    assert!(far.results[0].interval > base.results[0].interval);
    // A sensor change does rerun them.
    simulate(&mut sim, &set(&one_flight(4), json!({"sensorRate": 5.0}))).unwrap();
    assert_eq!(sim.drone_runs(), 2 * runs);
}

#[test]
fn many_seeds_keep_their_drone_runs_for_the_next_link_setting() {
    // 40 seeds and three drone filters: 120 drone runs, each one seed's. A cache that counted
    // them against a small number emptied itself within the run and computed all of them again
    // at the next data rate.
    let mut sim = Simulator::new();
    let many = set(&one_flight(4), json!({"seeds": 40}));
    let first = simulate(&mut sim, &many).unwrap();
    let runs = sim.drone_runs();
    assert_eq!(runs, 120, "one drone run per model and seed");
    let slower = set(&many, json!({"sf": 9, "bw": 125.0}));
    let again = simulate(&mut sim, &slower).unwrap();
    assert_eq!(sim.drone_runs(), runs, "a data rate change must reuse them");
    assert!(again.results[0].interval > first.results[0].interval);
    assert_eq!(again, simulate(&mut Simulator::new(), &slower).unwrap());
}

#[test]
fn reused_station_predictions_give_the_numbers_of_a_fresh_simulator() {
    let mut warm = Simulator::new();
    for prediction in [Prediction::Paper, Prediction::Bounded] {
        let at = |distance: f64, sf: i64| {
            set(
                &Scenario::default(),
                json!({"synthetic": "all", "prediction": prediction, "distance": distance, "sf": sf, "series": true}),
            )
        };
        // Warm the cache at 1 km, then move the gateway: the packets that still arrive are
        // served from remembered chains, longer gaps extend them.
        simulate(&mut warm, &at(1000.0, 7)).unwrap();
        // Other spreading factors add new schedules until the memory budget starts afresh.
        for (distance, sf) in [
            (3500.0, 7),
            (2000.0, 8),
            (4500.0, 9),
            (3000.0, 10),
            (2500.0, 7),
        ] {
            let reused = simulate(&mut warm, &at(distance, sf)).unwrap();
            let fresh = simulate(&mut Simulator::new(), &at(distance, sf)).unwrap();
            assert_eq!(reused, fresh, "{prediction:?} at {distance} m, SF{sf}");
        }
    }
}

#[test]
fn a_run_its_progress_stops_ends_stopped_and_the_next_gives_a_fresh_simulators_numbers() {
    let set_of = |sf: i64| {
        set(
            &Scenario::default(),
            json!({"synthetic": "all", "sf": sf, "seeds": 2}),
        )
    };
    let mut sim = Simulator::new();
    let mut calls = 0;
    let stopped = simulate_stoppable(&mut sim, &set_of(7), &mut |_, _| {
        calls += 1;
        false
    });
    let Err(ApiError::Sim(e)) = stopped else {
        panic!("a stopped run gave {stopped:?}");
    };
    assert_eq!(e, loratrack::SimError::Stopped);
    assert_eq!(
        e.to_string(),
        "the run was stopped by its progress callback"
    );
    // Natively the first batch (every drone filter) ends before the first tick says stop.
    assert!(calls > 0);
    // Nothing half done is remembered: the same run, and another link on the same drones, give
    // a fresh simulator's numbers.
    for sf in [7, 8] {
        let again = simulate(&mut sim, &set_of(sf)).unwrap();
        assert_eq!(
            again,
            simulate(&mut Simulator::new(), &set_of(sf)).unwrap(),
            "SF{sf}"
        );
    }
}

#[test]
fn five_km_at_sf7_loses_packets_and_tracks_worse_than_one_km() {
    let mut sim = Simulator::new();
    let near = simulate(&mut sim, &one_flight(5)).unwrap();
    let far = simulate(&mut sim, &set(&one_flight(5), json!({"distance": 5000.0}))).unwrap();
    for (n, f) in near.results.iter().zip(&far.results) {
        assert_eq!(
            n.delivery.packets_received, n.delivery.packets_sent,
            "{:?} at 1 km",
            n.model
        );
        assert!(
            f.delivery.packets_received < f.delivery.packets_sent / 2,
            "{:?} at 5 km: {}/{}",
            f.model,
            f.delivery.packets_received,
            f.delivery.packets_sent
        );
        assert!(f.error3d.count < n.error3d.count || f.error3d.p75 > n.error3d.p75);
    }
}

#[test]
fn the_whole_flight_error_counts_the_time_before_a_flights_first_packet() {
    let mut sim = Simulator::new();
    let flights = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "dr"}),
    );
    let fast = simulate(&mut sim, &flights).unwrap().results.remove(0);
    let slow = simulate(&mut sim, &set(&flights, json!({"sf": 12})))
        .unwrap()
        .results
        .remove(0);
    // SF7 sends every 3 s, SF12 / 250 kHz every 74 s, on flights of 88 s on average.
    assert!(fast.whole_flight.tracked > 0.95, "{:?}", fast.whole_flight);
    assert!(slow.whole_flight.tracked < 0.8, "{:?}", slow.whole_flight);
    assert!(!fast.whole_flight.partly_tracked && slow.whole_flight.partly_tracked);
    for r in [&fast, &slow] {
        // Untracked time only adds errors above every tracked one.
        if let Some(p) = r.whole_flight.p75 {
            assert!(p >= r.error3d.p75, "{p} < {}", r.error3d.p75);
        }
        assert_eq!(r.whole_flight.p75.is_none(), r.whole_flight.tracked < 0.75);
    }
    // Tracked and untracked times add up to the same evaluation grid at both rates.
    let grid = |r: &loratrack::ModelResult| r.error3d.count as f64 / r.whole_flight.tracked;
    assert!(
        (grid(&fast) - grid(&slow)).abs() < 0.5,
        "{} {}",
        grid(&fast),
        grid(&slow)
    );
}

#[test]
fn without_shadowing_delivery_is_all_or_nothing_around_the_range() {
    let mut sim = Simulator::new();
    let p = |d| {
        set(
            &one_flight(6),
            json!({"shadowing": 0.0, "distance": d, "model": "dr"}),
        )
    };
    let inside = simulate(&mut sim, &p(2000.0)).unwrap();
    let range = inside.config.range_m;
    assert_eq!(
        inside.results[0].delivery.packets_received,
        inside.results[0].delivery.packets_sent
    );
    let outside = simulate(&mut sim, &p(range + 500.0)).unwrap();
    assert_eq!(outside.results[0].delivery.packets_received, 0);
    assert_eq!(
        outside.results[0].error3d.count, 0,
        "no packet, no error counted"
    );
}

#[test]
fn intervals_follow_the_payload_sizes_and_the_overhead() {
    let r = simulate(
        &mut Simulator::new(),
        &set(&one_flight(1), json!({"sf": 8, "bw": 125.0, "overhead": 0})),
    )
    .unwrap();
    let interval = |m: ModelKind| {
        r.results
            .iter()
            .find(|x| x.model == m.into())
            .unwrap()
            .interval
    };
    assert!((interval(ModelKind::Dr) - 7.2192).abs() < 1e-9);
    assert!((interval(ModelKind::Ctra3d) - 8.2432).abs() < 1e-9);
    // Packets are never closer than the interval.
    let s = simulate(
        &mut Simulator::new(),
        &set(&one_flight(1), json!({"series": true})),
    )
    .unwrap();
    for m in &s.series.unwrap().models {
        let i = s
            .results
            .iter()
            .find(|x| x.model == m.model)
            .unwrap()
            .interval;
        for w in m.arrivals.windows(2) {
            assert!(w[1] - w[0] >= i - 1e-9);
        }
    }
}

#[test]
fn packets_go_out_on_sensor_steps_so_their_mean_spacing_is_the_interval_rounded_up_to_steps() {
    // The whole set: a spacing taken across two flights' packets would show here.
    for rate in [1.0, 2.0, 10.0] {
        let r = simulate(
            &mut Simulator::new(),
            &set(
                &Scenario::default(),
                json!({"synthetic": "all", "sensorRate": rate}),
            ),
        )
        .unwrap();
        for m in &r.results {
            let steps = (m.interval * rate - 1e-9).ceil();
            assert!(
                (m.sent_every - steps / rate).abs() < 1e-9,
                "{rate} Hz, {:?}: {} against {} steps",
                m.model,
                m.sent_every,
                steps
            );
            // Said where the steps add over 5 %: at 1 Hz for every station, at 10 Hz for none.
            assert_eq!(m.sent_slower, steps / rate > 1.05 * m.interval);
            if rate != 2.0 {
                assert_eq!(m.sent_slower, rate == 1.0, "{rate} Hz, {:?}", m.model);
            }
        }
    }
    // The CLI says it under each station where the page's cell does, with the report's number.
    for (rate, said) in [("1", true), ("10", false)] {
        let args = ["simulate", "--synthetic", "1", "--sensor-rate", rate];
        let text = String::from_utf8(crate::cli(&args).stdout).unwrap();
        let json: Value =
            serde_json::from_slice(&crate::cli(&[&args[..], &["--json"]].concat()).stdout).unwrap();
        for m in json["results"].as_array().unwrap() {
            let line = format!(
                "sent every {:.2} s on average; the interval column is what the plan allows",
                m["sentEvery"].as_f64().unwrap()
            );
            assert_eq!(text.contains(&line), said, "{rate} Hz: {text}");
            assert_eq!(m["sentSlower"].as_bool(), Some(said), "{rate} Hz: {m}");
        }
    }
    // An error-triggered drone waits for its threshold beyond the interval.
    let r = simulate(
        &mut Simulator::new(),
        &set(&one_flight(1), json!({"sender": "error", "threshold": 10})),
    )
    .unwrap();
    assert!(r.results.iter().all(|m| m.sent_slower), "{r:?}");
    // A drone that sent one packet has no spacing.
    let r = simulate(
        &mut Simulator::new(),
        &set(&one_flight(1), json!({"sf": 12, "bw": 125.0})),
    )
    .unwrap();
    assert!(r
        .results
        .iter()
        .all(|m| m.delivery.packets_sent == 1 && m.sent_every.is_nan()));
    let v = serde_json::to_value(&r).unwrap();
    assert!(v["results"][0]["sentEvery"].is_null());
}

#[test]
fn the_json_shape_is_the_spec_contract() {
    let r = simulate(
        &mut Simulator::new(),
        &set(&Scenario::default(), json!({"sample": "canberra"})),
    )
    .unwrap();
    let v = serde_json::to_value(&r).unwrap();
    assert!(v["config"]["flightTime"].as_f64().unwrap() > 160.0);
    for res in v["results"].as_array().unwrap() {
        for key in ["model", "interval", "packetsSent", "packetsReceived"] {
            assert!(!res[key].is_null(), "missing {key}");
        }
        for e in ["error3d", "errorX", "errorY", "errorZ"] {
            for s in ["mean", "p50", "p75", "p95", "max", "count"] {
                assert!(res[e][s].is_number(), "missing {e}.{s}");
            }
        }
    }
    assert_eq!(v["results"][2]["model"], "3d-ctra");
}

#[test]
fn bad_inputs_are_refused_with_messages() {
    let mut sim = Simulator::new();
    let cases = [
        (Scenario::default(), "choose a flight"),
        (set(&one_flight(1), json!({"sample": "x"})), "only one"),
        (
            set(&Scenario::default(), json!({"sample": "mars"})),
            "unknown sample",
        ),
        (set(&one_flight(1), json!({"sf": 13})), "sf must be 7..12"),
        (set(&one_flight(1), json!({"distance": -5.0})), "distance"),
        (set(&one_flight(1), json!({"eta": 2.0})), "eta"),
        (
            set(&Scenario::default(), json!({"trajectory": "t,x,y,z\n"})),
            "no data rows",
        ),
    ];
    for (p, expected) in cases {
        let e = simulate(&mut sim, &p).unwrap_err().to_string();
        assert!(e.contains(expected), "{e:?} should contain {expected:?}");
    }
}

#[test]
fn the_paper_sweep_covers_its_grid_and_richer_models_win_at_one_km() {
    let r = sweep_paper(
        &mut Simulator::new(),
        1,
        &[Prediction::Paper],
        &ModelChoice::all(),
    )
    .unwrap();
    assert_eq!(r.runs.len(), 6);
    assert!((r.flight_time - 2640.0).abs() < 1.0);
    let run = &r.runs[0];
    assert_eq!((run.sf, run.distance), (7, 1000.0));
    let p75 = |m: ModelKind| loratrack::api::p75(run, m.into());
    assert!(
        p75(ModelKind::Ctra3d) < p75(ModelKind::Dr),
        "3D-CTRA should beat DR at SF7 / 1 km"
    );
    // Errors rise at 3 km with SF7 (packet loss).
    let far = &r.runs[2];
    assert!(far.results[0].delivery.packets_received < far.results[0].delivery.packets_sent);
}

#[test]
fn the_caches_account_for_their_bytes_and_stay_within_the_budget() {
    let mut sim = Simulator::new();
    let whole = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "dr"}),
    );
    simulate(&mut sim, &whole).unwrap();
    let after_one = sim.cached_bytes();
    // The whole set at 100 Hz (flights) and its drone runs at 10 Hz, at least.
    assert!(after_one > 30 << 20, "{after_one} bytes");
    for seed in 2..=6 {
        simulate(
            &mut sim,
            &set(&whole, json!({"seed": seed, "sensorRate": 50})),
        )
        .unwrap();
        assert!(
            sim.cached_bytes() <= loratrack::MAX_CACHE_BYTES,
            "{} bytes",
            sim.cached_bytes()
        );
    }
    // What was used last is still there: the same run computes no drone filter.
    let runs = sim.drone_runs();
    simulate(&mut sim, &set(&whole, json!({"seed": 6, "sensorRate": 50}))).unwrap();
    assert_eq!(sim.drone_runs(), runs);
}

#[test]
fn a_station_too_long_for_a_quarter_of_the_budget_is_not_remembered() {
    // 200 s evaluated every millisecond: 2·10⁵ grid times, whose remembered predictions would
    // reserve ~100 MB; the flight and its drone runs take a few.
    let csv: String = std::iter::once("t,x,y,z\n".to_string())
        .chain((0..=2000).map(|i| {
            let t = i as f64 * 0.1;
            format!("{t},{},{},40\n", 5.0 * t, 20.0 * (t / 20.0).sin())
        }))
        .collect();
    let long = set(
        &Scenario::default(),
        json!({"trajectory": csv, "model": "3d-ctra", "step": 0.001}),
    );
    let mut sim = Simulator::new();
    let first = simulate(&mut sim, &long).unwrap();
    assert!(
        sim.cached_bytes() < loratrack::MAX_CACHE_BYTES / 8,
        "{} bytes cached",
        sim.cached_bytes()
    );
    // Predicting afresh gives the numbers a remembered chain would.
    let again = simulate(&mut sim, &set(&long, json!({"distance": 1500}))).unwrap();
    let short = simulate(
        &mut Simulator::new(),
        &set(&long, json!({"distance": 1500})),
    )
    .unwrap();
    assert_eq!(again.results[0].error3d, short.results[0].error3d);
    assert!(first.results[0].error3d.p75 > 0.0);
}

#[test]
fn drones_too_many_to_remember_are_streamed_once_then_the_costliest_are_remembered() {
    // 35 000 s sensed at 10 Hz: each model's drone run holds 3.5·10⁵ estimates (25 MB), so two
    // fit in the drone runs' quarter of the budget (64 MB) and three do not.
    let csv: String = std::iter::once("t,x,y,z\n".to_string())
        .chain((0..=3500).map(|i| {
            let t = i as f64 * 10.0;
            format!(
                "{t},{},{},40\n",
                200.0 * (t / 400.0).sin(),
                150.0 * (t / 300.0).cos()
            )
        }))
        .collect();
    let long = set(&Scenario::default(), json!({"trajectory": csv}));
    let one_drone = 350_001 * core::mem::size_of::<[f64; 9]>();
    let mut sim = Simulator::new();
    let first = simulate(&mut sim, &long).unwrap();
    let flight_only = sim.cached_bytes();
    assert!(
        flight_only < one_drone,
        "a single run streams its drones: {flight_only} bytes cached"
    );
    let far = set(&long, json!({"distance": 2500}));
    let second = simulate(&mut sim, &far).unwrap();
    let remembered = sim.cached_bytes() - flight_only;
    assert!(
        (2 * one_drone..3 * one_drone).contains(&remembered),
        "asked for again, two of the three drones are remembered: {remembered} bytes"
    );
    // A third run finds them, and every run gives the numbers a fresh simulator would.
    let third = simulate(&mut sim, &long).unwrap();
    assert_eq!(third.results, first.results);
    let fresh = simulate(&mut Simulator::new(), &far).unwrap();
    assert_eq!(second.results, fresh.results);
}

#[test]
fn seeds_pool_their_runs_and_give_each_statistic_an_interval() {
    let flight = set(&one_flight(3), json!({"model": "dr,3d-ctra"}));
    let mut sim = Simulator::new();
    let alone = simulate(&mut sim, &flight).unwrap();
    assert!(
        alone.results.iter().all(|m| m.ci95.is_none()),
        "one flight with one seed cannot show its own spread"
    );
    let second = simulate(&mut sim, &set(&flight, json!({"seed": 2}))).unwrap();
    let both = simulate(&mut sim, &set(&flight, json!({"seeds": 2}))).unwrap();
    for ((a, b), m) in alone.results.iter().zip(&second.results).zip(&both.results) {
        assert_eq!(
            m.delivery.packets_sent,
            a.delivery.packets_sent + b.delivery.packets_sent
        );
        assert_eq!(m.error3d.count, a.error3d.count + b.error3d.count);
        let ci = m.ci95.expect("two seeds: an interval");
        assert_eq!(ci.runs, 2);
        for [lo, hi] in [ci.mean, ci.p75, ci.p95] {
            assert!(lo <= hi);
        }
        let (lo, hi) = (
            a.error3d.p75.min(b.error3d.p75),
            a.error3d.p75.max(b.error3d.p75),
        );
        assert!(
            ci.p75[0] >= lo - 0.01 && ci.p75[1] <= hi + 0.01,
            "resampling two runs stays between their own p75s (up to interpolation): {ci:?}, {lo}..{hi}"
        );
    }
    assert_eq!(both.config.settings.run.seeds, 2);
    // The series stay the first seed's.
    let with_series = |s: Scenario| set(&s, json!({"series": true}));
    let a = simulate(&mut sim, &with_series(flight.clone())).unwrap();
    let b = simulate(&mut sim, &with_series(set(&flight, json!({"seeds": 3})))).unwrap();
    assert_eq!(a.series, b.series);
}

#[test]
fn every_station_is_compared_with_the_lowest_on_the_same_runs_resampled_together() {
    let flight = set(&one_flight(2), json!({"model": "dr,ctra-plus,3d-ctra"}));
    let mut sim = Simulator::new();
    let alone = simulate(&mut sim, &flight).unwrap();
    assert!(
        alone.results.iter().all(|m| m.p75_vs_lowest.is_none()),
        "one run: nothing to resample"
    );
    let r = simulate(&mut sim, &set(&flight, json!({"seeds": 6}))).unwrap();
    let lowest = r
        .results
        .iter()
        .min_by(|a, b| a.error3d.p75.total_cmp(&b.error3d.p75))
        .unwrap();
    assert!(
        lowest.p75_vs_lowest.is_none(),
        "the lowest is the reference"
    );
    for m in r.results.iter().filter(|m| m.model != lowest.model) {
        let v = m.p75_vs_lowest.expect("six seeds: a paired interval");
        assert_eq!((v.lowest, v.runs), (lowest.model, 6));
        assert!((v.ratio - m.error3d.p75 / lowest.error3d.p75).abs() < 1e-12);
        assert!(v.ratio >= 1.0 && v.interval[0] <= v.interval[1], "{v:?}");
        assert_eq!(v.clearly_higher(), v.interval[0] > 1.0);
    }
    // A station alone has nothing to be compared with.
    let one = simulate(&mut sim, &set(&flight, json!({"seeds": 6, "model": "dr"}))).unwrap();
    assert!(one.results[0].p75_vs_lowest.is_none());
    // CTRA+ against 3D-CTRA on the whole set at the paper's rate: their own intervals overlap,
    // paired they do not (docs/reference.md §12).
    let all = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "ctra-plus,3d-ctra"}),
    );
    let r = simulate(&mut sim, &all).unwrap();
    let (a, b) = (r.results[0].ci95.unwrap(), r.results[1].ci95.unwrap());
    assert!(a.p75[1] > b.p75[0] && b.p75[1] > a.p75[0], "{a:?} {b:?}");
    let paired = r.results[1].p75_vs_lowest.expect("3D-CTRA against CTRA+");
    assert!(paired.clearly_higher(), "{paired:?}");
}

#[test]
fn the_whole_set_gives_intervals_over_its_flights_and_seeds_multiply_the_work_limit() {
    let all = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "dr"}),
    );
    let r = simulate(&mut Simulator::new(), &all).unwrap();
    let ci = r.results[0].ci95.unwrap();
    assert_eq!(ci.runs, 30);
    let p75 = r.results[0].error3d.p75;
    assert!(ci.p75[0] < p75 && p75 < ci.p75[1], "{ci:?} around {p75}");
    // The report says how far the seeds may go: as many as the refusal below names.
    assert_eq!(r.config.max_seeds, 18);
    let one = simulate(&mut Simulator::new(), &set(&all, json!({"synthetic": 1}))).unwrap();
    assert_eq!(
        one.config.max_seeds, 100,
        "one flight: the seeds setting's own limit"
    );
    let too_many = simulate(&mut Simulator::new(), &set(&all, json!({"seeds": 30}))).unwrap_err();
    assert!(too_many
        .to_string()
        .contains("(at most 18 seeds, or shorten the flight"));
    // Fewer seeds would do: the seeds are the setting to change (the page marks its field).
    assert_eq!(too_many.setting(), Some("seeds"));
    // Where one seed is already too long, no one setting is at fault.
    let fast = set(&all, json!({"seeds": 2, "sensorRate": 400}));
    let e = simulate(&mut Simulator::new(), &fast).unwrap_err();
    assert!(e.to_string().contains("the run is too long"), "{e}");
    assert_eq!(e.setting(), None);
}

#[test]
fn seeds_are_checked_and_a_swarm_refuses_more_than_one() {
    for bad in [0, 101] {
        let e = simulate(
            &mut Simulator::new(),
            &set(&one_flight(1), json!({"seeds": bad})),
        );
        assert!(e.unwrap_err().to_string().contains("seeds must be 1..100"));
    }
    let swarm = set(&Scenario::default(), json!({"drones": 2, "seeds": 2}));
    let e = loratrack::api::swarm(&swarm).unwrap_err();
    assert_eq!(
        e.setting(),
        Some("seeds"),
        "the page and the JS API name it"
    );
    let e = e.to_string();
    assert!(e.starts_with("seeds must be 1 in a swarm"), "{e}");
    assert!(e.contains("a swarm runs one seed"), "{e}");
}

/// The CLI's lines under its table say what the numbers rest on exactly where the core's flags
/// (which the page's notes read) say so: the untracked time, too few packets, an error-triggered
/// drone's lost packets.
#[test]
fn the_cli_says_what_the_numbers_rest_on_for_the_runs_the_page_does() {
    let cli = |args: &[&str]| {
        let out = crate::cli(args);
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let runs: [&[&str]; 3] = [
        &["--bw", "125"],
        &["--bw", "125", "--sf", "12"],
        &[
            "--sender",
            "error",
            "--distance",
            "3000",
            "--prediction",
            "bounded",
        ],
    ];
    let mut said = [0; 3];
    for extra in runs {
        let args: Vec<&str> = ["simulate", "--synthetic", "1"]
            .iter()
            .chain(extra)
            .copied()
            .collect();
        let report: serde_json::Value =
            serde_json::from_str(&cli(&[args.as_slice(), &["--json"]].concat())).unwrap();
        let text = cli(&args);
        let any = |flag: &str| {
            report["results"]
                .as_array()
                .unwrap()
                .iter()
                .any(|m| m.pointer(flag).unwrap().as_bool().unwrap())
        };
        for (k, (flag, line)) in [
            ("/wholeFlight/partlyTracked", "\ntracked: "),
            ("/caveats/fewPackets", "\ntoo few packets to compare"),
            ("/caveats/silenceAfterLoss", "\nlost: "),
        ]
        .into_iter()
        .enumerate()
        {
            assert_eq!(any(flag), text.contains(line), "{extra:?}: {flag}");
            said[k] += usize::from(any(flag));
        }
    }
    // Each caveat is said by one of the runs and not by all of them.
    assert_eq!(said, [1, 1, 1], "{said:?}");
}
