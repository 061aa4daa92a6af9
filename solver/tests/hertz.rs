//! The plane-strain Hertz benchmark (issue #7): the quarter cylinder of
//! `scenes/hertz*.toml` pressed on a block, held only by unilateral contact.
//!
//! Reference (plane strain, both bodies E = 200, nu = 0.3, R = 10, load
//! P = 8.63 per unit thickness on the full cylinder):
//! `1/E* = 2 (1 - nu^2) / E`, `a = sqrt(4 P R / (pi E*))`,
//! `p0 = 2 P / (pi a)`, `p(x) = p0 sqrt(1 - x^2/a^2)`.
//!
//! The contact pressure is `p = -lambda` at the slave nodes (the multiplier
//! is a force per unit reference length, interpolated linearly along the
//! slave segments), plotted over the slave nodes' current x. The measured
//! values: the peak nodal pressure (at the axis, x = 0), and `a` and `p0`
//! of the least-squares fit of `p^2 = A + B x^2` over the nodes in contact
//! (`p0 = sqrt(A)`, `a = sqrt(-A/B)`).
//!
//! Reached (one load step, complete formulation, slave-normal):
//!
//! | mesh | peak | fit p0 | fit a | profile | Newton | time |
//! |---|---|---|---|---|---|---|
//! | coarse (h = 0.23 at the contact) | 5.339 (-2.8 %) | 5.459 (-0.6 %) | 0.998 (-0.2 %) | 12 % | 7 | 0.1 s |
//! | fine (h = 0.05) | 5.334 (-2.9 %) | 5.341 (-2.8 %) | 1.024 (+2.4 %) | 3.1 % | 21 (+ 22 in an attempt cut back) | 2.5 s (release) |
//! | coarse, triangles (0.245 at the contact) | 5.578 (+1.5 %) | 5.176 (-5.8 %) | 1.740 (+74 %) | 17 % | 7 | 0.4 s |
//!
//! (With 2 and 4 steps the fine mesh needs no cut-back: 21 and 29
//! iterations; the coarse mesh with 4 steps, 17.)
//!
//! On the fine mesh the peak error is -1.4 %, -2.1 %, -2.9 % at a quarter,
//! half and the full load: linear in the strain `p0 / E*` (5 % at the full
//! load), extrapolating to about -0.2 % at zero load. What is left at the
//! full load is the finite strain of the St Venant-Kirchhoff model (which
//! softens in compression), not the discretisation; Hertz is a
//! small-strain theory. (The coarse mesh's fit is close by a cancellation
//! of its oscillating nodal values.)

use std::path::PathBuf;

use solver::{Scene, Solution, SolveOptions, solve};

const YOUNG: f64 = 200.0;
const POISSON: f64 = 0.3;
const RADIUS: f64 = 10.0;
const LOAD: f64 = 8.63;

/// Hertz's half-width and peak pressure under the load `LOAD * scale`.
fn hertz_at(scale: f64) -> (f64, f64) {
    let load = LOAD * scale;
    let e_star = YOUNG / (2.0 * (1.0 - POISSON * POISSON));
    let a = (4.0 * load * RADIUS / (std::f64::consts::PI * e_star)).sqrt();
    (a, 2.0 * load / (std::f64::consts::PI * a))
}

/// Hertz's half-width and peak pressure under the scenes' load.
fn hertz() -> (f64, f64) {
    hertz_at(1.0)
}

/// What a run measured.
#[derive(Debug)]
struct Measured {
    /// Peak nodal pressure.
    peak: f64,
    /// `p0` of the fit.
    p0_fit: f64,
    /// `a` of the fit.
    a_fit: f64,
    /// Relative L2 error of the nodal pressures against Hertz's profile
    /// (over the nodes with x < 1.5 a).
    profile: f64,
    /// Nodes in contact.
    in_contact: usize,
}

fn scene(file: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(file);
    Scene::from_file(path).unwrap()
}

/// (current x, pressure) of the slave nodes, by x.
fn profile(sol: &Solution) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = sol
        .multiplier_dofs
        .iter()
        .zip(&sol.final_state.multipliers)
        .map(|(m, &lambda)| {
            let x = sol.mesh.nodes_ref[m.node][0] + sol.final_state.displacements[m.node][0];
            (x, -lambda)
        })
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

fn measure(sol: &Solution, scale: f64) -> Measured {
    let (a, p0) = hertz_at(scale);
    let nodes = profile(sol);
    let contact: Vec<(f64, f64)> = nodes.iter().copied().filter(|&(_, p)| p > 0.0).collect();
    // least squares p^2 = A + B x^2
    let n = contact.len() as f64;
    let (sx, sy, sxx, sxy) = contact.iter().fold((0.0, 0.0, 0.0, 0.0), |s, &(x, p)| {
        let (u, v) = (x * x, p * p);
        (s.0 + u, s.1 + v, s.2 + u * u, s.3 + u * v)
    });
    let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    let a0 = (sy - b * sx) / n;
    let exact = |x: f64| p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
    let (num, den) = nodes
        .iter()
        .filter(|&&(x, _)| x < 1.5 * a)
        .fold((0.0, 0.0), |s, &(x, p)| {
            (s.0 + (p - exact(x)).powi(2), s.1 + exact(x).powi(2))
        });
    Measured {
        peak: contact.iter().fold(0.0, |m, &(_, p)| f64::max(m, p)),
        p0_fit: a0.sqrt(),
        a_fit: (-a0 / b).sqrt(),
        profile: (num / den).sqrt(),
        in_contact: contact.len(),
    }
}

/// Solves `file` with its traction times `scale` and prints what it
/// measured against Hertz.
fn run(file: &str, scale: f64) -> Measured {
    let mut scene = scene(file);
    for t in &mut scene.tractions {
        t.force_per_length = t.force_per_length.map(|v| v * scale);
    }
    let sol = solve(&scene, &SolveOptions::from_scene(&scene)).unwrap();
    let m = measure(&sol, scale);
    let (a, p0) = hertz_at(scale);
    eprintln!(
        "{file} (load x {scale}): peak {:.4} ({:+.2} %), fit p0 {:.4} ({:+.2} %), fit a {:.4} ({:+.2} %), profile error {:.2} %, {} nodes in contact, {} Newton iterations, {:.2} s",
        m.peak,
        100.0 * (m.peak / p0 - 1.0),
        m.p0_fit,
        100.0 * (m.p0_fit / p0 - 1.0),
        m.a_fit,
        100.0 * (m.a_fit / a - 1.0),
        100.0 * m.profile,
        m.in_contact,
        sol.newton_iterations,
        sol.timings.total.as_secs_f64()
    );
    m
}

/// `|measured / reference - 1|`.
fn error(measured: f64, reference: f64) -> f64 {
    (measured / reference - 1.0).abs()
}

#[test]
fn hertz_reference_values() {
    let (a, p0) = hertz();
    assert!((a - 1.000).abs() < 5e-4, "{a}");
    assert!((p0 - 5.494).abs() < 5e-4, "{p0}");
}

/// The coarse mesh (h = 0.23 at the contact, 5 nodes in contact): about
/// 0.1 s.
#[test]
fn hertz_coarse() {
    let (a, p0) = hertz();
    let m = run("hertz-coarse.toml", 1.0);
    assert!(error(m.peak, p0) < 0.04, "{m:?}");
    assert!(error(m.p0_fit, p0) < 0.02, "{m:?}");
    assert!(error(m.a_fit, a) < 0.02, "{m:?}");
    assert!(m.profile < 0.15, "{m:?}");
}

/// The fine mesh (h = 0.05 at the contact, 21 nodes in contact): 2.5 s in
/// release, too long for the debug test run.
#[test]
#[ignore = "fine mesh: cargo test -p gapsim-solver --release --test hertz -- --ignored"]
fn hertz_fine() {
    let (a, p0) = hertz();
    let m = run("hertz.toml", 1.0);
    assert!(error(m.peak, p0) < 0.035, "{m:?}");
    assert!(error(m.p0_fit, p0) < 0.035, "{m:?}");
    assert!(error(m.a_fit, a) < 0.03, "{m:?}");
    assert!(m.profile < 0.04, "{m:?}");
}

/// The fine mesh under smaller loads: the errors against Hertz (a linear,
/// small-strain theory) shrink with the load, so what remains at the full
/// load is mostly the finite strain (p0 / E* = 5 %) of St Venant-Kirchhoff.
#[test]
#[ignore = "load study: cargo test -p gapsim-solver --release --test hertz -- --ignored --nocapture"]
fn hertz_fine_smaller_loads() {
    let errors: Vec<f64> = [0.25, 0.5, 1.0]
        .map(|scale| error(run("hertz.toml", scale).peak, hertz_at(scale).1))
        .to_vec();
    assert!(errors[0] < errors[1] && errors[1] < errors[2], "{errors:?}");
}

/// The all-triangle coarse mesh (`scenes/hertz-tri-coarse.toml`, written
/// by `scripts/make-hertz-mesh.py 0.5 --triangles`: 1711 linear triangles,
/// edges of 0.245 at the contact against the quadrilateral mesh's 0.227,
/// 4 nodes in contact): about 0.4 s.
///
/// Measured: peak 5.578 (+1.5 %), fit p0 5.176 (-5.8 %), fit a 1.74
/// (+74 %), profile error 17 %, 7 Newton iterations. The nodal pressures
/// oscillate from node to node as on the quadrilateral mesh, more strongly
/// (5.03, 5.58, 4.42, 4.87 at x = 0, 0.24, 0.49, 0.73 against Hertz's
/// 5.49, 5.33, 4.79, 3.73; the quadrilaterals at x = 0, 0.23, 0.45, 0.68:
/// 5.31, 5.34, 4.64, 4.75). So the peak is held to the quadrilateral
/// coarse mesh's tolerance (4 %: it is the largest of oscillating nodal values,
/// +1.5 % here and -2.8 % there), the profile to 20 % (17 % measured, 12 %
/// for the quadrilaterals); the fit, with 4 nodes in contact of which the
/// last overshoots, says little about `a` on this mesh and is not held.
#[test]
fn hertz_tri_coarse() {
    let (_, p0) = hertz();
    let m = run("hertz-tri-coarse.toml", 1.0);
    assert!(error(m.peak, p0) < 0.04, "{m:?}");
    assert!(m.profile < 0.20, "{m:?}");
    assert!(m.in_contact >= 4, "{m:?}");
}
