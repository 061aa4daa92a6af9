//! The 3-node quadratic-segment formulation (`quadratic-slave-normal`,
//! 12 coordinates) through the handles: a hand-computed curved
//! configuration, equivalence with `slave-normal` on straight segments (the
//! chain rule through the embedding of a two-node pair), the coordinate
//! count everywhere in the API, and the degenerate cases — zero-length
//! chord, folded segment, vanishing slave tangent, a projection Newton
//! cannot find — as typed errors, never NaN or a panic.
//!
//! (The num-dual checks on the verifier's 3-node families are in the
//! workspace root's tests/kernels_ad.rs.)
#![cfg(feature = "quadratic-slave-normal")]

use contact_kernels::{
    ApproxType, Formulation, GapBatch, GapOut, Kernel, KernelError, Projector, Segment, evaluate,
    project,
};

const F: Formulation = Formulation::QuadraticSlaveNormal;
const N: usize = 12;

/// Every type's kernel of the formulation.
fn kernels() -> Vec<Kernel> {
    ApproxType::ALL
        .iter()
        .map(|&ty| Kernel::new(F, ty).unwrap())
        .collect()
}

/// Slave straight along +x from (0, 0) to (2, 0) (mid node (1, 0)); master
/// below, running in -x, its mid node raised by 0.2: `x_m(xi) = (1 - xi,
/// -0.8 - 0.2 xi^2)`. At `xi_s = 0.5` the slave point is (1.5, 0), the slave
/// normal (0, -1), so `xi_m = -0.5` and `g = 0.85`.
const CURVED: [f64; N] = [
    0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 1.0, -0.8,
];

#[test]
fn a_curved_master_gives_the_hand_computed_gap_and_gradient() {
    for kernel in kernels() {
        assert_eq!(kernel.coords(), N);
        let mut out = GapOut::new(&kernel);
        assert_eq!(out.coords(), N);
        kernel.eval(&CURVED, 0.5, &mut out).unwrap();
        let ty = kernel.ty();
        assert!((out.gap() - 0.85).abs() < 1e-15, "{ty}: g {}", out.gap());
        assert!(
            (out.xi_m() + 0.5).abs() < 1e-15,
            "{ty}: xi_m {}",
            out.xi_m()
        );
        // The master's y coordinates move the master point vertically by
        // N_k(xi_m) and leave xi_m alone (t_s is horizontal): dg/dym_k =
        // -N_k(-0.5) = -0.375, 0.125, -0.75 in every type (x_ms is at least
        // linear in all of them).
        let g = out.grad();
        for (k, want) in [(7, -0.375), (9, 0.125), (11, -0.75)] {
            assert!((g[k] - want).abs() < 1e-15, "{ty}: grad[{k}] {}", g[k]);
        }
        assert_eq!(out.hess().is_some(), ty.has_hessian());
    }
    let p = Projector::new(F).unwrap();
    assert_eq!(p.coords(), N);
    let got = p.project(&CURVED, 0.5, &mut [0.0; N]).unwrap();
    assert!((got.gap - 0.85).abs() < 1e-15 && (got.xi_m + 0.5).abs() < 1e-15);
}

/// Two-node pair `q8` as 3-node segments: the mid nodes at the chord
/// midpoints.
fn embed(q8: &[f64; 8]) -> [f64; N] {
    let mid = |a: usize, b: usize, k: usize| 0.5 * (q8[2 * a + k] + q8[2 * b + k]);
    [
        q8[0],
        q8[1],
        q8[2],
        q8[3],
        mid(0, 1, 0),
        mid(0, 1, 1),
        q8[4],
        q8[5],
        q8[6],
        q8[7],
        mid(2, 3, 0),
        mid(2, 3, 1),
    ]
}

/// `d q12 / d q8` of [`embed`] (12 x 8, row-major).
fn embedding_matrix() -> [[f64; 8]; N] {
    let mut p = [[0.0; 8]; N];
    for (row, node8) in [(0, 0), (2, 1), (6, 2), (8, 3)] {
        p[row][2 * node8] = 1.0;
        p[row + 1][2 * node8 + 1] = 1.0;
    }
    for (row, a, b) in [(4, 0, 1), (10, 2, 3)] {
        for k in 0..2 {
            p[row + k][2 * a + k] = 0.5;
            p[row + k][2 * b + k] = 0.5;
        }
    }
    p
}

/// On straight segments the quadratic shape functions reproduce the linear
/// ones: the gap is slave-normal's, and by the chain rule through the
/// embedding `P`, `P^T g'_12 = g'_8` and `P^T g''_12 P = g''_8` for every
/// type (truncation keeps or drops the same terms on both sides).
#[test]
fn straight_three_node_segments_are_slave_normal() {
    let p = embedding_matrix();
    let base = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    for k in 0..8 {
        let t = k as f64;
        let q8: [f64; 8] = std::array::from_fn(|i| {
            base[i] + 0.05 * (t * (i as f64 + 1.0)).sin() + 10.0 * (k % 3) as f64
        });
        let xi_s = -0.9 + 0.25 * t;
        let q12 = embed(&q8);
        for ty in ApproxType::ALL {
            let lin = evaluate(Formulation::SlaveNormal, ty, &q8, xi_s).unwrap();
            let kernel = Kernel::new(F, ty).unwrap();
            let mut out = GapOut::new(&kernel);
            kernel.eval(&q12, xi_s, &mut out).unwrap();
            let what = format!("type {ty}, configuration {k}");
            assert!((out.gap() - lin.gap).abs() <= 1e-13, "{what}: g");
            assert!((out.xi_m() - lin.xi_m).abs() <= 1e-13, "{what}: xi_m");
            let g = out.grad();
            for (j, &want) in lin.grad.iter().enumerate() {
                let pulled: f64 = (0..N).map(|i| p[i][j] * g[i]).sum();
                assert!(
                    (pulled - want).abs() <= 1e-12 * (1.0 + lin.grad.norm()),
                    "{what}: grad[{j}] {pulled} vs {want}"
                );
            }
            match (out.hess(), lin.hess) {
                (None, None) => {}
                (Some(h), Some(h8)) => {
                    for a in 0..8 {
                        for b in 0..8 {
                            let pulled: f64 = (0..N)
                                .flat_map(|i| (0..N).map(move |j| (i, j)))
                                .map(|(i, j)| p[i][a] * h[i * N + j] * p[j][b])
                                .sum();
                            assert!(
                                (pulled - h8[(a, b)]).abs() <= 1e-11 * (1.0 + h8.norm()),
                                "{what}: hess[{a}][{b}] {pulled} vs {}",
                                h8[(a, b)]
                            );
                        }
                    }
                }
                (h, h8) => panic!(
                    "{what}: Hessian presence {} vs {}",
                    h.is_some(),
                    h8.is_some()
                ),
            }
        }
    }
}

#[test]
fn the_api_takes_twelve_coordinates() {
    let kernel = Kernel::new(F, ApproxType::Type6).unwrap();
    assert_eq!(F.coords(), Some(N));
    assert_eq!(Formulation::SlaveNormal.coords(), Some(8));
    assert!(!contact_kernels::pair_formulations().contains(&F));
    assert!(contact_kernels::compiled_formulations().contains(&F));
    let mut out = GapOut::new(&kernel);
    // The two-node value API is refused with a typed error, not a panic.
    let q8 = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    assert_eq!(
        evaluate(F, ApproxType::Type6, &q8, 0.3),
        Err(KernelError::CoordinateCount {
            expected: N,
            found: 8
        })
    );
    assert!(matches!(
        project(F, &q8, 0.3),
        Err(KernelError::CoordinateCount { expected: N, .. })
    ));
    assert_eq!(
        kernel.eval(&q8, 0.3, &mut out),
        Err(KernelError::CoordinateCount {
            expected: N,
            found: 8
        })
    );
    let mut small = GapOut::with_coords(8);
    assert_eq!(
        kernel.eval(&CURVED, 0.5, &mut small),
        Err(KernelError::BufferSize {
            expected: N,
            found: 8
        })
    );
    // Input errors index `q` as given; `xi_s` is `q.len()`.
    assert_eq!(
        kernel
            .eval(&CURVED, f64::NAN, &mut out)
            .unwrap_err()
            .to_string(),
        "non-finite input: coordinate 12 is NaN"
    );
    // The batch takes 12 coordinates per point.
    let mut batch = GapBatch::new(&kernel);
    assert_eq!(batch.coords(), N);
    let qs: Vec<f64> = CURVED.iter().chain(&CURVED).copied().collect();
    assert_eq!(kernel.eval_batch(&qs, &[0.5, -0.25], &mut batch), Ok(2));
    kernel.eval(&CURVED, -0.25, &mut out).unwrap();
    assert_eq!(batch.gap(1).unwrap().0.to_bits(), out.gap().to_bits());
    assert_eq!(batch.hess(1).unwrap(), out.hess());
}

/// Every entry point's error on `q`, `xi_s`: the projector's and each
/// type's.
fn all_errors(q: &[f64; N], xi_s: f64) -> Vec<KernelError> {
    let mut errs = vec![
        Projector::new(F)
            .unwrap()
            .project(q, xi_s, &mut [0.0; N])
            .expect_err("the projection must fail"),
    ];
    for kernel in kernels() {
        let mut out = GapOut::new(&kernel);
        errs.push(
            kernel
                .eval(q, xi_s, &mut out)
                .expect_err("the kernel must fail"),
        );
    }
    errs
}

#[test]
fn zero_length_chords_are_degenerate() {
    // Slave ends coincide (mid node elsewhere: a closed loop, no chord).
    let mut q = CURVED;
    q[2] = q[0];
    q[3] = q[1];
    for e in all_errors(&q, 0.5) {
        assert!(
            matches!(
                e,
                KernelError::DegenerateSegment {
                    segment: Segment::Slave,
                    ..
                }
            ),
            "{e:?}"
        );
    }
    let mut q = CURVED;
    q[8] = q[6];
    q[9] = q[7];
    for e in all_errors(&q, 0.5) {
        assert!(
            matches!(
                e,
                KernelError::DegenerateSegment {
                    segment: Segment::Master,
                    ..
                }
            ),
            "{e:?}"
        );
    }
}

/// The mid node at the quarter point (the tangent vanishes at an end) or
/// beyond it (the segment runs backwards), on either segment, and
/// off the chord too: folded. Just inside the quarter point: accepted.
#[test]
fn a_mid_node_that_folds_the_segment_is_refused() {
    // Slave chord (0,0)-(2,0): midpoint (1,0), quarter point offset 0.5.
    // Within the margin (`DEGENERATE_LENGTH` of the half chord squared)
    // of the quarter point is folded too.
    let margin = 1.0 + 0.5 * (1.0 - 1e-11);
    for (mid_x, mid_y) in [
        (1.5, 0.0),
        (0.5, 0.0),
        (margin, 0.0),
        (1.9, 0.3),
        (3.0, -0.2),
        (-4.0, 0.0),
    ] {
        let mut q = CURVED;
        q[4] = mid_x;
        q[5] = mid_y;
        for e in all_errors(&q, 0.5) {
            match e {
                KernelError::FoldedSegment {
                    segment: Segment::Slave,
                    mid_offset,
                } => assert!(
                    (mid_offset - (mid_x - 1.0) / 2.0).abs() < 1e-15,
                    "{mid_offset}"
                ),
                other => panic!("slave mid node ({mid_x}, {mid_y}): {other:?}"),
            }
        }
    }
    // Master chord (2,-1)-(0,-1): its midpoint (1,-1), quarter at x = 0.5, 1.5.
    let mut q = CURVED;
    q[10] = 0.5;
    for e in all_errors(&q, 0.5) {
        assert!(
            matches!(
                e,
                KernelError::FoldedSegment {
                    segment: Segment::Master,
                    ..
                }
            ),
            "{e:?}"
        );
    }
    assert!(
        e_string(&q).contains("folded master segment"),
        "{}",
        e_string(&q)
    );
    // Just inside the quarter point the segment is accepted.
    let mut q = CURVED;
    q[4] = 1.0 + 0.5 * (1.0 - 1e-6);
    Projector::new(F)
        .unwrap()
        .project(&q, 0.5, &mut [0.0; N])
        .unwrap();
}

fn e_string(q: &[f64; N]) -> String {
    all_errors(q, 0.5)[0].to_string()
}

/// A slave point where the slave tangent vanishes (possible outside
/// `[-1, 1]` for an accepted segment: `t(xi) = 1 - xi / 2` vanishes at
/// `xi = 2`): the projection equation is `0 = 0`, refused as no projection.
#[test]
fn a_zero_slave_tangent_is_no_projection() {
    let mut q = CURVED;
    q[4] = 1.25; // mid node at offset 1/8 of the chord: t(xi) = (1 - xi / 2, 0)
    for e in all_errors(&q, 2.0) {
        assert!(matches!(e, KernelError::NoProjection { .. }), "{e:?}");
    }
}

/// The slave normal line misses a master curving away from it
/// (`x_m(xi).x = 3 + xi^2 > 1` for the slave point at x = 1): Newton finds
/// no root and the kernels say so.
#[test]
fn a_projection_newton_cannot_find_is_an_error() {
    let q = [
        0.0, 0.0, 2.0, 0.0, 1.0, 0.0, // slave along +x
        4.0, 1.0, 4.0, -1.0, 3.0, 0.0, // master: x = 3 + xi^2
    ];
    for e in all_errors(&q, 0.0) {
        assert!(
            matches!(
                e,
                KernelError::NoProjection { .. }
                    | KernelError::ProjectionDiverged { .. }
                    | KernelError::ProjectionOutOfReach { .. }
            ),
            "{e:?}"
        );
    }
    // Away from xi = 0 Newton oscillates without converging.
    for e in all_errors(&q, 0.3) {
        assert!(
            matches!(
                e,
                KernelError::NoProjection { .. }
                    | KernelError::ProjectionDiverged { .. }
                    | KernelError::ProjectionOutOfReach { .. }
            ),
            "{e:?}"
        );
    }
}

/// Random and extreme input: `Ok` with finite outputs and a symmetric
/// Hessian, or a typed error; never a panic, never NaN.
#[test]
fn the_kernels_never_panic_or_return_nan() {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let kernels = kernels();
    let mut outs: Vec<GapOut> = kernels.iter().map(GapOut::new).collect();
    let (mut ok, mut refused) = (0, 0);
    for case in 0..3000 {
        let scale = [1.0, 1e-150, 1e150, 1e300][case % 4];
        let q: [f64; N] = std::array::from_fn(|_| scale * (4.0 * next() - 2.0));
        let xi_s = 3.0 * next() - 1.5;
        for (kernel, out) in kernels.iter().zip(&mut outs) {
            match kernel.eval(&q, xi_s, out) {
                Ok(()) => {
                    ok += 1;
                    assert!(out.gap().is_finite() && out.xi_m().is_finite());
                    assert!(out.grad().iter().all(|v| v.is_finite()));
                    if let Some(h) = out.hess() {
                        assert!(h.iter().all(|v| v.is_finite()));
                        let max = h.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                        for i in 0..N {
                            for j in 0..i {
                                assert!((h[i * N + j] - h[j * N + i]).abs() <= 1e-12 * max);
                            }
                        }
                    }
                }
                Err(e) => {
                    refused += 1;
                    assert!(!matches!(e, KernelError::NotCompiled(_)), "{e:?}");
                }
            }
        }
    }
    assert!(ok > 0 && refused > 0, "ok {ok}, refused {refused}");
}
