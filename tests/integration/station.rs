//! The station under loss (issue: bounded prediction, IMM, honest uncertainty): the bounded
//! predictor is the paper's while packets come on time and stays physical after a gap; the IMM
//! reports its members' probabilities; the 95 % coverage is right for a correctly specified case.

use loratrack::api::simulate;
use loratrack::{
    inside_95, new_tracker, Bounds, Ctra3d, CtraPlus, Dr, ModelChoice, ModelKind, ModelResult,
    MotionModel, Prediction, Rng, Scenario, Simulator, StationModel, StationPredictor,
    StationSetup, Tracker, Ukf, MANOEUVRE_SPREAD, PAPER_Q, PAPER_R_DIAGONAL,
};
use nalgebra::{Matrix3, SMatrix, SVector};
use serde_json::{json, Value};

/// `base` with the flat JSON settings of `changes` applied.
fn set(base: &Scenario, changes: Value) -> Scenario {
    base.with(&changes).unwrap()
}

fn setup(prediction: Prediction) -> StationSetup {
    StationSetup {
        prediction,
        bounds: Bounds::default(),
        step: 0.1,
        eta: 0.9,
        q: PAPER_Q,
        r_diagonal: PAPER_R_DIAGONAL,
        interval: 2.0,
        error_triggered: false,
        drone_covariance: None,
    }
}

/// The true state of a steady climbing turn at time t (8 m/s, 0.3 rad/s, 5° pitch).
fn steady_turn(t: f64) -> [f64; 9] {
    let s = SVector::<f64, 9>::from([0.0, 0.0, 40.0, 0.2, 0.087, 8.0, 0.0, 0.3, 0.0]);
    let x = Ctra3d.propagate(&s, t);
    core::array::from_fn(|i| x[i])
}

/// How far, m, a position `p` is from the steady turn at time `t`.
fn off_the_turn(t: f64, p: [f64; 3]) -> f64 {
    let truth = steady_turn(t);
    (0..3)
        .map(|i| (p[i] - truth[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// A paper and a bounded station of `model` fed a steady climbing turn's packets every 2 s for a
/// minute, both predicting every 0.1 s: `check(t, age, paper, bounded)` after each step.
fn fly_steady_turn<const N: usize, M: MotionModel<N> + Copy>(
    model: M,
    mut check: impl FnMut(f64, f64, &StationPredictor<N, M>, &StationPredictor<N, M>),
) {
    let mut paper = StationPredictor::new(model, setup(Prediction::Paper));
    let mut bounded = StationPredictor::new(model, setup(Prediction::Bounded));
    for k in 0..30 {
        let sent = 2.0 * k as f64;
        paper.reset(&steady_turn(sent), sent);
        bounded.reset(&steady_turn(sent), sent);
        for j in 1..=20 {
            let t = sent + 0.1 * j as f64;
            paper.predict_to(t);
            bounded.predict_to(t);
            check(t, t - sent, &paper, &bounded);
        }
    }
}

/// While packets come on time no limit binds and no decay but the acceleration's starts, so the
/// bounded station flies the paper's equations; it differs in its sigma points (non-negative
/// weights, points at ±√n σ instead of ±√3 σ), which move the unscented mean by centimetres
/// over a 2 s interval, and in its uncertainty.
fn paper_and_bounded_agree<const N: usize, M: MotionModel<N> + Copy>(model: M, within: f64) {
    let (mut paper_off, mut bounded_off) = (0.0, 0.0);
    fly_steady_turn(model, |t, _, paper, bounded| {
        let (a, b) = (paper.position(), bounded.position());
        assert!(
            (0..3).all(|i| (a[i] - b[i]).abs() < within),
            "{:?} at {t}: {a:?} vs {b:?}",
            M::KIND
        );
        paper_off += off_the_turn(t, a);
        bounded_off += off_the_turn(t, b);
    });
    assert!(
        bounded_off <= paper_off,
        "{:?}: summed error {bounded_off} m against the paper's {paper_off} m",
        M::KIND
    );
}

#[test]
fn bounded_prediction_keeps_to_the_papers_while_packets_arrive_on_time_and_is_no_farther_off() {
    // Measured: DR's mean moves at most 3 cm, CTRA+'s (whose turn rate spreads the heading) 10 cm.
    paper_and_bounded_agree(Dr, 0.05);
    paper_and_bounded_agree(CtraPlus, 0.15);
}

#[test]
fn the_bounded_3d_ctra_station_lets_the_tilt_rates_uncertainty_die_with_it_and_tracks_closer() {
    // The paper decays psi but not its variance, which then grows with q for ever; its sigma
    // points fly up and down and pull the unscented mean off a steady climbing turn.
    let (mut worse, mut better) = (0, 0);
    fly_steady_turn(Ctra3d, |t, _, paper, bounded| {
        let (a, b) = (
            off_the_turn(t, paper.position()),
            off_the_turn(t, bounded.position()),
        );
        worse += usize::from(b > a + 1e-9);
        better += usize::from(b < a - 1e-9);
    });
    assert!(
        better > 500 && worse == 0,
        "closer {better} times, farther {worse}"
    );
}

#[test]
fn after_a_long_gap_the_bounded_speed_stays_physical_and_the_paper_does_not() {
    let v_max = Bounds::default().v_max;
    for a in [-3.0, 3.0] {
        let start = [0.0, 0.0, 40.0, 0.0, 0.0, 12.0, a, 0.4, 0.2];
        let mut bounded = StationPredictor::new(Ctra3d, setup(Prediction::Bounded));
        let mut paper = StationPredictor::new(Ctra3d, setup(Prediction::Paper));
        bounded.reset(&start, 0.0);
        paper.reset(&start, 0.0);
        for j in 1..=600 {
            let t = 0.1 * j as f64;
            bounded.predict_to(t);
            paper.predict_to(t);
            let v = bounded.state()[5];
            assert!((0.0..=v_max).contains(&v), "a = {a}: v = {v} at {t} s");
            assert!(bounded.state().iter().all(|x| x.is_finite()));
        }
        let v = paper.state()[5];
        assert!(
            !(0.0..=v_max).contains(&v),
            "the paper's station keeps accelerating: {v}"
        );
    }
}

/// A linear model (constant velocity in Cartesian coordinates): the unscented transform is exact
/// for it, so a filter fed the truth's own noise must be consistent.
#[derive(Clone, Copy)]
struct ConstantVelocity;

impl MotionModel<6> for ConstantVelocity {
    const KIND: ModelKind = ModelKind::Dr;
    fn propagate(&self, s: &SVector<f64, 6>, dt: f64) -> SVector<f64, 6> {
        let mut out = *s;
        for k in 0..3 {
            out[k] += s[k + 3] * dt;
        }
        out
    }
}

#[test]
fn coverage_of_a_correctly_specified_linear_station_is_95_percent() {
    let (q, dt, r) = (0.1, 0.1, 0.5);
    let mut rng = Rng::new(3);
    let p0 = SMatrix::<f64, 6, 6>::identity() * r;
    let qm = SMatrix::<f64, 6, 6>::identity() * q;
    let mut ukf = Ukf::new(SVector::zeros(), p0, qm, Default::default(), &[]).unwrap();
    let mut truth = SVector::<f64, 6>::from([0.0, 0.0, 0.0, 3.0, -1.0, 0.5]);
    let (mut inside, mut total) = (0usize, 0usize);
    for k in 0..200_000 {
        if k % 30 == 0 {
            // A "packet": the truth with noise of covariance P0, as the station assumes.
            let z = truth.map(|x| x + r.sqrt() * rng.normal());
            ukf.reset(z, p0);
        }
        ukf.predict(&ConstantVelocity, dt);
        truth = ConstantVelocity.propagate(&truth, dt)
            + SVector::<f64, 6>::from_fn(|_, _| (q * dt).sqrt() * rng.normal());
        let e = [
            ukf.x[0] - truth[0],
            ukf.x[1] - truth[1],
            ukf.x[2] - truth[2],
        ];
        let p: Matrix3<f64> = ukf.p.fixed_view::<3, 3>(0, 0).into_owned();
        inside += usize::from(inside_95(&e, &p));
        total += 1;
    }
    let c = inside as f64 / total as f64;
    assert!((c - 0.95).abs() <= 0.01, "coverage {c}");
}

fn whole_set(prediction: Prediction, distance: f64) -> Scenario {
    set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "dr,3d-ctra,imm", "prediction": prediction, "sf": 7, "bw": 250.0, "distance": distance, "overhead": 0}),
    )
}

#[test]
fn the_bounded_station_stays_sane_where_packets_are_lost() {
    let mut sim = Simulator::new();
    let paper = simulate(&mut sim, &whole_set(Prediction::Paper, 3000.0)).unwrap();
    let bounded = simulate(&mut sim, &whole_set(Prediction::Bounded, 3000.0)).unwrap();
    let get = |r: &loratrack::SimReport, m: StationModel| {
        r.results.iter().find(|x| x.model == m).unwrap().error3d
    };
    let (dr, d3) = (
        StationModel::Single(ModelKind::Dr),
        StationModel::Single(ModelKind::Ctra3d),
    );
    let (b_dr, b_3d, p_3d) = (get(&bounded, dr), get(&bounded, d3), get(&paper, d3));
    assert!(
        b_3d.mean <= b_dr.mean && b_3d.p95 <= b_dr.p95,
        "{b_3d:?} vs DR {b_dr:?}"
    );
    assert!(
        b_3d.mean < p_3d.mean / 5.0,
        "bounded {} vs paper {}",
        b_3d.mean,
        p_3d.mean
    );
    let imm = bounded
        .results
        .iter()
        .find(|x| x.model == StationModel::Imm)
        .unwrap();
    assert!(
        imm.error3d.p95 <= b_dr.p95,
        "IMM p95 {} vs DR {}",
        imm.error3d.p95,
        b_dr.p95
    );
}

/// At SF8 the forecasts of packets 4 s apart barely tell the members apart; the packets' own
/// manoeuvre fields do (before them the IMM was 1.08× its best member here).
#[test]
fn the_bounded_imm_station_is_within_2_percent_of_its_best_member_at_sf8() {
    let s = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "dr,ctra-plus,3d-ctra,imm", "prediction": "bounded", "sf": 8, "bw": 250.0, "distance": 1000.0, "overhead": 0}),
    );
    let r = simulate(&mut Simulator::new(), &s).unwrap();
    let p75 = |m: StationModel| r.results.iter().find(|x| x.model == m).unwrap().error3d.p75;
    let best = ModelKind::ALL
        .map(|k| p75(StationModel::Single(k)))
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let imm = p75(StationModel::Imm);
    assert!(imm <= 1.02 * best, "IMM p75 {imm} vs best member {best}");
}

#[test]
fn the_bounded_stations_95_percent_region_covers_93_to_97_percent_at_1_and_3_km() {
    // The paper's station resets to one fix's R and never widens for its model's blind spot:
    // at 1 km its region is far too wide, at 3 km (lost packets) far too narrow.
    let mut sim = Simulator::new();
    for distance in [1000.0, 3000.0] {
        let mut run = |prediction, overhead: u32| {
            let mut p = whole_set(prediction, distance);
            p = set(&p, json!({"model": "3d-ctra", "overhead": overhead}));
            simulate(&mut sim, &p).unwrap().results[0].clone()
        };
        // With LoRaWAN's 13-byte overhead (the page as it opens) the region holds; without it
        // (the paper's frames, packets every 2.1 s) it is a hair wide, since the drone filter's
        // settled covariance a packet resets to is wider than its errors on these smooth
        // flights and the calibration shrinks only the growth since the packet (seed 1 0.972 at
        // 1 km, 0.970 at 3 km; README, reference §4). At the precision every report prints.
        let three = |c: f64| (c * 1000.0).round() / 1000.0;
        for (overhead, upper) in [(13, 0.97), (0, 0.975)] {
            let bounded = run(Prediction::Bounded, overhead);
            assert_honest_region(
                &bounded,
                three(bounded.coverage95),
                0.93..=upper,
                &format!("{distance} m, overhead {overhead}"),
            );
        }
        let paper = run(Prediction::Paper, 0);
        assert!(
            (paper.coverage95 - 0.95).abs() > 0.04 && (paper.nees - 3.0).abs() > 2.0,
            "{distance} m: the paper's station {} / {}",
            paper.coverage95,
            paper.nees
        );
    }
}

/// Asserts a station's 95 % region is about honest: `coverage` (its coverage95, as the test
/// reads it) within `expected`, and its mean NEES within 1.5–4.5 (3 for an honest one).
fn assert_honest_region(
    m: &ModelResult,
    coverage: f64,
    expected: std::ops::RangeInclusive<f64>,
    what: &str,
) {
    assert!(
        expected.contains(&coverage),
        "{what}: coverage {}",
        m.coverage95
    );
    assert!((1.5..=4.5).contains(&m.nees), "{what}: NEES {}", m.nees);
}

#[test]
fn on_the_jerkier_real_flight_the_calibrated_region_still_covers_about_95_percent() {
    // The model error is calibrated on the synthetic set; the real Canberra flight outruns it
    // (0.82 uncalibrated). The station widens its region from its own forecasts' misses.
    let mut sim = Simulator::new();
    let real = json!({"sample": "canberra", "model": "3d-ctra", "prediction": "bounded", "sf": 7,
        "bw": 250.0, "overhead": 0, "seeds": 8});
    for distance in [1000.0, 3000.0] {
        let mut p = set(&Scenario::default(), real.clone());
        p = set(&p, json!({ "distance": distance }));
        let m = simulate(&mut sim, &p).unwrap().results[0].clone();
        assert_honest_region(&m, m.coverage95, 0.9..=0.97, &format!("{distance} m"));
    }
}

#[test]
fn an_adaptive_heading_noise_takes_the_straight_legs_and_leaves_the_loitering_flight_its_hedge() {
    // The synthetic set flies straight legs between manoeuvres: its packets soon show that a
    // forecast without the hedge misses least. The real Canberra flight loiters: the choice may
    // go either way there, but must not cost it.
    let mut sim = Simulator::new();
    let run = |sim: &mut Simulator, settings: serde_json::Value, noise: &str| {
        let mut p = set(&Scenario::default(), settings);
        p = set(
            &p,
            json!({ "model": "3d-ctra", "prediction": "bounded", "headingNoise": noise }),
        );
        simulate(sim, &p).unwrap().results[0].error3d
    };
    for overhead in [0, 13] {
        let synthetic = json!({ "synthetic": "all", "sf": 7, "bw": 250.0, "overhead": overhead });
        let (fixed, adaptive) = (
            run(&mut sim, synthetic.clone(), "fixed"),
            run(&mut sim, synthetic, "adaptive"),
        );
        assert!(
            adaptive.p75 < 0.96 * fixed.p75,
            "overhead {overhead}: p75 {} against {}",
            adaptive.p75,
            fixed.p75
        );
        assert!(
            adaptive.p95 < 0.96 * fixed.p95,
            "overhead {overhead}: p95 {} against {}",
            adaptive.p95,
            fixed.p95
        );
    }
    let real = json!({ "sample": "canberra", "seeds": 8 });
    let (fixed, adaptive) = (
        run(&mut sim, real.clone(), "fixed"),
        run(&mut sim, real, "adaptive"),
    );
    assert!(
        adaptive.p95 < 1.05 * fixed.p95,
        "Canberra p95 {} against {}",
        adaptive.p95,
        fixed.p95
    );
}

#[test]
fn an_adaptive_heading_noise_is_refused_for_the_paper_station_and_changes_nothing_where_packets_are_few(
) {
    let p = set(&Scenario::default(), json!({ "headingNoise": "adaptive" }));
    let e = p.validate().unwrap_err().to_string();
    assert!(e.contains("set `prediction` to bounded"), "{e}");
    // At SF12 a synthetic flight brings one or two packets: none is chosen from five.
    let mut sim = Simulator::new();
    let slow = json!({ "synthetic": "all", "sf": 12, "bw": 125.0, "prediction": "bounded", "model": "dr,3d-ctra" });
    let fixed = simulate(&mut sim, &set(&Scenario::default(), slow.clone())).unwrap();
    let adaptive = simulate(
        &mut sim,
        &set(
            &set(&Scenario::default(), slow),
            json!({ "headingNoise": "adaptive" }),
        ),
    )
    .unwrap();
    for (f, a) in fixed.results.iter().zip(&adaptive.results) {
        assert_eq!(f.error3d.p75, a.error3d.p75, "{:?}", f.model);
    }
}

/// Root mean square of the speed, acceleration and turn rate, of the acceleration DR leaves
/// out and the jerk CTRA+/3D-CTRA leave out (per axis), and of the tilt rate, over `flights`
/// sampled every 0.1 s.
fn manoeuvre_spreads(flights: &[loratrack::Trajectory]) -> [f64; 6] {
    let dt = 0.1;
    let (mut n, mut sums) = (0.0, [0.0; 6]);
    let unmodelled = |s: &[f64; 9]| [s[6], s[5] * s[7], s[5] * s[8]];
    for f in flights {
        let mut hint = 0;
        let mut t = f.t[0] + dt;
        while t < f.t[f.t.len() - 1] - dt {
            let (a, b, c) = (
                f.state_at(t - dt, &mut hint),
                f.state_at(t, &mut hint),
                f.state_at(t + dt, &mut hint),
            );
            let (ua, ub, uc) = (unmodelled(&a), unmodelled(&b), unmodelled(&c));
            sums[0] += b[5] * b[5];
            sums[1] += b[6] * b[6];
            sums[2] += b[7] * b[7];
            sums[3] += ub.iter().map(|x| x * x).sum::<f64>() / 3.0;
            sums[4] += (0..3)
                .map(|i| ((uc[i] - ua[i]) / (2.0 * dt)).powi(2))
                .sum::<f64>()
                / 3.0;
            sums[5] += b[8] * b[8];
            n += 1.0;
            t += dt;
        }
    }
    sums.map(|s| (s / n).sqrt())
}

#[test]
fn the_bounded_stations_manoeuvre_spreads_are_those_the_flights_show() {
    // Bounds documents each spread against the synthetic set and the Canberra flight.
    let canberra = loratrack::parse_csv(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/data/ardupilot-log171-quad-canberra.csv"
        ))
        .unwrap(),
        "canberra",
    )
    .unwrap();
    let synthetic = manoeuvre_spreads(&loratrack::synthetic_set());
    // The IMM's manoeuvre evidence expects the synthetic set's acceleration, turn and tilt rates.
    for (k, spread) in [1, 2, 5].into_iter().zip(MANOEUVRE_SPREAD) {
        assert!(
            (synthetic[k] - spread).abs() < 0.03 * spread,
            "{k}: {}",
            synthetic[k]
        );
    }
    let documented = [
        ("synthetic", synthetic, [5.4, 0.92, 0.27, 0.98, 0.59, 0.12]),
        (
            "canberra",
            manoeuvre_spreads(&[canberra]),
            [3.7, 1.8, 0.73, 1.39, 3.4, 0.37],
        ),
    ];
    for (name, measured, doc) in documented {
        for k in 0..6 {
            assert!(
                (measured[k] - doc[k]).abs() < 0.03 * doc[k] + 0.01,
                "{name} spread {k}: measured {} documented {}",
                measured[k],
                doc[k]
            );
        }
    }
    let b = Bounds::default();
    // The chosen values sit between (or, for the jerk, below) what the two flights show.
    assert!((0.98..=1.39).contains(&b.unmodelled_acceleration));
    assert!(b.unmodelled_jerk < 0.59 && (3.7..=5.4).contains(&b.sigma_v));
}

#[test]
fn every_result_reports_coverage_and_the_imm_its_model_probabilities() {
    let p = set(
        &Scenario::default(),
        json!({"synthetic": 3, "model": ModelChoice::parse("dr, imm").unwrap()}),
    );
    let r = simulate(&mut Simulator::new(), &p).unwrap();
    assert_eq!(r.results.len(), 2);
    for m in &r.results {
        assert!((0.0..=1.0).contains(&m.coverage95), "{}", m.coverage95);
        assert!(m.nees.is_finite() && m.nees > 0.0, "{}", m.nees);
    }
    assert!(r.results[0].model_probability.is_none());
    let probs = r.results[1].model_probability.as_ref().unwrap();
    assert_eq!(probs.len(), 3);
    assert!(
        (probs.values().sum::<f64>() - 1.0).abs() < 1e-9,
        "{probs:?}"
    );
    // The IMM station sends the 3D-CTRA payload, so it sees the 3D-CTRA station's packets.
    assert_eq!(r.results[1].payload_bytes, 12);
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["results"][1]["model"], "imm");
    assert_eq!(json["config"]["prediction"], "paper");
}

#[test]
fn model_lists_are_parsed_and_bad_names_refused() {
    let m = ModelChoice::parse("imm,dr,imm").unwrap();
    assert_eq!(
        m.models(),
        &[StationModel::Imm, StationModel::Single(ModelKind::Dr)]
    );
    assert_eq!(ModelChoice::parse("ALL").unwrap(), ModelChoice::all());
    let e = ModelChoice::parse("dr,kalman").unwrap_err();
    assert!(e.contains("unknown model 'kalman'"), "{e}");
    // It lists every station the parser takes, the mission station too.
    assert!(
        e.contains("expected dr, ctra-plus, 3d-ctra, imm, mission,"),
        "{e}"
    );
    assert!(ModelChoice::parse(" ")
        .unwrap_err()
        .starts_with("model: name at least one of"));
    // An empty name (a doubled comma) is named as such, not as an unknown model ''.
    let e = ModelChoice::parse("dr,,imm").unwrap_err();
    assert!(e.starts_with("model: an empty name in the list"), "{e}");
}

/// Under an error-triggered drone a bounded station hedges, as a periodic drone's does, until the
/// drone could have sent again (one 2 s interval here: before then its silence says nothing), and
/// from then on follows its model: on a straight line it advances along the line at the packet's
/// speed, where the unscented mean of a periodic drone's station falls further behind.
#[test]
fn an_error_triggered_drones_station_hedges_in_the_off_time_then_holds_a_straight_line() {
    let packet = [0.0, 0.0, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0];
    // Positions at 1.9, 2.0 and 2.9 s, within the 3 s grace (1.5 intervals of 2 s).
    let at = |error_triggered: bool| {
        let s = StationSetup {
            error_triggered,
            ..setup(Prediction::Bounded)
        };
        let mut tracker = new_tracker(StationModel::Single(ModelKind::Ctra3d), s, None);
        tracker.reset(&packet, 0.0);
        let mut seen = Vec::new();
        for k in 1..=29 {
            tracker.predict_to(0.1 * k as f64);
            if [19, 20, 29].contains(&k) {
                seen.push(tracker.position());
            }
        }
        seen
    };
    let (error, periodic) = (at(true), at(false));
    assert_eq!(
        error[..2],
        periodic[..2],
        "within the off-time both hedge alike"
    );
    let advanced = error[2][0] - error[1][0];
    assert!(
        (advanced - 4.5).abs() < 1e-6 && error[2][1].abs() < 1e-6,
        "{error:?}"
    );
    assert!(
        periodic[2][0] - periodic[1][0] < 4.5 - 0.01,
        "the hedge shortens the line: {periodic:?}"
    );
}
