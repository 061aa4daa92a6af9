//! The reference gap, gradient and Hessian in double-double precision:
//! the gap of two straight segments written once over [`Hd`]
//! (closed-form projection, as the kernels solve it), differentiated
//! exactly by hyper-dual seeding, one evaluation per Hessian entry
//! `(j, k)`, `j <= k`.
//!
//! ```text
//! x_s = lerp(xs1, xs2, xi_s),  t_s = xs2 - xs1,  t_m = xm2 - xm1
//! slave-normal:  t = t_s, n = perp(t_s) / |t_s|
//! closest-point: t = t_m, n = -perp(t_m) / |t_m|
//! xi_m = -2 (c_m - x_s) . t / (t_m . t),  c_m = (xm1 + xm2) / 2
//! g = n . (lerp(xm1, xm2, xi_m) - x_s)
//! ```

use contact_kernels::Formulation;

use super::dd::Dd;
use super::hyper::Hd;

/// Gap, `xi_m`, gradient and full Hessian (row-major) in double-double.
#[derive(Debug, Clone)]
pub struct Reference {
    /// The gap.
    pub gap: Dd,
    /// The projection coordinate.
    pub xi_m: Dd,
    /// `dg/dq`.
    pub grad: [Dd; 8],
    /// `d2g/dq2`, row-major.
    pub hess: [Dd; 64],
}

fn lerp(a: [Hd; 2], b: [Hd; 2], xi: Hd) -> [Hd; 2] {
    let half = Hd::constant(0.5);
    let one = Hd::constant(1.0);
    let n1 = (one - xi) * half;
    let n2 = (one + xi) * half;
    [a[0] * n1 + b[0] * n2, a[1] * n1 + b[1] * n2]
}

fn sub(a: [Hd; 2], b: [Hd; 2]) -> [Hd; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [Hd; 2], b: [Hd; 2]) -> Hd {
    a[0] * b[0] + a[1] * b[1]
}

/// `(g, xi_m)` at `q` (see the module docs).
fn gap(f: Formulation, q: &[Hd; 8], xi_s: f64) -> (Hd, Hd) {
    let node = |k: usize| [q[2 * k], q[2 * k + 1]];
    let (xs1, xs2, xm1, xm2) = (node(0), node(1), node(2), node(3));
    let x_s = lerp(xs1, xs2, Hd::constant(xi_s));
    let (t_s, t_m) = (sub(xs2, xs1), sub(xm2, xm1));
    let c_m = lerp(xm1, xm2, Hd::constant(0.0));
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
        // The sweep runs `pair_formulations()` (8 coordinates) only.
        Formulation::Tri3SlaveNormal
        | Formulation::Tri3ClosestPoint
        | Formulation::Quad4SlaveNormal
        | Formulation::Quad4ClosestPoint
        | Formulation::Tri3Quad4SlaveNormal
        | Formulation::Tri3Quad4ClosestPoint
        | Formulation::Quad4Tri3SlaveNormal
        | Formulation::Quad4Tri3ClosestPoint => {
            unreachable!("the stability sweep takes segment pairs (pair_formulations) only")
        }
    };
    let xi = -(dot(sub(c_m, x_s), t) * Hd::constant(2.0)) / dot(t_m, t);
    (dot(n, sub(lerp(xm1, xm2, xi), x_s)), xi)
}

/// The reference at `q`, `xi_s`.
pub fn reference(f: Formulation, q: &[f64; 8], xi_s: f64) -> Reference {
    let mut out = Reference {
        gap: Dd::default(),
        xi_m: Dd::default(),
        grad: [Dd::default(); 8],
        hess: [Dd::default(); 64],
    };
    for j in 0..8 {
        for k in j..8 {
            let seeded: [Hd; 8] = std::array::from_fn(|i| Hd::variable(q[i], i == j, i == k));
            let (g, xi) = gap(f, &seeded, xi_s);
            out.hess[8 * j + k] = g.e12;
            out.hess[8 * k + j] = g.e12;
            if k == j {
                out.grad[j] = g.e1;
            }
            if j == 0 && k == 0 {
                out.gap = g.re;
                out.xi_m = xi.re;
            }
        }
    }
    out
}
