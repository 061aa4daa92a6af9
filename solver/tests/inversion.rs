//! Elements that invert during the solve (issue "Nothing silently wrong in
//! 3D", item 1): a block crushed past its own height has no state without
//! an inverted element, so the solve must end in an error naming one,
//! never in a result; the same block crushed to half its height solves,
//! with every element's volume ratio positive.

use solver::{CutbackReason, Scene, SolveOptions, SolverError, solve};

/// A block of height 0.5 on a clamped base, its top pressed down by
/// `press` (3D: 2 x 2 x 2 hexahedra; 2D: 2 x 2 quadrilaterals), with the
/// finite-strain material.
fn crushed(dim: usize, press: f64, steps: usize) -> String {
    let (origin, size, cells, top, fix_bottom, press_top) = if dim == 3 {
        (
            "[0.0, 0.0, 0.0]",
            "[1.0, 1.0, 0.5]",
            "nx = 2\nny = 2\nnz = 2",
            "z = 0.5",
            "z = 0.0",
            format!("ux = 0.0\nuy = 0.0\nuz = {}", -press),
        )
    } else {
        (
            "[0.0, 0.0]",
            "[1.0, 0.5]",
            "nx = 2\nny = 2",
            "y = 0.5",
            "y = 0.0",
            format!("ux = 0.0\nuy = {}", -press),
        )
    };
    format!(
        r#"
[material]
young = 100.0
poisson = 0.3

[[body]]
name = "block"
origin = {origin}
size = {size}
{cells}

[[fix]]
name = "base"
{fix_bottom}

[[prescribe]]
name = "press"
{top}
{press_top}

[loading]
load_factor_end = 1.0
steps = [{steps}]
"#
    )
}

fn options(scene: &Scene) -> SolveOptions {
    SolveOptions::from_scene(scene)
}

/// Pressed 0.6 through its 0.5 height: the error names an inverted
/// element, in 2D and in 3D, with the step and its cut-backs.
#[test]
fn a_block_crushed_through_its_height_is_an_error_naming_the_element() {
    for dim in [2, 3] {
        let scene = Scene::from_toml_str(&crushed(dim, 0.6, 2), "crushed.toml").unwrap();
        let result = if dim == 3 {
            solve::<3>(&scene, &options(&scene)).map(|_| ())
        } else {
            solve::<2>(&scene, &options(&scene)).map(|_| ())
        };
        let err = result.expect_err("a crushed block must not solve");
        let text = err.to_string();
        match &err {
            SolverError::Diverged {
                reason: CutbackReason::InvertedElement(inv),
                ..
            } => {
                assert!(inv.det_f <= 0.0, "{inv:?}");
                let kind = if dim == 3 {
                    "(8-node hexahedron) of body `block`"
                } else {
                    "(4-node quadrilateral) of body `block`"
                };
                assert!(inv.label.contains(kind), "{text}");
            }
            other => panic!("{dim}D: expected an inverted element, got {other}"),
        }
        assert!(text.contains("is inverted (det F = "), "{text}");
        assert!(text.starts_with("step 2: no convergence"), "{text}");
    }
}

/// Half its height: solved, every element's smallest `det F` positive (and
/// about a half: the block is squeezed to 0.25 of its 0.5).
#[test]
fn a_block_crushed_to_half_its_height_solves_with_positive_volumes() {
    let scene = Scene::from_toml_str(&crushed(3, 0.25, 2), "half.toml").unwrap();
    let sol = solve::<3>(&scene, &options(&scene)).unwrap();
    let u = &sol.final_state.displacements;
    let flat: Vec<f64> = u.iter().flatten().copied().collect();
    assert_eq!(sol.mesh.most_inverted(&flat).unwrap(), None);
    for e in 0..sol.mesh.element_count() {
        let el = solver::ids::ElementId::new(e);
        let det = sol
            .mesh
            .geometry(el)
            .unwrap()
            .min_det_f(&sol.mesh.element_displacements(el, &flat));
        assert!(det > 0.3 && det < 0.7, "element {e}: {det}");
    }
}
