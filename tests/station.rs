//! The station under loss (issue: bounded prediction, IMM, honest uncertainty): the bounded
//! predictor is the paper's while packets come on time and stays physical after a gap; the IMM
//! reports its members' probabilities; the 95 % coverage is right for a correctly specified case.
#![cfg(not(target_arch = "wasm32"))]

use loratrack::api::simulate;
use loratrack::{
    inside_95, Bounds, Ctra3d, CtraPlus, Dr, ModelChoice, ModelKind, MotionModel, Prediction, Rng,
    Scenario, Simulator, StationModel, StationPredictor, StationSetup, Tracker, Ukf, PAPER_Q,
    PAPER_R_DIAGONAL,
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
    }
}

/// The true state of a steady climbing turn at time t (8 m/s, 0.3 rad/s, 5° pitch).
fn steady_turn(t: f64) -> [f64; 9] {
    let s = SVector::<f64, 9>::from([0.0, 0.0, 40.0, 0.2, 0.087, 8.0, 0.0, 0.3, 0.0]);
    let x = Ctra3d.propagate(&s, t);
    core::array::from_fn(|i| x[i])
}

fn paper_and_bounded_agree<const N: usize, M: MotionModel<N> + Copy>(model: M) {
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
            assert_eq!(paper.position(), bounded.position(), "{:?} at {t}", M::KIND);
            assert_eq!(paper.position_covariance(), bounded.position_covariance());
        }
    }
}

#[test]
fn bounded_prediction_equals_the_paper_while_packets_arrive_on_time() {
    paper_and_bounded_agree(Dr);
    paper_and_bounded_agree(CtraPlus);
    paper_and_bounded_agree(Ctra3d);
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
    assert!(ModelChoice::parse("").is_err());
}
