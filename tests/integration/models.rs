//! The closed forms of DR, CTRA+ and 3D-CTRA against an accurate numerical integration of the
//! ODE of reference §3, everywhere in the required envelope and especially at and near the special
//! cases omega = 0, psi = 0, omega = ±psi.

use loratrack::{Ctra3d, CtraPlus, Dr, MotionModel};
use nalgebra::SVector;
use proptest::prelude::*;

/// State of the ODE: x y z theta phi v a omega psi.
type Ode = [f64; 9];

fn derivative(s: &Ode) -> Ode {
    let (theta, phi, v) = (s[3], s[4], s[5]);
    [
        v * theta.cos() * phi.cos(),
        v * theta.sin() * phi.cos(),
        v * phi.sin(),
        s[7],
        s[8],
        s[6],
        0.0,
        0.0,
        0.0,
    ]
}

/// Classic fourth-order Runge–Kutta with enough steps that its error (~h^4) is far below 1e-6 m.
fn integrate(s0: Ode, dt: f64) -> Ode {
    let n = ((dt.abs() * 2000.0).ceil() as usize).max(200);
    let h = dt / n as f64;
    let mut s = s0;
    let add = |a: &Ode, b: &Ode, k: f64| -> Ode { core::array::from_fn(|i| a[i] + k * b[i]) };
    for _ in 0..n {
        let k1 = derivative(&s);
        let k2 = derivative(&add(&s, &k1, h / 2.0));
        let k3 = derivative(&add(&s, &k2, h / 2.0));
        let k4 = derivative(&add(&s, &k3, h));
        s = core::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    s
}

const TOLERANCE_M: f64 = 1e-6;

/// A rate that is either anywhere in ±2 rad/s, or exactly/nearly at `anchor` (offset 0 or ±1e-12…1e-2).
fn near(anchor: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => -2.0f64..2.0,
        1 => Just(anchor),
        2 => (-12.0f64..-2.0, prop::bool::ANY).prop_map(move |(e, neg)| anchor + if neg { -1.0 } else { 1.0 } * 10f64.powf(e)),
    ]
}

/// 0, or ±10^e rad/s with e uniform in −320..0 (subnormal rates included).
fn tiny_rate() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        4 => (-320.0f64..0.0, prop::bool::ANY).prop_map(|(e, neg)| if neg { -1.0 } else { 1.0 } * 10f64.powf(e)),
    ]
}

/// (omega, psi) concentrated on the singular set psi = 0, omega = 0, omega = psi, omega = −psi.
fn rates() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        (-2.0f64..2.0, -2.0f64..2.0),
        (-2.0f64..2.0).prop_flat_map(|psi| (near(psi), Just(psi))),
        (-2.0f64..2.0).prop_flat_map(|psi| (near(-psi), Just(psi))),
        (-2.0f64..2.0).prop_flat_map(|omega| (Just(omega), near(0.0))),
        (-2.0f64..2.0).prop_flat_map(|psi| (near(0.0), Just(psi))),
        (near(0.0), near(0.0)),
    ]
    .prop_filter("within envelope", |(o, p)| o.abs() <= 2.0 && p.abs() <= 2.0)
}

fn assert_close(
    model: &str,
    got: &[f64],
    want: &Ode,
    start: &Ode,
    dt: f64,
) -> Result<(), TestCaseError> {
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        prop_assert!(
            (got[k] - want[k]).abs() <= TOLERANCE_M,
            "{model} {name}: closed form {} vs ODE {} (|diff| {:e}) from {:?} over {dt} s",
            got[k],
            want[k],
            (got[k] - want[k]).abs(),
            start
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, .. ProptestConfig::default() })]

    #[test]
    fn ctra3d_matches_the_ode(
        theta in -3.2f64..3.2, phi in -1.5f64..1.5, v in -30.0f64..30.0, a in -5.0f64..5.0,
        (omega, psi) in rates(), dt in 0.0f64..10.0,
    ) {
        let start: Ode = [1.0, -2.0, 3.0, theta, phi, v, a, omega, psi];
        let got = Ctra3d.propagate(&SVector::from(start), dt);
        assert_close("3D-CTRA", got.as_slice(), &integrate(start, dt), &start, dt)?;
    }

    #[test]
    fn ctra_plus_matches_the_ode_with_psi_zero(
        theta in -3.2f64..3.2, phi in -1.5f64..1.5, v in -30.0f64..30.0, a in -5.0f64..5.0,
        omega in near(0.0), dt in 0.0f64..10.0,
    ) {
        let start: Ode = [0.0, 0.0, 0.0, theta, phi, v, a, omega, 0.0];
        let s8: [f64; 8] = core::array::from_fn(|i| start[i]);
        let got = CtraPlus.propagate(&SVector::from(s8), dt);
        assert_close("CTRA+", got.as_slice(), &integrate(start, dt), &start, dt)?;
    }

    #[test]
    fn dr_matches_the_ode_with_constant_velocity(
        theta in -3.2f64..3.2, phi in -1.5f64..1.5, v in -30.0f64..30.0, dt in 0.0f64..10.0,
    ) {
        let start: Ode = [5.0, 6.0, 7.0, theta, phi, v, 0.0, 0.0, 0.0];
        let s6: [f64; 6] = core::array::from_fn(|i| start[i]);
        let got = Dr.propagate(&SVector::from(s6), dt);
        assert_close("DR", got.as_slice(), &integrate(start, dt), &start, dt)?;
    }

    /// Every finite rate, subnormals included: omega and psi drawn log-uniformly over
    /// 1e-320..1 rad/s (either sign) or exactly 0, so the closed form's switch to its series is
    /// exact for all of them (a 1.5e-323 rad/s turn once gave 13.3 m for a 10 m straight flight).
    #[test]
    fn ctra3d_matches_the_ode_at_tiny_and_subnormal_rates(
        theta in -3.2f64..3.2, phi in -1.5f64..1.5, v in -30.0f64..30.0, a in -5.0f64..5.0,
        omega in tiny_rate(), psi in tiny_rate(), dt in 0.0f64..10.0,
    ) {
        let start: Ode = [1.0, -2.0, 3.0, theta, phi, v, a, omega, psi];
        let got = Ctra3d.propagate(&SVector::from(start), dt);
        assert_close("3D-CTRA", got.as_slice(), &integrate(start, dt), &start, dt)?;
        let s8: [f64; 8] = core::array::from_fn(|i| start[i]);
        let plus = CtraPlus.propagate(&SVector::from(s8), dt);
        let start8: Ode = [1.0, -2.0, 3.0, theta, phi, v, a, omega, 0.0];
        assert_close("CTRA+", plus.as_slice(), &integrate(start8, dt), &start8, dt)?;
    }

    /// Continuity: crossing a special case moves the result by no more than the crossing itself.
    #[test]
    fn ctra3d_is_continuous_across_special_cases(
        theta in -3.2f64..3.2, phi in -1.5f64..1.5, v in -30.0f64..30.0, a in -5.0f64..5.0,
        psi in -2.0f64..2.0, sign in prop_oneof![Just(1.0), Just(-1.0), Just(0.0)], e in -12.0f64..-6.0, dt in 0.0f64..10.0,
    ) {
        // omega on the singular set (psi, -psi or 0) and eps either side of it.
        let omega = sign * psi;
        let eps = 10f64.powf(e);
        let at = |o: f64| Ctra3d.propagate(&SVector::from([0.0, 0.0, 0.0, theta, phi, v, a, o, psi]), dt);
        let (lo, mid, hi) = (at(omega - eps), at(omega), at(omega + eps));
        for k in 0..3 {
            // d(position)/d(omega) is bounded by |v| t² + |a| t³ over the envelope.
            let bound = eps * (30.0 * dt * dt + 5.0 * dt * dt * dt) + 1e-9;
            prop_assert!((lo[k] - mid[k]).abs() <= bound && (hi[k] - mid[k]).abs() <= bound);
        }
    }
}

#[test]
fn spec_2d_ctra_reference_values() {
    let s = SVector::<f64, 9>::from([0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0]);
    let out = Ctra3d.propagate(&s, 0.5);
    assert!((out[0] - 0.5967208697966773).abs() < 1e-12);
    assert!((out[1] - 0.16305169576864387).abs() < 1e-12);
    assert_eq!(out[5], 1.5);
    assert_eq!(out[3], 0.5);
    let mut straight = s;
    straight[7] = 0.0;
    assert!((Ctra3d.propagate(&straight, 0.5)[0] - 0.625).abs() < 1e-15);
}

#[test]
fn ctra_plus_with_phi_zero_is_2d_ctra() {
    // 2D CTRA by its textbook closed form (Tsogas 2005), omega = 0.8.
    let (v, a, w, t, th) = (4.0f64, 0.5f64, 0.8f64, 2.0f64, 0.3f64);
    let x = ((v + a * t) * w * (th + w * t).sin() + a * (th + w * t).cos()
        - v * w * th.sin()
        - a * th.cos())
        / (w * w);
    let y = (-(v + a * t) * w * (th + w * t).cos() + a * (th + w * t).sin() + v * w * th.cos()
        - a * th.sin())
        / (w * w);
    let out = CtraPlus.propagate(&SVector::from([0.0, 0.0, 0.0, th, 0.0, v, a, w]), t);
    assert!((out[0] - x).abs() < 1e-12 && (out[1] - y).abs() < 1e-12);
    assert_eq!(out[2], 0.0);
}

#[test]
fn tilt_rate_decays_by_eta_per_step_in_the_station_predictor() {
    use loratrack::api::{predict, PredictParams};
    use loratrack::ModelKind;
    let p = PredictParams {
        model: ModelKind::Ctra3d,
        state: vec![0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.5],
        dt: 1.0,
        step: Some(0.1),
        eta: Some(0.9),
    };
    let r = predict(&p).unwrap();
    // Ten steps: psi × 0.9^10; the decay per second is eta^(1/T).
    assert!((r.state[8] - 0.5 * 0.9f64.powi(10)).abs() < 1e-12);
    // The pitch gained is the sum of the decaying rates times the step.
    let phi: f64 = (0..10).map(|k| 0.5 * 0.9f64.powi(k) * 0.1).sum();
    assert!((r.state[4] - phi).abs() < 1e-12);
}

/// A deterministic sweep of every singular set at offsets from 1e-12 to 1e-2 with the envelope's
/// largest speed, acceleration and step, where cancellation in a naive closed form is worst.
#[test]
fn ctra3d_is_accurate_near_every_special_case_at_the_envelope_edge() {
    let mut worst = 0.0f64;
    for i in 0..=40 {
        let eps = 10f64.powf(-12.0 + 10.0 * f64::from(i) / 40.0);
        for sign in [1.0, -1.0] {
            let psi = 1.3;
            let cases = [
                (psi + sign * eps, psi),         // omega ≈ psi
                (-psi + sign * eps, psi),        // omega ≈ -psi
                (sign * eps, psi),               // omega ≈ 0
                (0.9, sign * eps),               // psi ≈ 0
                (sign * eps, -sign * eps * 0.5), // both ≈ 0
            ];
            for (omega, psi) in cases {
                for (v, a) in [(30.0, 5.0), (-30.0, -5.0), (30.0, -5.0)] {
                    let start: Ode = [0.0, 0.0, 0.0, 0.7, -0.4, v, a, omega, psi];
                    let got = Ctra3d.propagate(&SVector::from(start), 10.0);
                    let want = integrate(start, 10.0);
                    for k in 0..3 {
                        worst = worst.max((got[k] - want[k]).abs());
                        assert!(
                            (got[k] - want[k]).abs() <= TOLERANCE_M,
                            "omega {omega:e} psi {psi:e} v {v} a {a}: axis {k} off by {:e}",
                            (got[k] - want[k]).abs()
                        );
                    }
                }
            }
        }
    }
    assert!(worst.is_finite());
}
