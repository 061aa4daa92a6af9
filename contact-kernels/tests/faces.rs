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
