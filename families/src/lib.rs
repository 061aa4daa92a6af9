//! The configurations gapsim's contact kernels are checked on: seeded
//! random configurations and the hard families of segment pairs, one
//! generator for every checker. The kernel verifier (`gapsim::verify`,
//! `gapsim verify`, the root crate's `tests/kernels_ad.rs`) draws them
//! through `gapsim::verify::families` (a re-export of this crate), and
//! contact-kernels' `tests/c_kernels.rs` (a dev-dependency: contact-kernels
//! cannot depend on the root crate, which depends on it) compares the C
//! kernels with the Rust kernels on them. Pure `f64` geometry on `rand` and
//! `rand_chacha`: no kernel, no formulation parser.
//!
//! ## Two-node segments
//!
//! A formulation of two-node segment pairs (four points `xs1, xs2, xm1,
//! xm2` and one parameter `xi_s`) is checked on [`all`]:
//!
//! | family | configurations |
//! |---|---|
//! | `worked` | the worked example of docs/conventions.md |
//! | `random` | 400 constructed: slave 0.2–5 long at any direction, master 0.2–5 at ±57° from facing it, `xi_s` in [-1, 1], `xi_m` in [-1.2, 1.2], gap ±0.5 slave lengths, slave node 1 in [-10, 10]² |
//! | `uniform` | 400 uniform coordinate sets in [-2, 2]^8 (ill-posed draws are skipped by the verifier) |
//! | `far` | 100 constructed, offset by ~1e6 from the origin |
//! | `scale` | 40 unit configurations scaled by 1e-6 and by 1e6 |
//! | `rotation` | a unit configuration rotated by 60 random angles |
//! | `steep` | 100 with the master at 80–89° (either side) to the slave |
//! | `ends` | projection at the master ends (`xi_m = ±1`), slave point at the slave ends (`xi_s = ±1`), penetration (gap -0.3, -1e-3) |
//!
//! A constructed configuration ([`Shape`]) places the master segment so
//! that the slave point, moved by `gap` along a chosen unit normal
//! ([`Normal`]), lies at master coordinate `xi_m`: exactly the projection of
//! a formulation whose normal that is (slave-normal: [`Normal::Slave`];
//! closest-point: [`Normal::Master`]).
//!
//! ## 3-node segments
//!
//! Formulations of two 3-node quadratic segments (six points `xs1, xs2,
//! xs3, xm1, xm2, xm3`, Gmsh line3 order: ends, then mid node) are checked
//! on [`quadratic`]: the same families built from a [`QuadShape`] (each
//! segment curved by its mid node's offset across the chord, `bow`, and
//! along it, `shift`, in chord lengths; `|shift| < 1/4` keeps it unfolded),
//! constructed along the slave normal at `x_s(xi_s)`, each redrawn until the
//! master tangent at `xi_m` is at most 89° from the slave tangent at `xi_s`
//! (the two-node `steep` family's limit: the projection's conditioning
//! `1 / cos` of that angle amplifies the Hessian's errors by its square):
//!
//! | family | configurations |
//! |---|---|
//! | `worked` | a straight slave and a master curved towards it (contact-kernels' tests/quadratic.rs hand-computes it), and a curved version |
//! | `random` | 400 constructed: as the two-node family, bows ±0.3, shifts ±0.15 |
//! | `near-straight` | 100 with bows and shifts of 1e-9..1e-4 chord lengths |
//! | `curved` | 100 strongly curved: bows 0.3–0.6 of either sign on both segments |
//! | `uniform` | 400 uniform coordinate sets in [-2, 2]^12, folded draws replaced |
//! | `far` | 100 constructed, offset by ~1e6 from the origin |
//! | `scale` | 40 unit configurations scaled by 1e-6 and by 1e6 |
//! | `rotation` | a curved unit configuration rotated by 60 random angles |
//! | `steep` | 100 with the master chord at 80–89° (either side) to the slave chord |
//! | `ends` | `xi_m = ±1`, `xi_s = ±1`, penetration (gap -0.3, -1e-3) |

//!
//! ## 3D faces
//!
//! Formulations of tri3 and quad4 face pairs (`inputs!(dim 3; ..; ..; xi_s:
//! 2)`) are checked on [`faces::faces`] (see that module: random, rotated,
//! warped, edges and corners, far, scale, steep, penetration).

#![warn(missing_docs)]

pub mod faces;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// One configuration: coordinates and parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// The family and index, e.g. `steep #17`.
    pub label: String,
    /// The coordinates `q` (point-major).
    pub q: Vec<f64>,
    /// The parameters (`[xi_s]`).
    pub params: Vec<f64>,
}

/// Which unit normal a constructed gap is measured along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normal {
    /// The slave segment's outward normal `(t_s.y, -t_s.x) / |t_s|`.
    Slave,
    /// The master segment's inward normal `(-t_m.y, t_m.x) / |t_m|`.
    Master,
}

/// A configuration built so that the slave point `x_s(xi_s)` moved by
/// `gap` along a unit normal lies at master coordinate `xi_m`.
#[derive(Debug, Clone, Copy)]
pub struct Shape {
    /// Slave node 1.
    pub origin: [f64; 2],
    /// Slave segment length.
    pub slave_len: f64,
    /// Direction of the slave tangent.
    pub slave_angle: f64,
    /// Angle between the master tangent and the reversed slave tangent
    /// (0: parallel, facing segments as in the paper scene).
    pub master_angle: f64,
    /// Master segment length.
    pub master_len: f64,
    /// The slave parameter.
    pub xi_s: f64,
    /// The master coordinate of the constructed point.
    pub xi_m: f64,
    /// The constructed gap.
    pub gap: f64,
}

/// `(1 - xi)/2 a + (1 + xi)/2 b`.
pub fn lerp(a: [f64; 2], b: [f64; 2], xi: f64) -> [f64; 2] {
    let (n1, n2) = ((1.0 - xi) * 0.5, (1.0 + xi) * 0.5);
    [a[0] * n1 + b[0] * n2, a[1] * n1 + b[1] * n2]
}

impl Shape {
    /// The coordinates `[xs1, ys1, xs2, ys2, xm1, ym1, xm2, ym2]`, the gap
    /// measured along `normal`.
    pub fn q(&self, normal: Normal) -> [f64; 8] {
        let t_s = [
            self.slave_len * self.slave_angle.cos(),
            self.slave_len * self.slave_angle.sin(),
        ];
        let a_m = self.slave_angle + std::f64::consts::PI + self.master_angle;
        let t_m = [self.master_len * a_m.cos(), self.master_len * a_m.sin()];
        let xs1 = self.origin;
        let xs2 = [xs1[0] + t_s[0], xs1[1] + t_s[1]];
        let x_s = lerp(xs1, xs2, self.xi_s);
        let n = match normal {
            Normal::Slave => [t_s[1] / self.slave_len, -t_s[0] / self.slave_len],
            Normal::Master => [-t_m[1] / self.master_len, t_m[0] / self.master_len],
        };
        let p = [x_s[0] + self.gap * n[0], x_s[1] + self.gap * n[1]];
        let c_m = [
            p[0] - 0.5 * self.xi_m * t_m[0],
            p[1] - 0.5 * self.xi_m * t_m[1],
        ];
        [
            xs1[0],
            xs1[1],
            xs2[0],
            xs2[1],
            c_m[0] - 0.5 * t_m[0],
            c_m[1] - 0.5 * t_m[1],
            c_m[0] + 0.5 * t_m[0],
            c_m[1] + 0.5 * t_m[1],
        ]
    }

    /// A random constructed shape (the `random` family's distribution).
    pub fn random(rng: &mut ChaCha8Rng) -> Shape {
        let slave_len = rng.random_range(0.2..5.0);
        Shape {
            origin: [rng.random_range(-10.0..10.0), rng.random_range(-10.0..10.0)],
            slave_len,
            slave_angle: rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
            master_angle: rng.random_range(-1.0..1.0),
            master_len: rng.random_range(0.2..5.0),
            xi_s: rng.random_range(-1.0..=1.0),
            xi_m: rng.random_range(-1.2..1.2),
            gap: slave_len * rng.random_range(-0.5..0.5),
        }
    }

    /// A unit-size shape (the rotation and end families' base).
    pub fn unit() -> Shape {
        Shape {
            origin: [0.0, 0.0],
            slave_len: 1.0,
            slave_angle: 0.3,
            master_angle: 0.25,
            master_len: 1.3,
            xi_s: -0.4,
            xi_m: 0.35,
            gap: 0.12,
        }
    }
}

/// The worked example of docs/conventions.md.
pub const WORKED_Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
/// The worked example's `xi_s`.
pub const WORKED_XI_S: f64 = 0.3;

/// The seeded generator of a family.
pub fn seeded(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// `q` rotated by `theta` point by point about the origin.
pub fn rotate(q: &[f64; 8], theta: f64) -> [f64; 8] {
    let (c, s) = (theta.cos(), theta.sin());
    std::array::from_fn(|i| {
        let (x, y) = (q[i - i % 2], q[i - i % 2 + 1]);
        if i % 2 == 0 {
            c * x - s * y
        } else {
            s * x + c * y
        }
    })
}

fn config(label: String, q: [f64; 8], xi_s: f64) -> Config {
    Config {
        label,
        q: q.to_vec(),
        params: vec![xi_s],
    }
}

/// Every family, constructed along `normal` (see the module
/// documentation), in a fixed order.
pub fn all(normal: Normal) -> Vec<Config> {
    let mut out = vec![config("worked".into(), WORKED_Q, WORKED_XI_S)];
    let mut rng = seeded(0x6a95_0001);
    for k in 0..400 {
        let s = Shape::random(&mut rng);
        out.push(config(format!("random #{k}"), s.q(normal), s.xi_s));
    }
    let mut rng = seeded(0x6a95_0002);
    for k in 0..400 {
        let q: [f64; 8] = std::array::from_fn(|_| rng.random_range(-2.0..2.0));
        let xi_s = rng.random_range(-1.0..=1.0);
        out.push(config(format!("uniform #{k}"), q, xi_s));
    }
    let mut rng = seeded(0x6a95_0003);
    for k in 0..100 {
        let mut s = Shape::random(&mut rng);
        s.origin = [
            1e6 + rng.random_range(-1.0..1.0),
            -1e6 + rng.random_range(-1.0..1.0),
        ];
        out.push(config(format!("far #{k}"), s.q(normal), s.xi_s));
    }
    let mut rng = seeded(0x6a95_0004);
    for k in 0..40 {
        let mut s = Shape::random(&mut rng);
        s.origin = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        let q1 = s.q(normal);
        for scale in [1e-6, 1e6] {
            let q = q1.map(|v| v * scale);
            out.push(config(format!("scale {scale:e} #{k}"), q, s.xi_s));
        }
    }
    let mut rng = seeded(0x6a95_0005);
    let q0 = Shape::unit().q(normal);
    for k in 0..60 {
        let theta = rng.random_range(0.0..std::f64::consts::TAU);
        out.push(config(
            format!("rotation #{k}"),
            rotate(&q0, theta),
            Shape::unit().xi_s,
        ));
    }
    let mut rng = seeded(0x6a95_0006);
    for k in 0..100 {
        let mut s = Shape::random(&mut rng);
        let deg = rng.random_range(80.0..=89.0_f64);
        let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
        s.master_angle = sign * deg.to_radians();
        s.xi_m = rng.random_range(-0.9..0.9);
        out.push(config(format!("steep #{k}"), s.q(normal), s.xi_s));
    }
    let base = Shape::unit();
    for xi_m in [-1.0, 1.0] {
        let s = Shape { xi_m, ..base };
        out.push(config(format!("ends xi_m={xi_m}"), s.q(normal), s.xi_s));
    }
    for xi_s in [-1.0, 1.0] {
        let s = Shape { xi_s, ..base };
        out.push(config(format!("ends xi_s={xi_s}"), s.q(normal), xi_s));
    }
    for gap in [-0.3, -1e-3] {
        let s = Shape { gap, ..base };
        out.push(config(format!("penetration {gap}"), s.q(normal), s.xi_s));
    }
    out
}

/// The Lagrange shape functions of a 3-node segment (Gmsh line3 order: end,
/// end, mid): `[xi (xi - 1) / 2, xi (xi + 1) / 2, 1 - xi^2]`.
pub fn shape3(xi: f64) -> [f64; 3] {
    [0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi]
}

/// Their derivatives `[xi - 1/2, xi + 1/2, -2 xi]`.
pub fn shape3_xi(xi: f64) -> [f64; 3] {
    [xi - 0.5, xi + 0.5, -2.0 * xi]
}

/// `sum_k w[k] p[k]`.
fn combine(p: [[f64; 2]; 3], w: [f64; 3]) -> [f64; 2] {
    [
        p[0][0] * w[0] + p[1][0] * w[1] + p[2][0] * w[2],
        p[0][1] * w[0] + p[1][1] * w[1] + p[2][1] * w[2],
    ]
}

/// A 3-node segment from its first end `a`, chord direction `angle`, chord
/// length `len`, and mid node offsets from the chord's midpoint in chord
/// lengths: `shift` along the chord, `bow` across it (to the left).
fn segment3(a: [f64; 2], angle: f64, len: f64, shift: f64, bow: f64) -> [[f64; 2]; 3] {
    let (s, c) = angle.sin_cos();
    let b = [a[0] + len * c, a[1] + len * s];
    let m = [
        0.5 * (a[0] + b[0]) + len * (shift * c - bow * s),
        0.5 * (a[1] + b[1]) + len * (shift * s + bow * c),
    ];
    [a, b, m]
}

/// Whether a 3-node segment (ends `p[0]`, `p[1]`, mid `p[2]`) folds: its
/// mid node's offset along the chord reaches a quarter of the chord
/// (contact-kernels refuses it; with a margin of 1e-3 here).
pub fn folded(p: [[f64; 2]; 3]) -> bool {
    let c = [p[1][0] - p[0][0], p[1][1] - p[0][1]];
    let chord2 = c[0] * c[0] + c[1] * c[1];
    let along: f64 = (0..2)
        .map(|k| (p[0][k] + p[1][k] - 2.0 * p[2][k]) * c[k])
        .sum();
    // (A NaN counts as folded.)
    along.abs() >= 0.499 * chord2 || along.is_nan()
}

/// A configuration of two 3-node segments built so that the slave point
/// `x_s(xi_s)` moved by `gap` along the slave's unit normal there lies at
/// master coordinate `xi_m` (a root of the slave-normal projection).
#[derive(Debug, Clone, Copy)]
pub struct QuadShape {
    /// Slave node 1.
    pub origin: [f64; 2],
    /// Slave chord length.
    pub slave_len: f64,
    /// Direction of the slave chord.
    pub slave_angle: f64,
    /// The slave mid node's offset along its chord (chord lengths).
    pub slave_shift: f64,
    /// The slave mid node's offset across its chord (chord lengths).
    pub slave_bow: f64,
    /// Angle between the master chord and the reversed slave chord.
    pub master_angle: f64,
    /// Master chord length.
    pub master_len: f64,
    /// The master mid node's offset along its chord (chord lengths).
    pub master_shift: f64,
    /// The master mid node's offset across its chord (chord lengths).
    pub master_bow: f64,
    /// The slave parameter.
    pub xi_s: f64,
    /// The master coordinate of the constructed point.
    pub xi_m: f64,
    /// The constructed gap.
    pub gap: f64,
}

impl QuadShape {
    /// The coordinates `[xs1, xs2, xs3, xm1, xm2, xm3]` (x, y each).
    pub fn q(&self) -> [f64; 12] {
        let slave = segment3(
            self.origin,
            self.slave_angle,
            self.slave_len,
            self.slave_shift,
            self.slave_bow,
        );
        let x_s = combine(slave, shape3(self.xi_s));
        let t = combine(slave, shape3_xi(self.xi_s));
        let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let n = [t[1] / len, -t[0] / len];
        let p = [x_s[0] + self.gap * n[0], x_s[1] + self.gap * n[1]];
        let a_m = self.slave_angle + std::f64::consts::PI + self.master_angle;
        let master0 = segment3(
            [0.0, 0.0],
            a_m,
            self.master_len,
            self.master_shift,
            self.master_bow,
        );
        let x0 = combine(master0, shape3(self.xi_m));
        let master = master0.map(|v| [v[0] + p[0] - x0[0], v[1] + p[1] - x0[1]]);
        let mut q = [0.0; 12];
        for (k, v) in slave.iter().chain(&master).enumerate() {
            q[2 * k] = v[0];
            q[2 * k + 1] = v[1];
        }
        q
    }

    /// `|cos|` of the angle between the slave tangent at `xi_s` and the
    /// master tangent at `xi_m`: the projection's conditioning (its
    /// derivatives grow like `1 / cos`, their errors like `1 / cos^2`).
    pub fn tangent_cos(&self) -> f64 {
        let q = self.q();
        let node = |i: usize| [q[2 * i], q[2 * i + 1]];
        let t_s = combine([node(0), node(1), node(2)], shape3_xi(self.xi_s));
        let t_m = combine([node(3), node(4), node(5)], shape3_xi(self.xi_m));
        let norm = |t: [f64; 2]| (t[0] * t[0] + t[1] * t[1]).sqrt();
        (t_s[0] * t_m[0] + t_s[1] * t_m[1]).abs() / (norm(t_s) * norm(t_m))
    }

    /// Whether the tangents at the constructed point are at most 89° apart
    /// (the two-node `steep` family's limit), so that the tolerance holds
    /// with room to spare.
    pub fn well_conditioned(&self) -> bool {
        self.tangent_cos() >= 89.0_f64.to_radians().cos()
    }

    /// A random constructed shape (the `random` family's distribution).
    pub fn random(rng: &mut ChaCha8Rng) -> QuadShape {
        let slave_len = rng.random_range(0.2..5.0);
        QuadShape {
            origin: [rng.random_range(-10.0..10.0), rng.random_range(-10.0..10.0)],
            slave_len,
            slave_angle: rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
            slave_shift: rng.random_range(-0.15..0.15),
            slave_bow: rng.random_range(-0.3..0.3),
            master_angle: rng.random_range(-1.0..1.0),
            master_len: rng.random_range(0.2..5.0),
            master_shift: rng.random_range(-0.15..0.15),
            master_bow: rng.random_range(-0.3..0.3),
            xi_s: rng.random_range(-1.0..=1.0),
            xi_m: rng.random_range(-1.0..1.0),
            gap: slave_len * rng.random_range(-0.3..0.3),
        }
    }

    /// A curved unit-size shape (the rotation and end families' base).
    pub fn unit() -> QuadShape {
        QuadShape {
            origin: [0.0, 0.0],
            slave_len: 1.0,
            slave_angle: 0.3,
            slave_shift: 0.05,
            slave_bow: 0.12,
            master_angle: 0.25,
            master_len: 1.3,
            master_shift: -0.08,
            master_bow: -0.2,
            xi_s: -0.4,
            xi_m: 0.35,
            gap: 0.12,
        }
    }
}

/// The hand-computed configuration of contact-kernels' tests/quadratic.rs:
/// a straight slave along +x and a master curved towards it (`xi_s = 0.5`,
/// `xi_m = -0.5`, `g = 0.85`).
pub const QUADRATIC_WORKED_Q: [f64; 12] = [
    0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 1.0, -0.8,
];
/// Its `xi_s`.
pub const QUADRATIC_WORKED_XI_S: f64 = 0.5;

/// The first draw of [`QuadShape::random`], modified by `modify`, that is
/// [`QuadShape::well_conditioned`].
fn conditioned(
    rng: &mut ChaCha8Rng,
    modify: impl Fn(&mut ChaCha8Rng, QuadShape) -> QuadShape,
) -> QuadShape {
    loop {
        let s = QuadShape::random(rng);
        let s = modify(rng, s);
        if s.well_conditioned() {
            return s;
        }
    }
}

fn config12(label: String, q: [f64; 12], xi_s: f64) -> Config {
    Config {
        label,
        q: q.to_vec(),
        params: vec![xi_s],
    }
}

/// Every 3-node family (see the module documentation), in a fixed order.
pub fn quadratic() -> Vec<Config> {
    let mut out = vec![config12(
        "worked".into(),
        QUADRATIC_WORKED_Q,
        QUADRATIC_WORKED_XI_S,
    )];
    let unit = QuadShape::unit();
    out.push(config12("worked curved".into(), unit.q(), unit.xi_s));
    let mut rng = seeded(0x6a95_1001);
    for k in 0..400 {
        let s = conditioned(&mut rng, |_, s| s);
        out.push(config12(format!("random #{k}"), s.q(), s.xi_s));
    }
    let mut rng = seeded(0x6a95_1002);
    for k in 0..100 {
        let s = conditioned(&mut rng, |rng, mut s| {
            let mut tiny = || {
                let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                sign * 10f64.powf(rng.random_range(-9.0..-4.0))
            };
            s.slave_bow = tiny();
            s.slave_shift = tiny();
            s.master_bow = tiny();
            s.master_shift = tiny();
            s
        });
        out.push(config12(format!("near-straight #{k}"), s.q(), s.xi_s));
    }
    let mut rng = seeded(0x6a95_1003);
    for k in 0..100 {
        let s = conditioned(&mut rng, |rng, mut s| {
            let mut strong = || {
                let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                sign * rng.random_range(0.3..0.6)
            };
            s.slave_bow = strong();
            s.master_bow = strong();
            s.gap = s.slave_len * rng.random_range(-0.1..0.1);
            s
        });
        out.push(config12(format!("curved #{k}"), s.q(), s.xi_s));
    }
    let mut rng = seeded(0x6a95_1004);
    let mut k = 0;
    while k < 400 {
        let q: [f64; 12] = std::array::from_fn(|_| rng.random_range(-2.0..2.0));
        let xi_s = rng.random_range(-1.0..=1.0);
        let node = |i: usize| [q[2 * i], q[2 * i + 1]];
        if folded([node(0), node(1), node(2)]) || folded([node(3), node(4), node(5)]) {
            continue;
        }
        out.push(config12(format!("uniform #{k}"), q, xi_s));
        k += 1;
    }
    let mut rng = seeded(0x6a95_1005);
    for k in 0..100 {
        let s = conditioned(&mut rng, |rng, mut s| {
            s.origin = [
                1e6 + rng.random_range(-1.0..1.0),
                -1e6 + rng.random_range(-1.0..1.0),
            ];
            s
        });
        out.push(config12(format!("far #{k}"), s.q(), s.xi_s));
    }
    let mut rng = seeded(0x6a95_1006);
    for k in 0..40 {
        let s = conditioned(&mut rng, |rng, mut s| {
            s.origin = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            s
        });
        let q1 = s.q();
        for scale in [1e-6, 1e6] {
            let q = q1.map(|v| v * scale);
            out.push(config12(format!("scale {scale:e} #{k}"), q, s.xi_s));
        }
    }
    let mut rng = seeded(0x6a95_1007);
    let q0 = unit.q();
    for k in 0..60 {
        let theta = rng.random_range(0.0..std::f64::consts::TAU);
        let (s, c) = theta.sin_cos();
        let q: [f64; 12] = std::array::from_fn(|i| {
            let (x, y) = (q0[i - i % 2], q0[i - i % 2 + 1]);
            if i % 2 == 0 {
                c * x - s * y
            } else {
                s * x + c * y
            }
        });
        out.push(config12(format!("rotation #{k}"), q, unit.xi_s));
    }
    let mut rng = seeded(0x6a95_1008);
    for k in 0..100 {
        let s = conditioned(&mut rng, |rng, mut s| {
            let deg = rng.random_range(80.0..=89.0_f64);
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            s.master_angle = sign * deg.to_radians();
            s.master_bow *= 0.2;
            s.xi_m = rng.random_range(-0.9..0.9);
            s
        });
        out.push(config12(format!("steep #{k}"), s.q(), s.xi_s));
    }
    for xi_m in [-1.0, 1.0] {
        let s = QuadShape { xi_m, ..unit };
        out.push(config12(format!("ends xi_m={xi_m}"), s.q(), s.xi_s));
    }
    for xi_s in [-1.0, 1.0] {
        let s = QuadShape { xi_s, ..unit };
        out.push(config12(format!("ends xi_s={xi_s}"), s.q(), xi_s));
    }
    for gap in [-0.3, -1e-3] {
        let s = QuadShape { gap, ..unit };
        out.push(config12(format!("penetration {gap}"), s.q(), s.xi_s));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The family sizes of the module docs, in order, and the same
    /// configurations on every call (seeded).
    #[test]
    fn families_are_seeded_and_sized() {
        let count = |configs: &[Config], prefix: &str| {
            configs
                .iter()
                .filter(|c| c.label.starts_with(prefix))
                .count()
        };
        for normal in [Normal::Slave, Normal::Master] {
            let a = all(normal);
            assert_eq!(a, all(normal));
            assert_eq!(a[0].q, WORKED_Q);
            assert!(a.iter().all(|c| c.q.len() == 8 && c.params.len() == 1));
            let sizes = [
                ("random", 400),
                ("uniform", 400),
                ("far", 100),
                ("scale", 80),
                ("rotation", 60),
                ("steep", 100),
                ("ends", 4),
                ("penetration", 2),
            ];
            for (family, n) in sizes {
                assert_eq!(count(&a, family), n, "{family}");
            }
            assert_eq!(a.len(), 1 + sizes.iter().map(|s| s.1).sum::<usize>());
        }
        let q = quadratic();
        assert_eq!(q, quadratic());
        assert_eq!(q[0].q, QUADRATIC_WORKED_Q);
        assert!(q.iter().all(|c| c.q.len() == 12 && c.params.len() == 1));
        for (family, n) in [("random", 400), ("near-straight", 100), ("curved", 100)] {
            assert_eq!(count(&q, family), n, "{family}");
        }
    }

    /// A constructed two-node configuration: the slave point moved by `gap`
    /// along the chosen unit normal is the master point at `xi_m`.
    #[test]
    fn shapes_are_constructed_as_documented() {
        let mut rng = seeded(7);
        for _ in 0..50 {
            let s = Shape::random(&mut rng);
            for normal in [Normal::Slave, Normal::Master] {
                let q = s.q(normal);
                let node = |i: usize| [q[2 * i], q[2 * i + 1]];
                let x_s = lerp(node(0), node(1), s.xi_s);
                let x_m = lerp(node(2), node(3), s.xi_m);
                let (t_s, t_m) = ([q[2] - q[0], q[3] - q[1]], [q[6] - q[4], q[7] - q[5]]);
                let n = match normal {
                    Normal::Slave => [t_s[1], -t_s[0]].map(|v| v / s.slave_len),
                    Normal::Master => [-t_m[1], t_m[0]].map(|v| v / s.master_len),
                };
                for k in 0..2 {
                    let p = x_s[k] + s.gap * n[k];
                    assert!((p - x_m[k]).abs() < 1e-12 * (1.0 + p.abs()), "{s:?}");
                }
            }
        }
    }

    /// 3-node configurations: constructed ones are unfolded and within the
    /// 89° limit; the gap is measured along the slave normal at `xi_s`.
    #[test]
    fn quadratic_shapes_are_constructed_as_documented() {
        let mut rng = seeded(11);
        for _ in 0..50 {
            let s = conditioned(&mut rng, |_, s| s);
            assert!(s.well_conditioned());
            let q = s.q();
            let node = |i: usize| [q[2 * i], q[2 * i + 1]];
            assert!(!folded([node(0), node(1), node(2)]));
            assert!(!folded([node(3), node(4), node(5)]));
            let slave = [node(0), node(1), node(2)];
            let master = [node(3), node(4), node(5)];
            let x_s = combine(slave, shape3(s.xi_s));
            let t = combine(slave, shape3_xi(s.xi_s));
            let len = t[0].hypot(t[1]);
            let x_m = combine(master, shape3(s.xi_m));
            for (k, n) in [t[1] / len, -t[0] / len].into_iter().enumerate() {
                let p = x_s[k] + s.gap * n;
                assert!((p - x_m[k]).abs() < 1e-12 * (1.0 + p.abs()), "{s:?}");
            }
        }
        // A mid node a quarter chord from the chord's midpoint folds.
        assert!(folded([[0.0, 0.0], [2.0, 0.0], [1.5, 0.0]]));
        assert!(!folded([[0.0, 0.0], [2.0, 0.0], [1.2, 0.3]]));
    }
}
