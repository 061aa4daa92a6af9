//! The plane-strain Hertz benchmark (issue #7; [`gapsim::hertz`]): the
//! quarter cylinder of `scenes/hertz*.toml` pressed on a block, held only
//! by unilateral contact, against Hertz's solution.
//!
//! Targets (on `scenes/hertz-small-strain.toml`, linear elasticity as
//! Hertz assumes, element size 0.05 at the contact): peak pressure, fitted
//! `p0` and fitted half-width within 2 %, the profile's relative L2 error
//! below 4 %. The finite-strain scenes (`hertz.toml`, the scene as
//! written) are a few per cent softer: St Venant–Kirchhoff at the strain
//! `p0 / E* = a / (2R) = 5 %`; `hertz_finite_strain_error_grows_with_load`
//! shows that this part vanishes with the load. The refinement study
//! (`cargo run --release --example hertz_refinement`, docs/hertz/) has the
//! numbers for every mesh.

use std::path::PathBuf;

use gapsim::hertz::{HertzMeasured, HertzProblem, SCENES, measure};
use gapsim::solver::{Scene, SolveOptions, solve};

fn scene(file: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    Scene::from_file(path).unwrap()
}

/// Solves `file` with its traction times `scale` (one load step) and
/// prints what it measured against Hertz.
fn run(file: &str, scale: f64) -> (HertzMeasured, HertzProblem) {
    let mut scene = scene(file);
    for t in &mut scene.tractions {
        t.force_per_length = t.force_per_length.map(|v| v.map(|c| c * scale));
    }
    let problem = SCENES.scaled(scale);
    let sol = solve(&scene, &SolveOptions::from_scene(&scene)).unwrap();
    let m = measure(&sol, &problem);
    eprintln!(
        "{file} (load x {scale}): peak {:.4} ({:+.2} %), fit p0 {:?}, fit a {:?}, profile error {:.2} %, {} nodes in contact, {} Newton iterations",
        m.peak,
        100.0 * m.peak_error(&problem),
        m.p0_fit_error(&problem),
        m.a_fit_error(&problem),
        100.0 * m.profile,
        m.in_contact,
        sol.newton_iterations,
    );
    (m, problem)
}

/// The targets of issue #7 on the small-strain scene (2886 nodes; a few
/// seconds in the test profile).
#[test]
fn hertz_small_strain_meets_the_targets() {
    let (m, problem) = run("hertz-small-strain.toml", 1.0);
    assert!(m.peak_error(&problem).abs() < 0.02, "{m:?}");
    assert!(m.p0_fit_error(&problem).unwrap().abs() < 0.02, "{m:?}");
    assert!(m.a_fit_error(&problem).unwrap().abs() < 0.02, "{m:?}");
    assert!(m.profile < 0.04, "{m:?}");
    assert!(m.in_contact >= 15, "{m:?}");
}

/// The scene as written, on the coarse mesh (h = 0.25 at the
/// contact, 5 nodes in contact): it runs (the first iteration is not
/// singular) and lands within 4 % (peak) and 2 % (fit).
#[test]
fn hertz_coarse_finite_strain() {
    let (m, problem) = run("hertz-coarse.toml", 1.0);
    assert!(m.peak_error(&problem).abs() < 0.04, "{m:?}");
    assert!(m.p0_fit_error(&problem).unwrap().abs() < 0.02, "{m:?}");
    assert!(m.a_fit_error(&problem).unwrap().abs() < 0.02, "{m:?}");
    assert!(m.profile < 0.15, "{m:?}");
}

/// The coarsest mesh of the refinement study (segments of 0.36 at the
/// contact): no slave node meets the touching rule there, the closest one
/// is activated (`solver::contact` `NEARLY_TOUCHING`), so the first
/// iteration is not singular; a coarse mesh is still within 4 %.
#[test]
fn hertz_coarsest_mesh_is_not_singular() {
    let mut s = scene("hertz-small-strain.toml");
    s.mesh.as_mut().unwrap().file = "hertz-refinement/h0.8.msh".to_string();
    let sol = solve(&s, &SolveOptions::from_scene(&s)).unwrap();
    let m = measure(&sol, &SCENES);
    assert!(m.peak_error(&SCENES).abs() < 0.04, "{m:?}");
    assert!(m.in_contact >= 3, "{m:?}");
}

/// The finite-strain fine mesh under a quarter, half and the full load:
/// the peak error against Hertz (a small-strain theory) grows with the
/// strain `a / (2R)`, so what separates `hertz.toml` from Hertz at the full
/// load is the finite strain of St Venant–Kirchhoff, not the
/// discretisation (which the small-strain test bounds).
#[test]
#[ignore = "about 6 s in release: cargo test --release --test hertz -- --ignored --nocapture"]
fn hertz_finite_strain_error_grows_with_load() {
    let errors: Vec<f64> = [0.25, 0.5, 1.0]
        .map(|scale| {
            let (m, problem) = run("hertz.toml", scale);
            m.peak_error(&problem).abs()
        })
        .to_vec();
    assert!(errors[0] < errors[1] && errors[1] < errors[2], "{errors:?}");
}

/// The all-triangle coarse mesh (`scenes/hertz-tri-coarse.toml`, written
/// by `scripts/make-hertz-mesh.py 0.5 --triangles`: 1711 linear triangles,
/// edges of 0.245 at the contact against the quadrilateral mesh's 0.227,
/// 4 nodes in contact, finite strain).
///
/// Measured: peak 5.578 (+1.5 %), fit p0 -5.8 %, fit a +74 %, profile
/// error 17 %, 7 Newton iterations. The nodal pressures oscillate from node
/// to node as on the quadrilateral mesh, more strongly (5.03, 5.58, 4.42,
/// 4.87 at x = 0, 0.24, 0.49, 0.73 against Hertz's 5.49, 5.33, 4.79,
/// 3.73). So the peak is held to the quadrilateral coarse mesh's tolerance
/// (4 %), the profile to 20 %; the fit, with 4 nodes in contact of which
/// the last overshoots, says little about `a` on this mesh and is not held.
#[test]
fn hertz_tri_coarse() {
    let (m, problem) = run("hertz-tri-coarse.toml", 1.0);
    assert!(m.peak_error(&problem).abs() < 0.04, "{m:?}");
    assert!(m.profile < 0.20, "{m:?}");
    assert!(m.in_contact >= 4, "{m:?}");
}
