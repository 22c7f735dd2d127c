//! The UKF over long, noisy flights: the covariance must stay symmetric positive definite and
//! every number finite for 10^5 steps per model (reference §4), and the filter must actually track.

use loratrack::{
    measurement_noise, process_noise, Ctra3d, CtraPlus, Dr, MotionModel, Rng, SigmaParams, Ukf,
    ANGLES, PAPER_Q, PAPER_R_DIAGONAL,
};
use nalgebra::{Cholesky, SVector};

const STEPS: usize = 100_000;
const DT: f64 = 0.1;

/// Ground truth: a 3D-CTRA flight whose a, omega and psi change every 20 s, kept within a
/// quadcopter's envelope (speed 0–15 m/s, pitch within ±0.6 rad).
fn truth(steps: usize, seed: u64) -> Vec<SVector<f64, 9>> {
    let mut rng = Rng::new(seed);
    let mut s = SVector::<f64, 9>::from([0.0, 0.0, 50.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0]);
    let mut out = Vec::with_capacity(steps);
    for k in 0..steps {
        if k % 200 == 0 {
            s[6] = rng.range(-1.0, 1.0);
            s[7] = rng.range(-0.5, 0.5);
            s[8] = rng.range(-0.1, 0.1);
        }
        if s[5] > 15.0 {
            s[6] = -s[6].abs();
        }
        if s[5] < 1.0 {
            s[6] = s[6].abs();
        }
        if s[4].abs() > 0.6 {
            s[8] = -s[4].signum() * s[8].abs();
        }
        s = Ctra3d.propagate(&s, DT);
        out.push(s);
    }
    out
}

fn run<const N: usize, M: MotionModel<N>>(model: M, sigma: SigmaParams) -> (u64, f64) {
    let flight = truth(STEPS, 11);
    let mut rng = Rng::new(5);
    let r = measurement_noise::<N>(&PAPER_R_DIAGONAL);
    let first = SVector::<f64, N>::from_fn(|i, _| flight[0][i]);
    let mut ukf = Ukf::new(first, r, process_noise(PAPER_Q), sigma, ANGLES).unwrap();
    let mut sq_err = 0.0;
    for (k, t) in flight.iter().enumerate() {
        let z = SVector::<f64, N>::from_fn(|i, _| t[i] + r[(i, i)].sqrt() * rng.normal());
        ukf.predict(&model, DT);
        ukf.update(&z, &r);
        assert!(
            ukf.x.iter().all(|v| v.is_finite()),
            "{:?} step {k}: state not finite",
            M::KIND
        );
        assert!(
            ukf.p.iter().all(|v| v.is_finite()),
            "{:?} step {k}: covariance not finite",
            M::KIND
        );
        if k % 1000 == 0 {
            assert!(
                (ukf.p - ukf.p.transpose()).abs().max() == 0.0,
                "not symmetric at {k}"
            );
            assert!(
                Cholesky::new(ukf.p).is_some(),
                "{:?} step {k}: covariance not PD",
                M::KIND
            );
        }
        sq_err += (ukf.x[0] - t[0]).powi(2) + (ukf.x[1] - t[1]).powi(2);
    }
    (ukf.recoveries(), (sq_err / STEPS as f64).sqrt())
}

#[test]
fn covariance_stays_positive_definite_for_100k_steps_per_model() {
    for (name, (recoveries, rms)) in [
        ("DR", run(Dr, SigmaParams::default())),
        ("CTRA+", run(CtraPlus, SigmaParams::default())),
        ("3D-CTRA", run(Ctra3d, SigmaParams::default())),
    ] {
        // The filter must track: horizontal RMS error well below the raw GPS noise (0.91 m per axis).
        assert!(rms < 1.0, "{name}: horizontal RMS error {rms} m");
        assert!(recoveries < 100, "{name}: {recoveries} covariance repairs");
    }
}

#[test]
fn small_alpha_does_not_break_the_filter() {
    let (_, rms) = run(
        Ctra3d,
        SigmaParams {
            alpha: 1e-3,
            beta: 2.0,
            kappa: Some(0.0),
        },
    );
    assert!(rms < 1.0, "horizontal RMS error {rms} m");
}

#[test]
fn the_filter_beats_the_raw_measurements() {
    // On a straight flight the DR filter must average the GPS noise down.
    let r = measurement_noise::<6>(&PAPER_R_DIAGONAL);
    let mut rng = Rng::new(1);
    let mut truth = SVector::<f64, 6>::from([0.0, 0.0, 20.0, 0.5, 0.0, 8.0]);
    let mut ukf = Ukf::new(
        truth,
        r,
        process_noise(0.01),
        SigmaParams::default(),
        ANGLES,
    )
    .unwrap();
    let (mut raw, mut filtered) = (0.0, 0.0);
    for _ in 0..2000 {
        truth = Dr.propagate(&truth, DT);
        let z = SVector::<f64, 6>::from_fn(|i, _| truth[i] + r[(i, i)].sqrt() * rng.normal());
        ukf.predict(&Dr, DT);
        ukf.update(&z, &r);
        raw += (z[0] - truth[0]).powi(2);
        filtered += (ukf.x[0] - truth[0]).powi(2);
    }
    assert!(filtered < 0.5 * raw, "filtered {filtered} vs raw {raw}");
}
