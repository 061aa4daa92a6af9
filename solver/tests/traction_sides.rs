//! `[[traction]]` on the side of a block body (`body` and `side`, as a
//! contact face names it): consistent nodal loads `t L / 2` per segment end,
//! exactly as on a mesh curve. Checked against the equivalent `[[load]]`
//! nodal forces (to the bit where the arithmetic is the same), against the
//! nodal forces computed by hand, against the exact solution of a uniform
//! tension, and for every way of naming the side wrongly.

use solver::{Scene, SceneError, SolveOptions, solve};

/// A block `[0, 3] x [0, 1]` of 3 x 1 elements under `extra`, clamped at
/// `x = 0`.
fn block(extra: &str) -> String {
    format!(
        r#"
[material]
young = 1000.0
poisson = 0.3

[[body]]
name = "beam"
origin = [0.0, 0.0]
size = [3.0, 1.0]
nx = 3
ny = 1

[[fix]]
x = 0.0

{extra}

[loading]
load_factor_end = 1.0
steps = [2]
"#
    )
}

/// The model's external force vector at load factor one: every point load
/// added into its dof in model order, as the solver assembles them.
fn nodal_forces(scene: &Scene) -> Vec<f64> {
    let model = scene.build_model::<2>().unwrap();
    let mut f = vec![0.0; 2 * model.mesh.node_count()];
    for l in &model.loads {
        assert!(l.amplitude.is_none());
        f[l.dof.index()] += l.value;
    }
    f
}

fn read(text: &str) -> Scene {
    Scene::from_toml_str(text, "traction.toml").unwrap()
}

/// A traction on the top side of a block gives the nodal forces of the
/// `[[load]]`s a user would write (`t h / 2` at the side's ends, `t h`
/// between; `h = 1` here, so the halving and the sum of two halves are
/// exact): the same force vector and the same solution, bit for bit.
#[test]
fn a_side_traction_is_the_equivalent_nodal_loads_to_the_bit() {
    let t = [0.3, -0.7];
    let traction = read(&block(&format!(
        "[[traction]]\nbody = \"beam\"\nside = \"top\"\nforce_per_length = [{}, {}]",
        t[0], t[1]
    )));
    let loads: String = [(0.0, 0.5), (1.0, 1.0), (2.0, 1.0), (3.0, 0.5)]
        .iter()
        .map(|&(x, share)| {
            format!(
                "[[load]]\nat = [{x:?}, 1.0]\nforce = [{:?}, {:?}]\n",
                t[0] * share,
                t[1] * share
            )
        })
        .collect();
    let loaded = read(&block(&loads));
    let (ft, fl) = (nodal_forces(&traction), nodal_forces(&loaded));
    assert_eq!(
        ft.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        fl.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        "traction {ft:?}\nloads {fl:?}"
    );
    // the force vector is not trivially zero: the top nodes carry t
    assert_eq!(fl[2 * 5 + 1], t[1]);
    let (st, sl) = (
        solve::<2>(&traction, &SolveOptions::from_scene(&traction)).unwrap(),
        solve::<2>(&loaded, &SolveOptions::from_scene(&loaded)).unwrap(),
    );
    assert!(st.strain_energy > 0.0);
    assert_eq!(st.strain_energy.to_bits(), sl.strain_energy.to_bits());
    assert_eq!(
        format!("{:?}", st.final_state.displacements),
        format!("{:?}", sl.final_state.displacements)
    );
}

/// Segment lengths that are not exact (the left side of a block at an
/// offset, 4 segments of 0.075): the nodal forces are `t L / 2` per segment
/// end, as computed by hand, to 1e-14 relative; the sum is `t` times the
/// side's length; and the side is loaded counter-clockwise like a contact
/// face (every side of the block, each on its own nodes).
#[test]
fn side_tractions_match_the_hand_computed_nodal_forces() {
    let (x0, y0, w, h, nx, ny) = (0.1, 0.2, 0.7, 0.3, 3usize, 4usize);
    let t = [-1.3, 0.45];
    for side in ["bottom", "right", "top", "left"] {
        let text = format!(
            r#"
[material]
young = 1000.0
poisson = 0.3
[[body]]
name = "b"
origin = [{x0:?}, {y0:?}]
size = [{w:?}, {h:?}]
nx = {nx}
ny = {ny}
[[fix]]
at = [{x0:?}, {y0:?}]
[[traction]]
body = "b"
side = "{side}"
force_per_length = [{}, {}]
[loading]
load_factor_end = 1.0
steps = [1]
"#,
            t[0], t[1]
        );
        let f = nodal_forces(&read(&text));
        // block node (i, j) is j (nx + 1) + i; the side's nodes and segment
        // length by hand
        let (nodes, length): (Vec<usize>, f64) = match side {
            "bottom" => ((0..=nx).collect(), w / nx as f64),
            "top" => ((0..=nx).map(|i| ny * (nx + 1) + i).collect(), w / nx as f64),
            "left" => ((0..=ny).map(|j| j * (nx + 1)).collect(), h / ny as f64),
            _ => ((0..=ny).map(|j| j * (nx + 1) + nx).collect(), h / ny as f64),
        };
        let mut expected = vec![0.0; f.len()];
        for (k, &n) in nodes.iter().enumerate() {
            let share = if k == 0 || k + 1 == nodes.len() {
                0.5
            } else {
                1.0
            };
            for c in 0..2 {
                expected[2 * n + c] = t[c] * length * share;
            }
        }
        for (d, (a, e)) in f.iter().zip(&expected).enumerate() {
            assert!(
                (a - e).abs() <= 1e-14 * e.abs(),
                "{side}: dof {d}: {a} against {e}"
            );
        }
        let side_length = if matches!(side, "bottom" | "top") {
            w
        } else {
            h
        };
        for (c, tc) in t.iter().enumerate() {
            let total: f64 = f.iter().skip(c).step_by(2).sum();
            assert!(
                (total - tc * side_length).abs() <= 1e-14 * (tc * side_length).abs(),
                "{side}: total {total}"
            );
        }
    }
}

/// A single rectangle in uniform tension by a traction on its right side
/// (linear elasticity, plane stress, rollers on the left and bottom): the
/// exact solution `u = t x / E`, `v = -nu t y / E`, strain energy
/// `t^2 A / (2 E)`, which the bilinear elements reproduce exactly.
#[test]
fn a_right_side_traction_stretches_a_block_as_by_hand() {
    let (young, nu, t, w, h) = (1000.0, 0.25, 5.0, 2.0, 1.0);
    let text = format!(
        r#"
[material]
young = {young:?}
poisson = {nu:?}
kinematics = "small"
[[body]]
name = "bar"
origin = [0.0, 0.0]
size = [{w:?}, {h:?}]
nx = 2
ny = 3
[[fix]]
x = 0.0
dofs = "x"
[[fix]]
y = 0.0
dofs = "y"
[[traction]]
body = "bar"
side = "right"
force_per_length = [{t:?}, 0.0]
[loading]
load_factor_end = 1.0
steps = [1]
"#
    );
    let scene = read(&text);
    let s = solve(&scene, &SolveOptions::from_scene(&scene)).unwrap();
    for (n, u) in s.final_state.displacements.iter().enumerate() {
        let [x, y] = s.mesh.nodes_ref[n];
        let exact = [t * x / young, -nu * t * y / young];
        for c in 0..2 {
            assert!(
                (u[c] - exact[c]).abs() <= 1e-12 * (t * w / young),
                "node {n} at ({x}, {y}): {u:?} against {exact:?}"
            );
        }
    }
    let energy = t * t * w * h / (2.0 * young);
    assert!(
        (s.strain_energy - energy).abs() <= 1e-12 * energy,
        "{} against {energy}",
        s.strain_energy
    );
}

fn invalid(text: &str) -> (String, String) {
    match Scene::from_toml_str(text, "traction.toml") {
        Err(SceneError::Invalid { field, message, .. }) => (field, message),
        other => panic!("expected an invalid field, got {other:?}"),
    }
}

/// Every wrong way of naming a traction's face is an error naming the field.
#[test]
fn a_wrongly_named_side_is_an_error_naming_the_field() {
    let with = |keys: &str| {
        block(&format!(
            "[[traction]]\n{keys}\nforce_per_length = [0.0, -1.0]"
        ))
    };
    let cases = [
        (
            "side = \"top\"",
            "traction[0].body",
            "a `side` needs its `body`",
        ),
        (
            "body = \"beam\"",
            "traction[0]",
            "give `body` and `side`, or `group`",
        ),
        ("", "traction[0]", "give `body` and `side`, or `group`"),
        (
            "body = \"beam\"\nside = \"top\"\ngroup = \"edge\"",
            "traction[0]",
            "give either `side` or `group`, not both",
        ),
        (
            "body = \"bean\"\nside = \"top\"",
            "traction[0].body",
            "no body named `bean` (bodies: beam)",
        ),
        (
            "group = \"edge\"",
            "traction[0].group",
            "physical groups need a `[mesh] file`",
        ),
    ];
    for (keys, field, message) in cases {
        assert_eq!(
            invalid(&with(keys)),
            (field.to_owned(), message.to_owned()),
            "{keys}"
        );
    }
    // an unknown side is a syntax error naming the field and the value
    let e =
        Scene::from_toml_str(&with("body = \"beam\"\nside = \"up\""), "traction.toml").unwrap_err();
    assert!(
        matches!(&e, SceneError::Syntax { field, message, .. }
            if field == "traction[0].side" && message.contains("`up`")),
        "{e:?}"
    );
}

/// A side of a body read from a mesh file is refused (it has no sides:
/// its curves are loaded by `group`), and a curve named with the wrong
/// `body` is refused naming both bodies.
#[test]
fn mesh_bodies_have_no_sides_and_a_curve_keeps_to_its_body() {
    let mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/src/mesh/gmsh/testdata/mixed.msh"
    );
    let scene = |keys: &str| {
        format!(
            r#"
[mesh]
file = "{mesh}"
[material]
young = 100.0
poisson = 0.3
[[body]]
name = "base"
[[body]]
name = "top"
[[fix]]
group = "bottom"
[[traction]]
{keys}
force_per_length = [0.0, -3.0]
[loading]
load_factor_end = 1.0
steps = [1]
"#
        )
    };
    assert_eq!(
        invalid(&scene("body = \"top\"\nside = \"top\"")),
        (
            "traction[0].side".to_owned(),
            "body `top` is not a block body (load a physical curve with `group`)".to_owned()
        )
    );
    assert_eq!(
        invalid(&scene("body = \"base\"\ngroup = \"top_top\"")),
        (
            "traction[0].body".to_owned(),
            "physical curve `top_top` has a node of `top`, not of `base`".to_owned()
        )
    );
    // with its own body the curve loads as without one
    let with_body = read(&scene("body = \"top\"\ngroup = \"top_top\""));
    let without = read(&scene("group = \"top_top\""));
    assert_eq!(nodal_forces(&with_body), nodal_forces(&without));
    assert!(nodal_forces(&without).iter().any(|&v| v != 0.0));
}

/// `scenes/pressed-blocks.toml` loads its block's top with the five
/// `[[load]]`s of a uniform traction 1 (0.125 at the corners, 0.25 between);
/// the one `[[traction]]` on that side gives the same force vector and the
/// same solution (contact pressures included), bit for bit.
#[test]
fn the_pressed_blocks_loads_are_one_side_traction() {
    let text = include_str!("../../scenes/pressed-blocks.toml");
    let start = text.find("[[load]]").unwrap();
    let end = text.find("[[contact]]").unwrap();
    let with_traction = format!(
        "{}[[traction]]\nbody = \"block\"\nside = \"top\"\nforce_per_length = [0.0, -1.0]\n\n{}",
        &text[..start],
        &text[end..]
    );
    assert_eq!(text[start..end].matches("[[load]]").count(), 5);
    let (loads, traction) = (read(text), read(&with_traction));
    let bits = |f: Vec<f64>| f.into_iter().map(f64::to_bits).collect::<Vec<_>>();
    assert_eq!(bits(nodal_forces(&loads)), bits(nodal_forces(&traction)));
    let (sl, st) = (
        solve::<2>(&loads, &SolveOptions::from_scene(&loads)).unwrap(),
        solve::<2>(&traction, &SolveOptions::from_scene(&traction)).unwrap(),
    );
    assert!(sl.strain_energy > 0.0);
    assert_eq!(sl.strain_energy.to_bits(), st.strain_energy.to_bits());
    // Debug prints the shortest round-trip text: equal text, equal bits
    assert_eq!(
        format!("{:?}", sl.final_state.displacements),
        format!("{:?}", st.final_state.displacements)
    );
    assert_eq!(
        format!("{:?}", sl.final_state.multipliers),
        format!("{:?}", st.final_state.multipliers)
    );
}
