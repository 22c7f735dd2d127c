//! `cargo bench`: criterion benchmarks of the core (targets in the README).
use criterion::{criterion_group, criterion_main, Criterion};
use loratrack::api::simulate;
use loratrack::{
    measurement_noise, process_noise, time_on_air, Bandwidth, Ctra3d, CtraPlus, Dr, LoraParams,
    MotionModel, Scenario, SigmaParams, Simulator, SpreadingFactor, Ukf, ANGLES, PAPER_Q,
    PAPER_R_DIAGONAL,
};
use nalgebra::SVector;
use serde_json::{json, Value};
use std::hint::black_box;

/// `base` with the flat JSON settings of `changes` applied.
fn set(base: &Scenario, changes: Value) -> Scenario {
    base.with(&changes).unwrap()
}

fn airtime(c: &mut Criterion) {
    let p = LoraParams::new(SpreadingFactor::new(9).unwrap(), Bandwidth::Khz125);
    c.bench_function("time_on_air", |b| {
        b.iter(|| time_on_air(black_box(&p), black_box(25)))
    });
}

fn ukf_steps<const N: usize, M: MotionModel<N> + Copy>(c: &mut Criterion, name: &str, model: M) {
    let state: [f64; 9] = [10.0, -5.0, 40.0, 0.4, 0.1, 8.0, 0.3, 0.2, 0.05];
    let x = SVector::<f64, N>::from_fn(|i, _| state[i]);
    let r = measurement_noise::<N>(&PAPER_R_DIAGONAL);
    let fresh = Ukf::new(x, r, process_noise(PAPER_Q), SigmaParams::default(), ANGLES).unwrap();
    // Consecutive predictions, as the station runs them between packets; the filter restarts
    // before its covariance grows far from a real one. `npm run bench` does the same.
    let mut ukf = fresh.clone();
    c.bench_function(&format!("ukf_predict/{name}"), |b| {
        b.iter(|| {
            ukf.predict(black_box(&model), black_box(0.1));
            if ukf.p[(0, 0)] > 100.0 {
                ukf = fresh.clone();
            }
        })
    });
    // Updates with P restored to R each time, so every iteration does the same work.
    let mut ukf = fresh.clone();
    let z = x.map(|v| v + 0.05);
    c.bench_function(&format!("ukf_update/{name}"), |b| {
        b.iter(|| {
            ukf.update(black_box(&z), black_box(&r));
            ukf.p = r;
        })
    });
}

fn propagation(c: &mut Criterion) {
    let s9 = SVector::<f64, 9>::from([10.0, -5.0, 40.0, 0.4, 0.1, 8.0, 0.3, 0.2, 0.05]);
    c.bench_function("propagate/3d-ctra", |b| {
        b.iter(|| Ctra3d.propagate(black_box(&s9), black_box(0.1)))
    });
}

fn filters(c: &mut Criterion) {
    ukf_steps::<6, _>(c, "dr", Dr);
    ukf_steps::<8, _>(c, "ctra-plus", CtraPlus);
    ukf_steps::<9, _>(c, "3d-ctra", Ctra3d);
}

fn simulation(c: &mut Criterion) {
    let mut g = c.benchmark_group("simulate");
    g.sample_size(10);
    let all = set(&Scenario::default(), json!({"synthetic": "all"}));
    g.bench_function("whole_set_all_models_cold", |b| {
        b.iter(|| simulate(&mut Simulator::new(), black_box(&all)).unwrap())
    });
    let mut warm = Simulator::new();
    simulate(&mut warm, &all).unwrap();
    g.bench_function("whole_set_all_models_link_change_only", |b| {
        b.iter(|| {
            simulate(
                &mut warm,
                black_box(&set(&all.clone(), json!({"distance": 2000.0}))),
            )
            .unwrap()
        })
    });
    let one = set(&Scenario::default(), json!({"synthetic": 1}));
    g.bench_function("one_flight_all_models_cold", |b| {
        b.iter(|| simulate(&mut Simulator::new(), black_box(&one)).unwrap())
    });
    g.finish();
}

/// The mission station's cost beside bounded 3D-CTRA's: the whole set, one station, cold (both
/// run the same 3D-CTRA drone filter; the mission station also traces each flight's plan and
/// runs its bounded fallback beside the plan).
fn mission(c: &mut Criterion) {
    let mut g = c.benchmark_group("mission");
    g.sample_size(10);
    for model in ["3d-ctra", "mission"] {
        let p = set(
            &Scenario::default(),
            json!({"synthetic": "all", "model": model, "prediction": "bounded"}),
        );
        g.bench_function(format!("whole_set_cold/{model}"), |b| {
            b.iter(|| simulate(&mut Simulator::new(), black_box(&p)).unwrap())
        });
    }
    g.finish();
}

fn swarms(c: &mut Criterion) {
    let mut g = c.benchmark_group("swarm");
    g.sample_size(10);
    for drones in [72, 300] {
        let p = set(
            &loratrack::Scenario::default(),
            json!({"drones": drones, "duration": 600.0, "bw": 125, "model": "3d-ctra"}),
        );
        g.bench_function(format!("{drones}_drones_600_s_every_core"), |b| {
            b.iter(|| loratrack::api::swarm(black_box(&p)).unwrap())
        });
    }
    // The page's two-minute swarm under TTN's fair use: one slot per 4270 s, so the slotted
    // capacity search packs thousands of drones per try (5.2 s before it became linear).
    let fair = set(
        &loratrack::Scenario::default(),
        json!({"drones": 50, "duration": 120.0, "sf": 12, "bw": 125, "fairUse": "ttn", "sfPlan": "fixed", "model": "3d-ctra"}),
    );
    g.bench_function("50_drones_120_s_sf12_fair_use", |b| {
        b.iter(|| loratrack::api::swarm(black_box(&fair)).unwrap())
    });
    g.finish();
}

/// A flight of `rows` samples every `dt` s: a slow climbing circle, velocities and accelerations
/// given when `derivatives` (else derived by the importer), written the way a log would be.
fn long_flight(rows: usize, dt: f64, derivatives: bool) -> String {
    use std::fmt::Write;
    // 8 m/s on a 40 m circle; at most ~62 bytes a row, so 10⁶ rows stay under the 64 MiB limit.
    let (r, w) = (40.0, 0.2);
    let mut csv = String::from(if derivatives {
        "t,x,y,z,vx,vy,vz,ax,ay,az\n"
    } else {
        "t,x,y,z\n"
    });
    for i in 0..rows {
        let t = i as f64 * dt;
        let (s, c) = (w * t).sin_cos();
        write!(
            csv,
            "{t:.4},{:.3},{:.3},{:.3}",
            r * s,
            r * (1.0 - c),
            40.0 + 1e-3 * t
        )
        .unwrap();
        if derivatives {
            let (v, a) = (r * w, r * w * w);
            write!(
                csv,
                ",{:.3},{:.3},0.001,{:.3},{:.3},0",
                v * c,
                v * s,
                -a * s,
                a * c
            )
            .unwrap();
        }
        csv.push('\n');
    }
    csv
}

/// A 10⁶-row flight through the four stations (the paper's three and IMM), parsing included:
/// at 25 Hz without derivatives (40 000 s: the drones' filters and the stations' predictions
/// dominate) and at 10 kHz with them (100 s: the import dominates). Each file is also written
/// to `target/tmp/long-flight-*.csv`, for measuring the CLI's peak memory on it (README).
fn long_flights(c: &mut Criterion) {
    let mut g = c.benchmark_group("long_flight");
    g.sample_size(10);
    for (name, dt, derivatives) in [("25hz", 0.04, false), ("10khz", 1e-4, true)] {
        let csv = long_flight(1_000_000, dt, derivatives);
        let file = format!("{}/long-flight-{name}.csv", env!("CARGO_TARGET_TMPDIR"));
        std::fs::write(&file, &csv).unwrap();
        let p = set(
            &Scenario::default(),
            json!({"trajectory": csv, "model": "dr,ctra-plus,3d-ctra,imm"}),
        );
        g.bench_function(format!("{name}_four_stations_cold"), |b| {
            b.iter(|| simulate(&mut Simulator::new(), black_box(&p)).unwrap())
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    airtime,
    propagation,
    filters,
    simulation,
    mission,
    swarms,
    long_flights
);
criterion_main!(benches);
