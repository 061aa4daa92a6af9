//! Tests of the 3D reader ([`MshVolumeMesh`]): the hand-written fixtures
//! `testdata/cube.msh` (one hexahedron, its bottom written inward, a point)
//! and `testdata/tets.msh` (two tetrahedra sharing a face), their binary
//! copies (`testdata/make-fixtures.py`), every 3D error, and that the 2D
//! reader still refuses them. The proptests of `tests.rs` read every
//! fixture, these included, through both readers.

use std::path::Path;

use super::tests::{
    CUBE, CUBE_BINARY, TETS, TETS_BINARY, assert_kinds, assert_message, edited, kind_in,
};
use super::*;
use crate::element::FaceKind;
use crate::mesh::volume::dot;

fn cube(edit: impl FnOnce(String) -> String) -> Result<MshVolumeMesh, MshError> {
    edited(CUBE, "cube.msh", edit)
}

fn tets(edit: impl FnOnce(String) -> String) -> Result<MshVolumeMesh, MshError> {
    edited(TETS, "tets.msh", edit)
}

fn kind(result: Result<MshVolumeMesh, MshError>, file: &str) -> MshErrorKind {
    kind_in(result, file)
}

fn faces(mesh: &MshVolumeMesh, group: &str) -> Vec<Face> {
    mesh.surface_faces(group)
        .unwrap()
        .iter()
        .map(|f| f.face)
        .collect()
}

/// Every face of every physical surface points out of its owner: along
/// the line from the owner's centroid to the face's.
pub(super) fn assert_outward(mesh: &MshVolumeMesh) {
    let x = |n: usize| mesh.nodes()[n];
    for g in mesh.groups().iter().filter(|g| g.dim == 2) {
        for f in mesh.surface_faces(&g.name).unwrap() {
            let owner = mesh
                .elements()
                .iter()
                .find(|e| e.tag == f.owner)
                .and_then(MshElement::cell)
                .expect("the owner is a volume element");
            let cell = owner.nodes();
            let centre: [f64; 3] = std::array::from_fn(|c| {
                cell.iter().map(|&n| x(n)[c]).sum::<f64>() / cell.len() as f64
            });
            let face = f.face.map_nodes(x);
            let c = face.centroid();
            let out = [c[0] - centre[0], c[1] - centre[1], c[2] - centre[2]];
            assert!(
                dot(face.normal(), out) > 0.0,
                "face {} of `{}` points into element {}",
                f.element,
                g.name,
                f.owner
            );
            // and it is a face of its owner
            assert!(owner.faces().iter().any(|o| {
                let mut a = o.nodes().to_vec();
                let mut b = f.face.nodes().to_vec();
                a.sort_unstable();
                b.sort_unstable();
                a == b
            }));
        }
    }
}

#[test]
fn the_cube_reads_with_outward_faces() {
    let mesh = cube(|s| s).unwrap();
    assert_eq!(mesh.nodes().len(), 8);
    assert_eq!(mesh.nodes()[6], [1.0, 1.0, 1.0]);
    let body = mesh.volume_elements("body").unwrap();
    assert_eq!(body.len(), 1);
    assert_eq!(body[0].tag, 1);
    assert_eq!(body[0].kind, MshElementType::Hexahedron);
    assert_eq!(body[0].entity, Entity { dim: 3, tag: 1 });
    assert_eq!(body[0].cell(), Some(Cell::Hex8([0, 1, 2, 3, 4, 5, 6, 7])));
    // written 1 2 3 4 (normal +z, into the cube): turned outward
    assert_eq!(faces(&mesh, "bottom"), [Face::Quad4([0, 3, 2, 1])]);
    let bottom = mesh.surface_faces("bottom").unwrap();
    assert_eq!((bottom[0].element, bottom[0].owner), (2, 1));
    // written outward: kept as written
    assert_eq!(faces(&mesh, "top"), [Face::Quad4([4, 5, 6, 7])]);
    assert_eq!(
        faces(&mesh, "sides"),
        [Face::Quad4([0, 1, 5, 4]), Face::Quad4([3, 7, 6, 2])]
    );
    assert_outward(&mesh);
    assert_eq!(mesh.group_nodes("corner").unwrap(), [0]);
    assert_eq!(mesh.group_nodes("top").unwrap(), [4, 5, 6, 7]);
    for i in 0..8 {
        assert_eq!(mesh.node_index(mesh.node_tag(i).unwrap()), Some(i));
    }
}

#[test]
fn the_tetrahedra_read_with_outward_faces() {
    let mesh = tets(|s| s).unwrap();
    let solid = mesh.volume_elements("solid").unwrap();
    assert_eq!(
        solid.iter().map(|e| e.cell().unwrap()).collect::<Vec<_>>(),
        [Cell::Tet4([0, 1, 2, 3]), Cell::Tet4([1, 2, 3, 4])]
    );
    // 1 2 3 is inward (normal +z at z = 0); 3 5 2 is outward already
    assert_eq!(faces(&mesh, "base"), [Face::Tri3([0, 2, 1])]);
    assert_eq!(faces(&mesh, "cap"), [Face::Tri3([2, 4, 1])]);
    assert_eq!(mesh.surface_faces("cap").unwrap()[0].owner, 2);
    assert_outward(&mesh);
}

#[test]
fn a_face_in_any_order_is_oriented_by_its_owner() {
    // the top written backwards, from node 8: outward again, from node 8
    let mesh = cube(|s| s.replace("3 5 6 7 8\n", "3 8 7 6 5\n")).unwrap();
    assert_eq!(faces(&mesh, "top"), [Face::Quad4([7, 4, 5, 6])]);
    // crossed (not a cycle of the face): the owner's cycle
    let mesh = cube(|s| s.replace("3 5 6 7 8\n", "3 5 7 6 8\n")).unwrap();
    assert_eq!(faces(&mesh, "top"), [Face::Quad4([4, 5, 6, 7])]);
    let mesh = tets(|s| s.replace("4 3 5 2\n", "4 5 3 2\n")).unwrap();
    assert_eq!(faces(&mesh, "cap"), [Face::Tri3([4, 1, 2])]);
}

/// Binary and ASCII files of one mesh read the same.
fn assert_same(a: &MshVolumeMesh, b: &MshVolumeMesh) {
    assert_eq!(a.nodes(), b.nodes());
    let tags = |m: &MshVolumeMesh| {
        (0..m.nodes().len())
            .map(|i| m.node_tag(i))
            .collect::<Vec<_>>()
    };
    assert_eq!(tags(a), tags(b));
    assert_eq!(a.elements(), b.elements());
    assert_eq!(a.groups(), b.groups());
    for g in a.groups().iter().filter(|g| g.dim == 2) {
        assert_eq!(
            a.surface_faces(&g.name).unwrap(),
            b.surface_faces(&g.name).unwrap()
        );
    }
}

#[test]
fn binary_files_equal_ascii() {
    let binary = MshVolumeMesh::from_bytes(CUBE_BINARY, "cube-binary.msh").unwrap();
    assert_same(&cube(|s| s).unwrap(), &binary);
    let binary = MshVolumeMesh::from_bytes(TETS_BINARY, "tets-binary.msh").unwrap();
    assert_same(&tets(|s| s).unwrap(), &binary);
}

#[test]
fn the_2d_reader_still_refuses_3d_meshes() {
    for (bytes, node) in [(CUBE.as_bytes(), 5), (CUBE_BINARY, 5), (TETS_BINARY, 4)] {
        let e = MshMesh::from_bytes(bytes, "c.msh").unwrap_err();
        assert!(
            matches!(e.kind, MshErrorKind::NotPlanar { node: n, .. } if n == node),
            "{e}"
        );
    }
    // a flat hexahedron: the 2D reader refuses the type, in its words
    let flat = CUBE.replace(
        "0 0 1\n1 0 1\n1 1 1\n0 1 1\n",
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n",
    );
    let e = MshMesh::from_bytes(flat.as_bytes(), "flat.msh").unwrap_err();
    assert!(
        matches!(
            e.kind,
            MshErrorKind::UnsupportedElement { gmsh_type: 5, .. }
        ),
        "{e}"
    );
    assert!(
        e.to_string().ends_with(
            "only 1-node points, 2-node lines, 3-node triangles and 4-node quadrangles are read"
        ),
        "{e}"
    );
    // and the 3D reader finds it degenerate
    let e = kind(
        MshVolumeMesh::from_bytes(flat.as_bytes(), "flat.msh"),
        "flat.msh",
    );
    assert!(
        matches!(e, MshErrorKind::InvertedElement { element: 1, .. }),
        "{e}"
    );
}

#[test]
fn a_2d_mesh_read_as_3d_has_unowned_faces() {
    let square = include_bytes!("testdata/square.msh");
    let e = kind(MshVolumeMesh::from_bytes(square, "sq.msh"), "sq.msh");
    assert!(
        matches!(&e, MshErrorKind::UnownedFace { group, .. } if group == "left" || group == "right"),
        "{e}"
    );
    assert!(
        e.to_string().contains("is no face of a volume element"),
        "{e}"
    );
}

#[test]
fn inverted_elements_name_their_tag() {
    // top and bottom swapped: inverted at every corner
    let e = kind(
        cube(|s| s.replace("1 1 2 3 4 5 6 7 8", "1 5 6 7 8 1 2 3 4")),
        "cube.msh",
    );
    assert!(
        matches!(e, MshErrorKind::InvertedElement { element: 1, det_j, .. } if det_j < 0.0),
        "{e}"
    );
    let text = e.to_string();
    assert!(
        text.contains("element 1 (8-node hexahedron) is inverted"),
        "{text}"
    );
    // one corner (node 7) pushed inside: inverted there only
    let e = kind(
        cube(|s| s.replace("1 1 1\n0 1 1\n$EndNodes", "0.2 0.2 0.2\n0 1 1\n$EndNodes")),
        "cube.msh",
    );
    assert!(
        matches!(
            e,
            MshErrorKind::InvertedElement {
                element: 1,
                node: 7,
                ..
            }
        ),
        "{e}"
    );
    // a tetrahedron drawn the other way round
    let e = kind(tets(|s| s.replace("2 2 3 4 5", "2 3 2 4 5")), "tets.msh");
    assert!(
        matches!(e, MshErrorKind::InvertedElement { element: 2, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("4-node tetrahedron"), "{e}");
}

#[test]
fn faces_no_element_owns_are_named() {
    // the face the two tetrahedra share
    let e = kind(tets(|s| s.replace("4 3 5 2\n", "4 2 3 4\n")), "tets.msh");
    assert!(
        matches!(&e, MshErrorKind::UnownedFace { element: 4, group, .. } if group == "cap"),
        "{e}"
    );
    assert!(e.to_string().contains("between 2 volume elements"), "{e}");
    // three nodes of no face
    let e = kind(tets(|s| s.replace("4 3 5 2\n", "4 1 2 5\n")), "tets.msh");
    assert!(
        matches!(e, MshErrorKind::UnownedFace { element: 4, .. }),
        "{e}"
    );
    // a diagonal section of the cube
    let e = kind(
        cube(|s| s.replace("4 1 2 6 5\n", "4 1 2 7 8\n")),
        "cube.msh",
    );
    let text = e.to_string();
    assert!(
        text.contains("element 4 (4-node quadrangle) of physical surface `sides` is no face"),
        "{text}"
    );
    // a triangle on three nodes of a hexahedron's face is no face either
    let e = kind(
        cube(|s| s.replace("2 2 3 1\n3 5 6 7 8\n", "2 2 2 1\n3 5 6 7\n")),
        "cube.msh",
    );
    assert!(
        matches!(e, MshErrorKind::UnownedFace { element: 3, .. }),
        "{e}"
    );
}

#[test]
fn other_3d_types_and_misplaced_volumes_are_refused() {
    // a 6-node prism
    let e = kind(
        cube(|s| s.replace("3 1 5 1\n1 1 2 3 4 5 6 7 8", "3 1 6 1\n1 1 2 3 4 5 6")),
        "cube.msh",
    );
    assert!(
        matches!(e, MshErrorKind::UnsupportedElement { gmsh_type: 6, .. }),
        "{e}"
    );
    assert!(
        e.to_string().contains(
            "4-node tetrahedra and 8-node hexahedra are read; mesh the volumes with tetrahedra or hexahedra only"
        ),
        "{e}"
    );
    // a hexahedron on a surface entity
    let e = kind(cube(|s| s.replace("3 1 5 1\n", "2 1 5 1\n")), "cube.msh");
    assert!(matches!(e, MshErrorKind::ElementDimension { .. }), "{e}");
}

#[test]
fn queries_of_the_wrong_dimension() {
    let mesh = cube(|s| s).unwrap();
    assert_kinds(
        [
            mesh.volume_elements("top").map(|_| ()),
            mesh.surface_faces("body").map(|_| ()),
            mesh.group_nodes("body").map(|_| ()),
        ],
        |k| matches!(k, MshErrorKind::WrongDimension { .. }),
    );
    assert_message(
        mesh.volume_elements("top"),
        "`top` has dimension 2, but 3 (a physical volume)",
    );
    assert_kinds([mesh.surface_faces("lid")], |k| {
        matches!(k, MshErrorKind::UnknownGroup { .. })
    });
    // a named volume no entity belongs to
    let mesh = cube(|s| s.replace("5\n0 4 \"corner\"", "6\n3 9 \"void\"\n0 4 \"corner\"")).unwrap();
    assert_kinds([mesh.volume_elements("void")], |k| {
        matches!(k, MshErrorKind::EmptyGroup { .. })
    });
}

#[test]
fn the_fixtures_survive_the_fuzz_reader() {
    // `read_any` (the proptests' oracle) accepts the intact fixtures too
    for bytes in [CUBE.as_bytes(), CUBE_BINARY, TETS.as_bytes(), TETS_BINARY] {
        super::tests::read_any(bytes);
    }
}

// ----- the 3D Hertz meshes (scripts/make-hertz3d-mesh.py) --------------------

const R: f64 = 10.0;

fn scene_file(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

/// What every 3D Hertz mesh promises: its groups, elements of `kind`
/// only, the bodies apart, each group on its plane or sphere with its
/// faces owned and outward, and spacing about `h` at the contact.
/// `counts`: nodes, volume elements, surface elements (as Gmsh counted them
/// when it wrote the file).
fn check_hertz3d(file: &str, kind: MshElementType, counts: [usize; 3]) {
    let mesh = MshVolumeMesh::read(scene_file(file)).unwrap();
    let mut names: Vec<&str> = mesh.groups().iter().map(|g| g.name.as_str()).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "block",
            "block_top",
            "bottom",
            "indenter",
            "indenter_surface",
            "indenter_top",
            "symmetry_x",
            "symmetry_y"
        ]
    );
    let indenter = mesh.volume_elements("indenter").unwrap();
    let block = mesh.volume_elements("block").unwrap();
    assert!(indenter.iter().chain(&block).all(|e| e.kind == kind));
    let surfaces = mesh.elements().iter().filter(|e| e.kind.dim() == 2).count();
    assert_eq!(
        [mesh.nodes().len(), indenter.len() + block.len(), surfaces],
        counts,
        "{file}"
    );
    // the bodies share no nodes, and every node is in one
    let nodes_of = |elements: &[&MshElement]| {
        let mut n: Vec<usize> = elements.iter().flat_map(|e| e.nodes().to_vec()).collect();
        n.sort_unstable();
        n.dedup();
        n
    };
    let (ind_nodes, blk_nodes) = (nodes_of(&indenter), nodes_of(&block));
    assert!(
        ind_nodes
            .iter()
            .all(|n| blk_nodes.binary_search(n).is_err())
    );
    assert_eq!(ind_nodes.len() + blk_nodes.len(), mesh.nodes().len());
    // each touches the origin with a node of its own
    let at_origin = |nodes: &[usize]| {
        nodes
            .iter()
            .any(|&n| mesh.nodes()[n].iter().all(|c| c.abs() < 1e-12))
    };
    assert!(at_origin(&ind_nodes) && at_origin(&blk_nodes));

    assert_outward(&mesh);
    let x = |n: usize| mesh.nodes()[n];
    let owner_body = |f: &SurfaceFace| {
        if indenter.iter().any(|e| e.tag == f.owner) {
            "indenter"
        } else {
            "block"
        }
    };
    // (group, the bodies it is on, on its surface, its outward direction)
    let on_plane = |axis: usize, value: f64| move |p: [f64; 3]| (p[axis] - value).abs() < 1e-9;
    type Check<'a> = (
        &'a str,
        &'a [&'a str],
        Box<dyn Fn([f64; 3]) -> bool>,
        [f64; 3],
    );
    let checks: [Check; 6] = [
        (
            "symmetry_x",
            &["indenter", "block"],
            Box::new(on_plane(0, 0.0)),
            [-1.0, 0.0, 0.0],
        ),
        (
            "symmetry_y",
            &["indenter", "block"],
            Box::new(on_plane(1, 0.0)),
            [0.0, -1.0, 0.0],
        ),
        (
            "bottom",
            &["block"],
            Box::new(on_plane(2, -10.0)),
            [0.0, 0.0, -1.0],
        ),
        (
            "block_top",
            &["block"],
            Box::new(on_plane(2, 0.0)),
            [0.0, 0.0, 1.0],
        ),
        (
            "indenter_top",
            &["indenter"],
            Box::new(on_plane(2, 5.0)),
            [0.0, 0.0, 1.0],
        ),
        (
            "indenter_surface",
            &["indenter"],
            Box::new(|p: [f64; 3]| (p[0].hypot(p[1]).hypot(p[2] - R) - R).abs() < 1e-9),
            [0.0, 0.0, -1.0],
        ),
    ];
    for (group, bodies, on_surface, outward) in checks {
        let faces = mesh.surface_faces(group).unwrap();
        let mut seen: Vec<&str> = faces.iter().map(owner_body).collect();
        seen.sort();
        seen.dedup();
        let mut expected = bodies.to_vec();
        expected.sort();
        assert_eq!(seen, expected, "{group}");
        for f in &faces {
            assert!(f.face.kind() == FaceKind::of(kind), "{group}");
            assert!(f.face.nodes().iter().all(|&n| on_surface(x(n))), "{group}");
            // the sphere's outward normals point down wherever its slope is
            // below 90 degrees: everywhere here (45 degrees at most, at the
            // indenter's corner x = y = 5)
            assert!(dot(f.face.map_nodes(x).normal(), outward) > 0.0, "{group}");
        }
    }
    // spacing about h = 0.1 where the bodies touch: the mean edge of the
    // contact faces within 1 of the axis
    for group in ["indenter_surface", "block_top"] {
        let mut edges = Vec::new();
        for f in mesh.surface_faces(group).unwrap() {
            let p = f.face.map_nodes(x);
            let c = p.centroid();
            if c[0].hypot(c[1]) < 1.0 {
                let n = p.nodes();
                for k in 0..n.len() {
                    let (a, b) = (n[k], n[(k + 1) % n.len()]);
                    edges.push(
                        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2))
                            .sqrt(),
                    );
                }
            }
        }
        let mean = edges.iter().sum::<f64>() / edges.len() as f64;
        assert!(
            (0.08..0.13).contains(&mean),
            "{file} {group}: mean edge {mean}"
        );
    }
}

impl FaceKind {
    /// The face kind of a volume element type's faces (hexahedra: quad4,
    /// tetrahedra: tri3).
    fn of(kind: MshElementType) -> FaceKind {
        match kind {
            MshElementType::Hexahedron => FaceKind::Quad4,
            _ => FaceKind::Tri3,
        }
    }
}

#[test]
fn the_hexahedral_hertz3d_mesh_reads() {
    check_hertz3d(
        "hertz3d-hex.msh",
        MshElementType::Hexahedron,
        [30532, 26982, 4710],
    );
}

#[test]
fn the_tetrahedral_hertz3d_mesh_reads() {
    check_hertz3d(
        "hertz3d-tet.msh",
        MshElementType::Tetrahedron,
        [7851, 38971, 5754],
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    #[test]
    fn truncated_hertz3d_files_never_panic(
        at in proptest::prelude::any::<proptest::sample::Index>(),
    ) {
        // the 3D Hertz mesh (2 MB) cut anywhere
        let bytes = std::fs::read(scene_file("hertz3d-tet.msh")).unwrap();
        let end = at.index(bytes.len());
        super::tests::read_any(&bytes[..end]);
    }
}

/// `text` written to a fresh file named `name` in the temporary directory,
/// read by [`read_any`] (the scene's reader: the file's own dimension).
fn read_any_text(text: &str, name: &str) -> Result<AnyMsh, MshError> {
    let dir = std::env::temp_dir().join(format!("gapsim-read-any-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let result = read_any(&path);
    std::fs::remove_file(&path).unwrap();
    result
}

/// A 3D file's own problems reach the user as the 3D reader says them,
/// never as the 2D reader's complaint about a node's z: a NaN coordinate,
/// a duplicated node tag, a second-order tetrahedron (with what to do), an
/// extra 3-node line; the file as written reads as 3D, a 2D file as 2D.
#[test]
fn a_3d_file_s_errors_are_the_3d_reader_s() {
    assert!(matches!(
        read_any_text(TETS, "t.msh"),
        Ok(AnyMsh::Volume(_))
    ));
    let square = std::str::from_utf8(include_bytes!("testdata/square.msh")).unwrap();
    assert!(matches!(
        read_any_text(square, "sq.msh"),
        Ok(AnyMsh::Planar(_))
    ));

    let nan = TETS.replace("1 1 1\n$EndNodes", "nan 1 1\n$EndNodes");
    assert_ne!(nan, TETS);
    let e = read_any_text(&nan, "nan.msh").unwrap_err();
    assert!(
        matches!(e.kind, MshErrorKind::NonFiniteNode { node: 5, .. }),
        "{e}"
    );

    let twice = TETS.replace("1\n2\n3\n4\n5\n", "1\n2\n3\n4\n4\n");
    assert_ne!(twice, TETS);
    let e = read_any_text(&twice, "twice.msh").unwrap_err();
    assert!(matches!(e.kind, MshErrorKind::DuplicateNode(4)), "{e}");

    // the two tetrahedra as one 10-node second-order tetrahedron
    let second = TETS.replace("3 4 1 4\n", "3 3 1 4\n").replace(
        "3 1 4 2\n1 1 2 3 4\n2 2 3 4 5\n",
        "3 1 11 1\n1 1 2 3 4 5 1 2 3 4 5\n",
    );
    assert_ne!(second, TETS);
    let e = read_any_text(&second, "second.msh").unwrap_err();
    assert!(
        matches!(
            e.kind,
            MshErrorKind::UnsupportedElement { gmsh_type: 11, .. }
        ),
        "{e}"
    );
    let text = e.to_string();
    assert!(
        text.contains("10-node second order tetrahedron (type 11)")
            && text.contains("gapsim's elements are linear")
            && text.contains("-order 1"),
        "{text}"
    );

    // an extra 3-node line on a curve
    let line = TETS
        .replace("3 4 1 4\n", "4 5 1 5\n")
        .replace("$EndElements", "1 1 8 1\n5 1 2 3\n$EndElements");
    let e = read_any_text(&line, "line.msh").unwrap_err();
    assert!(
        matches!(
            e.kind,
            MshErrorKind::UnsupportedElement { gmsh_type: 8, .. }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("3-node second order line"), "{e}");
}
