//! Tests of the Gmsh source: a small hand-written mesh (two bodies, curves
//! drawn either way, an interior curve, a point, a triangle), the faces'
//! orientation, groups in every item, tractions, and every bad input named
//! with its file and item; a second hand-written mesh that mixes triangles
//! and quadrilaterals (`mesh/gmsh/testdata/mixed.msh`), read through a
//! scene and solved.

use std::path::{Path, PathBuf};

use super::*;
use crate::ids::DofId;
use crate::model::Model;
use crate::scene::source::resolve;

/// Surface `a`: two quadrangles on [0, 2] x [0, 1] (nodes 1..6); surface
/// `b`: one quadrangle on [0, 2] x [1, 2] (nodes 7..10, its own nodes);
/// surface `t`: one triangle (nodes 11..13). Curves: `a_top` (drawn
/// clockwise around `a`: 6 -> 5 -> 4), `a_middle` (the edge between `a`'s
/// two elements), `a_bottom` (1 -> 2 -> 3), `b_bottom` (7 -> 8); point
/// `b_corner` (node 10).
const MESH: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
9
0 20 \"b_corner\"
1 11 \"a_top\"
1 12 \"a_middle\"
1 13 \"a_bottom\"
1 14 \"b_bottom\"
2 1 \"a\"
2 2 \"b\"
2 3 \"t\"
2 4 \"ab\"
$EndPhysicalNames
$Entities
1 4 3 0
1 0 2 0 1 20
1 0 1 0 2 1 0 1 11 0
2 1 0 0 1 1 0 1 12 0
3 0 0 0 2 0 0 1 13 0
4 0 1 0 2 1 0 1 14 0
1 0 0 0 2 1 0 2 1 4 0
2 0 1 0 2 2 0 2 2 4 0
3 5 0 0 6 1 0 1 3 0
$EndEntities
$Nodes
3 13 1 13
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
2 1 0
1 1 0
0 1 0
2 2 0 4
7
8
9
10
0 1 0
2 1 0
2 2 0
0 2 0
2 3 0 3
11
12
13
5 0 0
6 0 0
5 1 0
$EndNodes
$Elements
8 11 1 11
0 1 15 1
1 10
1 1 1 2
2 6 5
3 5 4
1 2 1 1
4 2 5
1 3 1 2
5 1 2
6 2 3
1 4 1 1
7 7 8
2 1 3 2
8 1 2 5 6
9 2 3 4 5
2 2 3 1
10 7 8 9 10
2 3 2 1
11 11 12 13
$EndElements
";

const SCENE: &str = r#"
[mesh]
file = "two.msh"

[material]
young = 100.0
poisson = 0.25

[[body]]
name = "a"

[[body]]
name = "upper"
group = "b"

[[fix]]
group = "a_bottom"

[[load]]
group = "b_corner"
force = [1.0, 0.0]

[[traction]]
group = "a_bottom"
force_per_length = [0.0, -2.0]

[[contact]]
slave = { group = "b_bottom" }
master = { group = "a_top", body = "a" }

[loading]
load_factor_end = 1.0
steps = [1]
"#;

/// A fresh directory holding `two.msh` (the [`MESH`] after `edit`), for
/// the test `name`.
fn dir_with_mesh(name: &str, edit: impl FnOnce(String) -> String) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-gmsh-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("two.msh"), edit(MESH.to_owned())).unwrap();
    dir
}

/// The scene text `scene` read as `DIR/scene.toml`, next to the mesh.
fn build(
    name: &str,
    scene: &str,
    edit: impl FnOnce(String) -> String,
) -> Result<Model, SceneError> {
    let dir = dir_with_mesh(name, edit);
    let origin = dir.join("scene.toml");
    let result =
        Scene::from_toml_str(scene, &origin.display().to_string()).and_then(|s| s.build_model());
    std::fs::remove_dir_all(&dir).ok();
    result
}

/// The error message of a scene that must fail.
fn error(name: &str, scene: &str) -> String {
    build(name, scene, |m| m)
        .expect_err("the scene should be rejected")
        .to_string()
}

fn raw(segments: &[[NodeId; 2]]) -> Vec<[usize; 2]> {
    segments.iter().map(|s| s.map(NodeId::index)).collect()
}

#[test]
fn chains_follow_shared_nodes() {
    // 3 -> 4, 1 -> 2, 2 -> 3, and a separate 7 -> 8
    let segs = [[3, 4], [7, 8], [1, 2], [2, 3]];
    assert_eq!(chain(&segs), [[7, 8], [1, 2], [2, 3], [3, 4]]);
    // a closed loop starts at its first segment in the file
    let ring = [[2, 3], [3, 1], [1, 2]];
    assert_eq!(chain(&ring), [[2, 3], [3, 1], [1, 2]]);
}

#[test]
fn mesh_files_are_relative_to_the_scene() {
    assert_eq!(
        resolve("scenes/hertz.toml", "hertz.msh"),
        Path::new("scenes/hertz.msh")
    );
    assert_eq!(resolve("hertz.toml", "m/x.msh"), Path::new("m/x.msh"));
    assert_eq!(resolve("a/b.toml", "/abs/x.msh"), Path::new("/abs/x.msh"));
}

#[test]
fn groups_make_bodies_supports_loads_tractions_and_faces() {
    let m = build("good", SCENE, |m| m).unwrap();
    assert_eq!(m.mesh.bodies.len(), 2);
    assert_eq!(m.mesh.bodies[0].nodes, 0..6);
    assert_eq!(m.mesh.bodies[1].name, "upper");
    assert_eq!(m.mesh.bodies[1].nodes, 6..10);
    assert_eq!(m.mesh.nodes_ref[9], [0.0, 2.0]);
    let fixed: Vec<usize> = m.prescribed.iter().map(|p| p.dof.index()).collect();
    assert_eq!(fixed, [0, 1, 2, 3, 4, 5]);
    let loads: Vec<(usize, f64)> = m.loads.iter().map(|l| (l.dof.index(), l.value)).collect();
    // the point load on node 10 (mesh node 9), then t L / 2 on 1, 2 and 2, 3
    assert_eq!(
        loads,
        [
            (18, 1.0),
            (19, 0.0),
            (0, 0.0),
            (1, -1.0),
            (2, 0.0),
            (3, -1.0),
            (2, 0.0),
            (3, -1.0),
            (4, 0.0),
            (5, -1.0)
        ]
    );
    let c = &m.contacts[0];
    // b_bottom as drawn (7 -> 8 runs counter-clockwise around b)
    assert_eq!(raw(&c.slave), [[6, 7]]);
    // a_top was drawn 6 -> 5 -> 4: turned to 4 -> 5 -> 6 (mesh 3, 4, 5)
    assert_eq!(raw(&c.master), [[3, 4], [4, 5]]);
}

#[test]
fn faces_are_oriented_by_their_elements_however_drawn() {
    // the same mesh with every curve drawn the other way
    let flipped = |m: String| {
        m.replace("2 6 5\n3 5 4", "2 4 5\n3 5 6")
            .replace("7 7 8", "7 8 7")
    };
    let m = build("flipped", SCENE, flipped).unwrap();
    let c = &m.contacts[0];
    assert_eq!(raw(&c.slave), [[6, 7]]);
    assert_eq!(raw(&c.master), [[3, 4], [4, 5]]);
    // outward normals (t.y, -t.x): the slave's points down, the master's up
    let normal = |s: &[NodeId; 2]| {
        let (a, b) = (m.mesh.node_ref(s[0]), m.mesh.node_ref(s[1]));
        [b[1] - a[1], -(b[0] - a[0])]
    };
    assert!(normal(&c.slave[0])[1] < 0.0);
    assert!(c.master.iter().all(|s| normal(s)[1] > 0.0));
}

#[test]
fn blocks_and_mesh_bodies_mix() {
    let scene = SCENE.replace(
        "[[fix]]",
        "[[body]]\nname = \"block\"\norigin = [5.0, 5.0]\nsize = [1.0, 1.0]\nnx = 1\nny = 1\n\n[[fix]]\nbody = \"block\"\ny = 5.0\n\n[[fix]]",
    );
    let m = build("mixed", &scene, |m| m).unwrap();
    assert_eq!(m.mesh.bodies.len(), 3);
    assert_eq!(m.mesh.bodies[2].nodes, 10..14);
    assert_eq!(m.prescribed[0].dof, DofId::of(NodeId::new(10), 0));
}

#[test]
fn a_missing_mesh_file_is_named() {
    let msg = error("missing", &SCENE.replace("two.msh", "none.msh"));
    assert!(
        msg.contains("mesh.file") && msg.contains("none.msh"),
        "{msg}"
    );
    assert!(msg.contains("cannot read the file"), "{msg}");
}

#[test]
fn a_malformed_mesh_file_is_named() {
    let result = build("malformed", SCENE, |m| m.replace("$EndNodes", "$EndNodez"));
    let msg = result.unwrap_err().to_string();
    assert!(
        msg.contains("mesh.file") && msg.contains("two.msh"),
        "{msg}"
    );
    assert!(msg.contains("line"), "{msg}");
}

#[test]
fn unknown_groups_list_the_known_ones() {
    let msg = error(
        "unknown",
        &SCENE.replace(
            "group = \"a_bottom\"\n\n[[load]]",
            "group = \"a_botom\"\n\n[[load]]",
        ),
    );
    assert!(
        msg.contains("fix[0].group") && msg.contains("`a_botom`"),
        "{msg}"
    );
    assert!(msg.contains("`a_bottom`, `a_middle`"), "{msg}");
    assert!(msg.contains("two.msh"), "{msg}");
    let msg = error(
        "unknown-body",
        &SCENE.replace("name = \"a\"", "name = \"c\""),
    );
    assert!(msg.contains("body[0].name") && msg.contains("`c`"), "{msg}");
}

#[test]
fn groups_of_the_wrong_dimension_are_named() {
    let msg = error(
        "dimension",
        &SCENE.replace(
            "slave = { group = \"b_bottom\" }",
            "slave = { group = \"b\" }",
        ),
    );
    assert!(msg.contains("contact[0].slave.group"), "{msg}");
    assert!(msg.contains("`b` has dimension 2"), "{msg}");
    let msg = error(
        "dimension-body",
        &SCENE.replace("group = \"b\"", "group = \"b_bottom\""),
    );
    assert!(
        msg.contains("body[1].group") && msg.contains("dimension 1"),
        "{msg}"
    );
    let msg = error(
        "dimension-traction",
        &SCENE.replace(
            "group = \"a_bottom\"\nforce_per",
            "group = \"b_corner\"\nforce_per",
        ),
    );
    assert!(
        msg.contains("traction[0].group") && msg.contains("dimension 0"),
        "{msg}"
    );
}

#[test]
fn a_contact_group_off_the_boundary_is_named() {
    let msg = error(
        "interior",
        &SCENE.replace("group = \"a_top\"", "group = \"a_middle\""),
    );
    assert!(msg.contains("contact[0].master.group"), "{msg}");
    assert!(
        msg.contains("`a_middle` is not on the boundary of a body")
            && msg.contains("between two elements"),
        "{msg}"
    );
    assert!(msg.contains("two.msh"), "{msg}");
    // a curve whose body is not a [[body]] of the scene
    let scene = SCENE
        .replace("[[body]]\nname = \"upper\"\ngroup = \"b\"\n", "")
        .replace("[[load]]\ngroup = \"b_corner\"\nforce = [1.0, 0.0]\n", "");
    let msg = error("not-a-body", &scene);
    assert!(
        msg.contains("contact[0].slave.group") && msg.contains("no edge of an element"),
        "{msg}"
    );
    // the face's body named wrongly
    let msg = error(
        "wrong-body",
        &SCENE.replace("body = \"a\"", "body = \"upper\""),
    );
    assert!(
        msg.contains("contact[0].master.body") && msg.contains("is on body `a`"),
        "{msg}"
    );
}

#[test]
fn nodes_outside_every_body_are_named() {
    let scene = SCENE
        .replace("[[body]]\nname = \"upper\"\ngroup = \"b\"\n", "")
        .replace(
            "[[contact]]\nslave = { group = \"b_bottom\" }\nmaster = { group = \"a_top\", body = \"a\" }\n",
            "",
        );
    let msg = error("orphan", &scene);
    assert!(msg.contains("load[0].group"), "{msg}");
    assert!(
        msg.contains("node 10 of physical group `b_corner` belongs to no [[body]]"),
        "{msg}"
    );
}

#[test]
fn triangles_make_bodies() {
    let m = build("triangles", &SCENE.replace("group = \"b\"", "group = \"t\"").replace(
        "[[contact]]\nslave = { group = \"b_bottom\" }\nmaster = { group = \"a_top\", body = \"a\" }\n",
        "",
    ).replace("[[load]]\ngroup = \"b_corner\"\nforce = [1.0, 0.0]\n", ""), |m| m)
    .unwrap();
    let upper = &m.mesh.bodies[1];
    assert_eq!(upper.nodes, 6..9);
    assert_eq!(upper.elements, 2..3);
    assert_eq!(
        m.mesh.elements[2].map_nodes(NodeId::index),
        crate::mesh::Element::Tri3([6, 7, 8])
    );
    assert_eq!(m.mesh.nodes_ref[8], [5.0, 1.0]);
    assert!(
        (m.mesh
            .geometry(crate::ids::ElementId::new(2))
            .unwrap()
            .area_ref()
            - 0.5)
            .abs()
            < 1e-15
    );
}

#[test]
fn inverted_triangles_are_named() {
    let scene = SCENE.replace("group = \"b\"", "group = \"t\"");
    let result = build("inverted-tri", &scene, |m| {
        m.replace("11 11 12 13", "11 11 13 12")
    });
    let msg = result.unwrap_err().to_string();
    assert!(
        msg.contains("body[1].group") && msg.contains("two.msh"),
        "{msg}"
    );
    assert!(
        msg.contains(
            "element 11 of physical surface `t` is inverted or degenerate (3-node triangle"
        ),
        "{msg}"
    );
    // collinear nodes: degenerate
    let result = build("flat-tri", &scene, |m| {
        m.replace("5 1 0\n$EndNodes", "7 0 0\n$EndNodes")
    });
    let msg = result.unwrap_err().to_string();
    assert!(
        msg.contains("element 11 of physical surface `t` is inverted or degenerate"),
        "{msg}"
    );
}

#[test]
fn second_order_triangles_are_named() {
    // a 6-node triangle (Gmsh type 9) in place of the 3-node one
    let result = build("tri6", SCENE, |m| {
        m.replace("2 3 2 1\n11 11 12 13", "2 3 9 1\n11 11 12 13 1 2 3")
    });
    let msg = result.unwrap_err().to_string();
    assert!(
        msg.contains("mesh.file") && msg.contains("two.msh"),
        "{msg}"
    );
    assert!(
        msg.contains("6-node second order triangle (type 9)"),
        "{msg}"
    );
}

#[test]
fn bodies_share_no_nodes() {
    let msg = error("shared", &SCENE.replace("group = \"b\"", "group = \"a\""));
    assert!(
        msg.contains("body[1].group") && msg.contains("shares node 1 with body `a`"),
        "{msg}"
    );
    // one group over both surfaces is one body, and the two surfaces
    // touch at doubled nodes: the body falls apart there
    let scene = SCENE
        .replace("[[body]]\nname = \"upper\"\ngroup = \"b\"\n", "")
        .replace("name = \"a\"", "name = \"a\"\ngroup = \"ab\"")
        .replace(", body = \"a\"", "");
    let msg = error("one-body", &scene);
    assert!(
        msg.contains("body[0].group")
            && msg.contains("physical surface `ab` falls apart")
            && msg.contains("(the body is in 2 pieces)")
            && msg.contains("make the pieces separate bodies"),
        "{msg}"
    );
}

#[test]
fn inverted_elements_are_named() {
    let result = build("inverted", SCENE, |m| m.replace("8 1 2 5 6", "8 1 6 5 2"));
    let msg = result.unwrap_err().to_string();
    assert!(msg.contains("body[0].name"), "{msg}");
    assert!(
        msg.contains("element 8 of physical surface `a` is inverted"),
        "{msg}"
    );
}

#[test]
fn groups_need_a_mesh_file() {
    let text = r#"
[material]
young = 1.0
poisson = 0.0
[[body]]
name = "a"
origin = [0.0, 0.0]
size = [1.0, 1.0]
nx = 1
ny = 1
[[fix]]
group = "bottom"
[loading]
load_factor_end = 1.0
steps = [1]
"#;
    let msg = Scene::from_toml_str(text, "g.toml")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("fix[0].group") && msg.contains("[mesh] file"),
        "{msg}"
    );
    let msg = Scene::from_toml_str(
        &text.replace(
            "origin = [0.0, 0.0]\nsize = [1.0, 1.0]\nnx = 1\nny = 1\n",
            "",
        ),
        "g.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        msg.contains("body[0]") && msg.contains("[mesh] file"),
        "{msg}"
    );
}

/// `mesh/gmsh/testdata/mixed.msh`: body `base` on [0, 2] x [0, 1] (one
/// quadrangle and two triangles), body `top` on [0, 2] x [1, 2] (four
/// triangles, its own nodes); `top` rests on `base`, held only by contact
/// (`top_bottom`, drawn clockwise around `top`, against `base_top`, drawn
/// clockwise around `base`: both are turned by the triangles and the
/// quadrangle that own their edges), rollers on `bottom` and `left`, a dead
/// compression on `top_top`.
const MIXED: &str = r#"
[mesh]
file = "mixed.msh"
[material]
young = 100.0
poisson = 0.3
model = "plane-strain"
[[body]]
name = "base"
[[body]]
name = "top"
[[fix]]
group = "bottom"
dofs = "y"
[[fix]]
group = "left"
dofs = "x"
[[traction]]
group = "top_top"
force_per_length = [0.0, -3.0]
[[contact]]
slave = { group = "top_bottom" }
master = { group = "base_top" }
mode = "unilateral"
[loading]
load_factor_end = 1.0
steps = [2]
"#;

/// The mixed mesh read through a scene and solved: the exact solution is
/// homogeneous uniaxial compression of both bodies (with lateral
/// expansion, the two bodies' equal), which every element reproduces: the
/// same PK2 stress in all seven elements with `S_xx = 0` and the dead load
/// carried, `(1 + du_y/dY) S_yy = -3` (tolerances 1e-9 relative: Newton's
/// convergence); the displacement is linear in the reference coordinates,
/// and the contact pressure is the uniform traction.
#[test]
fn mixed_mesh_is_read_and_solved() {
    let origin = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/mesh/gmsh/testdata/mixed.toml");
    let scene = Scene::from_toml_str(MIXED, &origin.display().to_string()).unwrap();
    let model = scene.build_model::<2>().unwrap();
    let mesh = &model.mesh;
    let kinds: Vec<crate::mesh::ElementKind> = mesh.elements.iter().map(|e| e.kind()).collect();
    use crate::mesh::ElementKind::{Quad4, Tri3};
    assert_eq!(kinds, [Quad4, Tri3, Tri3, Tri3, Tri3, Tri3, Tri3]);
    // faces turned by their elements: outward normals (t.y, -t.x)
    let c = &model.contacts[0];
    let normal_y = |s: &[NodeId; 2]| -(mesh.node_ref(s[1])[0] - mesh.node_ref(s[0])[0]);
    assert_eq!(c.slave.len(), 2);
    assert!(c.slave.iter().all(|s| normal_y(s) < 0.0), "{:?}", c.slave);
    assert!(c.master.iter().all(|s| normal_y(s) > 0.0), "{:?}", c.master);
    let sol = crate::solve::<2>(&scene, &crate::SolveOptions::default()).unwrap();
    let s = sol.element_stresses(&sol.final_state).unwrap();
    let syy = s[0].pk2[1];
    assert!(syy < -1.0, "{s:?}");
    for (e, st) in s.iter().enumerate() {
        for k in 0..3 {
            assert!(
                (st.pk2[k] - s[0].pk2[k]).abs() < 1e-9 * syy.abs(),
                "element {e}: {st:?} vs {:?}",
                s[0]
            );
        }
        assert!(st.pk2[0].abs() < 1e-9 * syy.abs() && st.pk2[2].abs() < 1e-9 * syy.abs());
    }
    // u = (a X, b Y) in both bodies
    let at = |body: &str, x: [f64; 2]| sol.displacement(sol.node_at(body, x).unwrap());
    let a = at("base", [2.0, 0.0])[0] / 2.0;
    let b = at("top", [0.0, 2.0])[1] / 2.0;
    assert!(a > 0.0 && b < 0.0, "{a} {b}");
    for body in ["base", "top"] {
        for n in sol.mesh.bodies[sol.mesh.body_index(body).unwrap()].node_ids() {
            let x = sol.mesh.node_ref(n);
            let u = sol.displacement(n);
            assert!((u[0] - a * x[0]).abs() < 1e-9 * b.abs(), "{body} {x:?}");
            assert!((u[1] - b * x[1]).abs() < 1e-9 * b.abs(), "{body} {x:?}");
        }
    }
    assert!(((1.0 + b) * syy + 3.0).abs() < 1e-9 * 3.0, "{b} {syy}");
    // the multipliers carry the load: their sum over the interface, with
    // the tributary lengths, is the total force 3 x 2 (pressure positive)
    assert!(!sol.final_state.multipliers.is_empty());
    let pressure: Vec<f64> = sol.final_state.multipliers.iter().map(|l| -l).collect();
    for p in &pressure {
        assert!(
            (p - pressure[0]).abs() < 1e-9 * pressure[0].abs(),
            "{pressure:?}"
        );
    }
    assert!(pressure[0] > 0.0);
}
