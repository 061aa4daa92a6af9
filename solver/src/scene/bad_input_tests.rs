//! The bad-input cases of a scene with a `[mesh]` file, one test each: an
//! unknown group in every item lists the groups that exist, a contact
//! group that is not on a body's boundary, a degenerate element; a block
//! scene's unknown body lists the bodies. Every message names the scene
//! file first, then the field, then the mesh file and the item.

use std::path::PathBuf;

use super::Scene;

/// Two unit squares, one quadrangle each, sharing no nodes: `lower`
/// (nodes 1..4, element 6) and `upper` (nodes 5..8, element 7) on top of
/// it. Curves `ground` (1-2), `lower_top` (3-4), `upper_bottom` (5-6) and
/// `diagonal` (1-3, no element edge); point `peak` (node 7).
const MESH: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
7
0 10 \"peak\"
1 11 \"ground\"
1 12 \"lower_top\"
1 13 \"upper_bottom\"
1 14 \"diagonal\"
2 21 \"lower\"
2 22 \"upper\"
$EndPhysicalNames
$Entities
1 4 2 0
1 1 2 0 1 10
1 0 0 0 1 0 0 1 11 0
2 0 1 0 1 1 0 1 12 0
3 0 1 0 1 1 0 1 13 0
4 0 0 0 1 1 0 1 14 0
1 0 0 0 1 1 0 1 21 0
2 0 1 0 1 2 0 1 22 0
$EndEntities
$Nodes
2 8 1 8
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
2 2 0 4
5
6
7
8
0 1 0
1 1 0
1 2 0
0 2 0
$EndNodes
$Elements
7 7 1 7
0 1 15 1
1 7
1 1 1 1
2 1 2
1 2 1 1
3 3 4
1 3 1 1
4 5 6
1 4 1 1
5 1 3
2 1 3 1
6 1 2 3 4
2 2 3 1
7 5 6 7 8
$EndElements
";

const SCENE: &str = r#"[mesh]
file = "pair.msh"

[material]
young = 100.0
poisson = 0.3

[[body]]
name = "lower"

[[body]]
name = "upper"

[[fix]]
group = "ground"

[[fix]]
x = 0.0
dofs = "x"

[[load]]
group = "peak"
force = [0.0, -1.0]

[[traction]]
group = "ground"
force_per_length = [0.0, 1.0]

[[contact]]
slave = { group = "upper_bottom" }
master = { group = "lower_top" }
mode = "unilateral"

[loading]
load_factor_end = 1.0
steps = [1]
"#;

/// `SCENE` with `scene_edit`, next to `MESH` with `mesh_edit`, read from a
/// fresh directory; the error message and the scene's path.
fn error_of(
    name: &str,
    scene_edit: impl FnOnce(String) -> String,
    mesh_edit: impl FnOnce(String) -> String,
) -> (String, String) {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("gapsim-bad-input-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("pair.msh"), mesh_edit(MESH.to_owned())).unwrap();
    let origin = dir.join("scene.toml").display().to_string();
    let result = Scene::from_toml_str(&scene_edit(SCENE.to_owned()), &origin);
    std::fs::remove_dir_all(&dir).unwrap();
    let message = result
        .expect_err("the scene should be rejected")
        .to_string();
    assert!(message.starts_with(&format!("{origin}: ")), "{message}");
    (message, origin)
}

#[test]
fn the_scene_reads() {
    let dir = std::env::temp_dir().join(format!("gapsim-bad-input-{}-good", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("pair.msh"), MESH).unwrap();
    let model = Scene::from_toml_str(SCENE, &dir.join("scene.toml").display().to_string())
        .and_then(|scene| scene.build_model::<2>());
    std::fs::remove_dir_all(&dir).unwrap();
    let model = model.unwrap();
    assert_eq!(model.mesh.elements.len(), 2);
    assert_eq!(model.contacts.len(), 1);
}

#[test]
fn an_unknown_group_in_every_item_lists_the_known_ones() {
    let known =
        "the file has `diagonal`, `ground`, `lower`, `lower_top`, `peak`, `upper`, `upper_bottom`";
    let cases: [(&str, &str, &str); 7] = [
        (
            "body[0].group",
            "name = \"lower\"",
            "name = \"lower\"\ngroup = \"nope\"",
        ),
        (
            "fix[0].group",
            "group = \"ground\"\n\n[[fix]]",
            "group = \"nope\"\n\n[[fix]]",
        ),
        ("load[0].group", "group = \"peak\"", "group = \"nope\""),
        (
            "traction[0].group",
            "group = \"ground\"\nforce_per",
            "group = \"nope\"\nforce_per",
        ),
        (
            "contact[0].slave.group",
            "group = \"upper_bottom\"",
            "group = \"nope\"",
        ),
        (
            "contact[0].master.group",
            "group = \"lower_top\"",
            "group = \"nope\"",
        ),
        (
            "prescribe[0].group",
            "[loading]",
            "[[prescribe]]\ngroup = \"nope\"\nuy = 0.0\n\n[loading]",
        ),
    ];
    for (k, (field, from, to)) in cases.into_iter().enumerate() {
        let (message, origin) = error_of(
            &format!("unknown-{k}"),
            |s| {
                assert!(s.contains(from), "{from}");
                s.replacen(from, to, 1)
            },
            |m| m,
        );
        assert!(
            message.starts_with(&format!("{origin}: {field}: ")),
            "{message}"
        );
        assert!(
            message.contains("pair.msh: no physical group is named `nope`"),
            "{message}"
        );
        assert!(message.contains(known), "{message}");
    }
}

#[test]
fn a_contact_group_off_the_boundary_names_its_segment() {
    let (message, origin) = error_of(
        "diagonal",
        |s| s.replace("group = \"lower_top\"", "group = \"diagonal\""),
        |m| m,
    );
    assert_eq!(
        message,
        format!(
            "{origin}: contact[0].master.group: {mesh}: physical curve `diagonal` is not on the \
             boundary of a body: its segment from node 1 to node 3 is no edge of an element of a \
             [[body]]",
            mesh = origin.replace("scene.toml", "pair.msh")
        )
    );
}

#[test]
fn a_degenerate_element_is_named() {
    // element 6 with its four nodes on the x axis: zero area
    let (message, origin) = error_of(
        "degenerate",
        |s| s,
        |m| m.replacen("1 1 0\n0 1 0\n", "2 0 0\n3 0 0\n", 1),
    );
    assert!(
        message.starts_with(&format!("{origin}: body[0].name: ")),
        "{message}"
    );
    assert!(
        message.contains("element 6 of physical surface `lower` is inverted or degenerate"),
        "{message}"
    );
    assert!(message.contains("pair.msh"), "{message}");
}

#[test]
fn an_unknown_body_lists_the_bodies() {
    let text = crate::scenes::STACKED_CANTILEVER.replace(
        "slave = { body = \"slave\", side = \"bottom\" }",
        "slave = { body = \"slav\", side = \"bottom\" }",
    );
    let message = Scene::from_toml_str(&text, "cantilever.toml")
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("cantilever.toml: contact[0].slave"),
        "{message}"
    );
    assert!(
        message.contains("no body named `slav` (bodies: master, slave)"),
        "{message}"
    );
}
