//! Verification of every generated contact kernel against automatic
//! differentiation (num-dual hyper-dual numbers).
//!
//! The reference is the verifier of `gapsim verify` ([`gapsim::verify`]),
//! one library for both: num-dual hyper-dual numbers over the shipped
//! formulation files' expressions, independent of the generator's
//! derivative pipeline (no symbolic differentiation, truncation, jets or
//! lowering):
//!
//! * `xi_m(q)` by Newton's method on the formulation's residual, continued
//!   in dual arithmetic (implicit differentiation by AD).
//! * Type 6 is compared with num-dual's full gradient and Hessian of
//!   `g(q) = gap(E(q, xi_m(q)))` ([`exact_reference`]).
//! * Types 1–5 are compared with the truncated formula, assembled from
//!   num-dual partial derivatives of the entities `x_ms(q, xi)` and
//!   `n(q, xi)` (taken at a fixed, independent `xi`), of `xi_m(q)` and of
//!   the gap as a function of the entities ([`truncated_reference`]).
//! * [`the_verifier_passes_on_the_compiled_kernels`] runs the verifier's own
//!   loop (`gapsim::verify::verify`, every family) on the compiled kernels.
//!
//! The hard-family tests below draw from the verifier's generators
//! ([`gapsim::verify::families`]).
//!
//! ## Tolerances
//!
//! Unless a test says otherwise, an assertion is relative to the norm of the
//! reference block, with a floor at the block's natural scale so that
//! nearly-zero blocks are not compared at the round-off level. With `L` the
//! size of the configuration (largest coordinate difference from slave node
//! 1, as the kernels measure it):
//!
//! | block | error bound |
//! |---|---|
//! | `g`    | `tol * max(|g_ref|, L)` |
//! | `xi_m` | `tol * (1 + |xi_ref|)` |
//! | `g'`   | `tol * max(‖g'_ref‖, 1)` (Euclidean norm) |
//! | `g''`  | `tol * max(‖g''_ref‖_F, 1 / L)` (Frobenius norm) |
//!
//! `g` scales like `L`, `g'` like 1 and `g''` like `1 / L`, so these bounds
//! are scale-free. The default `tol` is [`TOL`] = 1e-10: both computations
//! are accurate to ~1e-14 on well-conditioned input, so this leaves four
//! orders of magnitude for the amplification by the projection's conditioning
//! (`1 / cos` of the slave–master angle for `xi'`, its square for `xi''`).

use contact_kernels::{
    ApproxType, EntityOrder, Formulation, GapDerivatives, GapOut, Kernel, KernelError, Projector,
    Segment, evaluate, op_count, project,
};
use gapsim::verify::families::{Normal, Shape, WORKED_Q, WORKED_XI_S, seeded};
use gapsim::verify::reference::TABLE;
use gapsim::verify::{self, AdFormulation, KernelOutput};
use nalgebra::{Matrix2, SMatrix, SVector};
use proptest::prelude::*;
use rand::Rng;

type V8 = SVector<f64, 8>;
type M8 = SMatrix<f64, 8, 8>;

/// Default relative tolerance (see the module documentation): the
/// verifier's.
const TOL: f64 = verify::TOL;

// ---------------------------------------------------------------------------
// References: the verifier's AD of the shipped formulation files.
// ---------------------------------------------------------------------------

/// The verifier's AD formulation of `f`, parsed once per test thread from
/// its file (a parsed formulation holds syn nodes, which stay on their
/// thread; the two leaked per thread are small).
fn ad(f: Formulation) -> &'static AdFormulation {
    fn parse(name: &str) -> &'static AdFormulation {
        let path = format!(
            "{}/contact-kernels/formulations/{name}.rs",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(&path).expect("read the formulation file");
        Box::leak(Box::new(
            AdFormulation::parse(name, &text).expect("the shipped formulation parses"),
        ))
    }
    thread_local! {
        static AD: [&'static AdFormulation; 3] = [
            parse("slave-normal"),
            parse("closest-point"),
            parse("quadratic-slave-normal"),
        ];
    }
    AD.with(|a| match f {
        Formulation::SlaveNormal => a[0],
        Formulation::ClosestPoint => a[1],
        Formulation::QuadraticSlaveNormal => a[2],
        _ => unreachable!("this file verifies the segment formulations"),
    })
}

/// The normal a constructed configuration's gap is measured along: the
/// formulation's own.
fn normal(f: Formulation) -> Normal {
    match f {
        Formulation::SlaveNormal | Formulation::QuadraticSlaveNormal => Normal::Slave,
        Formulation::ClosestPoint => Normal::Master,
        // Faces have their own families (families::faces).
        Formulation::Tri3SlaveNormal
        | Formulation::Tri3ClosestPoint
        | Formulation::Quad4SlaveNormal
        | Formulation::Quad4ClosestPoint
        | Formulation::Tri3Quad4SlaveNormal
        | Formulation::Tri3Quad4ClosestPoint
        | Formulation::Quad4Tri3SlaveNormal
        | Formulation::Quad4Tri3ClosestPoint => {
            unreachable!("the segment families take segment formulations")
        }
    }
}

/// The reference's projection `xi_m(q)` (Newton on the residual), `None`
/// beyond `|xi_m| = limit`.
fn reference_xi(f: Formulation, q: &[f64; 8], xi_s: f64, limit: f64) -> Option<f64> {
    ad(f).project(q, &[xi_s], limit).map(|xi| xi[0])
}

fn to_array<D: Copy, const N: usize>(v: &SVector<D, N>) -> [D; N] {
    std::array::from_fn(|i| v[i])
}

/// A reference value of the gap and its (kept) derivatives.
#[derive(Debug, Clone)]
struct Reference {
    gap: f64,
    xi_m: f64,
    grad: V8,
    hess: M8,
}

impl From<verify::Reference> for Reference {
    fn from(r: verify::Reference) -> Reference {
        Reference {
            gap: r.gap,
            xi_m: r.xi_m,
            grad: V8::from_column_slice(&r.grad),
            // Row-major and symmetric: the same entries.
            hess: M8::from_row_slice(&r.hess),
        }
    }
}

impl From<&Reference> for verify::Reference {
    fn from(r: &Reference) -> verify::Reference {
        verify::Reference {
            gap: r.gap,
            xi_m: r.xi_m,
            xi_rest: Vec::new(),
            grad: r.grad.as_slice().to_vec(),
            hess: r.hess.transpose().as_slice().to_vec(),
        }
    }
}

/// What the verifier compares: the kernel's output, Hessian row-major.
fn kernel_output(out: &GapDerivatives) -> KernelOutput {
    KernelOutput {
        gap: out.gap,
        xi_m: out.xi_m,
        xi_rest: Vec::new(),
        grad: out.grad.as_slice().to_vec(),
        hess: out.hess.map(|h| h.transpose().as_slice().to_vec()),
    }
}

/// Type 6: num-dual's full gradient and Hessian of the gap.
fn exact_reference(f: Formulation, q: &[f64; 8], xi_s: f64) -> Reference {
    let xi0 = reference_xi(f, q, xi_s, 1e6).expect("the reference projects");
    ad(f).exact(q, &[xi_s], &[xi0]).expect("reference").into()
}

/// The truncated `g`, `g'`, `g''` for one row of the table, assembled by
/// the verifier from num-dual partial derivatives of the entities.
fn truncated_reference(
    f: Formulation,
    row: [codegen::EntityOrder; 3],
    q: &[f64; 8],
    xi_s: f64,
) -> Reference {
    let xi0 = reference_xi(f, q, xi_s, 1e6).expect("the reference projects");
    ad(f)
        .truncated(q, &[xi_s], &[xi0], row)
        .expect("reference")
        .into()
}

/// the truncation table of docs/conventions.md as the verifier writes it
/// (independently of the generator).
fn table_row(ty: ApproxType) -> [codegen::EntityOrder; 3] {
    TABLE[ty.index() - 1]
}

/// The kernels' name for a table entry.
fn kernel_order(o: codegen::EntityOrder) -> EntityOrder {
    match o {
        codegen::EntityOrder::Constant => EntityOrder::Constant,
        codegen::EntityOrder::Linear => EntityOrder::Linear,
        codegen::EntityOrder::Quadratic => EntityOrder::Quadratic,
    }
}

/// The reference for `(f, ty)`: Type 6 from the full num-dual Hessian, the
/// others from the truncated formula.
fn reference(f: Formulation, ty: ApproxType, q: &[f64; 8], xi_s: f64) -> Reference {
    match ty {
        ApproxType::Type6 => exact_reference(f, q, xi_s),
        _ => truncated_reference(f, table_row(ty), q, xi_s),
    }
}

/// `q` shifted so that slave node 1 is at the origin (exact in floating
/// point for configurations whose coordinates share their binade).
fn relative_to_slave_node_1(q: &[f64; 8]) -> [f64; 8] {
    std::array::from_fn(|i| q[i] - q[i % 2])
}

/// The configuration's size `L`: the largest coordinate difference from
/// slave node 1 (the kernels' own measure).
fn size(q: &[f64; 8]) -> f64 {
    verify::size(&relative_to_slave_node_1(q))
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// `t_s = xs2 - xs1`.
fn slave_tangent(q: &[f64; 8]) -> [f64; 2] {
    sub([q[2], q[3]], [q[0], q[1]])
}

/// `t_m = xm2 - xm1`.
fn master_tangent(q: &[f64; 8]) -> [f64; 2] {
    sub([q[6], q[7]], [q[4], q[5]])
}

/// A unit-size configuration used by the transformation tests.
fn unit_shape() -> Shape {
    Shape::unit()
}

// ---------------------------------------------------------------------------
// Comparison.
// ---------------------------------------------------------------------------

/// The scaled errors of a kernel result against a reference (each block's
/// error divided by its bound at `tol = 1`, see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
struct Errors {
    gap: f64,
    xi_m: f64,
    grad: f64,
    hess: f64,
}

impl Errors {
    fn max(&self) -> f64 {
        self.gap.max(self.xi_m).max(self.grad).max(self.hess)
    }
    fn worst(self, other: Errors) -> Errors {
        Errors {
            gap: self.gap.max(other.gap),
            xi_m: self.xi_m.max(other.xi_m),
            grad: self.grad.max(other.grad),
            hess: self.hess.max(other.hess),
        }
    }
}

fn errors(out: &GapDerivatives, r: &Reference, ty: ApproxType, l: f64) -> Errors {
    let e = verify::scaled_errors(&kernel_output(out), &r.into(), l);
    let hess = match (ty.has_hessian(), out.hess) {
        (true, Some(_)) | (false, None) => e.hess,
        (true, None) | (false, Some(_)) => f64::INFINITY,
    };
    Errors {
        gap: e.gap,
        xi_m: e.xi_m,
        grad: e.grad,
        hess,
    }
}

/// Evaluates `(f, ty)` at `q` and asserts it matches `r` within `tol`
/// (relative to each block's norm, see the module documentation). Returns
/// the scaled errors.
#[track_caller]
fn assert_matches(
    what: &str,
    f: Formulation,
    ty: ApproxType,
    q: &[f64; 8],
    xi_s: f64,
    r: &Reference,
    tol: f64,
) -> Errors {
    let out = evaluate(f, ty, q, xi_s).unwrap_or_else(|e| {
        panic!("{what}: {f} type {ty} q={q:?} xi_s={xi_s}: unexpected error {e}")
    });
    assert_eq!(
        out.hess.is_some(),
        ty.has_hessian(),
        "{what}: {f} type {ty}: Hessian presence"
    );
    let e = errors(&out, r, ty, size(q));
    assert!(
        e.max() <= tol,
        "{what}: {f} type {ty}, q={q:?}, xi_s={xi_s}: scaled errors {e:?} exceed {tol:e}\n\
         kernel: gap {} xi_m {}\n grad {:?}\n hess {:?}\n\
         reference: gap {} xi_m {}\n grad {:?}\n hess {:?}",
        out.gap,
        out.xi_m,
        out.grad.as_slice(),
        out.hess.map(|h| h.as_slice().to_vec()),
        r.gap,
        r.xi_m,
        r.grad.as_slice(),
        r.hess.as_slice(),
    );
    e
}

/// Checks every type of formulation `f` at `q` against the references
/// computed at `q_ref` (the same configuration, possibly in shifted
/// coordinates).
#[track_caller]
fn check_all_types(
    what: &str,
    f: Formulation,
    q: &[f64; 8],
    q_ref: &[f64; 8],
    xi_s: f64,
    tol: f64,
) -> Errors {
    let mut worst = Errors::default();
    for ty in ApproxType::ALL {
        let r = reference(f, ty, q_ref, xi_s);
        worst = worst.worst(assert_matches(what, f, ty, q, xi_s, &r, tol));
    }
    worst
}

// ---------------------------------------------------------------------------
// The reference itself (independent of the kernels).
// ---------------------------------------------------------------------------

/// The published worked example of docs/conventions.md (the digits printed there).
struct Published {
    gap: f64,
    xi_m: f64,
    grad: [f64; 8],
    hess_row0: [f64; 8],
}

fn published(f: Formulation) -> Published {
    match f {
        Formulation::SlaveNormal => Published {
            gap: 0.129090446096668,
            xi_m: -0.278587699316629,
            grad: [
                0.0162732380162,
                0.345075719401,
                0.0293417606046,
                0.658454250255,
                -0.0291613880704,
                -0.641550537549,
                -0.0164536105503,
                -0.361979432107,
            ],
            hess_row0: [
                0.00046515059696,
                -0.00462332803342,
                -0.000356320738686,
                0.00701758491545,
                -0.00741001952566,
                -0.163020429564,
                0.00730118966738,
                0.160626172682,
            ],
        },
        Formulation::ClosestPoint => Published {
            gap: 0.128503680399779,
            xi_m: -0.267422680412371,
            grad: [
                0.0158926813215,
                0.349638989074,
                0.0295149795971,
                0.649329551137,
                -0.0287753496564,
                -0.63305769244,
                -0.0166323112623,
                -0.36591084777,
            ],
            hess_row0: [
                0.0,
                0.0,
                0.0,
                0.0,
                -0.00720905132111,
                -0.158599129064,
                0.00720905132111,
                0.158599129064,
            ],
        },
        _ => panic!("the worked example is published for the two-node formulations"),
    }
}

/// Compares with the published digits: relative 1e-10 per entry, plus an
/// absolute 1e-13 for the entries printed as exact zeros (the printed values
/// carry 11–15 significant digits, i.e. a rounding error below 1e-11
/// relative).
#[track_caller]
fn assert_published(
    what: &str,
    gap: f64,
    xi_m: f64,
    grad: &[f64],
    hess_row0: Option<&[f64]>,
    p: &Published,
) {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * b.abs() + 1e-13;
    assert!(
        close(gap, p.gap),
        "{what}: gap {gap} vs published {}",
        p.gap
    );
    assert!(
        close(xi_m, p.xi_m),
        "{what}: xi_m {xi_m} vs published {}",
        p.xi_m
    );
    for i in 0..8 {
        assert!(
            close(grad[i], p.grad[i]),
            "{what}: grad[{i}] {} vs published {}",
            grad[i],
            p.grad[i]
        );
        if let Some(h) = hess_row0 {
            assert!(
                close(h[i], p.hess_row0[i]),
                "{what}: hess[0][{i}] {} vs published {}",
                h[i],
                p.hess_row0[i]
            );
        }
    }
}

#[test]
fn reference_reproduces_the_worked_example() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let r = exact_reference(f, &WORKED_Q, WORKED_XI_S);
        let row: Vec<f64> = r.hess.row(0).iter().copied().collect();
        assert_published(
            &format!("num-dual reference, {f}"),
            r.gap,
            r.xi_m,
            r.grad.as_slice(),
            Some(&row),
            &published(f),
        );
    }
}

/// The truncated formula with every entity quadratic is the chain rule
/// itself: it must equal num-dual's full Hessian (to 1e-12 relative to the
/// block norms). This validates the test's own assembly of Types 1–5.
#[test]
fn reference_truncation_with_everything_quadratic_is_exact() {
    let mut rng = seeded(11);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        for _ in 0..50 {
            let s = Shape::random(&mut rng);
            let q = s.q(normal(f));
            let exact = exact_reference(f, &q, s.xi_s);
            let full = truncated_reference(f, table_row(ApproxType::Type6), &q, s.xi_s);
            let l = size(&q);
            assert!((exact.gap - full.gap).abs() <= 1e-12 * l);
            assert!(
                (exact.xi_m - s.xi_m).abs() <= 1e-12 * (1.0 + s.xi_m.abs()),
                "constructed xi_m"
            );
            assert!((exact.gap - s.gap).abs() <= 1e-12 * l, "constructed gap");
            assert!((exact.grad - full.grad).norm() <= 1e-12 * exact.grad.norm().max(1.0));
            assert!((exact.hess - full.hess).norm() <= 1e-12 * exact.hess.norm().max(1.0 / l));
        }
    }
}

/// The generated truncation table (the compiled kernels' and the
/// generator's) is the verifier's copy of docs/conventions.md's.
#[test]
fn truncation_table_matches_design() {
    for ty in ApproxType::ALL {
        assert_eq!(ty.orders(), table_row(ty).map(kernel_order), "type {ty}");
    }
    assert_eq!(codegen::TYPES, TABLE, "codegen's table");
}

/// The verifier's own loop (`gapsim verify`'s, every family of
/// [`gapsim::verify::families`], constructed along the formulation's
/// normal) on the compiled kernels: every type of both formulations passes
/// at [`TOL`], and nearly every configuration is compared.
#[test]
fn the_verifier_passes_on_the_compiled_kernels() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let kernel = |ty: usize, q: &[f64], params: &[f64]| {
            let ty = ApproxType::from_index(ty).expect("1..=6");
            let q: &[f64; 8] = q.try_into().expect("8 coordinates");
            evaluate(f, ty, q, params[0])
                .ok()
                .map(|o| kernel_output(&o))
        };
        let configs = verify::families::all(normal(f));
        let report = verify::verify(ad(f), &kernel, &configs, TOL).expect("verifier runs");
        eprintln!("{report}");
        assert!(report.passed(), "{f}:\n{report}");
        assert!(
            report.checked * 10 >= configs.len() * 9,
            "{f}: only {} of {} configurations compared",
            report.checked,
            configs.len()
        );
    }
}

/// The same verifier loop on the compiled 3-node kernels
/// (`quadratic-slave-normal`, 12 coordinates, through [`Kernel::eval`]) and
/// the verifier's 3-node families ([`verify::configurations`]: curved,
/// near-straight, strongly curved, uniform, far, scales, rotations, steep,
/// ends), every type within [`TOL`].
#[test]
fn the_verifier_passes_on_the_compiled_quadratic_kernels() {
    let f = Formulation::QuadraticSlaveNormal;
    let handles: Vec<Kernel> = ApproxType::ALL
        .iter()
        .map(|&ty| Kernel::new(f, ty).expect("the workspace tests compile it in"))
        .collect();
    let kernel = |ty: usize, q: &[f64], params: &[f64]| {
        let k = &handles[ty - 1];
        let mut out = GapOut::new(k);
        k.eval(q, params[0], &mut out).ok().map(|()| KernelOutput {
            gap: out.gap(),
            xi_m: out.xi_m(),
            xi_rest: Vec::new(),
            grad: out.grad().to_vec(),
            hess: out.hess().map(<[f64]>::to_vec),
        })
    };
    let configs = verify::configurations(ad(f)).expect("3-node families");
    assert!(configs.iter().all(|c| c.q.len() == 12));
    let report = verify::verify(ad(f), &kernel, &configs, TOL).expect("verifier runs");
    eprintln!("{report}");
    assert!(report.passed(), "{f}:\n{report}");
    assert!(
        report.checked * 10 >= configs.len() * 8,
        "{f}: only {} of {} configurations compared",
        report.checked,
        configs.len()
    );
}

// ---------------------------------------------------------------------------
// Kernels against the references.
// ---------------------------------------------------------------------------

/// the worked example of docs/conventions.md, Type 6, both formulations, against the
/// printed digits (relative 1e-10 per entry).
#[test]
fn worked_example_type6() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let out = evaluate(f, ApproxType::Type6, &WORKED_Q, WORKED_XI_S)
            .expect("worked example evaluates");
        let h = out.hess.expect("Type 6 has a Hessian");
        let row: Vec<f64> = h.row(0).iter().copied().collect();
        assert_published(
            &format!("kernel, {f}"),
            out.gap,
            out.xi_m,
            out.grad.as_slice(),
            Some(&row),
            &published(f),
        );
        let p = project(f, &WORKED_Q, WORKED_XI_S).expect("worked example projects");
        assert_published(
            &format!("projection, {f}"),
            p.gap,
            p.xi_m,
            out.grad.as_slice(),
            None,
            &published(f),
        );
    }
}

/// Every type of both formulations at the worked example against the
/// references (tolerance [`TOL`]).
#[test]
fn worked_example_all_types() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        check_all_types("worked example", f, &WORKED_Q, &WORKED_Q, WORKED_XI_S, TOL);
    }
}

/// 400 seeded random constructed configurations per formulation (slave
/// length 0.2–5 at any direction, master 0.2–5 at ±57° from facing the
/// slave, xi_s in [-1, 1], xi_m in [-1.2, 1.2], gap ±0.5 slave lengths,
/// slave node 1 in [-10, 10]²), every type. Tolerance [`TOL`].
#[test]
fn random_constructed_configurations() {
    let mut rng = seeded(0x6a95_0001);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let mut worst = Errors::default();
        for k in 0..400 {
            let s = Shape::random(&mut rng);
            let q = s.q(normal(f));
            worst = worst.worst(check_all_types(
                &format!("random #{k}"),
                f,
                &q,
                &q,
                s.xi_s,
                TOL,
            ));
        }
        eprintln!("{f}: worst scaled errors over 400 random configurations: {worst:?}");
    }
}

/// 400 seeded uniformly random coordinate sets in [-2, 2]^8 per formulation,
/// every type, skipping only ill-posed draws (a segment shorter than 0.1, a
/// projection condition `|t_m . t| / (|t_m| |t|) < 0.1` or `|xi_m| > 5`).
/// Tolerance [`TOL`]; at least half the draws must be kept.
#[test]
fn random_uniform_configurations() {
    let mut rng = seeded(0x6a95_0002);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let mut kept = 0;
        let mut worst = Errors::default();
        for k in 0..400 {
            let q: [f64; 8] = std::array::from_fn(|_| rng.random_range(-2.0..2.0));
            let xi_s = rng.random_range(-1.0..=1.0);
            let t_s = slave_tangent(&q);
            let t_m = master_tangent(&q);
            let (ls, lm) = (dot(t_s, t_s).sqrt(), dot(t_m, t_m).sqrt());
            let cond = match f {
                Formulation::SlaveNormal | Formulation::QuadraticSlaveNormal => {
                    dot(t_m, t_s).abs() / (ls * lm)
                }
                Formulation::ClosestPoint => 1.0,
                _ => unreachable!("segment pairs only"),
            };
            if ls < 0.1 || lm < 0.1 || cond < 0.1 || reference_xi(f, &q, xi_s, 5.0).is_none() {
                continue;
            }
            kept += 1;
            worst = worst.worst(check_all_types(
                &format!("uniform #{k}"),
                f,
                &q,
                &q,
                xi_s,
                TOL,
            ));
        }
        eprintln!("{f}: {kept}/400 uniform draws kept; worst scaled errors {worst:?}");
        assert!(kept >= 200, "{f}: only {kept} of 400 draws were well-posed");
    }
}

/// Far from the origin: configurations offset by ~1e6. The reference is
/// num-dual evaluated in coordinates relative to slave node 1 (the same
/// configuration, shifted exactly): num-dual in absolute coordinates would
/// itself lose ~6 digits to cancellation (1e6 · 2.2e-16 ≈ 2e-10 absolute
/// on O(1) differences, amplified in g''), so it could not tell an accurate
/// kernel from an inaccurate one. Tolerance [`TOL`].
#[test]
fn far_from_origin() {
    let mut rng = seeded(0x6a95_0003);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let mut worst = Errors::default();
        for k in 0..100 {
            let mut s = Shape::random(&mut rng);
            s.origin = [
                1e6 + rng.random_range(-1.0..1.0),
                -1e6 + rng.random_range(-1.0..1.0),
            ];
            let q = s.q(normal(f));
            let q_rel = relative_to_slave_node_1(&q);
            worst = worst.worst(check_all_types(
                &format!("far #{k}"),
                f,
                &q,
                &q_rel,
                s.xi_s,
                TOL,
            ));
        }
        eprintln!("{f}: far from origin, worst scaled errors {worst:?}");
    }
}

/// Tiny and huge configurations (scale 1e-6 and 1e6). Checked twice:
/// against num-dual at that scale with the scale-free bounds of the module
/// documentation (g relative to L, g' to 1, g'' to 1/L), and against the
/// kernel's own unit-scale result through the scaling laws g(sq) = s g(q),
/// g'(sq) = g'(q), g''(sq) = g''(q) / s (relative 1e-10 of each block).
#[test]
fn tiny_and_huge_scales() {
    let mut rng = seeded(0x6a95_0004);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        for k in 0..40 {
            let mut unit = Shape::random(&mut rng);
            unit.origin = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let q1 = unit.q(normal(f));
            for s in [1e-6, 1e6] {
                let q: [f64; 8] = q1.map(|v| v * s);
                check_all_types(&format!("scale {s:e} #{k}"), f, &q, &q, unit.xi_s, TOL);
                for ty in ApproxType::ALL {
                    let a = evaluate(f, ty, &q1, unit.xi_s).unwrap();
                    let b = evaluate(f, ty, &q, unit.xi_s).unwrap();
                    let scaled = GapDerivatives {
                        gap: b.gap / s,
                        xi_m: b.xi_m,
                        grad: b.grad,
                        hess: b.hess.map(|h| h * s),
                    };
                    let r = Reference {
                        gap: a.gap,
                        xi_m: a.xi_m,
                        grad: a.grad,
                        hess: a.hess.unwrap_or_else(M8::zeros),
                    };
                    let e = errors(&scaled, &r, ty, size(&q1));
                    assert!(
                        e.max() <= TOL,
                        "{f} type {ty} scale {s:e} #{k}: scaling law broken, {e:?}"
                    );
                }
            }
        }
    }
}

/// The 8x8 block rotation `diag(R, R, R, R)`.
fn block_rotation(theta: f64) -> M8 {
    let r = Matrix2::new(theta.cos(), -theta.sin(), theta.sin(), theta.cos());
    let mut b = M8::zeros();
    for k in 0..4 {
        b.fixed_view_mut::<2, 2>(2 * k, 2 * k).copy_from(&r);
    }
    b
}

/// Large rotations: the whole configuration rotated by random angles in
/// [0, 2π). Against num-dual at the rotated configuration (tolerance
/// [`TOL`]) and against the covariance laws g(Rq) = g(q), xi_m(Rq) = xi_m(q),
/// g'(Rq) = R g'(q), g''(Rq) = R g''(q) R^T (relative 1e-10 of each block).
#[test]
fn large_rotations() {
    let mut rng = seeded(0x6a95_0005);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let q0 = unit_shape().q(normal(f));
        let xi_s = unit_shape().xi_s;
        for k in 0..60 {
            let theta = rng.random_range(0.0..std::f64::consts::TAU);
            let rot = block_rotation(theta);
            let q = to_array(&(rot * V8::from(q0)));
            check_all_types(&format!("rotation {theta} #{k}"), f, &q, &q, xi_s, TOL);
            for ty in ApproxType::ALL {
                let a = evaluate(f, ty, &q0, xi_s).unwrap();
                let b = evaluate(f, ty, &q, xi_s).unwrap();
                let r = Reference {
                    gap: a.gap,
                    xi_m: a.xi_m,
                    grad: rot * a.grad,
                    hess: a
                        .hess
                        .map(|h| rot * h * rot.transpose())
                        .unwrap_or_else(M8::zeros),
                };
                let e = errors(&b, &r, ty, size(&q0));
                assert!(
                    e.max() <= TOL,
                    "{f} type {ty} rotation {theta}: covariance broken, {e:?}"
                );
            }
        }
    }
}

/// A steep master: 80–89° (either side) to the slave. For slave-normal the
/// projection's conditioning is 1/cos(angle) ≤ 57 (xi') and its square
/// ≤ 3300 (xi''); tolerance [`TOL`] still leaves two orders of magnitude.
#[test]
fn steep_master() {
    let mut rng = seeded(0x6a95_0006);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let mut worst = Errors::default();
        for k in 0..100 {
            let mut s = Shape::random(&mut rng);
            let deg = rng.random_range(80.0..=89.0_f64);
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            s.master_angle = sign * deg.to_radians();
            s.xi_m = rng.random_range(-0.9..0.9);
            let q = s.q(normal(f));
            worst = worst.worst(check_all_types(
                &format!("steep {deg:.1}° #{k}"),
                f,
                &q,
                &q,
                s.xi_s,
                TOL,
            ));
        }
        eprintln!("{f}: steep master, worst scaled errors {worst:?}");
    }
}

/// Special positions: projection exactly at a master segment end
/// (xi_m = ±1), the slave point at a slave segment end (xi_s = ±1), and
/// penetration (g < 0, whose sign the kernel must keep). Tolerance [`TOL`].
#[test]
fn segment_ends_and_penetration() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let base = unit_shape();
        for xi_m in [-1.0, 1.0] {
            let s = Shape { xi_m, ..base };
            let q = s.q(normal(f));
            check_all_types(&format!("xi_m = {xi_m}"), f, &q, &q, s.xi_s, TOL);
            let p = project(f, &q, s.xi_s).unwrap();
            assert!(
                (p.xi_m - xi_m).abs() <= 1e-12,
                "{f}: projection at the end: xi_m {}",
                p.xi_m
            );
        }
        for xi_s in [-1.0, 1.0] {
            let s = Shape { xi_s, ..base };
            let q = s.q(normal(f));
            check_all_types(&format!("xi_s = {xi_s}"), f, &q, &q, xi_s, TOL);
        }
        for gap in [-0.3, -1e-3] {
            let s = Shape { gap, ..base };
            let q = s.q(normal(f));
            check_all_types(&format!("penetration {gap}"), f, &q, &q, s.xi_s, TOL);
            for ty in ApproxType::ALL {
                let out = evaluate(f, ty, &q, s.xi_s).unwrap();
                assert!(
                    out.gap < 0.0,
                    "{f} type {ty}: penetration must give g < 0, got {}",
                    out.gap
                );
                assert!(
                    (out.gap - gap).abs() <= 1e-12,
                    "{f} type {ty}: g {} vs constructed {gap}",
                    out.gap
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Degenerate input: typed errors, never NaN, never a panic.
// ---------------------------------------------------------------------------

/// Every kernel entry point on `q`, `xi_s`: the errors of `project` and of
/// each type's `evaluate`.
fn all_errors(f: Formulation, q: &[f64; 8], xi_s: f64) -> Vec<KernelError> {
    let mut errs = vec![project(f, q, xi_s).expect_err("project must fail")];
    for ty in ApproxType::ALL {
        errs.push(evaluate(f, ty, q, xi_s).expect_err("evaluate must fail"));
    }
    errs
}

#[test]
fn zero_length_segments_are_typed_errors() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let slave = [1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0];
        for e in all_errors(f, &slave, 0.2) {
            assert!(
                matches!(
                    e,
                    KernelError::DegenerateSegment {
                        segment: Segment::Slave,
                        ..
                    }
                ),
                "{f}: zero-length slave gave {e:?}"
            );
        }
        let master = [0.0, 1.0, 2.0, 1.0, 1.0, 0.5, 1.0, 0.5];
        for e in all_errors(f, &master, 0.2) {
            assert!(
                matches!(
                    e,
                    KernelError::DegenerateSegment {
                        segment: Segment::Master,
                        ..
                    }
                ),
                "{f}: zero-length master gave {e:?}"
            );
        }
    }
}

/// Slave-normal with the master perpendicular to the slave (t_m . t_s = 0
/// exactly, and 1e-13 off): the projection does not exist or is absurdly
/// far. Closest-point projects the same configuration fine.
#[test]
fn perpendicular_master() {
    let exact = [0.0, 1.0, 2.0, 1.0, 1.5, 0.5, 1.5, -0.5];
    let nearly = [0.0, 1.0, 2.0, 1.0, 1.5, 0.5, 1.5 + 1e-13, -0.5];
    for q in [exact, nearly] {
        for e in all_errors(Formulation::SlaveNormal, &q, 0.1) {
            assert!(
                matches!(
                    e,
                    KernelError::NoProjection { .. } | KernelError::ProjectionOutOfReach { .. }
                ),
                "slave-normal, perpendicular master {q:?}: {e:?}"
            );
        }
        check_all_types(
            "closest-point, perpendicular master",
            Formulation::ClosestPoint,
            &q,
            &q,
            0.1,
            TOL,
        );
    }
}

#[test]
fn non_finite_input_is_a_typed_error() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..8 {
                let mut q = WORKED_Q;
                q[i] = bad;
                for e in all_errors(f, &q, WORKED_XI_S) {
                    assert!(
                        matches!(e, KernelError::NonFinite { index, value } if index == i && (value == bad || value.is_nan() && bad.is_nan())),
                        "{f}: q[{i}] = {bad}: {e:?}"
                    );
                }
            }
            for e in all_errors(f, &WORKED_Q, bad) {
                assert!(
                    matches!(e, KernelError::NonFinite { index: 8, .. }),
                    "{f}: xi_s = {bad}: {e:?}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Invariances and consistency.
// ---------------------------------------------------------------------------

/// Translating the whole configuration changes nothing (up to the rounding
/// of the translated input: relative 1e-10 of each block).
#[test]
fn translation_invariance() {
    let mut rng = seeded(0x6a95_0007);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        for k in 0..50 {
            let s = Shape::random(&mut rng);
            let q = s.q(normal(f));
            let t = [
                rng.random_range(-100.0..100.0),
                rng.random_range(-100.0..100.0),
            ];
            let qt: [f64; 8] = std::array::from_fn(|i| q[i] + t[i % 2]);
            for ty in ApproxType::ALL {
                let a = evaluate(f, ty, &q, s.xi_s).unwrap();
                let b = evaluate(f, ty, &qt, s.xi_s).unwrap();
                let r = Reference {
                    gap: a.gap,
                    xi_m: a.xi_m,
                    grad: a.grad,
                    hess: a.hess.unwrap_or_else(M8::zeros),
                };
                let e = errors(&b, &r, ty, size(&q));
                assert!(
                    e.max() <= TOL,
                    "{f} type {ty} #{k}: translation by {t:?} changed the result: {e:?}"
                );
            }
        }
    }
}

/// `project` and every type's `evaluate` agree on g and xi_m (relative
/// 1e-13: the same projection solve; the gap may come from differently
/// simplified code).
#[test]
fn project_agrees_with_evaluate() {
    let mut rng = seeded(0x6a95_0008);
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        for _ in 0..100 {
            let s = Shape::random(&mut rng);
            let q = s.q(normal(f));
            let p = project(f, &q, s.xi_s).unwrap();
            let l = size(&q);
            for ty in ApproxType::ALL {
                let out = evaluate(f, ty, &q, s.xi_s).unwrap();
                assert!(
                    (out.gap - p.gap).abs() <= 1e-13 * l,
                    "{f} type {ty}: gap {} vs project {}",
                    out.gap,
                    p.gap
                );
                assert!(
                    (out.xi_m - p.xi_m).abs() <= 1e-13 * (1.0 + p.xi_m.abs()),
                    "{f} type {ty}: xi_m {} vs project {}",
                    out.xi_m,
                    p.xi_m
                );
            }
        }
    }
}

/// Every compiled kernel reports an operation count (the projection kernel
/// too), and Type 1, which has no Hessian at all, is strictly the cheapest
/// of its formulation.
#[test]
fn op_counts_are_reported() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let counts: Vec<u32> = ApproxType::ALL
            .iter()
            .map(|&ty| {
                op_count(f, Some(ty))
                    .expect("compiled formulation has op counts")
                    .total()
            })
            .collect();
        assert!(op_count(f, None).expect("projection op count").total() > 0);
        assert!(
            counts[1..].iter().all(|&c| c > counts[0]),
            "{f}: op counts {counts:?}"
        );
    }
}

// ---------------------------------------------------------------------------
// Property tests.
// ---------------------------------------------------------------------------

/// The outcome contract on any input: either `Ok` with all outputs finite, a
/// (relatively, 1e-12 of the largest entry) symmetric Hessian present exactly
/// for Types 2–6, or a typed data error (never `NotCompiled`: both
/// formulations are compiled by default). `project` likewise.
fn check_contract(q: &[f64; 8], xi_s: f64) -> Result<(), TestCaseError> {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        handles_agree(f, q, xi_s)?;
        match project(f, q, xi_s) {
            Ok(p) => prop_assert!(p.gap.is_finite() && p.xi_m.is_finite(), "{f}: {p:?}"),
            Err(e) => prop_assert!(!matches!(e, KernelError::NotCompiled(_)), "{f}: {e:?}"),
        }
        for ty in ApproxType::ALL {
            match evaluate(f, ty, q, xi_s) {
                Ok(out) => {
                    prop_assert!(
                        out.gap.is_finite() && out.xi_m.is_finite(),
                        "{f} {ty}: {out:?}"
                    );
                    prop_assert!(out.grad.iter().all(|v| v.is_finite()), "{f} {ty}: {out:?}");
                    prop_assert_eq!(
                        out.hess.is_some(),
                        ty != ApproxType::Type1,
                        "{} {}: Hessian presence",
                        f,
                        ty
                    );
                    if let Some(h) = out.hess {
                        prop_assert!(h.iter().all(|v| v.is_finite()), "{f} {ty}: {h}");
                        let asym = (h - h.transpose()).amax();
                        prop_assert!(
                            asym <= 1e-12 * h.amax(),
                            "{f} {ty}: asymmetric Hessian by {asym:e}: {h}"
                        );
                    }
                }
                Err(e) => {
                    prop_assert!(!matches!(e, KernelError::NotCompiled(_)), "{f} {ty}: {e:?}")
                }
            }
        }
    }
    Ok(())
}

/// The handles (`Kernel::eval` into a reused `GapOut`, `Projector::project`)
/// give what the value API gives, bit for bit, errors included.
fn handles_agree(f: Formulation, q: &[f64; 8], xi_s: f64) -> Result<(), TestCaseError> {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let projector = Projector::new(f).unwrap();
    let mut scratch = vec![0.0; projector.coords()];
    match (
        project(f, q, xi_s),
        projector.project(q, xi_s, &mut scratch),
    ) {
        (Ok(a), Ok(b)) => prop_assert_eq!(bits(&[a.gap, a.xi_m]), bits(&[b.gap, b.xi_m])),
        (a, b) => prop_assert_eq!(format!("{a:?}"), format!("{b:?}"), "{} project", f),
    }
    let mut out = GapOut::with_coords(q.len());
    for ty in ApproxType::ALL {
        let kernel = Kernel::new(f, ty).unwrap();
        match (evaluate(f, ty, q, xi_s), kernel.eval(q, xi_s, &mut out)) {
            (Ok(a), Ok(())) => {
                prop_assert_eq!(bits(&[a.gap, a.xi_m]), bits(&[out.gap(), out.xi_m()]));
                prop_assert_eq!(bits(a.grad.as_slice()), bits(out.grad()));
                prop_assert_eq!(
                    a.hess.map(|h| bits(h.as_slice())),
                    out.hess().map(bits),
                    "{} {}",
                    f,
                    ty
                );
            }
            (a, b) => prop_assert_eq!(format!("{a:?}"), format!("{b:?}"), "{} {}", f, ty),
        }
    }
    Ok(())
}

/// Any finite f64, from subnormal to 1e308, zeros included.
fn any_finite() -> impl Strategy<Value = f64> {
    prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Moderate coordinates and xi_s anywhere in [-1, 1].
    #[test]
    fn kernels_never_panic_moderate(q in prop::array::uniform8(-10.0..10.0_f64), xi_s in -1.0..=1.0_f64) {
        check_contract(&q, xi_s)?;
    }

    /// Arbitrary finite coordinates and xi_s (overflowing differences,
    /// subnormals, coincident nodes).
    #[test]
    fn kernels_never_panic_extreme(q in prop::array::uniform8(any_finite()), xi_s in any_finite()) {
        check_contract(&q, xi_s)?;
    }

    /// Nearly degenerate: small perturbations of coincident nodes and of a
    /// perpendicular master.
    #[test]
    fn kernels_never_panic_near_degenerate(
        eps in prop::array::uniform8(-1e-9..1e-9_f64),
        pick in 0usize..3,
        xi_s in -1.0..=1.0_f64,
    ) {
        let base = match pick {
            0 => [1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0],
            1 => [0.0, 1.0, 2.0, 1.0, 1.0, 0.5, 1.0, 0.5],
            _ => [0.0, 1.0, 2.0, 1.0, 1.5, 0.5, 1.5, -0.5],
        };
        let q: [f64; 8] = std::array::from_fn(|i| base[i] + eps[i]);
        check_contract(&q, xi_s)?;
    }
}

/// The comparisons can tell the types apart: at the worked example the
/// kernels' Hessians of different types differ by more than 1e-3 of the
/// Type-6 Hessian's norm, except where docs/conventions.md predicts that types
/// coincide. With closest-point, n . x_xi = 0 and n_xi = 0, so the xi''
/// term vanishes: Types 3 and 4, and Types 5 and 6, must agree (within
/// [`TOL`]), and the Type-1 gradient is already exact. With slave-normal
/// every pair differs and Type 1's gradient is not exact.
#[test]
fn types_are_distinguishable() {
    for f in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
        let outs: Vec<GapDerivatives> = ApproxType::ALL
            .iter()
            .map(|&ty| evaluate(f, ty, &WORKED_Q, WORKED_XI_S).unwrap())
            .collect();
        let h6 = outs[5].hess.unwrap();
        let hess_of = |k: usize| outs[k].hess.unwrap_or_else(M8::zeros);
        let grad1_error = (outs[0].grad - outs[5].grad).norm() / outs[5].grad.norm();
        match f {
            Formulation::SlaveNormal | Formulation::QuadraticSlaveNormal => {
                assert!(grad1_error > 1e-3, "{f}: Type 1 gradient is exact?")
            }
            Formulation::ClosestPoint => assert!(
                grad1_error <= TOL,
                "{f}: Type 1 gradient {grad1_error:e} off"
            ),
            _ => unreachable!("segment pairs only"),
        }
        for a in 0..6 {
            for b in a + 1..6 {
                let d = (hess_of(a) - hess_of(b)).norm() / h6.norm();
                let coincide =
                    f == Formulation::ClosestPoint && matches!((a + 1, b + 1), (3, 4) | (5, 6));
                if coincide {
                    assert!(
                        d <= TOL,
                        "{f}: Types {} and {} should coincide, differ by {d:e}",
                        a + 1,
                        b + 1
                    );
                } else {
                    assert!(
                        d > 1e-3,
                        "{f}: Types {} and {} are indistinguishable ({d:e})",
                        a + 1,
                        b + 1
                    );
                }
            }
        }
    }
}
