//! `cargo bench`: criterion benchmarks of the core.
use criterion::{criterion_group, criterion_main, Criterion};
use loratrack::{time_on_air, Bandwidth, LoraParams, SpreadingFactor};
use std::hint::black_box;

fn airtime(c: &mut Criterion) {
    let p = LoraParams::new(SpreadingFactor::new(9).unwrap(), Bandwidth::Khz125);
    c.bench_function("time_on_air", |b| {
        b.iter(|| time_on_air(black_box(&p), black_box(25)))
    });
}

criterion_group!(benches, airtime);
criterion_main!(benches);
