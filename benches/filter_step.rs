//! `cargo bench --bench filter_step`: the fastest of repeated timings of one UKF step per model,
//! printed as a table. Criterion's mean (`--bench core`) is the benchmark of record, but on a
//! shared 2-core machine other work inflates a mean; the minimum over 40 rounds of 10⁵ steps shows
//! what the code costs when it has the core to itself (README, Benchmarks).
use loratrack::{
    measurement_noise, process_noise, Ctra3d, CtraPlus, Dr, MotionModel, SigmaParams, Ukf, ANGLES,
    PAPER_Q, PAPER_R_DIAGONAL,
};
use nalgebra::SVector;
use std::hint::black_box;
use std::time::Instant;

const ROUNDS: usize = 40;
const STEPS: usize = 100_000;

/// The fastest round's time per call of `step`, µs.
fn fastest(mut step: impl FnMut()) -> f64 {
    (0..ROUNDS)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..STEPS {
                step();
            }
            t.elapsed().as_secs_f64() * 1e6 / STEPS as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Predict (consecutive, as the station runs them), update (P restored each time, as in
/// `--bench core`) and a drone's predict + update, µs.
fn steps<const N: usize, M: MotionModel<N> + Copy>(model: M) -> [f64; 3] {
    let state: [f64; 9] = [10.0, -5.0, 40.0, 0.4, 0.1, 8.0, 0.3, 0.2, 0.05];
    let x = SVector::<f64, N>::from_fn(|i, _| state[i]);
    let r = measurement_noise::<N>(&PAPER_R_DIAGONAL);
    let fresh = Ukf::new(x, r, process_noise(PAPER_Q), SigmaParams::default(), ANGLES).unwrap();
    let z = x.map(|v| v + 0.05);
    let mut ukf = fresh.clone();
    let predict = fastest(|| {
        ukf.predict(black_box(&model), black_box(0.1));
        if ukf.p[(0, 0)] > 100.0 {
            ukf = fresh.clone();
        }
    });
    let mut ukf = fresh.clone();
    let update = fastest(|| {
        ukf.update(black_box(&z), black_box(&r));
        ukf.p = r;
    });
    let mut ukf = fresh.clone();
    let drone = fastest(|| {
        ukf.predict(black_box(&model), black_box(0.1));
        ukf.update(black_box(&z), black_box(&r));
    });
    [predict, update, drone]
}

fn main() {
    // `cargo test --benches` builds this target too; only `cargo bench` times it.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    println!(
        "fastest of {ROUNDS} rounds of {STEPS} steps, µs   predict   update   predict + update"
    );
    for (name, [p, u, d]) in [
        ("dr", steps::<6, _>(Dr)),
        ("ctra-plus", steps::<8, _>(CtraPlus)),
        ("3d-ctra", steps::<9, _>(Ctra3d)),
    ] {
        println!("{name:<48} {p:>8.3} {u:>8.3} {d:>18.3}");
    }
}
