//! Scenes in 3D: the keys a 3D scene has (three numbers, `nz`, `z`,
//! `uz`, `dofs` of x, y, z, `force_per_area`, the six sides), what each
//! dimension refuses (named by key), the scene's dimension from its
//! blocks or its mesh file, and the 3D Hertz scene as the issue writes it.

use std::path::PathBuf;

use super::{Coords, Dimension, Dofs, Scene, SceneError};
use crate::ids::NodeId;
use crate::mesh::Side;

/// A 3D block cantilever: 4 x 1 x 1 hexahedra, clamped at x = 0, a
/// traction on its free end.
const BLOCK3D: &str = r#"
[material]
young = 1000.0
poisson = 0.3

[[body]]
name = "beam"
origin = [0.0, 0.0, 0.0]
size = [4.0, 1.0, 1.0]
nx = 4
ny = 1
nz = 1

[[fix]]
x = 0.0

[[traction]]
body = "beam"
side = "right"
force_per_area = [0.0, 0.0, -0.01]

[loading]
load_factor_end = 1.0
steps = [1]
"#;

/// A 2D block (the first scene of docs/scenes.md).
const BLOCK2D: &str = r#"
[material]
young = 1000.0
poisson = 0.3

[[body]]
name = "beam"
origin = [0.0, 0.0]
size = [4.0, 1.0]
nx = 4
ny = 1

[[fix]]
x = 0.0

[[load]]
at = [4.0, 1.0]
force = [0.0, -0.5]

[loading]
load_factor_end = 1.0
steps = [2]
"#;

/// The 3D Hertz scene exactly as the issue writes it (`file` naming the
/// hexahedral mesh).
pub(super) const HERTZ3D: &str = r#"name = "hertz3d"
[mesh]
file = "hertz3d-hex.msh"
[material]
young = 200.0
poisson = 0.3
kinematics = "small"
[[body]]
name = "indenter"
[[body]]
name = "block"
[[fix]]
group = "symmetry_x"
dofs = "x"
[[fix]]
group = "symmetry_y"
dofs = "y"
[[fix]]
group = "bottom"
dofs = "xyz"
[[prescribe]]
group = "indenter_top"
uz = -0.1
[[contact]]
slave = { group = "indenter_surface" }
master = { group = "block_top" }
mode = "unilateral"
[loading]
load_factor_end = 1.0
steps = [1, 2, 4]
default_steps = 1
"#;

/// The scene file `name` in `scenes/` (for a `[mesh] file` next to it).
pub(super) fn scenes_dir(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
        .display()
        .to_string()
}

/// The `Invalid` error's field and message, or a panic naming the error.
fn invalid(text: &str) -> (String, String) {
    match Scene::from_toml_str(text, "bad.toml") {
        Err(SceneError::Invalid { field, message, .. }) => (field, message),
        other => panic!("expected an invalid field, got {other:?}"),
    }
}

#[test]
fn the_dimension_comes_from_the_blocks_or_the_mesh_file() {
    let s3 = error_free(BLOCK3D);
    assert_eq!(s3.dimension().unwrap(), Dimension::Three);
    assert_eq!(s3.bodies[0].origin, Some(Coords::Xyz([0.0, 0.0, 0.0])));
    assert_eq!(s3.bodies[0].nz, Some(1));
    let s2 = error_free(BLOCK2D);
    assert_eq!(s2.dimension().unwrap(), Dimension::Two);
    // the 3D Hertz mesh makes its scene 3D; the 2D Hertz mesh its 2D
    let mut hertz = super::error::parse(HERTZ3D, "hertz3d.toml").unwrap();
    hertz.origin = scenes_dir("hertz3d.toml");
    assert_eq!(hertz.dimension().unwrap(), Dimension::Three);
    let hertz2 = Scene::from_file(scenes_dir("hertz.toml")).unwrap();
    assert_eq!(hertz2.dimension().unwrap(), Dimension::Two);
}

/// Parsed, validated, and, if 3D with contact, not yet buildable.
fn error_free(text: &str) -> Scene {
    Scene::from_toml_str(text, "good.toml").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn bodies_of_both_dimensions_are_an_error_naming_the_body() {
    let text = BLOCK3D.replace(
        "[[fix]]",
        "[[body]]\nname = \"flat\"\norigin = [0.0, 2.0]\nsize = [1.0, 1.0]\nnx = 1\nny = 1\n\n[[fix]]",
    );
    let (field, message) = invalid(&text);
    assert_eq!(field, "body[1]");
    assert!(
        message.contains("2D block") && message.contains("`beam` is a 3D block"),
        "{message}"
    );
    // origin and size of different lengths in one block
    let (field, message) = invalid(&BLOCK3D.replace("size = [4.0, 1.0, 1.0]", "size = [4.0, 1.0]"));
    assert_eq!(field, "body[0].size");
    assert!(message.contains("`origin` has 3"), "{message}");
    // a 2D mesh file under 3D blocks
    let text = format!("[mesh]\nfile = \"hertz.msh\"\n{BLOCK3D}");
    match Scene::from_toml_str(&text, &scenes_dir("mixed.toml")) {
        Err(SceneError::Invalid { field, message, .. }) => {
            assert_eq!(field, "mesh.file");
            assert!(message.contains("is a 2D mesh"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn keys_of_3d_scenes_are_refused_in_2d_by_name() {
    for (from, to, field, says) in [
        (
            "ny = 1\n",
            "ny = 1\nnz = 2\n",
            "body[0].nz",
            "`nz` is for a 3D block",
        ),
        (
            "x = 0.0\n",
            "x = 0.0\nz = 0.0\n",
            "fix[0].z",
            "is for 3D scenes",
        ),
        (
            "x = 0.0\n",
            "x = 0.0\ndofs = \"xz\"\n",
            "fix[0].dofs",
            "the component z",
        ),
        (
            "at = [4.0, 1.0]",
            "at = [4.0, 1.0, 0.0]",
            "load[0].at",
            "needs two numbers [x, y] in a 2D scene, got 3",
        ),
        (
            "force = [0.0, -0.5]",
            "force = [0.0, -0.5, 0.0]",
            "load[0].force",
            "needs two numbers",
        ),
        (
            "[loading]",
            "[[prescribe]]\nx = 4.0\nuz = 0.1\n\n[loading]",
            "prescribe[0].uz",
            "is for 3D scenes",
        ),
        (
            "[loading]",
            "[[traction]]\nbody = \"beam\"\nside = \"top\"\nforce_per_area = [0.0, 0.0, 1.0]\n\n[loading]",
            "traction[0].force_per_area",
            "is for 3D scenes",
        ),
        (
            "[loading]",
            "[[traction]]\nbody = \"beam\"\nside = \"front\"\nforce_per_length = [0.0, 1.0]\n\n[loading]",
            "traction[0].side",
            "`front` is a side of a 3D block",
        ),
        (
            "[loading]",
            "[refine]\nz = 2\n\n[loading]",
            "refine.z",
            "is for 3D scenes",
        ),
    ] {
        assert!(BLOCK2D.contains(from), "{from}");
        let (f, message) = invalid(&BLOCK2D.replacen(from, to, 1));
        assert_eq!(f, field, "{to}: {message}");
        assert!(message.contains(says), "{to}: {message}");
    }
}

#[test]
fn keys_of_2d_scenes_are_refused_in_3d_by_name() {
    for (from, to, field, says) in [
        (
            "poisson = 0.3\n",
            "poisson = 0.3\nmodel = \"plane-strain\"\n",
            "material.model",
            "a 3D solid has no plane model",
        ),
        (
            "force_per_area = [0.0, 0.0, -0.01]",
            "force_per_length = [0.0, -0.01]",
            "traction[0].force_per_length",
            "a 3D traction is `force_per_area",
        ),
        (
            "x = 0.0\n",
            "at = [0.0, 0.0]\n",
            "fix[0].at",
            "needs three numbers [x, y, z] in a 3D scene, got 2",
        ),
        (
            "[loading]",
            "[[load]]\nat = [4.0, 1.0, 1.0]\nforce = [0.0, 1.0]\n\n[loading]",
            "load[0].force",
            "needs three numbers",
        ),
        (
            "[loading]",
            "[[traction]]\nbody = \"beam\"\nside = \"top\"\n\n[loading]",
            "traction[1]",
            "give `force_per_area",
        ),
    ] {
        assert!(BLOCK3D.contains(from), "{from}");
        let (f, message) = invalid(&BLOCK3D.replacen(from, to, 1));
        assert_eq!(f, field, "{to}: {message}");
        assert!(message.contains(says), "{to}: {message}");
    }
    // a body's own material, too
    let text = BLOCK3D.replace(
        "nz = 1\n",
        "nz = 1\nmaterial = { young = 1.0, poisson = 0.2, model = \"plane-stress\" }\n",
    );
    assert_eq!(invalid(&text).0, "body[0].material.model");
}

#[test]
fn coordinates_take_two_or_three_numbers() {
    for bad in ["[1.0]", "[1.0, 2.0, 3.0, 4.0]"] {
        let e = Scene::from_toml_str(
            &BLOCK2D.replace("[4.0, 1.0]\nnx", &format!("{bad}\nnx")),
            "bad.toml",
        )
        .unwrap_err();
        assert!(
            matches!(&e, SceneError::Syntax { field, message, .. }
                if field == "body[0].size"
                    && message.starts_with("needs two numbers [x, y] (2D) or three [x, y, z] (3D), got ")),
            "{bad}: {e:?}"
        );
    }
    let e = Scene::from_toml_str(
        &BLOCK3D.replace("[0.0, 0.0, -0.01]", "[0.0, -0.01]"),
        "bad.toml",
    )
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::Syntax { field, message, .. }
            if field == "traction[0].force_per_area" && message.contains("exactly three numbers")),
        "{e:?}"
    );
}

#[test]
fn dofs_are_any_set_of_x_y_z() {
    for (text, want) in [
        ("x", Dofs::X),
        ("y", Dofs::Y),
        ("z", Dofs::Z),
        ("xy", Dofs::XY),
        ("yx", Dofs::XY),
        ("xyz", Dofs::XYZ),
        ("zyx", Dofs::XYZ),
    ] {
        let d: Dofs = text.parse().unwrap();
        assert_eq!(d, want, "{text}");
    }
    let xz: Dofs = "zx".parse().unwrap();
    assert_eq!(xz.components().collect::<Vec<_>>(), [0, 2]);
    assert_eq!(xz.name(), "xz");
    for bad in ["", "xx", "w", "x y", "XY"] {
        let e = bad.parse::<Dofs>().unwrap_err();
        assert!(
            e.contains("non-empty set of the letters x, y, z"),
            "{bad}: {e}"
        );
    }
    // without `dofs` every component: two in 2D (as before), three in 3D
    assert_eq!(Dofs::all(2), Dofs::XY);
    assert_eq!(Dofs::all(3), Dofs::XYZ);
    let e = Scene::from_toml_str(
        &BLOCK2D.replace("x = 0.0\n", "x = 0.0\ndofs = \"xx\"\n"),
        "bad.toml",
    )
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::Syntax { field, .. } if field == "fix[0].dofs"),
        "{e:?}"
    );
}

#[test]
fn sides_have_six_names_and_four_in_2d() {
    for (name, side) in [
        ("left", Side::Left),
        ("right", Side::Right),
        ("front", Side::Front),
        ("back", Side::Back),
        ("bottom", Side::Bottom),
        ("top", Side::Top),
    ] {
        assert_eq!(side.name(), name);
        assert!(side.axis::<3>().is_some());
        assert_eq!(
            side.axis::<2>().is_none(),
            matches!(side, Side::Front | Side::Back)
        );
    }
}

#[test]
fn the_3d_hertz_scene_parses_as_written() {
    let origin = scenes_dir("hertz3d.toml");
    let scene = Scene::from_toml_str(HERTZ3D, &origin).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.dimension().unwrap(), Dimension::Three);
    assert_eq!(scene.bodies.len(), 2);
    assert_eq!(scene.fixes[2].dofs, Some(Dofs::XYZ));
    assert_eq!(scene.prescribes[0].uz, Some(-0.1));
    // the tetrahedral mesh, too
    let tet = HERTZ3D.replace("hertz3d-hex.msh", "hertz3d-tet.msh");
    Scene::from_toml_str(&tet, &origin).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn the_shipped_3d_hertz_scene_is_the_issues_text() {
    let file = std::fs::read_to_string(scenes_dir("hertz3d.toml")).unwrap();
    assert_eq!(file, HERTZ3D);
}

/// The 3D Hertz scene without its `[[contact]]` table.
fn hertz3d_without_contact(mesh: &str) -> String {
    let start = HERTZ3D.find("[[contact]]").unwrap();
    let end = HERTZ3D.find("[loading]").unwrap();
    let text = format!("{}{}", &HERTZ3D[..start], &HERTZ3D[end..]);
    text.replace("hertz3d-hex.msh", mesh)
}

#[test]
fn the_3d_hertz_scene_builds_its_face_pair_and_its_solve_refuses_it() {
    use crate::element::FaceKind;
    use crate::mesh::gmsh::MshVolumeMesh;
    use crate::mesh::volume::dot;
    use crate::model::{ContactMode, Integration};
    use contact_kernels::Formulation;
    for (mesh, kind) in [
        ("hertz3d-hex.msh", FaceKind::Quad4),
        ("hertz3d-tet.msh", FaceKind::Tri3),
    ] {
        let scene = Scene::from_toml_str(
            &HERTZ3D.replace("hertz3d-hex.msh", mesh),
            &scenes_dir("hertz3d.toml"),
        )
        .unwrap_or_else(|e| panic!("{mesh}: {e}"));
        let model = scene
            .build_model::<3>()
            .unwrap_or_else(|e| panic!("{mesh}: {e}"));
        assert_eq!(model.contacts.len(), 1);
        let pair = &model.contacts[0];
        assert_eq!(pair.name, "contact[0]");
        assert_eq!(
            (
                pair.formulation,
                pair.mode,
                pair.gauss_points,
                pair.integration
            ),
            (
                Formulation::SlaveNormal,
                ContactMode::Unilateral,
                None,
                Integration::Gauss
            )
        );
        // the file's faces of each surface, on the indenter and the block
        let msh = MshVolumeMesh::read(scenes_dir(mesh)).unwrap();
        let (indenter, block) = (&model.mesh.bodies[0], &model.mesh.bodies[1]);
        for (faces, group, body) in [
            (&pair.slave, "indenter_surface", indenter),
            (&pair.master, "block_top", block),
        ] {
            assert_eq!(
                faces.len(),
                msh.surface_faces(group).unwrap().len(),
                "{mesh}"
            );
            assert!(
                faces
                    .iter()
                    .all(|f| f.kind() == kind && f.nodes().iter().all(|&n| body.has_node(n))),
                "{mesh} {group}"
            );
        }
        // the block's top faces look up, out of the block
        for f in &pair.master {
            let n = f.map_nodes(|n| model.mesh.node_ref(n)).normal();
            assert!(dot(n, [0.0, 0.0, 1.0]) > 0.0, "{mesh}: {n:?}");
        }
        // segmented integration clips every slave face: the layout the
        // build makes of it succeeds
        let text = HERTZ3D.replace("hertz3d-hex.msh", mesh).replace(
            "mode = \"unilateral\"",
            "mode = \"unilateral\"\nintegration = \"segmented\"",
        );
        let segmented = Scene::from_toml_str(&text, &scenes_dir("hertz3d.toml"))
            .unwrap_or_else(|e| panic!("{mesh} segmented: {e}"));
        let model = segmented.build_model::<3>().unwrap();
        assert_eq!(model.contacts[0].integration, Integration::Segmented);
    }
    // nor is it a 2D model
    let scene = Scene::from_file(scenes_dir("hertz3d.toml")).unwrap();
    assert!(matches!(
        scene.build_model::<2>(),
        Err(SceneError::Invalid { field, message, .. })
            if field == "body[0]" && message.contains("`Scene::build_model::<3>`")
    ));
}

/// A tri3 slave surface (the tetrahedral Hertz mesh) takes the tri3
/// rules' counts.
#[test]
fn a_tri3_pair_refuses_a_count_without_a_triangle_rule() {
    let origin = scenes_dir("hertz3d.toml");
    let tet = HERTZ3D.replace("hertz3d-hex.msh", "hertz3d-tet.msh");
    let with = |extra: &str| {
        tet.replace(
            "mode = \"unilateral\"",
            &format!("mode = \"unilateral\"\n{extra}"),
        )
    };
    for n in [1, 3, 4, 6, 7] {
        let scene = Scene::from_toml_str(&with(&format!("gauss_points = {n}")), &origin)
            .unwrap_or_else(|e| panic!("{n}: {e}"));
        let model = scene.build_model::<3>().unwrap();
        assert_eq!(model.contacts[0].gauss_points, Some(n));
    }
    for n in [0, 2, 5, 8] {
        match Scene::from_toml_str(&with(&format!("gauss_points = {n}")), &origin) {
            Err(SceneError::Invalid { field, message, .. }) => {
                assert_eq!(field, "contact[0].gauss_points");
                assert!(
                    message.contains(&format!("no Gauss rule of {n} points on a tri3"))
                        && message.contains("available are 1, 3, 4, 6, 7"),
                    "{message}"
                );
            }
            other => panic!("{n}: {other:?}"),
        }
    }
}

/// Two 3D blocks, one on the other: the base 2 x 1 x 1 hexahedra under
/// the block's 3 x 2 x 1, both 0.5 thick; two pairs on the interface.
const BLOCKS3D: &str = r#"
[material]
young = 100.0
poisson = 0.3

[[body]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [2.0, 1.0, 0.5]
nx = 2
ny = 1
nz = 1

[[body]]
name = "block"
origin = [0.0, 0.0, 0.5]
size = [2.0, 1.0, 0.5]
nx = 3
ny = 2
nz = 1

[[fix]]
body = "base"
z = 0.0

[[prescribe]]
body = "block"
z = 1.0
uz = -0.01

[[contact]]
slave = { body = "block", side = "bottom" }
master = { body = "base", side = "top" }

[[contact]]
name = "swapped"
slave = { body = "base", side = "top" }
master = { body = "block", side = "bottom" }
formulation = "closest-point"
mode = "unilateral"
gauss_points = 3
integration = "segmented"

[loading]
load_factor_end = 1.0
steps = [1]
"#;

#[test]
fn a_3d_block_on_a_block_builds_its_face_pairs_in_order() {
    use crate::mesh::Block;
    use crate::mesh::volume::{Face, dot};
    use crate::model::{ContactMode, Integration};
    use contact_kernels::Formulation;
    let model = error_free(BLOCKS3D).build_model::<3>().unwrap();
    assert_eq!(model.contacts.len(), 2);
    // each block's side, its nodes offset by the body's first node
    let side = |b: usize, size: [usize; 3], z: f64, s: Side| -> Vec<Face<NodeId>> {
        let block = Block {
            origin: [0.0, 0.0, z],
            size: [2.0, 1.0, 0.5],
            cells: size,
        };
        let first = model.mesh.bodies[b].nodes.start;
        block
            .side(s)
            .unwrap()
            .into_iter()
            .map(|f| f.map_nodes(|n| NodeId::new(first + n)))
            .collect()
    };
    let base_top = side(0, [2, 1, 1], 0.0, Side::Top);
    let block_bottom = side(1, [3, 2, 1], 0.5, Side::Bottom);
    assert_eq!((base_top.len(), block_bottom.len()), (2, 6));
    let [first, second] = &model.contacts[..] else {
        unreachable!()
    };
    assert_eq!(first.name, "contact[0]");
    assert_eq!((&first.slave, &first.master), (&block_bottom, &base_top));
    assert_eq!(
        (
            first.formulation,
            first.mode,
            first.gauss_points,
            first.integration
        ),
        (
            Formulation::SlaveNormal,
            ContactMode::Persistent,
            None,
            Integration::Gauss
        )
    );
    assert_eq!(second.name, "swapped");
    assert_eq!((&second.slave, &second.master), (&base_top, &block_bottom));
    assert_eq!(
        (
            second.formulation,
            second.mode,
            second.gauss_points,
            second.integration
        ),
        (
            Formulation::ClosestPoint,
            ContactMode::Unilateral,
            Some(3),
            Integration::Segmented
        )
    );
    // outward: the block's bottom faces look down, the base's top up; on
    // the plane z = 0.5
    for (faces, out) in [(&block_bottom, -1.0), (&base_top, 1.0)] {
        for f in faces {
            let x = f.map_nodes(|n| model.mesh.node_ref(n));
            let n = x.normal();
            assert!(dot(n, [0.0, 0.0, out]) > 0.0, "{n:?}");
            assert!(n[0] == 0.0 && n[1] == 0.0, "{n:?}");
            assert!(x.nodes().iter().all(|p| p[2] == 0.5));
        }
    }
}

#[test]
fn a_3d_pair_refuses_counts_readings_and_faces_by_key() {
    // quad4 slave faces: 1..=8 per direction
    let first = "slave = { body = \"block\", side = \"bottom\" }\n";
    let pair = |extra: &str| BLOCKS3D.replacen(first, &format!("{first}{extra}\n"), 1);
    for n in 1..=8 {
        let model = error_free(&pair(&format!("gauss_points = {n}")))
            .build_model::<3>()
            .unwrap();
        assert_eq!(model.contacts[0].gauss_points, Some(n));
    }
    for n in [0, 9] {
        let (field, message) = invalid(&pair(&format!("gauss_points = {n}")));
        assert_eq!(field, "contact[0].gauss_points");
        assert!(
            message.contains(&format!("no Gauss rule of {n} points on a quad4"))
                && message.contains("available are 1, 2, 3, 4, 5, 6, 7, 8")
                && message.contains("per direction"),
            "{message}"
        );
    }
    // segmented: the clipped triangles' rules
    for n in [2, 4, 8] {
        let (field, message) =
            invalid(&BLOCKS3D.replace("gauss_points = 3", &format!("gauss_points = {n}")));
        assert_eq!(field, "contact[1].gauss_points");
        assert!(
            message.contains("1, 3 or 7 points on each clipped triangle, got"),
            "{message}"
        );
    }
    for n in [1, 7] {
        error_free(&BLOCKS3D.replace("gauss_points = 3", &format!("gauss_points = {n}")));
    }
    // a formulation that is no reading of 3D faces: refused by the parser
    // when its kernels are compiled in, else by the 3D build; by key either way
    for f in [
        "quadratic-slave-normal",
        "quad4-slave-normal",
        "tri3-closest-point",
    ] {
        match Scene::from_toml_str(&pair(&format!("formulation = \"{f}\"")), "bad.toml") {
            Err(SceneError::Syntax { field, .. } | SceneError::Invalid { field, .. }) => {
                assert_eq!(field, "contact[0].formulation", "{f}");
            }
            other => panic!("{f}: {other:?}"),
        }
    }
    let mut scene = error_free(BLOCKS3D);
    scene.contacts[1].formulation = contact_kernels::Formulation::QuadraticSlaveNormal;
    match scene.build_model::<3>() {
        Err(SceneError::Invalid { field, message, .. }) => {
            assert_eq!(field, "contact[1].formulation");
            assert!(
                message.contains("`quadratic-slave-normal` is not a reading of 3D faces")
                    && message.contains("`slave-normal` or `closest-point`"),
                "{message}"
            );
        }
        other => panic!("{:?}", other.map(|m| m.contacts.len())),
    }
    // both faces on one body
    let (field, message) = invalid(&BLOCKS3D.replacen(
        "master = { body = \"base\", side = \"top\" }",
        "master = { body = \"block\", side = \"top\" }",
        1,
    ));
    assert_eq!(field, "contact[0]");
    assert!(message.contains("different bodies"), "{message}");
}

/// 2D pairs are as before: absent `gauss_points` is 2 (the model bit for
/// bit that `gauss_points = 2` gives, not written back), 1..=8 checked.
#[test]
fn a_2d_pair_keeps_its_gauss_points() {
    let text = crate::scenes::STACKED_CANTILEVER;
    assert!(text.contains("gauss_points = 2\n"));
    let given = error_free(text);
    let absent = error_free(&text.replace("gauss_points = 2\n", ""));
    assert_eq!(
        (
            given.contacts[0].gauss_points,
            absent.contacts[0].gauss_points
        ),
        (Some(2), None)
    );
    let (mut a, b) = (
        given.build_model::<2>().unwrap(),
        absent.build_model::<2>().unwrap(),
    );
    // absent: the segment's default, 2 points (the layout's)
    assert_eq!(b.contacts[0].gauss_points, None);
    a.contacts[0].gauss_points = None;
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
    assert!(!absent.to_toml_string().contains("gauss_points"));
    assert!(given.to_toml_string().contains("gauss_points = 2"));
    for n in [0, 9] {
        let (field, message) =
            invalid(&text.replace("gauss_points = 2", &format!("gauss_points = {n}")));
        assert_eq!(field, "contact[0].gauss_points");
        assert_eq!(message, "must be in 1..=8");
    }
}

#[test]
fn the_3d_hertz_scene_without_contact_builds_a_3d_model() {
    use crate::mesh::gmsh::MshVolumeMesh;
    for mesh in ["hertz3d-hex.msh", "hertz3d-tet.msh"] {
        let origin = scenes_dir("hertz3d.toml");
        let scene = Scene::from_toml_str(&hertz3d_without_contact(mesh), &origin)
            .unwrap_or_else(|e| panic!("{mesh}: {e}"));
        let model = scene
            .build_model::<3>()
            .unwrap_or_else(|e| panic!("{mesh}: {e}"));
        let msh = MshVolumeMesh::read(scenes_dir(mesh)).unwrap();
        let names: Vec<&str> = model.mesh.bodies.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(names, ["indenter", "block"]);
        for (b, body) in model.mesh.bodies.iter().enumerate() {
            let cells = msh.volume_elements(&body.name).unwrap();
            assert_eq!(body.elements.len(), cells.len(), "{mesh} {}", body.name);
            let mut nodes: Vec<usize> = cells.iter().flat_map(|e| e.nodes().to_vec()).collect();
            nodes.sort_unstable();
            nodes.dedup();
            assert_eq!(body.nodes.len(), nodes.len());
            // the mesh nodes are the file's, by tag and position
            let tags = body.node_tags.as_ref().unwrap();
            for (k, &n) in nodes.iter().enumerate() {
                assert_eq!(tags[k], msh.node_tag(n).unwrap());
                assert_eq!(model.mesh.nodes_ref[body.nodes.start + k], msh.nodes()[n]);
            }
            assert!(
                model.mesh.element_body[body.elements.clone()]
                    .iter()
                    .all(|&e| e == b)
            );
        }
        let groups: Vec<&str> = model.supports.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(
            groups,
            ["symmetry_x", "symmetry_y", "bottom", "indenter_top"]
        );
        // the mesh node of each of the file's nodes of a group
        let node_of = |n: usize| {
            let tag = msh.node_tag(n).unwrap();
            model
                .mesh
                .bodies
                .iter()
                .find_map(|b| {
                    let k = b.node_tags.as_ref()?.iter().position(|&t| t == tag)?;
                    Some(b.nodes.start + k)
                })
                .unwrap()
        };
        let prescribed = |dof: usize| model.prescribed.iter().find(|p| p.dof.index() == dof);
        for (g, group, components, value) in [
            (0, "symmetry_x", &[0][..], 0.0),
            (1, "symmetry_y", &[1][..], 0.0),
            (2, "bottom", &[0, 1, 2][..], 0.0),
            (3, "indenter_top", &[2][..], -0.1),
        ] {
            let nodes: Vec<usize> = msh
                .group_nodes(group)
                .unwrap()
                .into_iter()
                .map(node_of)
                .collect();
            assert!(!nodes.is_empty(), "{group}");
            for &n in &nodes {
                for &c in components {
                    let p =
                        prescribed(3 * n + c).unwrap_or_else(|| panic!("{group}: node {n} {c}"));
                    assert_eq!(p.value, value, "{group}");
                    assert_eq!(p.amplitude, None);
                }
            }
            // the group's own dofs are its components of its nodes
            for p in &model.prescribed[model.supports[g].prescribed.clone()] {
                let (n, c) = (p.dof.index() / 3, p.dof.index() % 3);
                assert!(
                    nodes.contains(&n) && components.contains(&c),
                    "{group}: {n} {c}"
                );
            }
        }
        // the indenter's top is on the indenter, pushed down
        let top = &model.prescribed[model.supports[3].prescribed.clone()];
        assert!(
            top.iter()
                .all(|p| model.mesh.bodies[0].nodes.contains(&(p.dof.index() / 3)))
        );
        assert!(model.loads.is_empty() && model.contacts.is_empty());
        assert_eq!(model.load_factor_end, 1.0);
    }
}

#[test]
fn a_3d_block_fixes_every_component_and_loads_its_side_consistently() {
    let text = BLOCK3D.replace("ny = 1\nnz = 1", "ny = 2\nnz = 2");
    let scene = error_free(&text);
    let model = scene.build_model::<3>().unwrap();
    assert_eq!(model.mesh.node_count(), 5 * 3 * 3);
    assert_eq!(model.mesh.elements.len(), 4 * 2 * 2);
    // x = 0: 9 nodes, all three components, node by node
    let fixed: Vec<usize> = model.prescribed.iter().map(|p| p.dof.index()).collect();
    let want: Vec<usize> = (0..3)
        .flat_map(|k| (0..3).map(move |j| (k * 3 + j) * 5))
        .flat_map(|n| (0..3).map(move |c| 3 * n + c))
        .collect();
    assert_eq!(fixed, want);
    // the end face: 4 squares of 1/4; corners t/16, edges t/8, centre t/4
    let mut fz = vec![0.0; model.mesh.node_count()];
    for l in &model.loads {
        let (n, c) = (l.dof.index() / 3, l.dof.index() % 3);
        if c == 2 {
            fz[n] += l.value;
        } else {
            assert_eq!(l.value, 0.0);
        }
    }
    let t = -0.01;
    let total: f64 = fz.iter().sum();
    assert!((total - t).abs() <= 1e-15, "{total}");
    for k in 0..3 {
        for j in 0..3 {
            let n = (k * 3 + j) * 5 + 4;
            let edges = [j == 0 || j == 2, k == 0 || k == 2];
            let share = match edges {
                [true, true] => 1.0 / 16.0,
                [true, false] | [false, true] => 1.0 / 8.0,
                [false, false] => 1.0 / 4.0,
            };
            assert!((fz[n] - t * share).abs() <= 1e-17, "({j}, {k}): {}", fz[n]);
        }
    }
    // only the end face is loaded
    assert!(fz.iter().enumerate().all(|(n, &f)| n % 5 == 4 || f == 0.0));
}

#[test]
fn selections_and_refinement_in_3d() {
    // z selects a plane, `dofs` any set, [refine] z multiplies nz
    let text = BLOCK3D.replace(
        "[[fix]]\nx = 0.0\n",
        "[[fix]]\nz = 0.0\ndofs = \"zx\"\n\n[[prescribe]]\nat = [4.0, 1.0, 1.0]\nuz = -0.5\n",
    ) + "\n[refine]\nz = 3\n";
    let model = error_free(&text).build_model::<3>().unwrap();
    assert_eq!(model.mesh.node_count(), 5 * 2 * 4);
    let fix = &model.prescribed[model.supports[0].prescribed.clone()];
    assert_eq!(fix.len(), 2 * 10);
    for p in fix {
        let (n, c) = (p.dof.index() / 3, p.dof.index() % 3);
        assert_eq!(model.mesh.nodes_ref[n][2], 0.0);
        assert!(c == 0 || c == 2);
    }
    let top = &model.prescribed[model.supports[1].prescribed.clone()];
    assert_eq!(top.len(), 1);
    assert_eq!(
        model.mesh.nodes_ref[top[0].dof.index() / 3],
        [4.0, 1.0, 1.0]
    );
    assert_eq!((top[0].dof.index() % 3, top[0].value), (2, -0.5));
    // a point that no node has
    let text = BLOCK3D.replace("[[fix]]\nx = 0.0\n", "[[fix]]\nat = [0.5, 0.5, 0.5]\n");
    let (field, message) = invalid(&text);
    assert_eq!(field, "fix[0]");
    assert!(message.contains("no node at"), "{message}");
    // the sides of a 3D block by name; a mesh group without a mesh file
    let text = BLOCK3D.replace("side = \"right\"", "side = \"back\"");
    let model = error_free(&text).build_model::<3>().unwrap();
    assert!(
        model
            .loads
            .iter()
            .all(|l| l.value == 0.0 || model.mesh.nodes_ref[l.dof.index() / 3][1] == 1.0)
    );
    let text = BLOCK3D.replace("side = \"right\"", "group = \"end\"");
    assert_eq!(invalid(&text).0, "traction[0].group");
}

#[test]
fn a_3d_solid_needs_poisson_below_one_half() {
    let (field, message) = invalid(&BLOCK3D.replace("poisson = 0.3", "poisson = 0.5"));
    assert_eq!(field, "material");
    assert!(message.contains("(-1, 0.5) for a 3D solid"), "{message}");
    // plane stress admits 0.6 in 2D
    error_free(&BLOCK2D.replace("poisson = 0.3", "poisson = 0.6"));
}

/// A volume whose two tetrahedra meet at three doubled nodes (a face
/// meshed twice and not merged) falls apart: the scene is refused naming
/// the file's two tags, the point and what to do; with the nodes merged
/// (the reader's fixture `tets.msh`) it builds.
#[test]
fn a_body_that_falls_apart_at_unmerged_nodes_is_refused() {
    let fixture = include_str!("../mesh/gmsh/testdata/tets.msh");
    let split = fixture
        .replace("1 5 1 5\n3 1 0 5\n", "1 8 1 8\n3 1 0 8\n")
        .replace("5\n0 0 0\n", "5\n6\n7\n8\n0 0 0\n")
        .replace("1 1 1\n$EndNodes", "1 1 1\n1 0 0\n0 1 0\n0 0 1\n$EndNodes")
        .replace("2 2 3 4 5\n", "2 6 7 8 5\n")
        .replace("4 3 5 2\n", "4 7 5 6\n");
    let dir = std::env::temp_dir().join(format!("gapsim-falls-apart-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene_text = |file: &str| {
        format!(
            "[mesh]\nfile = \"{file}\"\n[material]\nyoung = 100.0\npoisson = 0.3\n\
             [[body]]\nname = \"solid\"\n[[fix]]\nz = 0.0\n\
             [loading]\nload_factor_end = 1.0\nsteps = [1]\n"
        )
    };
    let build = |msh: &str, name: &str| {
        std::fs::write(dir.join(name), msh).unwrap();
        let origin = dir.join("scene.toml");
        Scene::from_toml_str(&scene_text(name), origin.to_str().unwrap())
            .and_then(|s| s.build_model::<3>())
            .map(|_| ())
            .map_err(|e| e.to_string())
    };
    build(fixture, "tets.msh").unwrap();
    let e = build(&split, "split.msh").unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        e.contains(
            "physical volume `solid` falls apart: nodes 2 and 6 sit at the same point (1, 0, 0)"
        ) && e.contains("(the body is in 2 pieces)")
            && e.contains("removeDuplicateNodes"),
        "{e}"
    );
}
