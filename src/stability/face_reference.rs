//! The reference gap, gradient and Hessian of a 3D face pair in
//! double-double precision: the face gap of docs/conventions.md ("3D
//! faces") written once over [`Hd`], differentiated exactly by hyper-dual
//! seeding, one evaluation per Hessian entry `(j, k)`, `j <= k`.
//!
//! ```text
//! tri3:  x(u, v) = x1 + (x2 - x1) u + (x3 - x1) v
//! quad4: x(u, v) = sum_a (1 + u u_a)(1 + v v_a) / 4 x_a,  t_1 = dx/du, t_2 = dx/dv
//! slave-normal:  r_a = (x_m(xi) - x_s) . t_sa,     n =  t_s1 x t_s2 / |t_s1 x t_s2| at xi_s
//! closest-point: r_a = (x_m(xi) - x_s) . t_ma(xi), n = -t_m1 x t_m2 / |t_m1 x t_m2| at xi_m
//! g = n . (x_m(xi_m) - x_s)
//! ```
//!
//! The projection `r(xi_m) = 0` is solved by Newton's method in
//! double-double from the starting point the caller gives (the f64
//! kernel's `xi_m`, so that both pick the same root of a non-affine
//! residual) until the step is below 1e-28; then, for each seed, three
//! Newton steps over hyper-dual numbers from that (constant) solution give
//! `xi_m`'s first and second derivatives exactly: the error of the start
//! has no real part, so one step leaves only its `e1 e2` part and the next
//! none (on a tri3 master, whose residual is affine, one step is exact).

use contact_kernels::Formulation;

use super::dd::Dd;
use super::hyper::Hd;

/// Gap, `xi_m`, gradient and full Hessian (row-major, `n x n`) in
/// double-double.
#[derive(Debug, Clone)]
pub struct FaceReference {
    /// The gap.
    pub gap: Dd,
    /// The projection `(u, v)`.
    pub xi_m: [Dd; 2],
    /// `dg/dq` (`n` entries).
    pub grad: Vec<Dd>,
    /// `d2g/dq2`, row-major (`n * n` entries).
    pub hess: Vec<Dd>,
}

type V3 = [Hd; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> Hd {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A face's point, tangents `t_1`, `t_2` and mixed derivative `x_uv` at
/// `(u, v)` (`nodes`: 3 for a tri3, 4 for a quad4).
fn face(nodes: &[V3], u: Hd, v: Hd) -> (V3, V3, V3, V3) {
    let zero = Hd::constant(0.0);
    if nodes.len() == 3 {
        let (t1, t2) = (sub(nodes[1], nodes[0]), sub(nodes[2], nodes[0]));
        let x = std::array::from_fn(|k| nodes[0][k] + t1[k] * u + t2[k] * v);
        return (x, t1, t2, [zero; 3]);
    }
    const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let one = Hd::constant(1.0);
    let quarter = Hd::constant(0.25);
    let (mut x, mut t1, mut t2, mut xuv) = ([zero; 3], [zero; 3], [zero; 3], [zero; 3]);
    for (p, &[ua, va]) in nodes.iter().zip(&CORNERS) {
        let (ua, va) = (Hd::constant(ua), Hd::constant(va));
        let fu = one + u * ua;
        let fv = one + v * va;
        let n = fu * fv * quarter;
        let nu = ua * fv * quarter;
        let nv = fu * va * quarter;
        let nuv = ua * va * quarter;
        for k in 0..3 {
            x[k] = x[k] + n * p[k];
            t1[k] = t1[k] + nu * p[k];
            t2[k] = t2[k] + nv * p[k];
            xuv[k] = xuv[k] + nuv * p[k];
        }
    }
    (x, t1, t2, xuv)
}

/// The two faces of `q` and the slave point.
struct Pair {
    master: Vec<V3>,
    closest: bool,
    /// `x_s`, `t_s1`, `t_s2` at `xi_s`.
    x_s: V3,
    ts: [V3; 2],
}

impl Pair {
    fn new(f: Formulation, q: &[Hd], xi_s: [f64; 2]) -> Pair {
        let (ns, _) = f.face_nodes().expect("a compiled face formulation");
        let points: Vec<V3> = q.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        let (slave, master) = points.split_at(ns);
        let (x_s, ts1, ts2, _) = face(slave, Hd::constant(xi_s[0]), Hd::constant(xi_s[1]));
        Pair {
            master: master.to_vec(),
            closest: f.name().ends_with("closest-point"),
            x_s,
            ts: [ts1, ts2],
        }
    }

    /// One Newton step of the projection from `xi`.
    fn newton(&self, xi: [Hd; 2]) -> [Hd; 2] {
        let (x, t1, t2, xuv) = face(&self.master, xi[0], xi[1]);
        let d = sub(x, self.x_s);
        let tm = [t1, t2];
        let (r, a) = if self.closest {
            // d t_m1/du = 0, d t_m1/dv = d t_m2/du = x_uv, d t_m2/dv = 0
            let dxuv = dot(d, xuv);
            (
                [dot(d, t1), dot(d, t2)],
                [
                    [dot(t1, t1), dot(t2, t1) + dxuv],
                    [dot(t1, t2) + dxuv, dot(t2, t2)],
                ],
            )
        } else {
            (
                [dot(d, self.ts[0]), dot(d, self.ts[1])],
                std::array::from_fn(|i| std::array::from_fn(|c| dot(tm[c], self.ts[i]))),
            )
        };
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        let du = (a[1][1] * r[0] - a[0][1] * r[1]) / det;
        let dv = (a[0][0] * r[1] - a[1][0] * r[0]) / det;
        [xi[0] - du, xi[1] - dv]
    }

    /// The gap at the projection `xi`.
    fn gap(&self, xi: [Hd; 2]) -> Hd {
        let (x, t1, t2, _) = face(&self.master, xi[0], xi[1]);
        let d = sub(x, self.x_s);
        let c = if self.closest {
            cross(t1, t2).map(|c| -c)
        } else {
            cross(self.ts[0], self.ts[1])
        };
        let len = dot(c, c).sqrt();
        dot(c, d) / len
    }
}

/// The gap and `xi_m` at `q`, `xi_s` in double-double, the projection
/// started from `xi_start` (module docs).
pub fn face_gap(f: Formulation, q: &[f64], xi_s: [f64; 2], xi_start: [f64; 2]) -> (Dd, [Dd; 2]) {
    let plain: Vec<Hd> = q.iter().map(|&v| Hd::constant(v)).collect();
    let pair = Pair::new(f, &plain, xi_s);
    let xi = solve(&pair, xi_start);
    (pair.gap(xi).re, [xi[0].re, xi[1].re])
}

/// Newton's method on the real parts until the step is below 1e-28
/// (relative to `1 + max|xi|`; at most 60 steps).
fn solve(pair: &Pair, xi_start: [f64; 2]) -> [Hd; 2] {
    let mut xi = xi_start.map(Hd::constant);
    for _ in 0..60 {
        let next = pair.newton(xi);
        let step = (next[0].re - xi[0].re)
            .abs()
            .to_f64()
            .max((next[1].re - xi[1].re).abs().to_f64());
        xi = next;
        if step <= 1e-28 * (1.0 + xi[0].re.to_f64().abs().max(xi[1].re.to_f64().abs())) {
            break;
        }
    }
    xi
}

/// The reference at `q`, `xi_s` for the face formulation `f`, the
/// projection started from `xi_start` (module docs).
pub fn face_reference(
    f: Formulation,
    q: &[f64],
    xi_s: [f64; 2],
    xi_start: [f64; 2],
) -> FaceReference {
    let n = q.len();
    let (gap, [u, v]) = face_gap(f, q, xi_s, xi_start);
    let mut out = FaceReference {
        gap,
        xi_m: [u, v],
        grad: vec![Dd::default(); n],
        hess: vec![Dd::default(); n * n],
    };
    for j in 0..n {
        for k in j..n {
            let seeded: Vec<Hd> = (0..n).map(|i| Hd::variable(q[i], i == j, i == k)).collect();
            let pair = Pair::new(f, &seeded, xi_s);
            let mut xi = [
                Hd {
                    re: u,
                    ..Hd::default()
                },
                Hd {
                    re: v,
                    ..Hd::default()
                },
            ];
            for _ in 0..3 {
                xi = pair.newton(xi);
            }
            let g = pair.gap(xi);
            out.hess[n * j + k] = g.e12;
            out.hess[n * k + j] = g.e12;
            if k == j {
                out.grad[j] = g.e1;
            }
        }
    }
    out
}
