//! Regional plans (reference §14): each plan's data rates and limits as LoRaWAN Regional
//! Parameters RP002-1.0.4 gives them, and what they change for a tracking drone.

use loratrack::api::{simulate, swarm};
use loratrack::{Bandwidth, Region, Scenario, SimReport, Simulator};
use serde_json::{json, Value};

fn run(settings: Value) -> Result<SimReport, String> {
    let s = Scenario::default().with(&settings).unwrap();
    simulate(&mut Simulator::new(), &s).map_err(|e| e.to_string())
}

#[test]
fn each_plans_uplink_data_rates_are_the_regional_parameters_tables() {
    // (plan, DR, SF, bandwidth kHz, largest application payload N; None: barred by the dwell
    // time). RP002-1.0.4 Tables 14/17 (EU868), 31/35 (US915), 48/52 (AU915, dwell on),
    // 67/71 (AS923, dwell on), 83/86 (IN865).
    let table: &[(Region, u8, u8, f64, Option<usize>)] = &[
        (Region::Eu868, 0, 12, 125.0, Some(51)),
        (Region::Eu868, 3, 9, 125.0, Some(115)),
        (Region::Eu868, 6, 7, 250.0, Some(242)),
        (Region::Us915, 0, 10, 125.0, Some(11)),
        (Region::Us915, 1, 9, 125.0, Some(53)),
        (Region::Us915, 3, 7, 125.0, Some(242)),
        (Region::Us915, 4, 8, 500.0, Some(242)),
        (Region::Au915, 0, 12, 125.0, None),
        (Region::Au915, 2, 10, 125.0, Some(11)),
        (Region::Au915, 6, 8, 500.0, Some(242)),
        (Region::As923, 1, 11, 125.0, None),
        (Region::As923, 4, 8, 125.0, Some(125)),
        (Region::As923, 6, 7, 250.0, Some(242)),
        (Region::In865, 0, 12, 125.0, Some(51)),
        (Region::In865, 5, 7, 125.0, Some(242)),
    ];
    for &(region, dr, sf, bw, n) in table {
        let bw = Bandwidth::from_khz(bw).unwrap();
        let rate = region
            .rate(sf, bw)
            .unwrap_or_else(|| panic!("{region:?} SF{sf}"));
        assert_eq!((rate.dr, rate.max_payload), (dr, n), "{region:?} SF{sf}");
    }
    assert_eq!(Region::Us915.rates().len(), 5, "US915 uplinks: DR0..DR4");
    assert_eq!(
        Region::In865.rates().len(),
        6,
        "IN865: DR0..DR5, no 250 kHz rate"
    );
    for region in [Region::Us915, Region::Au915, Region::As923] {
        assert_eq!(region.dwell_time(), Some(0.4), "{region:?}");
    }
    assert_eq!(
        Region::ALL.map(|r| r.channels()),
        [3, 8, 8, 2, 3],
        "EU868, US915, AU915, AS923, IN865"
    );
}

#[test]
fn us915_at_sf9_sends_as_often_as_the_interval_allows_and_tracks_closer_than_eu868() {
    let base = json!({"synthetic": "all", "sf": 9, "bw": 125, "distance": 1000});
    let eu = run(base.clone()).unwrap();
    let mut us_settings = base.clone();
    us_settings["region"] = json!("us915");
    let us = run(us_settings).unwrap();
    assert_eq!(us.config.data_rate, Some(1), "SF9/125 kHz is US915 DR1");
    assert_eq!(us.config.settings.network.channels, Some(8));
    for (u, e) in us.results.iter().zip(&eu.results) {
        assert_eq!(u.interval, 1.0, "{}: the default interval", u.model);
        assert!(e.interval > 20.0, "{}: EU868's 1 % at SF9", e.model);
        assert!(
            u.error3d.p75 < e.error3d.p75,
            "{}: US915 p75 {} against EU868 {}",
            u.model,
            u.error3d.p75,
            e.error3d.p75
        );
    }
}

#[test]
fn us915_refuses_sf11_and_sf12_and_a_frame_over_the_dwell_time_with_the_reason() {
    for sf in [11, 12] {
        let e = run(json!({"synthetic": 1, "region": "us915", "sf": sf, "bw": 125})).unwrap_err();
        assert!(
            e.contains(&format!("US915 has no uplink data rate at SF{sf}/125 kHz")),
            "{e}"
        );
    }
    let e = run(json!({"synthetic": 1, "region": "us915", "sf": 10, "bw": 125})).unwrap_err();
    assert!(e.contains("3D-CTRA sends 12 bytes"), "{e}");
    assert!(e.contains("411.6 ms"), "{e}");
    assert!(e.contains("400 ms dwell time"), "{e}");
    // Its remedies name the smaller payloads as the page and the CLI both show them.
    assert!(
        e.contains("or a station with a smaller payload (DR: 9 bytes, CTRA+: 11)"),
        "{e}"
    );
    // DR's own frame, too long with a larger overhead, has no smaller payload to suggest.
    let e = run(json!({"synthetic": 1, "region": "us915", "sf": 10, "bw": 125, "model": "dr", "overhead": 30})).unwrap_err();
    assert!(e.contains("DR sends 9 bytes (+30 overhead)"), "{e}");
    assert!(e.ends_with("choose a faster data rate"), "{e}");
    // DR's and CTRA+'s frames fit at DR0.
    let ok = run(
        json!({"synthetic": 1, "region": "us915", "sf": 10, "bw": 125, "model": "dr,ctra-plus"}),
    )
    .unwrap();
    assert_eq!(ok.results.len(), 2);
}

#[test]
fn the_interval_and_fair_use_decide_how_often_a_drone_sends_where_they_apply() {
    let every = |settings: Value| run(settings).unwrap().results[0].interval;
    assert_eq!(
        every(
            json!({"synthetic": 1, "model": "dr", "region": "in865", "sf": 7, "bw": 125, "interval": 2.5})
        ),
        2.5
    );
    // TTN's 30 s a day: one packet every time-on-air × 2880.
    let r = run(json!({"synthetic": 1, "model": "dr", "fairUse": "ttn"})).unwrap();
    let toa = r.results[0].time_on_air;
    assert!((r.results[0].interval - toa * 2880.0).abs() < 1e-6 * toa * 2880.0);
    // An interval in a duty-cycled plan would be ignored: refused instead.
    let e = run(json!({"synthetic": 1, "interval": 2})).unwrap_err();
    assert!(e.contains("EU868 limits sending by its duty cycle"), "{e}");
    let e = run(json!({"synthetic": 1, "region": "us915", "sf": 9, "bw": 125, "interval": 0.1}))
        .unwrap_err();
    assert!(e.contains("at least the time on air"), "{e}");
    let e = run(json!({"synthetic": 1, "region": "us915", "adr": "lorawan", "sf": 9, "bw": 125}))
        .unwrap_err();
    assert!(e.contains("`adr` runs EU868's data rates"), "{e}");
}

#[test]
fn a_swarm_hops_over_its_plans_channels() {
    let s = Scenario::default()
        .with(&json!({"drones": 16, "duration": 60, "region": "us915", "sf": 7, "bw": 125, "sfPlan": "fixed", "model": "dr"}))
        .unwrap();
    let r = swarm(&s).unwrap();
    assert_eq!(r.drones[0].channel_use.len(), 8);
    let used: usize = r
        .drones
        .iter()
        .map(|d| d.channel_use.iter().filter(|&&n| n > 0).count())
        .max()
        .unwrap();
    assert!(
        used > 3,
        "a drone hops over more than EU868's three channels"
    );
}

#[test]
fn a_spread_swarm_gets_the_data_rates_that_carry_its_frame() {
    let sfs = |settings: Value| -> Result<Vec<u8>, String> {
        let s = Scenario::default().with(&settings).unwrap();
        let r = swarm(&s).map_err(|e| e.to_string())?;
        let mut sfs: Vec<u8> = r.drones.iter().map(|d| d.sf).collect();
        sfs.sort_unstable();
        sfs.dedup();
        Ok(sfs)
    };
    let us915 = json!({"drones": 8, "duration": 30, "region": "us915", "bw": 125, "interval": 5, "sfPlan": "spread"});
    // DR's 22-byte frame fits US915's DR0 (SF10) within the dwell time; 3D-CTRA's 25 bytes do not,
    // so its swarm spreads over SF7..SF9 where a fixed SF10 is refused with the reason.
    let mut dr = us915.clone();
    dr["model"] = json!("dr");
    assert_eq!(sfs(dr).unwrap(), [7, 8, 9, 10]);
    assert_eq!(sfs(us915.clone()).unwrap(), [7, 8, 9]);
    let mut fixed = us915;
    fixed["sfPlan"] = json!("fixed");
    fixed["sf"] = json!(10);
    assert!(sfs(fixed).unwrap_err().contains("400 ms dwell time"));
    // EU868 carries every frame at every SF.
    let eu = json!({"drones": 6, "duration": 30, "sfPlan": "spread"});
    assert_eq!(sfs(eu).unwrap(), [7, 8, 9, 10, 11, 12]);
}

/// The CLI's texts say what an interval rests on: the duty cycle set, listen before talk or the
/// interval set, and fair use; two runs that differ only in it do not print alike.
#[test]
fn the_cli_says_what_paces_the_uplinks_beside_each_interval() {
    let text = |args: &[&str]| {
        let out = crate::cli(args);
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let airtime = |extra: &[&str]| {
        let args = [
            &["airtime", "--sf", "7", "--bw", "125", "--payload", "12"][..],
            extra,
        ]
        .concat();
        let out = text(&args);
        out.lines()
            .find(|l| l.starts_with("min interval"))
            .unwrap()
            .to_string()
    };
    let one_sub_band = airtime(&[]);
    assert!(
        one_sub_band.ends_with(" s (1 % duty cycle)"),
        "{one_sub_band}"
    );
    assert!(airtime(&["--duty-cycle", "0.02"]).ends_with(" s (2 % duty cycle)"));
    assert!(airtime(&["--access", "lbt"])
        .ends_with(" s (listen-before-talk, 100 s of airtime per hour)"));
    assert!(airtime(&["--fair-use", "ttn"]).ends_with(" s (1 % duty cycle, TTN fair use)"));
    let us915 = |extra: &[&str]| {
        let args = [
            "airtime",
            "--sf",
            "9",
            "--bw",
            "125",
            "--payload",
            "12",
            "--region",
            "us915",
        ];
        text(&[&args[..], extra].concat())
    };
    let us = us915(&[]);
    assert!(
        us.contains("min interval     1.000 s (every 1 s, no duty cycle)"),
        "{us}"
    );
    // An interval shorter than the frame is the interval's refusal, not the data rate's.
    let short = us915(&["--interval", "0.1"]);
    assert!(
        short.contains(
            "data rate        US915 DR1\nmin interval     refused: interval must be at least"
        ),
        "{short}"
    );
    // A fraction whose product with 100 is no short float is written as it was given.
    let header = text(&["simulate", "--synthetic", "1", "--duty-cycle", "0.0007"]);
    assert!(
        header.starts_with(
            "synthetic 1 (1 flight, 81 s), SF7 / 250 kHz (EU868 DR6, 0.07 % duty cycle),"
        ),
        "{header}"
    );
    let swarm = |extra: &[&str]| {
        let args = [&["swarm", "--drones", "2", "--duration", "60"][..], extra].concat();
        text(&args).lines().next().unwrap().to_string()
    };
    let swarm_header = swarm(&[]);
    assert!(
        swarm_header.contains(", at 1000 m, EU868 (1 % duty cycle), 3 channels,"),
        "{swarm_header}"
    );
    assert!(swarm(&["--duty-cycle", "0.02"]).contains(", EU868 (2 % duty cycle),"));
    assert!(swarm(&["--access", "lbt"])
        .contains(", EU868 (listen-before-talk, 100 s of airtime per hour),"));
}
