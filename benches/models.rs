//! Criterion benchmarks of the stages `impactd bench` reports (see `impactd::stages`).

#![allow(clippy::unwrap_used)]

use criterion::{criterion_group, criterion_main, Criterion};

fn stages(c: &mut Criterion) {
    for mut stage in impactd::stages::all_stages() {
        let mut i = 0usize;
        c.bench_function(&stage.name, |b| {
            b.iter(|| {
                i = i.wrapping_add(1);
                std::hint::black_box((stage.run)(i))
            })
        });
    }
}

criterion_group!(benches, stages);
criterion_main!(benches);
