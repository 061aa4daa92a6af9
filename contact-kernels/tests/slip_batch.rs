//! `Slip::eval_batch` gives every point the bits `Slip::eval` gives it
//! (errors included): for segments 4 points per call of the slip's lane
//! kernels (portable and AVX2), every configuration of the num-dual and C
//! tests (`common/`: the verifier's families, degenerate, non-finite and
//! extreme input) in every lane position, with last converged projections
//! that include a non-finite one, every type; for the eight face pairs
//! (three lane functions per type, one per component) the face
//! configurations of the C test in every lane position; and it rejects
//! mismatched shapes.

mod common;

use contact_kernels::{
    ApproxType, Kernel, KernelError, LaneIsa, Slip, SlipBatch, SlipOut, pair_formulations,
};

/// The lane builds this CPU can run, as slips.
fn lane_isas(kernel: Kernel) -> Vec<Slip> {
    let mut out = vec![kernel.with_lane_isa(LaneIsa::Portable)];
    let avx2 = kernel.with_lane_isa(LaneIsa::Avx2);
    if avx2.lane_isa() == LaneIsa::Avx2 {
        out.push(avx2);
    }
    out.into_iter()
        .map(|k| k.slip().expect("every shipped formulation has a slip"))
        .collect()
}

/// The last converged projection of configuration `i` (`k` values): near
/// the slave point, a NaN for every seventh configuration.
fn xi_m0(i: usize, xi_s: &[f64]) -> Vec<f64> {
    xi_s.iter()
        .map(|x| if i % 7 == 3 { f64::NAN } else { 0.6 * x - 0.05 })
        .collect()
}

/// Point `p` of `batch` against `Slip::eval` of the same point: equal bits,
/// or the same error (compared by their Debug text, so that NaN fields
/// compare equal) and zero entries.
fn assert_point_equals_eval(
    slip: &Slip,
    batch: &SlipBatch,
    p: usize,
    q: &[f64],
    xi_s: &[f64],
    xi_m0: &[f64],
) {
    let mut single = SlipOut::new(slip);
    let what = || {
        format!(
            "{:?} ({:?}) point {p}: q = {q:?}, xi_s = {xi_s:?}, xi_m0 = {xi_m0:?}",
            slip.kernel(),
            slip.kernel().lane_isa()
        )
    };
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let c = slip.components();
    match slip.eval(q, xi_s, xi_m0, &mut single) {
        Ok(()) => {
            let got = batch.slip(p).unwrap_or_else(|e| panic!("{}: {e}", what()));
            assert_eq!(bits(got), bits(single.slip()), "{}", what());
            assert_eq!(
                bits(batch.xi_m(p).unwrap()),
                bits(single.xi_m_all()),
                "{}",
                what()
            );
            for j in 0..c {
                assert_eq!(
                    bits(batch.grad(p, j).unwrap()),
                    bits(single.grad(j)),
                    "{}",
                    what()
                );
                match (batch.hess(p, j).unwrap(), single.hess(j)) {
                    (Some(a), Some(b)) => assert_eq!(bits(a), bits(b), "{}", what()),
                    (None, None) => {}
                    other => panic!("{}: Hessian presence differs: {other:?}", what()),
                }
            }
        }
        Err(e) => {
            let got = batch
                .status(p)
                .expect_err("the batch must fail where eval fails");
            assert_eq!(format!("{got:?}"), format!("{e:?}"), "{}", what());
            assert!(batch.slips()[c * p..c * (p + 1)].iter().all(|&v| v == 0.0));
        }
    }
}

#[test]
fn segment_slip_lanes_equal_eval_bit_for_bit_on_every_test_configuration() {
    let configs = common::configurations();
    let qs: Vec<f64> = configs.iter().flat_map(|c| c.q).collect();
    let xi_s: Vec<f64> = configs.iter().map(|c| c.xi_s).collect();
    let xi_m0: Vec<f64> = (0..configs.len())
        .flat_map(|i| xi_m0(i, &[xi_s[i]]))
        .collect();
    let (mut points, mut failures) = (0, 0);
    for f in pair_formulations() {
        for ty in ApproxType::ALL {
            for slip in lane_isas(Kernel::new(f, ty).unwrap()) {
                assert_eq!(slip.components(), 1);
                let mut batch = SlipBatch::new(&slip);
                for skip in 0..4 {
                    let ok = slip
                        .eval_batch(&qs[8 * skip..], &xi_s[skip..], &xi_m0[skip..], &mut batch)
                        .unwrap();
                    assert_eq!(batch.len(), configs.len() - skip);
                    for (p, c) in configs[skip..].iter().enumerate() {
                        let i = p + skip;
                        assert_point_equals_eval(
                            &slip,
                            &batch,
                            p,
                            &c.q,
                            &[c.xi_s],
                            &xi_m0[i..i + 1],
                        );
                    }
                    points += batch.len();
                    failures += batch.len() - ok;
                }
            }
        }
    }
    eprintln!("segment slip lanes: {points} points, {failures} failures matched");
    assert!(failures > 0 && failures < points);
}

#[test]
fn face_slip_batches_equal_eval_bit_for_bit_on_every_face_configuration() {
    let (mut points, mut failures) = (0, 0);
    for &(f, _, s, m) in &common::faces::FACES {
        let configs = common::faces::face_configurations(s, m);
        let qs: Vec<f64> = configs.iter().flat_map(|c| c.q.iter().copied()).collect();
        let xi_s: Vec<f64> = configs.iter().flat_map(|c| c.xi_s).collect();
        let xi_m0: Vec<f64> = configs
            .iter()
            .enumerate()
            .flat_map(|(i, c)| xi_m0(i, &c.xi_s))
            .collect();
        for ty in ApproxType::ALL {
            let kernel = Kernel::new(f, ty).unwrap();
            let n = kernel.coords();
            for slip in lane_isas(kernel) {
                assert_eq!(slip.components(), 3);
                let mut batch = SlipBatch::new(&slip);
                for skip in 0..4 {
                    let ok = slip
                        .eval_batch(
                            &qs[n * skip..],
                            &xi_s[2 * skip..],
                            &xi_m0[2 * skip..],
                            &mut batch,
                        )
                        .unwrap();
                    assert_eq!(batch.len(), configs.len() - skip);
                    for (p, c) in configs[skip..].iter().enumerate() {
                        let i = p + skip;
                        assert_point_equals_eval(
                            &slip,
                            &batch,
                            p,
                            &c.q,
                            &c.xi_s,
                            &xi_m0[2 * i..2 * i + 2],
                        );
                    }
                    points += batch.len();
                    failures += batch.len() - ok;
                }
            }
        }
    }
    eprintln!("face slip batches: {points} points, {failures} failures matched");
    assert!(failures > 0 && failures < points);
}

#[test]
fn mismatched_shapes_are_errors() {
    let f = pair_formulations()[0];
    let slip = Kernel::new(f, ApproxType::Type6).unwrap().slip().unwrap();
    let mut batch = SlipBatch::new(&slip);
    assert!(matches!(
        slip.eval_batch(&[0.0; 15], &[0.0, 0.0], &[0.0, 0.0], &mut batch),
        Err(KernelError::CoordinateCount { .. })
    ));
    assert!(matches!(
        slip.eval_batch(&[0.0; 16], &[0.0, 0.0], &[0.0], &mut batch),
        Err(KernelError::ParamCount { .. })
    ));
    assert_eq!(slip.eval_batch(&[], &[], &[], &mut batch), Ok(0));
    assert!(batch.is_empty());
    let face = Kernel::new(common::faces::FACES[0].0, ApproxType::Type6)
        .unwrap()
        .slip()
        .unwrap();
    assert!(matches!(
        face.eval_batch(&[], &[], &[], &mut batch),
        Err(KernelError::BufferSize { .. })
    ));
}
