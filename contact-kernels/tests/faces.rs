//! 3D face kernels through the handles: the worked examples of
//! docs/conventions.md ("3D faces") to every printed digit, the slice
//! interface, validation errors and the batch.

use contact_kernels::{
    ApproxType, Formulation, GapBatch, GapOut, Kernel, KernelError, Projector, Segment,
};

/// A worked example: formulation, `q` (slave nodes then master nodes),
/// `xi_s`, and the printed `g`, `xi_m`, `g'[0..3]`, `g''[0][0..3]`.
struct Example {
    name: &'static str,
    q: &'static [f64],
    xi_s: [f64; 2],
    g: &'static str,
    xi_m: [&'static str; 2],
    grad: [&'static str; 3],
    hess: [&'static str; 3],
}

const QUAD: &[f64] = &[
    0.0, 0.0, 1.0, 0.0, 1.0, 1.1, 1.0, 1.0, 1.0, 1.0, 0.0, 0.9, // slave
    -0.2, -0.1, 0.8, 1.2, 0.0, 0.85, 1.1, 1.3, 0.75, -0.1, 1.2, 0.8, // master
];
const TRI: &[f64] = &[
    0.0, 0.0, 1.0, 0.1, 1.0, 1.05, 1.0, 0.1, 0.95, // slave
    -0.3, -0.2, 0.8, 1.4, 0.1, 0.85, 0.2, 1.5, 0.75, // master
];

const EXAMPLES: [Example; 4] = [
    Example {
        name: "quad4-slave-normal",
        q: QUAD,
        xi_s: [0.2, -0.1],
        g: "0.218076326621994",
        xi_m: ["-0.110497335826287", "0.0417194472152753"],
        grad: ["-0.000953472334217", "0.0083538721671", "0.215739398105"],
        hess: ["-0.000304926657037", "0.00181556552258", "0.00533739063435"],
    },
    Example {
        name: "quad4-closest-point",
        q: QUAD,
        xi_s: [0.2, -0.1],
        g: "0.215000086591845",
        xi_m: ["-0.0759095907202292", "-0.00591522445228139"],
        grad: ["-0.000651112677614", "0.00781805543079", "0.219860078372"],
        hess: [
            "-0.000474078606251",
            "0.00285040634233",
            "-0.000102762236522",
        ],
    },
    Example {
        name: "tri3-slave-normal",
        q: TRI,
        xi_s: [0.3, 0.25],
        g: "0.203900706766229",
        xi_m: ["0.254983710038689", "0.270469354510283"],
        grad: ["-0.0165821583512", "0.0182365997151", "0.452637528913"],
        hess: ["0.000971334372329", "-0.0010402673797", "0.0179626178838"],
    },
    Example {
        name: "tri3-closest-point",
        q: TRI,
        xi_s: [0.3, 0.25],
        g: "0.202111501551638",
        xi_m: ["0.270099406350851", "0.256393016986068"],
        grad: ["-0.0163992383156", "0.0180391621471", "0.449339129847"],
        hess: ["0", "0", "0"],
    },
];

/// `value` agrees with `printed` to its last printed digit: within half a
/// unit of that digit plus the rounding of any double-precision evaluation
/// (4 ulps of 1, the size of the configurations; the 16th decimals of
/// `xi_m` are at that level).
fn agrees(value: f64, printed: &str) -> bool {
    let want: f64 = printed.parse().unwrap();
    let decimals = printed.split('.').nth(1).map_or(0, str::len) as i32;
    let half_unit = 0.5 * 10f64.powi(-decimals);
    (value - want).abs() <= half_unit + 4.0 * f64::EPSILON
}

#[test]
fn the_worked_examples_to_every_printed_digit() {
    for ex in &EXAMPLES {
        let f: Formulation = ex.name.parse().unwrap();
        let k = Kernel::new(f, ApproxType::Type6).unwrap();
        assert_eq!(k.param_dim(), 2);
        assert_eq!(k.coords(), ex.q.len());
        let mut out = GapOut::new(&k);
        k.eval(ex.q, ex.xi_s, &mut out).unwrap();
        let n = k.coords();
        let hess = out.hess().unwrap();
        let got = [
            (out.gap(), ex.g),
            (out.xi_m_all()[0], ex.xi_m[0]),
            (out.xi_m_all()[1], ex.xi_m[1]),
            (out.grad()[0], ex.grad[0]),
            (out.grad()[1], ex.grad[1]),
            (out.grad()[2], ex.grad[2]),
            (hess[0], ex.hess[0]),
            (hess[1], ex.hess[1]),
            (hess[2], ex.hess[2]),
        ];
        for (i, (v, p)) in got.iter().enumerate() {
            assert!(agrees(*v, p), "{} value {i}: {v:.17e} vs {p}", ex.name);
        }
        // The Hessian is symmetric and the projector agrees.
        for j in 0..n {
            for l in 0..n {
                assert_eq!(hess[j * n + l].to_bits(), hess[l * n + j].to_bits());
            }
        }
        let p = Projector::new(f).unwrap();
        let mut scratch = vec![0.0; n];
        let pr = p.project(ex.q, &ex.xi_s[..], &mut scratch).unwrap();
        assert!(agrees(pr.gap, ex.g), "{}: {}", ex.name, pr.gap);
        assert_eq!(pr.xi_m_all().len(), 2);
        assert!(agrees(pr.xi_m_all()[1], ex.xi_m[1]));
        assert_eq!(pr.xi_m, pr.xi_m_all()[0]);
    }
}

fn kernel(name: &str) -> Kernel {
    Kernel::new(name.parse().unwrap(), ApproxType::Type6).unwrap()
}

fn eval(k: &Kernel, q: &[f64], xi_s: [f64; 2]) -> Result<f64, KernelError> {
    let mut out = GapOut::new(k);
    k.eval(q, xi_s, &mut out).map(|()| out.gap())
}

#[test]
fn bad_faces_and_points_are_typed_errors() {
    let k = kernel("quad4-slave-normal");
    let xi = [0.2, -0.1];
    // Degenerate slave: node 2 on node 1 (the normal vanishes at corner 0
    // and 1).
    let mut q = QUAD.to_vec();
    q[3..6].copy_from_slice(&[0.0, 0.0, 1.0]);
    assert!(matches!(
        eval(&k, &q, xi),
        Err(KernelError::DegenerateFace {
            face: Segment::Slave,
            corner: 0,
            ..
        })
    ));
    // A degenerate master tri3: its three nodes on a line (relative
    // threshold: scaled by 1e-9, still degenerate).
    let t = kernel("tri3-slave-normal");
    let mut q = TRI.to_vec();
    q[15..18].copy_from_slice(&[0.55, -0.05, 0.825]);
    for s in [1.0, 1e-9] {
        let qs: Vec<f64> = q.iter().map(|v| v * s).collect();
        assert!(
            matches!(
                eval(&t, &qs, [0.3, 0.25]),
                Err(KernelError::DegenerateFace {
                    face: Segment::Master,
                    ..
                })
            ),
            "scale {s}: {:?}",
            eval(&t, &qs, [0.3, 0.25])
        );
    }
    // A folded master quad4: nodes 3 and 4 swapped (a bow tie).
    let mut q = QUAD.to_vec();
    let (a, b) = (q[18..21].to_vec(), q[21..24].to_vec());
    q[18..21].copy_from_slice(&b);
    q[21..24].copy_from_slice(&a);
    assert!(matches!(
        eval(&k, &q, xi),
        Err(KernelError::FoldedFace {
            face: Segment::Master,
            ..
        })
    ));
    // Non-finite input: coordinates by index, xi_s after them.
    let mut q = QUAD.to_vec();
    q[7] = f64::NAN;
    assert_eq!(
        eval(&k, &q, xi).unwrap_err().to_string(),
        "non-finite input: coordinate 7 is NaN"
    );
    assert_eq!(
        eval(&k, QUAD, [0.2, f64::INFINITY])
            .unwrap_err()
            .to_string(),
        "non-finite input: coordinate 25 is inf"
    );
    // Outside the face: quad4 [-1, 1]^2 (edges accepted), tri3 the unit
    // triangle.
    assert!(eval(&k, QUAD, [1.0, -1.0]).is_ok());
    assert_eq!(
        eval(&k, QUAD, [1.0 + 1e-12, 0.0]),
        Err(KernelError::SlavePointOutside {
            u: 1.0 + 1e-12,
            v: 0.0
        })
    );
    assert!(eval(&t, TRI, [0.5, 0.5]).is_ok());
    assert!(matches!(
        eval(&t, TRI, [0.6, 0.5]),
        Err(KernelError::SlavePointOutside { .. })
    ));
    assert!(matches!(
        eval(&t, TRI, [-0.1, 0.5]),
        Err(KernelError::SlavePointOutside { .. })
    ));
    // Wrong lengths.
    let mut out = GapOut::new(&k);
    assert_eq!(
        k.eval(QUAD, 0.3, &mut out),
        Err(KernelError::ParamCount {
            expected: 2,
            found: 1
        })
    );
    assert_eq!(
        k.eval(&QUAD[..21], xi, &mut out),
        Err(KernelError::CoordinateCount {
            expected: 24,
            found: 21
        })
    );
}

/// Faces of two kinds in one pair: a tri3 slave on a quad4 master and a
/// quad4 slave on a tri3 master, each validated by its own kind.
#[test]
fn mixed_pairs_take_each_face_by_its_kind() {
    let tri_on_quad: Vec<f64> = TRI[..9].iter().chain(&QUAD[12..]).copied().collect();
    let quad_on_tri: Vec<f64> = QUAD[..12].iter().chain(&TRI[9..]).copied().collect();
    for reading in ["slave-normal", "closest-point"] {
        let k = kernel(&format!("tri3-quad4-{reading}"));
        assert_eq!(k.coords(), 21);
        let g = eval(&k, &tri_on_quad, [0.3, 0.25]).unwrap();
        assert!(g > 0.0 && g < 0.3, "{g}");
        // (0.6, 0.6) is on a quad4 but outside the tri3 slave.
        assert!(matches!(
            eval(&k, &tri_on_quad, [0.6, 0.6]),
            Err(KernelError::SlavePointOutside { .. })
        ));
        let k = kernel(&format!("quad4-tri3-{reading}"));
        assert_eq!(k.coords(), 21);
        assert!(eval(&k, &quad_on_tri, [-0.6, 0.6]).is_ok());
        // The master tri3 folded cannot be; its nodes on a line are
        // degenerate.
        let mut q = quad_on_tri.clone();
        q[18..21].copy_from_slice(&[0.55, -0.05, 0.825]);
        assert!(matches!(
            eval(&k, &q, [0.0, 0.0]),
            Err(KernelError::DegenerateFace {
                face: Segment::Master,
                ..
            })
        ));
    }
}

/// A master perpendicular to the slave: the slave-normal projection has no
/// solution (det A = 0) on a tri3 master (closed form) and a quad4 master
/// (Newton).
#[test]
fn no_projection_is_reported_not_returned() {
    // Master faces in the plane x = 2, perpendicular to the slave (z = 1).
    let tri = [
        0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, // slave
        2.0, 0.0, 0.0, 2.0, 1.0, 0.0, 2.0, 0.0, 2.0, // master
    ];
    match eval(&kernel("tri3-slave-normal"), &tri, [0.3, 0.3]) {
        Err(KernelError::NoProjection { .. }) => {}
        other => panic!("{other:?}"),
    }
    let quad = [
        0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0, // slave
        2.0, 0.0, 0.0, 2.0, 1.0, 0.0, 2.0, 1.0, 2.0, 2.0, 0.0, 2.0, // master
    ];
    match eval(&kernel("quad4-slave-normal"), &quad, [0.0, 0.0]) {
        Err(KernelError::NoProjection { .. } | KernelError::ProjectionOutOfReach { .. }) => {}
        other => panic!("{other:?}"),
    }
}

/// The batch of a face kernel (its lane kernels): each point the bits and
/// the error of `Kernel::eval`; `xi_s` two values per point.
#[test]
fn the_face_batch_is_eval_point_by_point() {
    let k = kernel("quad4-closest-point");
    assert_eq!(k.param_dim(), 2);
    let mut qs = Vec::new();
    let mut xs = Vec::new();
    for p in 0..7 {
        let mut q = QUAD.to_vec();
        q[13] += 0.01 * p as f64;
        if p == 3 {
            q[0] = f64::NAN;
        }
        qs.extend(q);
        xs.extend([0.1 * p as f64 - 0.3, 0.05 * p as f64]);
    }
    let mut batch = GapBatch::new(&k);
    let ok = k.eval_batch(&qs, &xs, &mut batch).unwrap();
    assert_eq!((ok, batch.len()), (6, 7));
    let mut out = GapOut::new(&k);
    for p in 0..7 {
        let single = k.eval(&qs[24 * p..24 * (p + 1)], &xs[2 * p..2 * p + 2], &mut out);
        match single {
            Ok(()) => {
                assert_eq!(batch.gap(p).unwrap().0.to_bits(), out.gap().to_bits());
                assert_eq!(batch.xi_m(p).unwrap(), out.xi_m_all());
                assert_eq!(batch.grad(p).unwrap(), out.grad());
                assert_eq!(batch.hess(p).unwrap(), out.hess());
            }
            Err(e) => {
                // (NaN fields: compare the messages.)
                assert_eq!(batch.status(p).unwrap_err().to_string(), e.to_string());
                assert_eq!(&batch.xi_ms()[2 * p..2 * p + 2], [0.0, 0.0]);
            }
        }
    }
    assert_eq!(
        k.eval_batch(&qs, &xs[..13], &mut batch),
        Err(KernelError::ParamCount {
            expected: 2,
            found: 13
        })
    );
}
