//! The handles against the value API: same bits, reused buffers, typed
//! size errors; every `xi_s` argument form; what is compiled in.

use contact_kernels::*;

/// the worked example of docs/conventions.md.
const Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
const XI_S: f64 = 0.3;

/// A few configurations around the worked example (deterministic).
fn configurations() -> Vec<([f64; 8], f64)> {
    let mut out = vec![(Q, XI_S)];
    for k in 1..8 {
        let t = k as f64;
        let mut q = Q;
        for (i, v) in q.iter_mut().enumerate() {
            *v += 0.05 * (t * (i as f64 + 1.0)).sin() + 100.0 * (k % 3) as f64;
        }
        out.push((q, -0.9 + 0.25 * t));
    }
    out
}

#[test]
fn a_reused_gap_out_gives_the_bits_of_evaluate() {
    for f in pair_formulations() {
        for ty in ApproxType::ALL {
            let kernel = Kernel::new(f, ty).unwrap();
            assert_eq!(kernel.has_hessian(), ty.has_hessian());
            assert_eq!(kernel.op_count(), op_count(f, Some(ty)).unwrap());
            let mut out = GapOut::new(&kernel);
            // Fill the buffers with another type's values first: reuse must
            // not leak them.
            Kernel::new(f, ApproxType::Type6)
                .unwrap()
                .eval(&Q, XI_S, &mut out)
                .unwrap();
            for (q, xi_s) in configurations() {
                let want = evaluate(f, ty, &q, xi_s).unwrap();
                kernel.eval(&q, xi_s, &mut out).unwrap();
                assert_eq!(out.gap().to_bits(), want.gap.to_bits(), "{f} {ty}");
                assert_eq!(out.xi_m().to_bits(), want.xi_m.to_bits(), "{f} {ty}");
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(out.grad()), bits(want.grad.as_slice()), "{f} {ty}");
                match (out.hess(), want.hess) {
                    (None, None) => {}
                    (Some(h), Some(w)) => assert_eq!(bits(h), bits(w.as_slice()), "{f} {ty}"),
                    (h, w) => panic!("{f} {ty}: Hessian presence {h:?} vs {w:?}"),
                }
            }
        }
    }
}

#[test]
fn the_projector_gives_the_bits_of_project() {
    for f in pair_formulations() {
        let p = Projector::new(f).unwrap();
        let mut scratch = vec![0.0; p.coords()];
        for (q, xi_s) in configurations() {
            let want = project(f, &q, xi_s).unwrap();
            let got = p.project(&q, xi_s, &mut scratch).unwrap();
            assert_eq!(got.gap.to_bits(), want.gap.to_bits());
            assert_eq!(got.xi_m.to_bits(), want.xi_m.to_bits());
        }
    }
}

#[test]
fn wrong_sizes_are_typed_errors() {
    let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type3).unwrap();
    let mut out = GapOut::new(&kernel);
    assert_eq!(kernel.coords(), PAIR_COORDS);
    for len in [0, 6, 7, 9, 12] {
        let q = vec![0.5; len];
        assert_eq!(
            kernel.eval(&q, XI_S, &mut out),
            Err(KernelError::CoordinateCount {
                expected: 8,
                found: len
            })
        );
    }
    let mut small = GapOut::with_coords(6);
    assert_eq!(
        kernel.eval(&Q, XI_S, &mut small),
        Err(KernelError::BufferSize {
            expected: 8,
            found: 6
        })
    );
    let p = Projector::new(Formulation::SlaveNormal).unwrap();
    assert_eq!(
        p.project(&Q, XI_S, &mut [0.0; 7]),
        Err(KernelError::BufferSize {
            expected: 8,
            found: 7
        })
    );
    assert!(matches!(
        p.project(&Q[..6], XI_S, &mut [0.0; 8]),
        Err(KernelError::CoordinateCount { found: 6, .. })
    ));
    // Input errors index `q` as given; `xi_s` is `q.len()`.
    assert_eq!(
        kernel.eval(&Q, f64::NAN, &mut out).unwrap_err().to_string(),
        "non-finite input: coordinate 8 is NaN"
    );
}

/// `xi_s` as `f64`, `[f64; 1]`, `&[f64]` or `Vec<f64>`: one call, the same
/// bits; `xi_m_all` is `[xi_m]`; another length is a typed error.
#[test]
// The borrowed forms are the point: `&[f64; 1]` is one of them.
#[allow(clippy::needless_borrows_for_generic_args)]
fn every_xi_argument_form_is_the_scalar_call() {
    for f in pair_formulations() {
        let kernel = Kernel::new(f, ApproxType::Type6).unwrap();
        assert_eq!(kernel.param_dim(), 1);
        assert_eq!(f.param_dim(), Some(1));
        let (mut a, mut b) = (GapOut::new(&kernel), GapOut::new(&kernel));
        for (q, xi_s) in configurations() {
            kernel.eval(&q, xi_s, &mut a).unwrap();
            for form in 0..4 {
                match form {
                    0 => kernel.eval(&q, [xi_s], &mut b),
                    1 => kernel.eval(&q, &[xi_s][..], &mut b),
                    2 => kernel.eval(&q, vec![xi_s], &mut b),
                    _ => kernel.eval(&q, &[xi_s], &mut b),
                }
                .unwrap();
                assert_eq!(a, b, "{f} form {form}");
                assert_eq!(b.xi_m_all(), [b.xi_m()]);
            }
            let p = Projector::new(f).unwrap();
            assert_eq!(p.param_dim(), 1);
            let mut scratch = vec![0.0; p.coords()];
            let one = p.project(&q, xi_s, &mut scratch).unwrap();
            let slice = p.project(&q, &[xi_s][..], &mut scratch).unwrap();
            assert_eq!(one, slice);
            assert_eq!(one.xi_m_all(), [one.xi_m]);
        }
        for bad in [&[][..], &[0.1, 0.2][..], &[0.1, 0.2, 0.3][..]] {
            let want = Err(KernelError::ParamCount {
                expected: 1,
                found: bad.len(),
            });
            assert_eq!(kernel.eval(&Q, bad, &mut a), want);
            let p = Projector::new(f).unwrap();
            assert_eq!(p.project(&Q, bad, &mut [0.0; 8]).map(|_| ()), want);
        }
    }
    let e = KernelError::ParamCount {
        expected: 2,
        found: 1,
    };
    assert_eq!(
        e.to_string(),
        "expected 2 slave parametric coordinate(s), got 1"
    );
}

#[test]
fn formulations_not_compiled_in_are_reported() {
    for f in Formulation::ALL {
        let compiled = compiled_formulations().contains(&f);
        for ty in ApproxType::ALL {
            match Kernel::new(f, ty) {
                Ok(_) => assert!(compiled),
                Err(e) => {
                    assert!(!compiled);
                    assert_eq!(e, KernelError::NotCompiled(f));
                }
            }
        }
        assert_eq!(Projector::new(f).is_ok(), compiled);
    }
}

/// Every compiled formulation with a slip has its slip's lane kernels, so
/// `Slip::eval_batch` runs them: segments always, faces where the CPU has
/// AVX2 (their only build), and never on a portable face kernel.
#[test]
fn every_compiled_slip_has_lane_kernels() {
    let mut faces = 0;
    for f in compiled_formulations() {
        for ty in ApproxType::ALL {
            let k = Kernel::new(f, ty).unwrap();
            let scalar = k.slip().is_some();
            let face = k.param_dim() == 2;
            faces += usize::from(face);
            let avx2 = k.lane_isa() == LaneIsa::Avx2;
            assert_eq!(
                k.has_slip_lanes(),
                scalar && (!face || avx2),
                "{f:?} {ty:?}"
            );
            let portable = k.with_lane_isa(LaneIsa::Portable);
            assert_eq!(portable.has_slip_lanes(), scalar && !face, "{f:?} {ty:?}");
        }
    }
    assert_eq!(
        faces,
        8 * 6,
        "the eight face pairs are compiled in for tests"
    );
}

/// `XiArg`: every argument form gives its values.
#[test]
fn every_argument_form_gives_its_values() {
    assert_eq!(0.3.as_xi(), [0.3]);
    assert_eq!([0.2, -0.1].as_xi(), [0.2, -0.1]);
    assert_eq!(<&[f64; 2] as XiArg>::as_xi(&&[0.2, -0.1]), [0.2, -0.1]);
    let v = vec![0.5, 0.25];
    assert_eq!((&v[..]).as_xi(), [0.5, 0.25]);
    assert_eq!(<&Vec<f64> as XiArg>::as_xi(&&v), [0.5, 0.25]);
    assert_eq!(v.as_xi(), [0.5, 0.25]);
}
