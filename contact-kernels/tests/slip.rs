//! The slip's worked examples of docs/conventions.md ("The slip"), pinned
//! to every printed digit (within half a unit of the last digit plus 4
//! ulps of 1), and the slip handle's buffer checks.

use contact_kernels::{ApproxType, Formulation, Kernel, KernelError, SlipOut};

/// `got` equals the printed `want` to its last digit.
fn digits(got: f64, want: &str) {
    let w: f64 = want.parse().unwrap();
    let decimals = want.split('.').nth(1).map_or(0, str::len) as i32;
    let tol = 0.5 * 10f64.powi(-decimals) + 4.0 * f64::EPSILON;
    assert!((got - w).abs() <= tol, "{got} is not {want}");
}

const Q2: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
const Q3: [f64; 24] = [
    0.0, 0.0, 1.0, 0.0, 1.0, 1.1, 1.0, 1.0, 1.0, 1.0, 0.0, 0.9, -0.2, -0.1, 0.8, 1.2, 0.0, 0.85,
    1.1, 1.3, 0.75, -0.1, 1.2, 0.8,
];

#[test]
fn the_segment_worked_example() {
    let cases = [
        (
            Formulation::SlaveNormal,
            "0.0861423892282",
            [
                "0.352577010203",
                "-0.0427956659919",
                "0.646175328674",
                "0.0927332829358",
            ],
            [
                "0.00208087637722",
                "-0.0114806115831",
                "-0.00332620348305",
                "0.0363871536998",
            ],
        ),
        (
            Formulation::ClosestPoint,
            "0.0742415256020",
            [
                "0.349638989074",
                "-0.0158926813215",
                "0.649329551137",
                "-0.0295149795971",
            ],
            ["0", "0", "0", "0"],
        ),
    ];
    for (f, s, grad, hess) in cases {
        let slip = Kernel::new(f, ApproxType::Type6).unwrap().slip().unwrap();
        let mut out = SlipOut::new(&slip);
        slip.eval(&Q2, 0.3, -0.2, &mut out).unwrap();
        digits(out.slip()[0], s);
        for (g, w) in out.grad(0).iter().zip(grad) {
            digits(*g, w);
        }
        for (h, w) in out.hess(0).unwrap().iter().zip(hess) {
            digits(*h, w);
        }
    }
    // Type 1 keeps only the master nodes' part, N(xi_m) - N(xi_m0) along
    // the tangent.
    let slip = Kernel::new(Formulation::SlaveNormal, ApproxType::Type1)
        .unwrap()
        .slip()
        .unwrap();
    let mut out = SlipOut::new(&slip);
    slip.eval(&Q2, 0.3, -0.2, &mut out).unwrap();
    digits(out.slip()[0], "0.0861423892282");
    assert_eq!(&out.grad(0)[..4], [0.0; 4]);
    digits(out.grad(0)[4], "0.0392448242498");
    assert!(out.hess(0).is_none());
}

#[test]
fn the_face_worked_example() {
    let cases = [
        (
            "quad4-slave-normal",
            ["-0.0705882352941", "0.0205882352941", "0.00911764705882"],
        ),
        (
            "quad4-closest-point",
            ["-0.0493636520761", "-0.00764077173329", "0.000125510176605"],
        ),
    ];
    for (name, s) in cases {
        let f: Formulation = name.parse().unwrap();
        let slip = Kernel::new(f, ApproxType::Type6).unwrap().slip().unwrap();
        assert_eq!(slip.components(), 3);
        let mut out = SlipOut::new(&slip);
        slip.eval(&Q3, [0.2, -0.1], [0.0, 0.0], &mut out).unwrap();
        for (got, want) in out.slip().iter().zip(s) {
            digits(*got, want);
        }
        assert_eq!(out.grad(2).len(), 24);
        assert_eq!(out.hess(2).unwrap().len(), 24 * 24);
    }
}

#[test]
fn buffers_of_another_size_are_refused() {
    let segment = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6)
        .unwrap()
        .slip()
        .unwrap();
    let face = Kernel::new("quad4-slave-normal".parse().unwrap(), ApproxType::Type6)
        .unwrap()
        .slip()
        .unwrap();
    let mut out = SlipOut::new(&face);
    let e = segment.eval(&Q2, 0.3, -0.2, &mut out).unwrap_err();
    assert!(
        matches!(e, KernelError::BufferSize { expected: 8, .. }),
        "{e}"
    );
}
