//! A/B kernel benchmark: the kernels of an earlier revision (`old`) and of
//! this tree (`new`), measured in one criterion run at the worked example of
//! docs/conventions.md.
//!
//! Per compiled formulation and type: `old/evaluate` (the earlier
//! revision's `contact_kernels::evaluate`), `new/evaluate` (this tree's
//! `evaluate`, the same call on top of the handle) and `new/handle`
//! (`Kernel::eval` into a reused `GapOut`); plus the projection through
//! `project` of both. Built and run by `scripts/ab-kernel-bench.sh REV`,
//! which also prints the table (`table.rs`).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

const Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
const XI_S: f64 = 0.3;

fn ab(c: &mut Criterion) {
    for f_new in new::compiled_formulations() {
        let name = f_new.name();
        let f_old = old::Formulation::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .expect("the earlier revision has the formulation");
        let mut group = c.benchmark_group(format!("ab-{name}"));
        for t in 1..=6 {
            let ty_new = new::ApproxType::from_index(t).unwrap();
            let ty_old = old::ApproxType::from_index(t).unwrap();
            group.bench_function(format!("type{t}-old-evaluate"), |b| {
                b.iter(|| old::evaluate(f_old, ty_old, black_box(&Q), black_box(XI_S)).unwrap())
            });
            group.bench_function(format!("type{t}-new-evaluate"), |b| {
                b.iter(|| new::evaluate(f_new, ty_new, black_box(&Q), black_box(XI_S)).unwrap())
            });
            let kernel = new::Kernel::new(f_new, ty_new).unwrap();
            let mut out = new::GapOut::new(&kernel);
            group.bench_function(format!("type{t}-new-handle"), |b| {
                b.iter(|| {
                    kernel.eval(black_box(&Q), black_box(XI_S), &mut out).unwrap();
                    black_box(&out);
                })
            });
        }
        group.bench_function("project-old", |b| {
            b.iter(|| old::project(f_old, black_box(&Q), black_box(XI_S)).unwrap())
        });
        group.bench_function("project-new", |b| {
            b.iter(|| new::project(f_new, black_box(&Q), black_box(XI_S)).unwrap())
        });
        group.finish();
    }
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(60)
}

criterion_group! {
    name = benches;
    config = config();
    targets = ab
}
criterion_main!(benches);
