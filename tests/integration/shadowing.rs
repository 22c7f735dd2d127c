//! Shadowing fixed in space (`shadowingModel: "field"`): runs that differ only in when they send
//! meet the same fades, so their comparison is paired seed by seed.

use loratrack::api::simulate;
use loratrack::{Scenario, Simulator};
use serde_json::json;

/// Per seed, the log of the whole-flight p75 of `option` over that of `base` (both applied to
/// the same 3 km run), under `model`.
fn log_ratios(model: &str, base: serde_json::Value, option: serde_json::Value) -> Vec<f64> {
    let mut sim = Simulator::new();
    let run = Scenario::default()
        .with(&json!({"synthetic": "all", "model": "3d-ctra", "distance": 3000, "overhead": 0, "shadowingModel": model}))
        .unwrap();
    (1..=8)
        .map(|seed| {
            let mut p75 = |extra: &serde_json::Value| {
                let s = run
                    .with(&json!({"seed": seed}))
                    .unwrap()
                    .with(extra)
                    .unwrap();
                simulate(&mut sim, &s).unwrap().results[0]
                    .whole_flight
                    .p75
                    .unwrap()
            };
            (p75(&option) / p75(&base)).ln()
        })
        .collect()
}

fn spread(x: &[f64]) -> f64 {
    let mean = x.iter().sum::<f64>() / x.len() as f64;
    (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
}

#[test]
fn with_fades_fixed_in_space_two_data_rates_are_compared_on_the_same_fades() {
    // DR6 and DR5 at 3 km: DR6's frames, half as long, go twice as often and are lost more.
    let (dr5, dr6) = (json!({"sf": 7, "bw": 125}), json!({"sf": 7, "bw": 250}));
    let path = spread(&log_ratios("path", dr5.clone(), dr6.clone()));
    let field = spread(&log_ratios("field", dr5, dr6));
    // Along the path the two runs draw other fades for every frame; in the field a frame meets
    // the fade of its place, wherever the other rate's frames met it. Seeds 1–8: 0.93 and 0.54.
    assert!(
        field < 0.75 * path,
        "per-seed spread: field {field}, path {path}"
    );
}

/// Without shadowing (0 dB) there are no fades to place, so where they vary changes nothing:
/// a model other than the default is refused there, as every setting nothing reads is.
#[test]
fn without_shadowing_the_model_of_its_fades_is_refused() {
    let run = |model: &str| {
        let s = Scenario::default()
            .with(&json!({"synthetic": 2, "distance": 3000, "shadowing": 0, "adr": "tracking", "shadowingModel": model}))
            .unwrap();
        simulate(&mut Simulator::new(), &s).map(|_| ())
    };
    assert!(run("path").is_ok());
    let e = run("field").unwrap_err().to_string();
    assert!(
        e.starts_with("`shadowingModel` is a shadowing's")
            && e.ends_with("set `shadowing` above 0"),
        "{e}"
    );
}
