//! Kernel benchmark: every compiled (formulation, type) kernel through
//! `contact_kernels::evaluate` (values, nalgebra) and through the
//! `Kernel::eval` handle (into a reused `GapOut`), the projection kernel
//! through `contact_kernels::project` and the `Projector` handle, and
//! num-dual's `hessian` of the same gap written generically (the function of
//! `tests/kernels_ad.rs`), all at the same configuration (the worked example of
//! docs/conventions.md), in one run so the handle/value ratio can be read off.
//!
//! Run `cargo bench --bench kernels`, then
//! `cargo run --release --example bench_table` for the Markdown table.
//! Results land in `target/criterion/<formulation>/<id>/new/estimates.json`
//! with `<id>` one of `type1`..`type6`, `project`, `num-dual-hessian`
//! (the value API) and `type1-handle`..`type6-handle`, `project-handle`
//! (the handles): the names `examples/bench_table.rs` reads.
//!
//! The group `points64` evaluates 64 configurations near the worked
//! example per iteration (seeded, the same every run), for the slave-normal
//! formulation: the sympy-cse peer (`benches/peer/`, as Kratos and IPC
//! Toolkit generate theirs), gapsim's Types 1, 3 and 6 through `evaluate`,
//! the handle and `Kernel::eval_batch` (the SIMD lane kernels, 4 points per
//! call; AVX2 where the CPU has it, and Type 6 also with the portable lane
//! build: `type6-batch-portable`), the value-only projection, and
//! num-dual's `hessian`; `bench_table` divides by 64. Run only this group
//! with `cargo bench --bench kernels -- points64`.
//!
//! The group `faces-tri3-slave-normal` does the same for 3D faces: 64
//! tri3-on-tri3 configurations near the worked example of
//! docs/conventions.md ("3D faces"), the sympy-cse 3D peer
//! (`benches/peer/sympy_kernel_3d.rs`), gapsim's `tri3-slave-normal` Types 1
//! and 6 one point at a time through the handle (`Kernel::eval`) and the
//! 64 points in one `Kernel::eval_batch` call (the face lane kernels, 4
//! points per lane call; Type 6 also with the portable lane build), and
//! num-dual's `hessian` of the same gap (18 coordinates). Run it alone
//! with `cargo bench --bench kernels -- faces`, then
//! `cargo run --release --example bench_table -- --faces` for its table.
//!
//! The groups `slip-slave-normal` and `slip-quad4-slave-normal` time the
//! slip kernels against the gap kernels of the same type in one run
//! (`gap-type{1,3,6}`: `Kernel::eval`; `slip-type{1,3,6}`: `Slip::eval`,
//! one point, the slip's worked examples of docs/conventions.md, "The
//! slip"), and for segments num-dual's `hessian` of the same slip written
//! generically (`num-dual-slip-hessian`). Run them with `cargo bench
//! --bench kernels -- slip`, then `cargo run --release --example
//! bench_table -- --slip`.
//!
//! The group `slip-batch64` times 64 points per iteration of the slip of
//! Type 6 one point at a time (`Slip::eval`, the path every slip took
//! before its lane kernels) against one `Slip::eval_batch` call (the slip's
//! lane kernels, 4 points per call; AVX2 where the CPU has it, and the
//! portable lane build), for slave-normal segments (the `points64`
//! configurations, `xi_m0 = 0.6 xi_s - 0.05`) and tri3-slave-normal faces
//! (the faces group's). `bench_table -- --slip` prints its table too.
//!
//! Warm-up and measurement are 1 s each so the whole run takes about a
//! minute of measurement (44 benchmarks).

use std::hint::black_box;
use std::time::Duration;

// `SYMPY_OPS` is checked by tests/peer.rs, not used here.
#[allow(dead_code)]
#[path = "peer/sympy_kernel.rs"]
mod sympy_kernel;

// `SYMPY_OPS_3D` likewise.
#[allow(dead_code)]
#[path = "peer/sympy_kernel_3d.rs"]
mod sympy_kernel_3d;

use contact_kernels::{
    ApproxType, Formulation, GapBatch, GapOut, Kernel, LaneIsa, Projector, SlipBatch, SlipOut,
    evaluate, pair_formulations, project,
};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::SVector;
use num_dual::{Dual2SVec64, DualNum, hessian};

/// the worked example of docs/conventions.md.
const Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
const XI_S: f64 = 0.3;

// The gap written generically over num-dual numbers, as in
// tests/kernels_ad.rs (closed-form projection of straight segments).

fn lerp<D: DualNum<Primitive = f64> + Copy>(a: [D; 2], b: [D; 2], xi: D) -> [D; 2] {
    let n1 = (D::from(1.0) - xi) * 0.5;
    let n2 = (D::from(1.0) + xi) * 0.5;
    [a[0] * n1 + b[0] * n2, a[1] * n1 + b[1] * n2]
}

fn sub<D: DualNum<Primitive = f64> + Copy>(a: [D; 2], b: [D; 2]) -> [D; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot<D: DualNum<Primitive = f64> + Copy>(a: [D; 2], b: [D; 2]) -> D {
    a[0] * b[0] + a[1] * b[1]
}

/// `g(q) = n . (x_m(xi_m) - x_s)` with `xi_m` solving
/// `(x_m(xi) - x_s) . t = 0` (`t = t_s` slave-normal, `t_m` closest-point).
fn gap<D: DualNum<Primitive = f64> + Copy>(f: Formulation, q: &[D; 8], xi_s: f64) -> D {
    let node = |k: usize| [q[2 * k], q[2 * k + 1]];
    let (xs1, xs2, xm1, xm2) = (node(0), node(1), node(2), node(3));
    let x_s = lerp(xs1, xs2, D::from(xi_s));
    let (t_s, t_m) = (sub(xs2, xs1), sub(xm2, xm1));
    let c_m = lerp(xm1, xm2, D::from(0.0));
    let (t, n) = match f {
        // (A 3-node formulation is not swept; on straight segments,
        // quadratic-slave-normal is slave-normal.)
        Formulation::SlaveNormal | Formulation::QuadraticSlaveNormal => {
            let len = dot(t_s, t_s).sqrt();
            (t_s, [t_s[1] / len, -t_s[0] / len])
        }
        Formulation::ClosestPoint => {
            let len = dot(t_m, t_m).sqrt();
            (t_m, [-t_m[1] / len, t_m[0] / len])
        }
        // The segment benches run `pair_formulations()` (8 coordinates).
        Formulation::Tri3SlaveNormal
        | Formulation::Tri3ClosestPoint
        | Formulation::Quad4SlaveNormal
        | Formulation::Quad4ClosestPoint
        | Formulation::Tri3Quad4SlaveNormal
        | Formulation::Tri3Quad4ClosestPoint
        | Formulation::Quad4Tri3SlaveNormal
        | Formulation::Quad4Tri3ClosestPoint => {
            unreachable!("faces are not segment pairs")
        }
    };
    let xi = -(dot(sub(c_m, x_s), t) * 2.0) / dot(t_m, t);
    dot(n, sub(lerp(xm1, xm2, xi), x_s))
}

fn kernels(c: &mut Criterion) {
    let qv = SVector::<f64, 8>::from(Q);
    for f in pair_formulations() {
        let mut group = c.benchmark_group(f.name());
        for ty in ApproxType::ALL {
            group.bench_function(format!("type{}", ty.index()), |b| {
                b.iter(|| evaluate(f, ty, black_box(&Q), black_box(XI_S)).unwrap())
            });
            let kernel = Kernel::new(f, ty).unwrap();
            let mut out = GapOut::new(&kernel);
            group.bench_function(format!("type{}-handle", ty.index()), |b| {
                b.iter(|| {
                    kernel
                        .eval(black_box(&Q), black_box(XI_S), &mut out)
                        .unwrap();
                    black_box(&out);
                })
            });
        }
        group.bench_function("project", |b| {
            b.iter(|| project(f, black_box(&Q), black_box(XI_S)).unwrap())
        });
        let projector = Projector::new(f).unwrap();
        let mut scratch = vec![0.0; projector.coords()];
        group.bench_function("project-handle", |b| {
            b.iter(|| {
                projector
                    .project(black_box(&Q), black_box(XI_S), &mut scratch)
                    .unwrap()
            })
        });
        group.bench_function("num-dual-hessian", |b| {
            b.iter(|| {
                hessian(
                    |v: SVector<Dual2SVec64<8>, 8>| {
                        gap(f, &std::array::from_fn(|i| v[i]), black_box(XI_S))
                    },
                    black_box(&qv),
                )
            })
        });
        group.finish();
    }
}

/// The slip's last converged projection in the 2D worked example.
const XI_M0: f64 = -0.2;

/// slave-normal's slip written generically: `tau . (x_m(xi_m) -
/// x_m(xi_m0))`, `tau = (-n.y, n.x)`, with the closed-form projection of
/// `gap` (docs/conventions.md, "The slip").
fn slip_slave_normal<D: DualNum<Primitive = f64> + Copy>(q: &[D; 8], xi_s: f64, xi_m0: f64) -> D {
    let node = |k: usize| [q[2 * k], q[2 * k + 1]];
    let (xs1, xs2, xm1, xm2) = (node(0), node(1), node(2), node(3));
    let x_s = lerp(xs1, xs2, D::from(xi_s));
    let (t_s, t_m) = (sub(xs2, xs1), sub(xm2, xm1));
    let c_m = lerp(xm1, xm2, D::from(0.0));
    let len = dot(t_s, t_s).sqrt();
    let n = [t_s[1] / len, -t_s[0] / len];
    let xi = -(dot(sub(c_m, x_s), t_s) * 2.0) / dot(t_m, t_s);
    let s_m = sub(lerp(xm1, xm2, xi), lerp(xm1, xm2, D::from(xi_m0)));
    dot([-n[1], n[0]], s_m)
}

/// The 3D worked example (docs/conventions.md, "3D faces").
const Q3: [f64; 24] = [
    0.0, 0.0, 1.0, 0.0, 1.0, 1.1, 1.0, 1.0, 1.0, 1.0, 0.0, 0.9, -0.2, -0.1, 0.8, 1.2, 0.0, 0.85,
    1.1, 1.3, 0.75, -0.1, 1.2, 0.8,
];

/// One case of the slip groups: the formulation, `q`, `xi_s` and `xi_m0`
/// (a segment's in the first component).
type SlipCase<'a> = (Formulation, &'a [f64], [f64; 2], [f64; 2]);

/// The slip against the gap, type by type, one point (module docs).
fn slip(c: &mut Criterion) {
    let cases: [SlipCase; 2] = [
        (Formulation::SlaveNormal, &Q, [XI_S, 0.0], [XI_M0, 0.0]),
        (Formulation::Quad4SlaveNormal, &Q3, [0.2, -0.1], [0.0, 0.0]),
    ];
    for (f, q, xi_s, xi_m0) in cases {
        let mut group = c.benchmark_group(format!("slip-{}", f.name()));
        let p = if q.len() == 8 { 1 } else { 2 };
        for ty in [ApproxType::Type1, ApproxType::Type3, ApproxType::Type6] {
            let kernel = Kernel::new(f, ty).unwrap();
            let mut out = GapOut::new(&kernel);
            group.bench_function(format!("gap-type{}", ty.index()), |b| {
                b.iter(|| {
                    kernel
                        .eval(black_box(q), black_box(&xi_s[..p]), &mut out)
                        .unwrap();
                    black_box(&out);
                })
            });
            let slip = kernel.slip().unwrap();
            let mut out = SlipOut::new(&slip);
            group.bench_function(format!("slip-type{}", ty.index()), |b| {
                b.iter(|| {
                    slip.eval(
                        black_box(q),
                        black_box(&xi_s[..p]),
                        black_box(&xi_m0[..p]),
                        &mut out,
                    )
                    .unwrap();
                    black_box(&out);
                })
            });
        }
        if p == 1 {
            let qv = SVector::<f64, 8>::from(Q);
            group.bench_function("num-dual-slip-hessian", |b| {
                b.iter(|| {
                    hessian(
                        |v: SVector<Dual2SVec64<8>, 8>| {
                            slip_slave_normal(
                                &std::array::from_fn(|i| v[i]),
                                black_box(XI_S),
                                black_box(XI_M0),
                            )
                        },
                        black_box(&qv),
                    )
                })
            });
        }
        group.finish();
    }
}

/// Configurations per iteration of the `points64` group.
const POINTS: usize = 64;

/// 64 configurations near the worked example: every coordinate moved by up
/// to +-0.05 and `xi_s` spread over (-0.9, 0.9), from a fixed seed.
fn points64() -> (Vec<[f64; 8]>, Vec<f64>) {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let qs = (0..POINTS)
        .map(|_| std::array::from_fn(|i| Q[i] + 0.1 * (uniform() - 0.5)))
        .collect();
    let xi_s = (0..POINTS).map(|_| 1.8 * uniform() - 0.9).collect();
    (qs, xi_s)
}

fn many_points(c: &mut Criterion) {
    let f = Formulation::SlaveNormal;
    if !pair_formulations().contains(&f) {
        return;
    }
    let (qs, xi_s) = points64();
    let flat: Vec<f64> = qs.iter().flatten().copied().collect();
    let mut group = c.benchmark_group("points64");
    group.bench_function("sympy-cse", |b| {
        let (mut g, mut xi_m) = (0.0, 0.0);
        let mut grad = [0.0; 8];
        let mut hess = [[0.0; 8]; 8];
        b.iter(|| {
            for (q, &xi) in qs.iter().zip(&xi_s) {
                sympy_kernel::gap_hess_sympy(
                    black_box(q),
                    black_box(xi),
                    &mut g,
                    &mut xi_m,
                    &mut grad,
                    &mut hess,
                );
                black_box((&g, &xi_m, &grad, &hess));
            }
        })
    });
    for ty in [ApproxType::Type1, ApproxType::Type3, ApproxType::Type6] {
        let i = ty.index();
        group.bench_function(format!("type{i}"), |b| {
            b.iter(|| {
                for (q, &xi) in qs.iter().zip(&xi_s) {
                    black_box(evaluate(f, ty, black_box(q), black_box(xi)).unwrap());
                }
            })
        });
        let kernel = Kernel::new(f, ty).unwrap();
        let mut out = GapOut::new(&kernel);
        group.bench_function(format!("type{i}-handle"), |b| {
            b.iter(|| {
                for (q, &xi) in qs.iter().zip(&xi_s) {
                    kernel.eval(black_box(q), black_box(xi), &mut out).unwrap();
                    black_box(&out);
                }
            })
        });
        let mut batch = GapBatch::new(&kernel);
        let mut isas = vec![(format!("type{i}-batch"), kernel)];
        if ty == ApproxType::Type6 {
            let portable = kernel.with_lane_isa(LaneIsa::Portable);
            isas.push((format!("type{i}-batch-portable"), portable));
        }
        for (id, kernel) in isas {
            group.bench_function(id, |b| {
                b.iter(|| {
                    let ok = kernel
                        .eval_batch(black_box(&flat), black_box(&xi_s), &mut batch)
                        .unwrap();
                    assert_eq!(ok, POINTS);
                    black_box(&batch);
                })
            });
        }
    }
    let projector = Projector::new(f).unwrap();
    let mut scratch = vec![0.0; projector.coords()];
    group.bench_function("value-only", |b| {
        b.iter(|| {
            for (q, &xi) in qs.iter().zip(&xi_s) {
                black_box(
                    projector
                        .project(black_box(q), black_box(xi), &mut scratch)
                        .unwrap(),
                );
            }
        })
    });
    group.bench_function("num-dual-hessian", |b| {
        b.iter(|| {
            for (q, &xi) in qs.iter().zip(&xi_s) {
                let qv = SVector::<f64, 8>::from(*q);
                black_box(hessian(
                    |v: SVector<Dual2SVec64<8>, 8>| gap(f, &std::array::from_fn(|i| v[i]), xi),
                    black_box(&qv),
                ));
            }
        })
    });
    group.finish();
}

/// The tri3-on-tri3 worked example of docs/conventions.md ("3D faces").
const TRI: [f64; 18] = [
    0.0, 0.0, 1.0, 0.1, 1.0, 1.05, 1.0, 0.1, 0.95, -0.3, -0.2, 0.8, 1.4, 0.1, 0.85, 0.2, 1.5, 0.75,
];

fn sub3<D: DualNum<Primitive = f64> + Copy>(a: [D; 3], b: [D; 3]) -> [D; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3<D: DualNum<Primitive = f64> + Copy>(a: [D; 3], b: [D; 3]) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The tri3-slave-normal gap over num-dual numbers: `x_s = N(u, v) . s`,
/// `n = t1 x t2 / |t1 x t2|` (`t1 = s2 - s1`, `t2 = s3 - s1`), the master
/// point solving `(x_m(xi) - x_s) . t_a = 0` in closed form (2 x 2, Cramer).
fn gap_tri3<D: DualNum<Primitive = f64> + Copy>(q: &[D; 18], u: f64, v: f64) -> D {
    let p = |k: usize| [q[3 * k], q[3 * k + 1], q[3 * k + 2]];
    let (s1, s2, s3, m1, m2, m3) = (p(0), p(1), p(2), p(3), p(4), p(5));
    let (t1, t2) = (sub3(s2, s1), sub3(s3, s1));
    let x_s: [D; 3] = std::array::from_fn(|k| s1[k] + t1[k] * u + t2[k] * v);
    let c = [
        t1[1] * t2[2] - t1[2] * t2[1],
        t1[2] * t2[0] - t1[0] * t2[2],
        t1[0] * t2[1] - t1[1] * t2[0],
    ];
    let len = dot3(c, c).sqrt();
    let n = c.map(|x| x / len);
    let (e1, e2, r) = (sub3(m2, m1), sub3(m3, m1), sub3(m1, x_s));
    let (a00, a01, a10, a11) = (dot3(e1, t1), dot3(e2, t1), dot3(e1, t2), dot3(e2, t2));
    let (r0, r1) = (dot3(r, t1), dot3(r, t2));
    let det = a00 * a11 - a01 * a10;
    let xu = -(a11 * r0 - a01 * r1) / det;
    let xv = -(a00 * r1 - a10 * r0) / det;
    let x_ms: [D; 3] = std::array::from_fn(|k| r[k] + e1[k] * xu + e2[k] * xv);
    dot3(n, x_ms)
}

/// 64 tri3-on-tri3 configurations near the worked example: every
/// coordinate moved by up to +-0.05, `(u, v)` inside the slave triangle,
/// from a fixed seed.
fn tri64() -> (Vec<[f64; 18]>, Vec<[f64; 2]>) {
    let mut state: u64 = 0x3d3d_79b9_7f4a_7c15;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let qs = (0..POINTS)
        .map(|_| std::array::from_fn(|i| TRI[i] + 0.1 * (uniform() - 0.5)))
        .collect();
    let uv = (0..POINTS)
        .map(|_| {
            let u = 0.6 * uniform() + 0.05;
            [u, (0.9 - u) * uniform() + 0.05]
        })
        .collect();
    (qs, uv)
}

/// The slip of Type 6 at 64 points: one at a time against the batch
/// (module docs).
fn slip_batch(c: &mut Criterion) {
    let mut group = c.benchmark_group("slip-batch64");
    let (qs2, xi2) = points64();
    let (qs3, uv3) = tri64();
    let cases: [(Formulation, Vec<f64>, Vec<f64>, usize); 2] = [
        (
            Formulation::SlaveNormal,
            qs2.iter().flatten().copied().collect(),
            xi2,
            1,
        ),
        (
            Formulation::Tri3SlaveNormal,
            qs3.iter().flatten().copied().collect(),
            uv3.iter().flatten().copied().collect(),
            2,
        ),
    ];
    for (f, qs, xi_s, p) in cases {
        let Ok(kernel) = Kernel::new(f, ApproxType::Type6) else {
            continue;
        };
        let xi_m0: Vec<f64> = xi_s.iter().map(|x| 0.6 * x - 0.05).collect();
        let n = kernel.coords();
        let slip = kernel.slip().unwrap();
        let mut out = SlipOut::new(&slip);
        group.bench_function(format!("{}-points", f.name()), |b| {
            b.iter(|| {
                for k in 0..POINTS {
                    slip.eval(
                        black_box(&qs[k * n..(k + 1) * n]),
                        black_box(&xi_s[k * p..(k + 1) * p]),
                        black_box(&xi_m0[k * p..(k + 1) * p]),
                        &mut out,
                    )
                    .unwrap();
                    black_box(&out);
                }
            })
        });
        for (id, kernel) in [
            ("batch", kernel),
            ("batch-portable", kernel.with_lane_isa(LaneIsa::Portable)),
        ] {
            let slip = kernel.slip().unwrap();
            let mut batch = SlipBatch::new(&slip);
            group.bench_function(format!("{}-{id}", f.name()), |b| {
                b.iter(|| {
                    let ok = slip
                        .eval_batch(
                            black_box(&qs),
                            black_box(&xi_s),
                            black_box(&xi_m0),
                            &mut batch,
                        )
                        .unwrap();
                    assert_eq!(ok, POINTS);
                    black_box(&batch);
                })
            });
        }
    }
    group.finish();
}

fn faces(c: &mut Criterion) {
    let f = Formulation::Tri3SlaveNormal;
    if f.coords() != Some(18) {
        return;
    }
    let (qs, uv) = tri64();
    let flat: Vec<f64> = qs.iter().flatten().copied().collect();
    let flat_uv: Vec<f64> = uv.iter().flatten().copied().collect();
    let mut group = c.benchmark_group("faces-tri3-slave-normal");
    group.bench_function("sympy-cse", |b| {
        let (mut g, mut xi_m) = (0.0, [0.0; 2]);
        let mut grad = [0.0; 18];
        let mut hess = [[0.0; 18]; 18];
        b.iter(|| {
            for (q, &[u, v]) in qs.iter().zip(&uv) {
                sympy_kernel_3d::gap_hess_sympy_3d(
                    black_box(q),
                    black_box(u),
                    black_box(v),
                    &mut g,
                    &mut xi_m,
                    &mut grad,
                    &mut hess,
                );
                black_box((&g, &xi_m, &grad, &hess));
            }
        })
    });
    for ty in [ApproxType::Type1, ApproxType::Type6] {
        let i = ty.index();
        let kernel = Kernel::new(f, ty).unwrap();
        let mut out = GapOut::new(&kernel);
        group.bench_function(format!("type{i}-handle"), |b| {
            b.iter(|| {
                for (q, xi) in qs.iter().zip(&uv) {
                    kernel.eval(black_box(q), black_box(xi), &mut out).unwrap();
                    black_box(&out);
                }
            })
        });
        let mut batch = GapBatch::new(&kernel);
        let mut isas = vec![(format!("type{i}-batch"), kernel)];
        if ty == ApproxType::Type6 {
            let portable = kernel.with_lane_isa(LaneIsa::Portable);
            isas.push((format!("type{i}-batch-portable"), portable));
        }
        for (id, kernel) in isas {
            group.bench_function(id, |b| {
                b.iter(|| {
                    let ok = kernel
                        .eval_batch(black_box(&flat), black_box(&flat_uv), &mut batch)
                        .unwrap();
                    assert_eq!(ok, POINTS);
                    black_box(&batch);
                })
            });
        }
    }
    group.bench_function("num-dual-hessian", |b| {
        b.iter(|| {
            for (q, &[u, v]) in qs.iter().zip(&uv) {
                let qv = SVector::<f64, 18>::from(*q);
                black_box(hessian(
                    |x: SVector<Dual2SVec64<18>, 18>| {
                        gap_tri3(&std::array::from_fn(|i| x[i]), u, v)
                    },
                    black_box(&qv),
                ));
            }
        })
    });
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(1))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = kernels, many_points, faces, slip, slip_batch
}
criterion_main!(benches);
