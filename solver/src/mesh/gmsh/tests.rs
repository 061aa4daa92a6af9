//! Tests of the Gmsh reader: the checked-in Hertz meshes, the small
//! fixtures in `testdata/` (see `testdata/make-fixtures.py`), every error,
//! and property tests that no input makes it panic.

use std::path::{Path, PathBuf};

use proptest::prelude::*;

use super::*;

const SQUARE: &[u8] = include_bytes!("testdata/square.msh");
const SQUARE_BINARY: &[u8] = include_bytes!("testdata/square-binary.msh");
const HERTZ_COARSE_BINARY: &[u8] = include_bytes!("testdata/hertz-coarse-binary.msh");
pub(super) const CUBE: &str = include_str!("testdata/cube.msh");
pub(super) const CUBE_BINARY: &[u8] = include_bytes!("testdata/cube-binary.msh");
pub(super) const TETS: &str = include_str!("testdata/tets.msh");
pub(super) const TETS_BINARY: &[u8] = include_bytes!("testdata/tets-binary.msh");

/// One quadrangle (tags 1..4, the unit square), its bottom edge and a
/// point, written by hand; the error tests edit it.
const TINY: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
0 3 \"tip\"
1 1 \"edge\"
2 2 \"face\"
$EndPhysicalNames
$Entities
1 1 1 0
1 0 0 0 1 3
1 0 0 0 1 0 0 1 1 0
1 0 0 0 1 1 0 1 2 0
$EndEntities
$Nodes
1 4 1 4
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
3 3 1 3
0 1 15 1
1 1
1 1 1 1
2 1 2
2 1 3 1
3 1 2 3 4
$EndElements
";

fn scene_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

/// The fixture `text` after `edit`, read in dimension `D` as the file
/// `file`.
pub(super) fn edited<const D: usize>(
    text: &str,
    file: &str,
    edit: impl FnOnce(String) -> String,
) -> Result<Msh<D>, MshError> {
    Msh::from_bytes(edit(text.to_owned()).as_bytes(), file)
}

fn tiny(edit: impl FnOnce(String) -> String) -> Result<MshMesh, MshError> {
    edited(TINY, "tiny.msh", edit)
}

/// The kind of the error `result` is, after checking that it names the
/// file `file` first.
pub(super) fn kind_in<const D: usize>(
    result: Result<Msh<D>, MshError>,
    file: &str,
) -> MshErrorKind {
    let error = result.expect_err("the file should be rejected");
    assert_eq!(error.file, Path::new(file));
    assert!(
        error.to_string().starts_with(&format!("{file}: ")),
        "{error}"
    );
    error.kind
}

fn kind(result: Result<MshMesh, MshError>) -> MshErrorKind {
    kind_in(result, "tiny.msh")
}

/// Every one of `results` is an error whose kind `is` accepts.
pub(super) fn assert_kinds<T>(
    results: impl IntoIterator<Item = Result<T, MshError>>,
    is: impl Fn(&MshErrorKind) -> bool,
) {
    for result in results {
        let Err(error) = result else {
            panic!("an error was expected");
        };
        assert!(is(&error.kind), "{error}");
    }
}

/// `result` is an error whose message contains `part`.
pub(super) fn assert_message<T>(result: Result<T, MshError>, part: &str) {
    let Err(error) = result else {
        panic!("an error containing `{part}` was expected");
    };
    let text = error.to_string();
    assert!(text.contains(part), "{text}");
}

fn count(mesh: &MshMesh, kind: MshElementType) -> usize {
    mesh.elements().iter().filter(|e| e.kind == kind).count()
}

/// Twice the signed area of a polygon.
fn signed_area2(mesh: &MshMesh, nodes: &[usize]) -> f64 {
    let p = |k: usize| mesh.nodes()[nodes[k % nodes.len()]];
    (0..nodes.len())
        .map(|k| p(k)[0] * p(k + 1)[1] - p(k + 1)[0] * p(k)[1])
        .sum()
}

// ----- the small fixtures ---------------------------------------------------

#[test]
fn tiny_file_reads() {
    let mesh = tiny(|s| s).unwrap();
    assert_eq!(
        mesh.nodes(),
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    );
    let face = mesh.surface_elements("face").unwrap();
    assert_eq!(face.len(), 1);
    assert_eq!(face[0].kind, MshElementType::Quad);
    assert_eq!(face[0].nodes(), &[0, 1, 2, 3]);
    assert_eq!(face[0].tag, 3);
    assert_eq!(face[0].entity, Entity { dim: 2, tag: 1 });
    assert_eq!(mesh.curve_segments("edge").unwrap(), vec![[0, 1]]);
    assert_eq!(mesh.group_nodes("edge").unwrap(), vec![0, 1]);
    assert_eq!(mesh.group_nodes("tip").unwrap(), vec![0]);
    let names: Vec<&str> = mesh.groups().iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["tip", "edge", "face"]);
}

#[test]
fn square_has_quads_triangles_lines_and_a_point() {
    let mesh = MshMesh::from_bytes(SQUARE, "square.msh").unwrap();
    assert_eq!(mesh.nodes().len(), 15);
    assert_eq!(count(&mesh, MshElementType::Point), 1);
    assert_eq!(count(&mesh, MshElementType::Line), 6);
    assert_eq!(count(&mesh, MshElementType::Quad), 4);
    assert_eq!(count(&mesh, MshElementType::Triangle), 8);

    let left = mesh.surface_elements("left").unwrap();
    assert_eq!(left.len(), 4);
    assert!(left.iter().all(|e| e.kind == MshElementType::Quad));
    let right = mesh.surface_elements("right").unwrap();
    assert_eq!(right.len(), 8);
    assert!(right.iter().all(|e| e.kind == MshElementType::Triangle));
    for e in left.iter().chain(&right) {
        // Gmsh writes surface elements counter-clockwise about +z here.
        assert!(signed_area2(&mesh, e.nodes()) > 0.0);
    }
    // A curve group made of two curves.
    let bottom = mesh.curve_segments("bottom").unwrap();
    assert_eq!(bottom.len(), 4);
    for [a, b] in bottom {
        assert_eq!(mesh.nodes()[a][1], 0.0);
        assert_eq!(mesh.nodes()[b][1], 0.0);
    }
    let inner = mesh.group_nodes("inner").unwrap();
    assert_eq!(inner.len(), 3);
    assert!(inner.iter().all(|&n| mesh.nodes()[n][0] == 1.0));
    let corner = mesh.group_nodes("corner").unwrap();
    assert_eq!(corner.len(), 1);
    assert_eq!(mesh.nodes()[corner[0]], [0.0, 0.0]);
    // Tags and indices invert each other.
    for i in 0..mesh.nodes().len() {
        assert_eq!(mesh.node_index(mesh.node_tag(i).unwrap()), Some(i));
    }
}

/// Binary and ASCII files of one mesh read the same (coordinates to
/// rounding: Gmsh prints 16 significant digits).
fn assert_same_mesh(a: &MshMesh, b: &MshMesh) {
    assert_eq!(a.nodes().len(), b.nodes().len());
    for (p, q) in a.nodes().iter().zip(b.nodes()) {
        for k in 0..2 {
            assert!(
                (p[k] - q[k]).abs() <= 1e-14 * (1.0 + p[k].abs()),
                "{p:?} {q:?}"
            );
        }
    }
    assert_eq!(a.tables.node_tags, b.tables.node_tags);
    assert_eq!(a.elements(), b.elements());
    assert_eq!(a.groups(), b.groups());
}

#[test]
fn square_binary_equals_ascii() {
    let ascii = MshMesh::from_bytes(SQUARE, "square.msh").unwrap();
    let binary = MshMesh::from_bytes(SQUARE_BINARY, "square-binary.msh").unwrap();
    assert_same_mesh(&ascii, &binary);
}

// ----- the Hertz meshes ------------------------------------------------------

const R: f64 = 10.0;

/// The checks every Hertz mesh passes, whatever its size: elements of
/// `kind` only, counter-clockwise.
fn check_hertz(mesh: &MshMesh, kind: MshElementType, nodes: usize, cylinder: usize, block: usize) {
    assert_eq!(mesh.nodes().len(), nodes);
    let mut names: Vec<&str> = mesh.groups().iter().map(|g| g.name.as_str()).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "block",
            "block_top",
            "bottom",
            "cylinder",
            "cylinder_surface",
            "load_edge",
            "symmetry"
        ]
    );
    let cyl = mesh.surface_elements("cylinder").unwrap();
    let blk = mesh.surface_elements("block").unwrap();
    assert_eq!((cyl.len(), blk.len()), (cylinder, block));
    for e in cyl.iter().chain(&blk) {
        assert_eq!(e.kind, kind);
        assert!(signed_area2(mesh, e.nodes()) > 0.0, "element {}", e.tag);
    }
    // The bodies share no nodes.
    let nodes_of = |elements: &[&MshElement]| {
        let mut n: Vec<usize> = elements.iter().flat_map(|e| e.nodes().to_vec()).collect();
        n.sort_unstable();
        n.dedup();
        n
    };
    let (cyl_nodes, blk_nodes) = (nodes_of(&cyl), nodes_of(&blk));
    assert!(
        cyl_nodes
            .iter()
            .all(|n| blk_nodes.binary_search(n).is_err())
    );
    assert_eq!(cyl_nodes.len() + blk_nodes.len(), nodes);

    let at = |n: usize| mesh.nodes()[n];
    let tol = 1e-12;
    for [a, b] in mesh.curve_segments("block_top").unwrap() {
        assert!(at(a)[1].abs() < tol && at(b)[1].abs() < tol);
        assert!(blk_nodes.binary_search(&a).is_ok());
    }
    for n in mesh.group_nodes("cylinder_surface").unwrap() {
        let [x, y] = at(n);
        assert!((x.hypot(y - R) - R).abs() < 1e-9, "node {n} at ({x}, {y})");
        assert!(cyl_nodes.binary_search(&n).is_ok());
    }
    for n in mesh.group_nodes("load_edge").unwrap() {
        assert!((at(n)[1] - R).abs() < tol);
    }
    for n in mesh.group_nodes("symmetry").unwrap() {
        assert!(at(n)[0].abs() < tol);
    }
    for n in mesh.group_nodes("bottom").unwrap() {
        assert!((at(n)[1] + 20.0).abs() < tol);
    }
    // Both bodies touch the symmetry line and the contact point.
    let symmetry = mesh.group_nodes("symmetry").unwrap();
    assert!(symmetry.iter().any(|n| cyl_nodes.binary_search(n).is_ok()));
    assert!(symmetry.iter().any(|n| blk_nodes.binary_search(n).is_ok()));
}

#[test]
fn hertz_mesh_reads() {
    let mesh = MshMesh::read(scene_file("hertz.msh")).unwrap();
    check_hertz(&mesh, MshElementType::Quad, 2886, 1192, 1544);
    assert_eq!(mesh.curve_segments("cylinder_surface").unwrap().len(), 60);
}

#[test]
fn hertz_coarse_mesh_reads() {
    let mesh = MshMesh::read(scene_file("hertz-coarse.msh")).unwrap();
    check_hertz(&mesh, MshElementType::Quad, 852, 220, 548);
    assert_eq!(mesh.curve_segments("cylinder_surface").unwrap().len(), 28);
}

#[test]
fn hertz_triangle_mesh_reads() {
    let mesh = MshMesh::read(scene_file("hertz-tri-coarse.msh")).unwrap();
    check_hertz(&mesh, MshElementType::Triangle, 937, 461, 1250);
    assert_eq!(mesh.curve_segments("cylinder_surface").unwrap().len(), 26);
}

#[test]
fn hertz_coarse_binary_equals_ascii() {
    let ascii = MshMesh::read(scene_file("hertz-coarse.msh")).unwrap();
    let binary = MshMesh::from_bytes(HERTZ_COARSE_BINARY, "hertz-coarse-binary.msh").unwrap();
    check_hertz(&binary, MshElementType::Quad, 852, 220, 548);
    assert_same_mesh(&ascii, &binary);
}

// ----- errors ----------------------------------------------------------------

#[test]
fn a_missing_file_is_named() {
    let error = MshMesh::read("no/such/mesh.msh").unwrap_err();
    assert!(matches!(error.kind, MshErrorKind::Io(_)));
    assert!(
        error
            .to_string()
            .starts_with("no/such/mesh.msh: cannot read")
    );
}

#[test]
fn not_a_mesh_file() {
    let error = MshMesh::from_bytes(b"name = \"scene\"\n", "scene.toml").unwrap_err();
    assert!(matches!(error.kind, MshErrorKind::NotMsh), "{error}");
}

#[test]
fn msh2_is_named() {
    let e = kind(tiny(|s| s.replace("4.1 0 8", "2.2 0 8")));
    assert!(
        matches!(&e, MshErrorKind::UnsupportedVersion(v) if v == "2.2"),
        "{e}"
    );
    assert!(e.to_string().contains("msh41"), "{e}");
}

#[test]
fn malformed_headers() {
    for header in [
        "4.1 2 8",
        "4.1 0",
        "4.1 1 3",
        "4.1 0 99999999999999999999999",
        "x 0 8",
    ] {
        let e = kind(tiny(|s| s.replace("4.1 0 8", header)));
        assert!(matches!(e, MshErrorKind::BadHeader(_)), "{header}: {e}");
    }
}

#[test]
fn truncated_file_names_offset_and_line() {
    let cut = TINY.find("1 1 0\n0 1 0").unwrap() + 3;
    let e = kind(MshMesh::from_bytes(&TINY.as_bytes()[..cut], "tiny.msh"));
    let MshErrorKind::Malformed { line, .. } = &e else {
        panic!("{e}");
    };
    assert_eq!(*line, 25, "{e}");
    let text = e.to_string();
    assert!(text.contains("truncated"), "{text}");
    assert!(
        text.contains("in node section > node entity block (1 of 1)"),
        "{text}"
    );
}

#[test]
fn unsupported_element_types_are_named() {
    let e = kind(tiny(|s| {
        s.replace("2 1 3 1\n3 1 2 3 4", "2 1 10 1\n3 1 2 3 4 1 2 3 4 1")
    }));
    assert!(
        matches!(
            &e,
            MshErrorKind::UnsupportedElement {
                gmsh_type: 10,
                count: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains("9-node second order quadrangle (type 10)"),
        "{e}"
    );
    // A type mshio does not know at all.
    let e = kind(tiny(|s| s.replace("2 1 3 1\n", "2 1 77 1\n")));
    assert!(e.to_string().contains("77"), "{e}");
}

#[test]
fn unknown_node_tags_are_named() {
    let e = kind(tiny(|s| s.replace("3 1 2 3 4", "3 1 2 3 99")));
    assert!(
        matches!(
            e,
            MshErrorKind::UnknownNode {
                element: 3,
                node: 99
            }
        ),
        "{e}"
    );
}

#[test]
fn duplicate_node_tags_are_rejected() {
    let e = kind(tiny(|s| s.replace("1\n2\n3\n4\n", "1\n2\n2\n4\n")));
    assert!(matches!(e, MshErrorKind::DuplicateNode(2)), "{e}");
}

#[test]
fn duplicate_element_tags_are_rejected() {
    // the line element 2 takes the quadrangle's tag 3
    let e = kind(tiny(|s| s.replace("2 1 2\n", "3 1 2\n")));
    assert!(matches!(e, MshErrorKind::DuplicateElement(3)), "{e}");
    assert_eq!(e.to_string(), "element tag 3 appears twice");
}

#[test]
fn a_wrong_node_count_is_rejected() {
    // the `$Nodes` header declares 5 nodes; the block holds 4
    let e = kind(tiny(|s| {
        s.replace("$Nodes\n1 4 1 4\n", "$Nodes\n1 5 1 4\n")
    }));
    assert!(
        matches!(
            e,
            MshErrorKind::WrongCount {
                section: "$Nodes",
                declared: 5,
                found: 4,
                ..
            }
        ),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        "the `$Nodes` section's header declares 5 nodes, but its blocks hold 4"
    );
    let e = kind(tiny(|s| {
        s.replace("$Nodes\n1 4 1 4\n", "$Nodes\n1 3 1 4\n")
    }));
    assert!(
        matches!(e, MshErrorKind::WrongCount { declared: 3, .. }),
        "{e}"
    );
}

#[test]
fn a_wrong_element_count_is_rejected() {
    let e = kind(tiny(|s| {
        s.replace("$Elements\n3 3 1 3\n", "$Elements\n3 4 1 3\n")
    }));
    assert!(
        matches!(
            e,
            MshErrorKind::WrongCount {
                section: "$Elements",
                declared: 4,
                found: 3,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn dense_tags_out_of_order_are_kept() {
    // mshio drops dense tags; the reader reads them itself.
    let mesh = tiny(|s| s.replace("1\n2\n3\n4\n", "4\n3\n2\n1\n")).unwrap();
    assert_eq!(mesh.node_index(4), Some(0));
    assert_eq!(mesh.node_tag(0), Some(4));
    // Element 3 is 1 2 3 4 by tag, i.e. nodes 3 2 1 0.
    assert_eq!(
        mesh.surface_elements("face").unwrap()[0].nodes(),
        &[3, 2, 1, 0]
    );
}

#[test]
fn sparse_tags_are_mapped() {
    let mesh = tiny(|s| {
        s.replace("1 4 1 4\n", "1 4 1 40\n")
            .replace("1\n2\n3\n4\n0 0 0", "10\n20\n30\n40\n0 0 0")
            .replace("1 1\n1 1 1 1\n2 1 2", "1 10\n1 1 1 1\n2 10 20")
            .replace("3 1 2 3 4", "3 10 20 30 40")
    })
    .unwrap();
    assert_eq!(mesh.node_index(30), Some(2));
    assert_eq!(
        mesh.surface_elements("face").unwrap()[0].nodes(),
        &[0, 1, 2, 3]
    );
    assert_eq!(mesh.curve_segments("edge").unwrap(), vec![[0, 1]]);
}

#[test]
fn non_planar_and_non_finite_nodes_are_rejected() {
    let node_3 = |to: &str| {
        let to = format!("{to}\n0 1 0\n$EndNodes");
        tiny(move |s| s.replace("1 1 0\n0 1 0\n$EndNodes", &to))
    };
    let e = kind(node_3("1 1 0.5"));
    assert!(matches!(e, MshErrorKind::NotPlanar { node: 3, .. }), "{e}");
    // Rounding-level z is accepted.
    node_3("1 1 1e-15").unwrap();
    let e = kind(node_3("1 inf 0"));
    assert!(
        matches!(
            e,
            MshErrorKind::NonFiniteNode { node: 3, .. } | MshErrorKind::Malformed { .. }
        ),
        "{e}"
    );
}

#[test]
fn element_on_an_entity_of_another_dimension() {
    let e = kind(tiny(|s| s.replace("1 1 1 1\n2 1 2", "2 1 1 1\n2 1 2")));
    assert!(matches!(e, MshErrorKind::ElementDimension { .. }), "{e}");
}

#[test]
fn unknown_group_names_list_the_known_ones() {
    let mesh = tiny(|s| s).unwrap();
    let error = mesh.surface_elements("plate").unwrap_err();
    assert!(
        matches!(&error.kind, MshErrorKind::UnknownGroup { known, .. } if known == &["edge", "face", "tip"])
    );
    let text = error.to_string();
    assert!(text.starts_with("tiny.msh: "), "{text}");
    assert!(
        text.contains("`plate`") && text.contains("`edge`, `face`, `tip`"),
        "{text}"
    );

    // Without `$PhysicalNames` there are no names at all.
    let start = TINY.find("$PhysicalNames").unwrap();
    let end = TINY.find("$Entities").unwrap();
    let unnamed = format!("{}{}", &TINY[..start], &TINY[end..]);
    let mesh = MshMesh::from_bytes(unnamed.as_bytes(), "tiny.msh").unwrap();
    let text = mesh.group_nodes("edge").unwrap_err().to_string();
    assert!(text.contains("no `$PhysicalNames`"), "{text}");
}

#[test]
fn groups_of_the_wrong_dimension() {
    let mesh = tiny(|s| s).unwrap();
    assert_kinds(
        [
            mesh.surface_elements("edge").map(|_| ()),
            mesh.curve_segments("face").map(|_| ()),
            mesh.curve_segments("tip").map(|_| ()),
            mesh.group_nodes("face").map(|_| ()),
        ],
        |k| matches!(k, MshErrorKind::WrongDimension { .. }),
    );
    assert_message(
        mesh.surface_elements("edge"),
        "`edge` has dimension 1, but 2 (a physical surface)",
    );
}

#[test]
fn empty_groups_are_errors() {
    // A named group no entity belongs to.
    let mesh = tiny(|s| s.replace("3\n0 3 \"tip\"", "4\n1 9 \"nothing\"\n0 3 \"tip\"")).unwrap();
    assert_kinds([mesh.curve_segments("nothing")], |k| {
        matches!(k, MshErrorKind::EmptyGroup { .. })
    });
}

#[test]
fn malformed_physical_names() {
    for (from, to) in [
        ("3\n0 3", "4\n0 3"),
        ("1 1 \"edge\"", "1 1 edge"),
        ("1 1 \"edge\"", "7 1 \"edge\""),
        ("1 1 \"edge\"", "1 x \"edge\""),
        ("3\n0 3", "three\n0 3"),
    ] {
        let e = kind(tiny(|s| s.replace(from, to)));
        assert!(
            matches!(e, MshErrorKind::BadPhysicalNames { .. }),
            "{to}: {e}"
        );
    }
    let e = kind(tiny(|s| s.replace("2 2 \"face\"", "1 2 \"edge\"")));
    assert!(
        matches!(e, MshErrorKind::DuplicateGroupName { dim: 1, .. }),
        "{e}"
    );
    // Names may hold spaces.
    let mesh = tiny(|s| s.replace("\"face\"", "\"the face\"")).unwrap();
    assert_eq!(mesh.surface_elements("the face").unwrap().len(), 1);
}

// ----- what mshio does with bad input, and the guard --------------------------

/// Inputs on which `mshio` 0.4.2 panics (see `guard.rs`), each with the
/// edit of [`TINY`] that makes it.
fn panicking_edits() -> Vec<(&'static str, &'static str)> {
    vec![
        ("4.1 0 8", "4.1 0 99999999999999999999999"),
        ("1 4 1 4\n", "1 0 1 4\n"),
        ("3 3 1 3\n", "3 0 1 3\n"),
    ]
}

#[test]
fn mshio_panics_where_the_guard_rejects() {
    for (from, to) in panicking_edits() {
        let text = TINY.replace(from, to);
        let caught = std::panic::catch_unwind(|| {
            let _ = mshio::parse_msh_bytes(text.as_bytes());
        });
        // a build without overflow checks (release) may overflow silently
        // where a debug build panics; the guard rejects the input either way
        assert!(
            caught.is_err() || !cfg!(debug_assertions),
            "mshio no longer panics on `{to}`"
        );
        let e = kind(MshMesh::from_bytes(text.as_bytes(), "tiny.msh"));
        assert!(
            matches!(
                e,
                MshErrorKind::Malformed { .. } | MshErrorKind::BadHeader(_)
            ),
            "{e}"
        );
    }
    // A binary file with a size_t of 3 bytes.
    let mut bytes = SQUARE_BINARY.to_vec();
    let at = bytes.windows(7).position(|w| w == b"4.1 1 8").unwrap();
    bytes[at + 6] = b'3';
    let caught = std::panic::catch_unwind(|| {
        let _ = mshio::parse_msh_bytes(&bytes);
    });
    assert!(
        caught.is_err() || !cfg!(debug_assertions),
        "mshio no longer panics on size_t = 3"
    );
    let e = MshMesh::from_bytes(&bytes, "b.msh").unwrap_err();
    assert!(matches!(e.kind, MshErrorKind::BadHeader(_)), "{e}");
}

#[test]
fn binary_zero_counts_are_rejected() {
    for section in [&b"$Nodes\n"[..], b"$Elements\n"] {
        let mut bytes = SQUARE_BINARY.to_vec();
        let at = bytes
            .windows(section.len())
            .position(|w| w == section)
            .unwrap()
            + section.len();
        bytes[at + 8..at + 16].fill(0); // the number of nodes / elements
        let e = MshMesh::from_bytes(&bytes, "b.msh").unwrap_err();
        assert!(matches!(e.kind, MshErrorKind::Malformed { .. }), "{e}");
    }
}

// ----- never a panic ----------------------------------------------------------

/// Reads `bytes` as a 2D and as a 3D mesh and queries every group; a
/// panic fails the calling test, and so does an error that does not name
/// the file.
pub(super) fn read_any(bytes: &[u8]) {
    fn named<T>(result: Result<T, MshError>) {
        if let Err(e) = result {
            assert_eq!(e.file, Path::new("fuzz.msh"));
            assert!(e.to_string().starts_with("fuzz.msh: "), "{e}");
        }
    }
    match MshMesh::from_bytes(bytes, "fuzz.msh") {
        Ok(m) => {
            for g in m.groups() {
                named(m.surface_elements(&g.name));
                named(m.curve_segments(&g.name));
                named(m.group_nodes(&g.name));
            }
            named(m.group_nodes("no such group"));
        }
        Err(e) => named::<()>(Err(e)),
    }
    match MshVolumeMesh::from_bytes(bytes, "fuzz.msh") {
        Ok(m) => {
            for g in m.groups() {
                named(m.volume_elements(&g.name));
                named(m.surface_faces(&g.name));
                named(m.group_nodes(&g.name));
            }
            named(m.surface_faces("no such group"));
        }
        Err(e) => named::<()>(Err(e)),
    }
}

#[test]
fn every_truncation_is_an_error_or_ends_a_section() {
    let planar = [TINY.as_bytes(), SQUARE, SQUARE_BINARY].map(|f| (f, false));
    let volume = [CUBE.as_bytes(), CUBE_BINARY, TETS.as_bytes(), TETS_BINARY].map(|f| (f, true));
    for (file, is_volume) in planar.into_iter().chain(volume) {
        for end in 0..file.len() {
            let cut = &file[..end];
            let reads = if is_volume {
                MshVolumeMesh::from_bytes(cut, "cut.msh").is_ok()
            } else {
                MshMesh::from_bytes(cut, "cut.msh").is_ok()
            };
            if reads {
                // Sections are optional: a file cut just after one reads
                // (and its queries fail for want of groups or elements).
                let text = String::from_utf8_lossy(cut);
                let last = text.trim_end().rsplit('\n').next().unwrap_or("");
                assert!(
                    last.starts_with("$End"),
                    "cut at {end} of {} read",
                    file.len()
                );
            }
        }
    }
}

fn fixture() -> impl Strategy<Value = &'static [u8]> {
    prop_oneof![
        Just(TINY.as_bytes()),
        Just(SQUARE),
        Just(SQUARE_BINARY),
        Just(CUBE.as_bytes()),
        Just(CUBE_BINARY),
        Just(TETS.as_bytes()),
        Just(TETS_BINARY),
    ]
}

proptest! {
    #[test]
    fn random_byte_flips_never_panic(
        file in fixture(),
        flips in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
    ) {
        let mut bytes = file.to_vec();
        for (at, byte) in flips {
            let at = at.index(bytes.len());
            bytes[at] = byte;
        }
        read_any(&bytes);
    }

    #[test]
    fn random_digit_edits_never_panic(
        file in fixture(),
        edits in prop::collection::vec(
            (any::<prop::sample::Index>(), prop::sample::select(b"0123456789-. \n".to_vec())),
            1..6,
        ),
    ) {
        // Digits changed into digits keep the structure and reach the
        // counts, tags and types deep inside the file.
        let mut bytes = file.to_vec();
        let digits: Vec<usize> = (0..bytes.len()).filter(|&i| bytes[i].is_ascii_digit()).collect();
        for (at, byte) in edits {
            bytes[digits[at.index(digits.len())]] = byte;
        }
        read_any(&bytes);
    }

    #[test]
    fn random_cuts_and_insertions_never_panic(
        file in fixture(),
        at in any::<prop::sample::Index>(),
        cut in 0usize..64,
        insert in prop::collection::vec(any::<u8>(), 0..16),
    ) {
        let mut bytes = file.to_vec();
        let at = at.index(bytes.len());
        let end = (at + cut).min(bytes.len());
        bytes.splice(at..end, insert);
        read_any(&bytes);
    }
}

/// The byte ranges of the whitespace-separated tokens of `text` that are
/// numbers.
fn numeric_tokens(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some(i),
            (true, Some(s)) => {
                if text[s..i].parse::<f64>().is_ok() {
                    out.push(s..i);
                }
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Numbers the random edits write: the extremes of every width a field of
/// the format has, and ordinary values.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<i64>().prop_map(|v| v.to_string()),
        (-20i64..70).prop_map(|v| v.to_string()),
        any::<f64>().prop_map(|v| v.to_string()),
        prop::sample::select(vec![
            "18446744073709551615",
            "4294967295",
            "2147483648",
            "-2147483649",
            "1e308",
            "-1e400",
            "nan",
            "inf",
            "0",
            "-0",
        ])
        .prop_map(str::to_owned),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn random_numbers_in_ascii_files_never_panic(
        file in prop_oneof![
            Just(TINY.as_bytes()),
            Just(SQUARE),
            Just(CUBE.as_bytes()),
            Just(TETS.as_bytes()),
        ],
        edits in prop::collection::vec((any::<prop::sample::Index>(), number()), 1..4),
    ) {
        // whole numeric tokens replaced by other numbers: counts, tags,
        // types and coordinates out of range
        let mut text = String::from_utf8(file.to_vec()).expect("ASCII fixture");
        for (at, value) in edits {
            let numbers = numeric_tokens(&text);
            let range = numbers[at.index(numbers.len())].clone();
            text.replace_range(range, &value);
        }
        read_any(text.as_bytes());
    }

    #[test]
    fn random_words_in_binary_files_never_panic(
        file in prop_oneof![
            Just(SQUARE_BINARY),
            Just(HERTZ_COARSE_BINARY),
            Just(CUBE_BINARY),
            Just(TETS_BINARY),
        ],
        edits in prop::collection::vec(
            (
                any::<prop::sample::Index>(),
                prop_oneof![
                    any::<u64>().prop_map(|v| v.to_le_bytes().to_vec()),
                    any::<i32>().prop_map(|v| v.to_le_bytes().to_vec()),
                    (0u64..64).prop_map(|v| v.to_le_bytes().to_vec()),
                    any::<f64>().prop_map(|v| v.to_le_bytes().to_vec()),
                ],
            ),
            1..4,
        ),
    ) {
        // binary fields (counts, tags, sizes, coordinates) overwritten by
        // random numbers of their widths
        let mut bytes = file.to_vec();
        for (at, word) in edits {
            let at = at.index(bytes.len());
            let end = (at + word.len()).min(bytes.len());
            bytes[at..end].copy_from_slice(&word[..end - at]);
        }
        read_any(&bytes);
    }

    #[test]
    fn truncated_hertz_files_never_panic(
        at in any::<prop::sample::Index>(),
    ) {
        // the Hertz mesh (63 kB) is too large to cut at every byte, as
        // the small fixtures are above
        let end = at.index(HERTZ_COARSE_BINARY.len());
        read_any(&HERTZ_COARSE_BINARY[..end]);
    }
}
