//! `Kernel::eval_batch` gives every point the bits `Kernel::eval` gives it,
//! reports failures per point without disturbing the others, and rejects
//! mismatched shapes.

use contact_kernels::{ApproxType, GapBatch, GapOut, Kernel, KernelError, pair_formulations};

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
