//! The configurations the C comparison and the lane tests share: the
//! verifier's families (`gapsim_families`, the generators and seeds of
//! `gapsim verify` and `tests/kernels_ad.rs`) and the degenerate and extreme
//! input only these tests need.
#![allow(dead_code)] // each test binary uses part of it

pub mod faces;

use contact_kernels::Formulation;
use gapsim_families::{Normal, Shape, WORKED_Q, WORKED_XI_S, seeded};
use rand::Rng;

// ---------------------------------------------------------------------------
// The configurations: the verifier's families (gapsim-families), and the
// degenerate and extreme input only this test needs.
// ---------------------------------------------------------------------------

pub const BOTH: [Formulation; 2] = [Formulation::SlaveNormal, Formulation::ClosestPoint];

/// One configuration: its label (family and index), `q` and `xi_s`.
pub struct Config {
    /// Family and index.
    pub label: String,
    /// The 8 coordinates.
    pub q: [f64; 8],
    /// The slave coordinate.
    pub xi_s: f64,
}

/// Every configuration, family by family: the verifier's families
/// (`gapsim_families::all`, the generators and seeds of `gapsim verify` and
/// `tests/kernels_ad.rs`) constructed along the slave normal and along the
/// master normal (each formulation's own projection; the worked example
/// and the uniform draws do not depend on the normal and are taken once),
/// each also translated by a seeded offset, then degenerate, non-finite
/// and over- or underflowing input. Every configuration is evaluated under
/// both formulations.
pub fn configurations() -> Vec<Config> {
    let mut families = Vec::new();
    for (normal, tag) in [(Normal::Slave, "slave"), (Normal::Master, "master")] {
        for c in gapsim_families::all(normal) {
            let shared = c.label == "worked" || c.label.starts_with("uniform");
            if shared && normal == Normal::Master {
                continue;
            }
            let label = if shared {
                c.label
            } else {
                format!("{} ({tag} normal)", c.label)
            };
            let q: [f64; 8] =
                c.q.try_into()
                    .expect("two-node families have 8 coordinates");
            families.push(Config {
                label,
                q,
                xi_s: c.params[0],
            });
        }
    }
    // The kernels work in coordinates relative to slave node 1: the same
    // configurations moved by up to 100 in each direction.
    let mut rng = seeded(0x6a95_0007);
    let translated: Vec<Config> = families
        .iter()
        .map(|c| {
            let t = [
                rng.random_range(-100.0..100.0),
                rng.random_range(-100.0..100.0),
            ];
            Config {
                label: format!("{} translated", c.label),
                q: std::array::from_fn(|i| c.q[i] + t[i % 2]),
                xi_s: c.xi_s,
            }
        })
        .collect();
    let mut out = families;
    out.extend(translated);
    let mut push = |family: &str, q, xi_s| {
        out.push(Config {
            label: family.to_owned(),
            q,
            xi_s,
        })
    };
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
        ..Shape::unit()
    };
    for e in (-170..=-90).chain(90..=170) {
        let s = 10f64.powi(e);
        push("extreme scale", WORKED_Q.map(|v| v * s), WORKED_XI_S);
        push(
            "extreme scale",
            steep.q(Normal::Slave).map(|v| v * s),
            steep.xi_s,
        );
    }
    out
}
