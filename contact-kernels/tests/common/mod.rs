//! The configurations of the kernel tests that compare implementations bit
//! for bit (`c_kernels.rs`: C against Rust; `batch.rs`: the lane kernels
//! against `Kernel::eval`): the generators and seeds of the num-dual tests
//! (`tests/kernels_ad.rs` at the workspace root), in f64, plus degenerate,
//! non-finite and over- or underflowing input.

#![allow(dead_code)] // each test binary uses part of it

use contact_kernels::Formulation;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

pub fn lerp(a: [f64; 2], b: [f64; 2], xi: f64) -> [f64; 2] {
    let n1 = (1.0 - xi) * 0.5;
    let n2 = (1.0 + xi) * 0.5;
    [a[0] * n1 + b[0] * n2, a[1] * n1 + b[1] * n2]
}

/// A configuration built so that the slave point projects onto master
/// coordinate `xi_m` with gap `gap` in formulation `f`'s own sense (as in
/// kernels_ad.rs).
#[derive(Debug, Clone, Copy)]
pub struct Shape {
    origin: [f64; 2],
    slave_len: f64,
    slave_angle: f64,
    master_angle: f64,
    master_len: f64,
    xi_s: f64,
    xi_m: f64,
    gap: f64,
}

impl Shape {
    fn q(&self, f: Formulation) -> [f64; 8] {
        let t_s = [
            self.slave_len * self.slave_angle.cos(),
            self.slave_len * self.slave_angle.sin(),
        ];
        let a_m = self.slave_angle + std::f64::consts::PI + self.master_angle;
        let t_m = [self.master_len * a_m.cos(), self.master_len * a_m.sin()];
        let xs1 = self.origin;
        let xs2 = [xs1[0] + t_s[0], xs1[1] + t_s[1]];
        let x_s = lerp(xs1, xs2, self.xi_s);
        let n = match f {
            Formulation::SlaveNormal => [t_s[1] / self.slave_len, -t_s[0] / self.slave_len],
            Formulation::ClosestPoint => [-t_m[1] / self.master_len, t_m[0] / self.master_len],
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

    fn random(rng: &mut ChaCha8Rng) -> Shape {
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
}

pub fn unit_shape() -> Shape {
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

pub const WORKED_Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
pub const WORKED_XI_S: f64 = 0.3;
pub const BOTH: [Formulation; 2] = [Formulation::SlaveNormal, Formulation::ClosestPoint];

pub fn seeded(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// One configuration: its family, `q` and `xi_s`.
pub struct Config {
    pub family: &'static str,
    pub q: [f64; 8],
    pub xi_s: f64,
}

/// Every configuration, family by family (the num-dual tests' generators
/// and seeds, then degenerate and extreme input).
pub fn configurations() -> Vec<Config> {
    let mut out = Vec::new();
    let mut push = |family, q, xi_s| out.push(Config { family, q, xi_s });
    push("worked example", WORKED_Q, WORKED_XI_S);
    let mut rng = seeded(0x6a95_0001);
    for f in BOTH {
        for _ in 0..400 {
            let s = Shape::random(&mut rng);
            push("random constructed", s.q(f), s.xi_s);
        }
    }
    // All uniform draws, also those kernels_ad.rs skips as ill-posed.
    let mut rng = seeded(0x6a95_0002);
    for _ in BOTH {
        for _ in 0..400 {
            let q: [f64; 8] = std::array::from_fn(|_| rng.random_range(-2.0..2.0));
            let xi_s = rng.random_range(-1.0..=1.0);
            push("random uniform", q, xi_s);
        }
    }
    let mut rng = seeded(0x6a95_0003);
    for f in BOTH {
        for _ in 0..100 {
            let mut s = Shape::random(&mut rng);
            s.origin = [
                1e6 + rng.random_range(-1.0..1.0),
                -1e6 + rng.random_range(-1.0..1.0),
            ];
            push("far from origin", s.q(f), s.xi_s);
        }
    }
    let mut rng = seeded(0x6a95_0004);
    for f in BOTH {
        for _ in 0..40 {
            let mut unit = Shape::random(&mut rng);
            unit.origin = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let q1 = unit.q(f);
            push("tiny and huge scales", q1, unit.xi_s);
            for s in [1e-6, 1e6] {
                push("tiny and huge scales", q1.map(|v| v * s), unit.xi_s);
            }
        }
    }
    let mut rng = seeded(0x6a95_0005);
    for f in BOTH {
        let q0 = unit_shape().q(f);
        for _ in 0..60 {
            let theta: f64 = rng.random_range(0.0..std::f64::consts::TAU);
            let (s, c) = theta.sin_cos();
            let q: [f64; 8] = std::array::from_fn(|i| {
                let (x, y) = (q0[i - i % 2], q0[i - i % 2 + 1]);
                if i % 2 == 0 {
                    c * x - s * y
                } else {
                    s * x + c * y
                }
            });
            push("large rotations", q, unit_shape().xi_s);
        }
    }
    let mut rng = seeded(0x6a95_0006);
    for f in BOTH {
        for _ in 0..100 {
            let mut s = Shape::random(&mut rng);
            let deg = rng.random_range(80.0..=89.0_f64);
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            s.master_angle = sign * deg.to_radians();
            s.xi_m = rng.random_range(-0.9..0.9);
            push("steep master", s.q(f), s.xi_s);
        }
    }
    for f in BOTH {
        let base = unit_shape();
        for xi_m in [-1.0, 1.0] {
            push("segment ends", Shape { xi_m, ..base }.q(f), base.xi_s);
        }
        for xi_s in [-1.0, 1.0] {
            push("segment ends", Shape { xi_s, ..base }.q(f), xi_s);
        }
        for gap in [-0.3, -1e-3] {
            push("penetration", Shape { gap, ..base }.q(f), base.xi_s);
        }
    }
    let mut rng = seeded(0x6a95_0007);
    for f in BOTH {
        for _ in 0..50 {
            let s = Shape::random(&mut rng);
            let q = s.q(f);
            let t = [
                rng.random_range(-100.0..100.0),
                rng.random_range(-100.0..100.0),
            ];
            push("translation", q, s.xi_s);
            push(
                "translation",
                std::array::from_fn(|i| q[i] + t[i % 2]),
                s.xi_s,
            );
        }
    }
    // Degenerate input: zero-length segments, a perpendicular master.
    push(
        "zero-length slave",
        [1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0],
        0.2,
    );
    push(
        "zero-length master",
        [0.0, 1.0, 2.0, 1.0, 1.0, 0.5, 1.0, 0.5],
        0.2,
    );
    push(
        "perpendicular master",
        [0.0, 1.0, 2.0, 1.0, 1.5, 0.5, 1.5, -0.5],
        0.1,
    );
    push(
        "perpendicular master",
        [0.0, 1.0, 2.0, 1.0, 1.5, 0.5, 1.5 + 1e-13, -0.5],
        0.1,
    );
    // Non-finite input at every position.
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for i in 0..8 {
            let mut q = WORKED_Q;
            q[i] = bad;
            push("non-finite input", q, WORKED_XI_S);
        }
        push("non-finite input", WORKED_Q, bad);
    }
    // Scales where squares, cubes or their reciprocals underflow or
    // overflow: every decade from 1e-170 to 1e-90 and from 1e90 to 1e170,
    // on the worked example and on a steep master.
    let steep = Shape {
        master_angle: 1.55,
        ..unit_shape()
    };
    for e in (-170..=-90).chain(90..=170) {
        let s = 10f64.powi(e);
        push("extreme scale", WORKED_Q.map(|v| v * s), WORKED_XI_S);
        push(
            "extreme scale",
            steep.q(Formulation::SlaveNormal).map(|v| v * s),
            steep.xi_s,
        );
    }
    out
}
