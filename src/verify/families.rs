//! The configurations the verifier checks a segment-pair formulation on
//! (four points `xs1, xs2, xm1, xm2` and one parameter `xi_s`): seeded
//! random configurations and the hard families.
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
