//! `Kernel::eval_batch` gives every point the bits `Kernel::eval` gives it,
//! reports failures per point without disturbing the others, and rejects
//! mismatched shapes. It evaluates 4 points per call of the lane kernels
//! (portable and AVX2): every configuration of the num-dual and C tests
//! (`common/`, hard families, degenerate, non-finite and extreme input) is
//! evaluated in every lane position, by both lane builds, and compared
//! with `Kernel::eval` bit for bit, errors included. The face kernels' lanes
//! (`xi_s` and `xi_m` of two values) are checked the same way on the face
//! configurations of the C test (`common/faces.rs`).

mod common;

use contact_kernels::{
    ApproxType, GapBatch, GapOut, Kernel, KernelError, LaneIsa, pair_formulations,
};

/// A small deterministic generator (no dependency).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` configurations around the worked example, the third one with a
/// degenerate slave segment.
fn configurations(count: usize, rng: &mut Lcg) -> (Vec<f64>, Vec<f64>) {
    const Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    let mut qs = Vec::new();
    let mut xi_s = Vec::new();
    for p in 0..count {
        let mut q: Vec<f64> = Q.iter().map(|v| v + 0.2 * (rng.next() - 0.5)).collect();
        if p == 2 {
            q[2] = q[0];
            q[3] = q[1];
        }
        qs.extend(q);
        xi_s.push(2.0 * rng.next() - 1.0);
    }
    (qs, xi_s)
}

#[test]
fn batch_equals_single_evaluations_bit_for_bit() {
    let mut rng = Lcg(42);
    let (qs, xi_s) = configurations(40, &mut rng);
    for f in pair_formulations() {
        for ty in ApproxType::ALL {
            let kernel = Kernel::new(f, ty).unwrap();
            let mut batch = GapBatch::new(&kernel);
            // a larger batch first, so the buffers hold stale values
            let (big_q, big_xi) = configurations(50, &mut Lcg(7));
            kernel.eval_batch(&big_q, &big_xi, &mut batch).unwrap();
            let ok = kernel.eval_batch(&qs, &xi_s, &mut batch).unwrap();
            assert_eq!(batch.len(), 40);
            let mut single = GapOut::new(&kernel);
            let mut expected_ok = 0;
            for (p, q) in qs.chunks_exact(8).enumerate() {
                match kernel.eval(q, xi_s[p], &mut single) {
                    Ok(()) => {
                        expected_ok += 1;
                        let (gap, xi_m) = batch.gap(p).unwrap();
                        assert_eq!(gap.to_bits(), single.gap().to_bits());
                        assert_eq!(xi_m.to_bits(), single.xi_m().to_bits());
                        assert_eq!(batch.grad(p).unwrap(), single.grad());
                        assert_eq!(batch.hess(p).unwrap(), single.hess());
                    }
                    Err(e) => {
                        assert_eq!(batch.status(p), Err(&e), "point {p}");
                        assert_eq!(batch.gaps()[p], 0.0);
                        assert!(batch.grads()[8 * p..8 * p + 8].iter().all(|&v| v == 0.0));
                    }
                }
            }
            assert_eq!(ok, expected_ok);
            assert!(ok < 40, "the degenerate point must fail");
            assert!(matches!(
                batch.status(2),
                Err(KernelError::DegenerateSegment { .. })
            ));
        }
    }
}

#[test]
fn mismatched_shapes_are_errors() {
    let f = pair_formulations()[0];
    let kernel = Kernel::new(f, ApproxType::Type6).unwrap();
    let mut batch = GapBatch::new(&kernel);
    assert_eq!(
        kernel.eval_batch(&[0.0; 15], &[0.0, 0.0], &mut batch),
        Err(KernelError::CoordinateCount {
            expected: 16,
            found: 15
        })
    );
    assert_eq!(kernel.eval_batch(&[], &[], &mut batch), Ok(0));
    assert!(batch.is_empty());
}

/// A batch's projections come as slices of `param_dim` values per point:
/// for segments `xi_m(p) == [gap(p).1]`.
#[test]
fn batch_projections_are_slices_of_the_parametric_dimension() {
    let (qs, xi_s) = configurations(9, &mut Lcg(3));
    for f in pair_formulations() {
        let kernel = Kernel::new(f, ApproxType::Type2).unwrap();
        assert_eq!(kernel.param_dim(), 1);
        let mut batch = GapBatch::new(&kernel);
        kernel.eval_batch(&qs, &xi_s, &mut batch).unwrap();
        assert_eq!(batch.xi_ms().len(), 9);
        for p in 0..9 {
            match (batch.gap(p), batch.xi_m(p)) {
                (Ok((_, xi_m)), Ok(all)) => {
                    assert_eq!(all, [xi_m]);
                    assert_eq!(batch.xi_ms()[p], xi_m);
                }
                (Err(a), Err(b)) => {
                    assert_eq!(a, b);
                    assert_eq!(batch.xi_ms()[p], 0.0);
                }
                other => panic!("{f} point {p}: {other:?}"),
            }
        }
    }
}

/// The lane builds this CPU can run.
fn lane_isas(kernel: Kernel) -> Vec<Kernel> {
    let mut out = vec![kernel.with_lane_isa(LaneIsa::Portable)];
    let avx2 = kernel.with_lane_isa(LaneIsa::Avx2);
    if avx2.lane_isa() == LaneIsa::Avx2 {
        out.push(avx2);
    }
    assert_eq!(out[0].lane_isa(), LaneIsa::Portable);
    out
}

/// Point `p` of `batch` against `Kernel::eval` of the same point: equal
/// bits, or the same error (compared by their Debug text, so that NaN
/// fields compare equal).
fn assert_point_equals_eval(kernel: &Kernel, batch: &GapBatch, p: usize, q: &[f64], xi_s: &[f64]) {
    let mut single = GapOut::new(kernel);
    let what = || {
        format!(
            "{:?} ({:?}) point {p}: q = {q:?}, xi_s = {xi_s:?}",
            kernel,
            kernel.lane_isa()
        )
    };
    match kernel.eval(q, xi_s, &mut single) {
        Ok(()) => {
            let (gap, xi_m) = batch.gap(p).unwrap_or_else(|e| panic!("{}: {e}", what()));
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(gap.to_bits(), single.gap().to_bits(), "{}", what());
            assert_eq!(xi_m.to_bits(), single.xi_m().to_bits(), "{}", what());
            assert_eq!(
                bits(batch.xi_m(p).unwrap()),
                bits(single.xi_m_all()),
                "{}",
                what()
            );
            assert_eq!(
                bits(batch.grad(p).unwrap()),
                bits(single.grad()),
                "{}",
                what()
            );
            match (batch.hess(p).unwrap(), single.hess()) {
                (Some(a), Some(b)) => assert_eq!(bits(a), bits(b), "{}", what()),
                (None, None) => {}
                other => panic!("{}: Hessian presence differs: {other:?}", what()),
            }
        }
        Err(e) => {
            let got = batch
                .status(p)
                .expect_err("the batch must fail where eval fails");
            assert_eq!(format!("{got:?}"), format!("{e:?}"), "{}", what());
            let n = kernel.coords();
            assert_eq!(batch.gaps()[p], 0.0);
            assert!(batch.grads()[n * p..n * (p + 1)].iter().all(|&v| v == 0.0));
            if let Some(h) = batch.hessians() {
                assert!(h[n * n * p..n * n * (p + 1)].iter().all(|&v| v == 0.0));
            }
        }
    }
}

#[test]
fn lanes_equal_eval_bit_for_bit_on_every_test_configuration() {
    let configs = common::configurations();
    let qs: Vec<f64> = configs.iter().flat_map(|c| c.q).collect();
    let xi_s: Vec<f64> = configs.iter().map(|c| c.xi_s).collect();
    let mut failures = 0;
    for f in pair_formulations() {
        for ty in ApproxType::ALL {
            for kernel in lane_isas(Kernel::new(f, ty).unwrap()) {
                let mut batch = GapBatch::new(&kernel);
                // Start 0..4 points in: every configuration in every lane,
                // and last groups of every length.
                for skip in 0..4 {
                    let ok = kernel
                        .eval_batch(&qs[8 * skip..], &xi_s[skip..], &mut batch)
                        .unwrap();
                    assert_eq!(batch.len(), configs.len() - skip);
                    for (p, c) in configs[skip..].iter().enumerate() {
                        assert_point_equals_eval(&kernel, &batch, p, &c.q, &[c.xi_s]);
                    }
                    let failed = (0..batch.len())
                        .filter(|&p| batch.status(p).is_err())
                        .count();
                    assert_eq!(ok + failed, batch.len());
                    failures += failed;
                }
            }
        }
    }
    // The configurations include degenerate, non-finite, perpendicular and
    // overflowing ones: failures must have occurred (and matched).
    assert!(failures > 0);
}

#[test]
fn short_batches_and_failures_in_the_last_group() {
    let configs = common::configurations();
    // A valid point, then a non-finite one, then the worked example.
    let picks: Vec<&common::Config> = [
        configs.iter().find(|c| c.label.starts_with("random #")),
        configs.iter().find(|c| c.label == "non-finite input"),
        configs.iter().find(|c| c.label == "zero-length master"),
        configs.iter().find(|c| c.label == "perpendicular master"),
        configs.iter().find(|c| c.label == "worked"),
    ]
    .into_iter()
    .map(|c| c.expect("family present"))
    .collect();
    for f in pair_formulations() {
        for kernel in lane_isas(Kernel::new(f, ApproxType::Type6).unwrap()) {
            let mut batch = GapBatch::new(&kernel);
            for len in 1..=9 {
                let chosen: Vec<&common::Config> =
                    (0..len).map(|i| picks[(i * 3 + len) % 5]).collect();
                let qs: Vec<f64> = chosen.iter().flat_map(|c| c.q).collect();
                let xi_s: Vec<f64> = chosen.iter().map(|c| c.xi_s).collect();
                kernel.eval_batch(&qs, &xi_s, &mut batch).unwrap();
                assert_eq!(batch.len(), len);
                for (p, c) in chosen.iter().enumerate() {
                    assert_point_equals_eval(&kernel, &batch, p, &c.q, &[c.xi_s]);
                }
            }
        }
    }
}

#[test]
fn avx2_is_used_where_the_cpu_has_it() {
    let kernel = Kernel::new(pair_formulations()[0], ApproxType::Type6).unwrap();
    #[cfg(target_arch = "x86_64")]
    let expected = if std::is_x86_feature_detected!("avx2") {
        LaneIsa::Avx2
    } else {
        LaneIsa::Portable
    };
    #[cfg(not(target_arch = "x86_64"))]
    let expected = LaneIsa::Portable;
    assert_eq!(kernel.lane_isa(), expected);
}

/// The 3-node formulation's lanes (12 coordinates; the projection by
/// Newton's method in every lane, each lane to its own convergence) equal
/// `Kernel::eval` bit for bit on the verifier's 3-node families, errors
/// included (no real root, divergence), every configuration in every lane.
#[cfg(feature = "quadratic-slave-normal")]
#[test]
fn lanes_equal_eval_on_the_3_node_families() {
    let configs = gapsim_families::quadratic();
    let n = 12;
    let qs: Vec<f64> = configs.iter().flat_map(|c| c.q.iter().copied()).collect();
    let xi_s: Vec<f64> = configs.iter().map(|c| c.params[0]).collect();
    let mut failures = 0;
    for ty in ApproxType::ALL {
        let kernel = Kernel::new(contact_kernels::Formulation::QuadraticSlaveNormal, ty).unwrap();
        assert_eq!(kernel.coords(), n);
        for kernel in lane_isas(kernel) {
            let mut batch = GapBatch::new(&kernel);
            for skip in 0..4 {
                let ok = kernel
                    .eval_batch(&qs[n * skip..], &xi_s[skip..], &mut batch)
                    .unwrap();
                for (p, c) in configs[skip..].iter().enumerate() {
                    assert_point_equals_eval(&kernel, &batch, p, &c.q, &c.params);
                }
                failures += batch.len() - ok;
            }
        }
    }
    // Uniform draws without a real root are among the families.
    assert!(failures > 0);
}

/// The face lanes (every formulation of 3D faces, every type, both lane
/// builds) equal `Kernel::eval` bit for bit on the face configurations of
/// the C test (the verifier's face families plus non-finite, outside,
/// degenerate, folded, unprojectable, far and extreme input), errors
/// included, every configuration in every lane and last groups of every
/// length.
#[test]
fn face_lanes_equal_eval_bit_for_bit_on_every_face_configuration() {
    let mut failures = 0;
    let mut points = 0;
    for &(f, _, s, m) in &common::faces::FACES {
        let configs = common::faces::face_configurations(s, m);
        let qs: Vec<f64> = configs.iter().flat_map(|c| c.q.iter().copied()).collect();
        let xi_s: Vec<f64> = configs.iter().flat_map(|c| c.xi_s).collect();
        for ty in ApproxType::ALL {
            let kernel = Kernel::new(f, ty).unwrap();
            let n = kernel.coords();
            assert_eq!(kernel.param_dim(), 2);
            for kernel in lane_isas(kernel) {
                let mut batch = GapBatch::new(&kernel);
                for skip in 0..4 {
                    let ok = kernel
                        .eval_batch(&qs[n * skip..], &xi_s[2 * skip..], &mut batch)
                        .unwrap();
                    assert_eq!(batch.len(), configs.len() - skip);
                    for (p, c) in configs[skip..].iter().enumerate() {
                        assert_point_equals_eval(&kernel, &batch, p, &c.q, &c.xi_s);
                    }
                    points += batch.len();
                    failures += batch.len() - ok;
                }
            }
        }
    }
    eprintln!(
        "face lanes: {points} points compared with Kernel::eval, {failures} failures matched"
    );
    assert!(failures > 0);
}
