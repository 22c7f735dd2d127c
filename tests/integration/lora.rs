//! Time on air against the paper's Table II (with reference §3's two corrections) and independent
//! reference values; the channel's delivery statistics against the Gaussian tail.

use loratrack::api::{airtime, AirtimeParams};
use loratrack::{
    Bandwidth, Channel, ChannelAccess, ChannelParams, FairUse, LdroMode, Region, Rng, Shadowing,
    SpreadingFactor,
};

fn params(sf: i64, bw: f64, payload: usize, overhead: usize) -> AirtimeParams {
    AirtimeParams {
        sf,
        bw,
        payload,
        overhead,
        cr: 1,
        preamble: 8,
        implicit_header: false,
        no_crc: false,
        ldro: LdroMode::Auto,
        duty_cycle: 0.01,
        region: Region::Eu868,
        interval: None,
        access: ChannelAccess::DutyCycle,
        fair_use: FairUse::Off,
    }
}

#[test]
fn airtime_names_the_plans_data_rate_and_says_why_a_plan_refuses_a_packet() {
    let eu = airtime(&params(7, 250.0, 12, 13)).unwrap();
    assert_eq!((eu.data_rate, eu.refused.as_deref()), (Some(6), None));
    let raw = airtime(&params(8, 250.0, 12, 0)).unwrap();
    assert_eq!(
        (raw.data_rate, raw.refused.as_deref()),
        (None, None),
        "raw LoRa in EU868"
    );
    let us = |sf, payload| {
        airtime(&AirtimeParams {
            region: Region::Us915,
            ..params(sf, 125.0, payload, 13)
        })
        .unwrap()
    };
    assert_eq!(us(9, 12).data_rate, Some(1));
    assert_eq!(
        us(9, 12).min_interval,
        1.0,
        "no duty cycle: the default interval"
    );
    assert!(us(10, 12)
        .refused
        .unwrap()
        .contains("over the 400 ms dwell time"));
    assert!(us(10, 9).refused.is_none());
    assert!(us(12, 9).refused.unwrap().contains("no uplink data rate"));
    let lbt = airtime(&AirtimeParams {
        access: ChannelAccess::Lbt,
        ..params(7, 125.0, 12, 13)
    })
    .unwrap();
    assert!((lbt.min_interval * 100.0 / 3600.0 - lbt.time_on_air).abs() < 1e-12);
}

#[test]
fn airtime_refuses_a_duty_cycle_outside_the_limits_a_simulation_keeps() {
    let at = |duty_cycle| {
        airtime(&AirtimeParams {
            duty_cycle,
            ..params(7, 125.0, 9, 0)
        })
    };
    for refused in [2.0, 1e-5, 0.0] {
        let e = at(refused).unwrap_err();
        assert_eq!(e.setting(), Some("dutyCycle"), "{refused}");
        assert!(
            e.to_string().starts_with("dutyCycle must be 0.0001..1"),
            "{e}"
        );
    }
    // Two sub-bands halve the interval of one (reference §6.1).
    let (one, two) = (at(0.01).unwrap(), at(0.02).unwrap());
    assert!((one.min_interval - 2.0 * two.min_interval).abs() < 1e-12);
}

#[test]
fn paper_table_ii_with_the_corrections_of_spec_section_3() {
    // (SF, kHz, payloads, transmission time s, min interval s), no LoRaWAN overhead.
    let table: [(i64, f64, &[usize], f64, f64); 6] = [
        (7, 125.0, &[9, 11, 12], 0.0412, 4.12), // paper prints 4.21 (erratum)
        (7, 250.0, &[9, 11, 12], 0.0206, 2.06),
        (8, 125.0, &[9], 0.0722, 7.22),
        (8, 125.0, &[11, 12], 0.0824, 8.24),
        (8, 250.0, &[9], 0.0361, 3.61), // paper prints 0.0391 (erratum)
        (8, 250.0, &[11, 12], 0.0412, 4.12),
    ];
    for (sf, bw, payloads, toa, interval) in table {
        for &pl in payloads {
            let r = airtime(&params(sf, bw, pl, 0)).unwrap();
            assert!(
                (r.time_on_air - toa).abs() < 0.00005,
                "SF{sf}/{bw}/{pl}B: {}",
                r.time_on_air
            );
            assert!(
                (r.min_interval - interval).abs() < 0.005,
                "SF{sf}/{bw}/{pl}B: {}",
                r.min_interval
            );
        }
    }
    assert!((airtime(&params(7, 125.0, 12, 0)).unwrap().time_on_air - 0.041216).abs() < 1e-9);
    assert!((airtime(&params(8, 125.0, 9, 0)).unwrap().time_on_air - 0.072192).abs() < 1e-9);
}

#[test]
fn independent_reference_values_to_the_microsecond() {
    for (sf, bw, pl, expected) in [
        (7, 125.0, 14, 0.046336),
        (7, 250.0, 14, 0.023168),
        (8, 125.0, 14, 0.082432),
        (11, 125.0, 14, 0.659456),
        (7, 125.0, 25, 0.061696),
    ] {
        let r = airtime(&params(sf, bw, pl, 0)).unwrap();
        assert!(
            (r.time_on_air - expected).abs() < 1e-6,
            "SF{sf}/{bw}/{pl}: {}",
            r.time_on_air
        );
    }
}

#[test]
fn lorawan_overhead_is_13_bytes_by_default_and_limits_are_refused() {
    let r = airtime(&params(7, 125.0, 12, 13)).unwrap();
    assert_eq!(r.phy_payload_bytes, 25);
    assert!((r.time_on_air - 0.061696).abs() < 1e-9);
    assert!(airtime(&params(7, 125.0, 243, 13))
        .unwrap_err()
        .to_string()
        .contains("255"));
    assert!(airtime(&params(6, 125.0, 12, 13)).is_err());
    assert!(airtime(&params(7, 300.0, 12, 13)).is_err());
    let mut p = params(7, 125.0, 12, 13);
    p.duty_cycle = 0.0;
    assert!(airtime(&p).unwrap_err().to_string().contains("dutyCycle"));
}

#[test]
fn delivery_probability_with_shadowing_matches_the_gaussian_tail() {
    let channel = Channel::new(ChannelParams::default()).unwrap();
    let (sf, bw) = (SpreadingFactor::new(7).unwrap(), Bandwidth::Khz250);
    let d = 3000.0;
    let margin = channel.mean_rx_power_dbm(d) - Channel::sensitivity_dbm(sf, bw);
    let sigma = 4.0;
    // P(margin + N(0, sigma) >= 0) = Phi(margin / sigma).
    let expected = 0.5 * (1.0 + erf(margin / sigma / std::f64::consts::SQRT_2));
    let mut rng = Rng::new(77);
    // Independent samples: 10 km between transmissions, far beyond the 110 m decorrelation.
    let mut shadow = Shadowing::new(sigma, 110.0);
    let n = 40_000;
    let received = (0..n)
        .filter(|_| channel.received(sf, bw, d, shadow.next(10_000.0, &mut rng)))
        .count();
    let p = received as f64 / n as f64;
    let se = (expected * (1.0 - expected) / n as f64).sqrt();
    assert!(
        (p - expected).abs() < 4.0 * se,
        "delivery {p} vs {expected} (4 se = {})",
        4.0 * se
    );
}

/// Abramowitz & Stegun 7.1.26, |error| < 1.5e-7: enough for a 4-standard-error check.
fn erf(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.3275911 * x.abs());
    let y = 1.0
        - (((((1.061405429 * t - 1.453152027) * t) + 1.421413741) * t - 0.284496736) * t
            + 0.254829592)
            * t
            * (-x * x).exp();
    y.copysign(x)
}

#[test]
fn the_link_budget_puts_half_delivery_at_each_range_and_falls_with_distance() {
    use loratrack::api::{link_budget, LinkBudgetParams};
    let base = LinkBudgetParams::default();
    let r = link_budget(&base).unwrap();
    for s in &r.sfs {
        assert!(s.delivery.windows(2).all(|w| w[1] <= w[0]), "SF{}", s.sf);
        let at = link_budget(&LinkBudgetParams {
            distances: vec![s.range_m],
            ..base.clone()
        })
        .unwrap();
        let d = at.sfs.iter().find(|x| x.sf == s.sf).unwrap().delivery[0];
        assert!((d - 0.5).abs() < 1e-9, "SF{}: {d} at its range", s.sf);
    }
    assert!(r.sfs.windows(2).all(|w| w[1].range_m > w[0].range_m));
    // Without shadowing delivery is a step at the range.
    let sharp = link_budget(&LinkBudgetParams {
        shadowing: 0.0,
        ..base.clone()
    })
    .unwrap();
    let sf7 = &sharp.sfs[0];
    for (d, p) in sharp.distances.iter().zip(&sf7.delivery) {
        assert_eq!(*p, if *d <= sf7.range_m { 1.0 } else { 0.0 }, "{d} m");
    }
    assert!(link_budget(&LinkBudgetParams {
        distances: vec![0.0],
        ..base
    })
    .is_err());
}
