//! `scenes/cantilever3d.toml` through the scene path: a 3D block of 80 x 2
//! x 4 hexahedra (10 x 1 x 1), clamped at x = 0, with a uniform traction
//! on its free end (a tip load P), small strain. Its tip deflection, the
//! mean z displacement of the end face, against Timoshenko's beam,
//!
//! ```text
//! delta = P L^3 / (3 E I) + P L / (k G A),   I = b h^3 / 12, k = 5/6,
//! ```
//!
//! The scene takes Poisson's ratio 0, so that the clamp does not restrain
//! the section's lateral contraction, which beam theory leaves out (with
//! 0.3 the clamped solid is 3.0 % stiffer than the beam at this mesh);
//! what is left, -0.8 %, is the discretisation error of the fully
//! integrated trilinear hexahedra, slightly too stiff in bending.

use std::path::Path;

use solver::{Scene, SolveOptions, solve_model};

#[test]
fn the_3d_cantilever_bends_as_beam_theory_says() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cantilever3d.toml");
    let scene = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let model = scene.build_model::<3>().unwrap_or_else(|e| panic!("{e}"));
    let material = scene.material.unwrap().material();
    let (e, nu) = (material.young, material.poisson);
    let size = scene.bodies[0].size.unwrap().point::<3>().unwrap();
    let (l, b, h) = (size[0], size[1], size[2]);
    let t = scene.tractions[0].force_per_area.unwrap();
    let p = -t[2] * b * h;
    let solution = solve_model(&model, &SolveOptions::from_scene(&scene)).unwrap();
    let tip: Vec<usize> = (0..model.mesh.node_count())
        .filter(|&n| (model.mesh.nodes_ref[n][0] - l).abs() < 1e-12)
        .collect();
    assert_eq!(tip.len(), 3 * 5);
    let deflection = -tip
        .iter()
        .map(|&n| solution.final_state.displacements[n][2])
        .sum::<f64>()
        / tip.len() as f64;
    let i = b * h.powi(3) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    let beam = p * l.powi(3) / (3.0 * e * i) + p * l / (5.0 / 6.0 * g * b * h);
    let error = (deflection - beam) / beam;
    println!("tip deflection {deflection:.6e}, Timoshenko {beam:.6e}, relative error {error:+.4}");
    assert!(
        error.abs() < 0.03,
        "tip deflection {deflection}, beam theory {beam}"
    );
    // the end face moves down as a whole, no sideways drift
    for &n in &tip {
        let u = solution.final_state.displacements[n];
        assert!(u[1].abs() < 1e-3 * deflection, "{u:?}");
        assert!((-u[2] - deflection).abs() < 0.05 * deflection, "{u:?}");
    }
}
