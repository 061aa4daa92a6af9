//! Tests of the element seam: dispatch gives each element's own bits, and
//! meshes that mix triangles and quadrilaterals work end to end (mesh
//! checks, assembly against finite differences, a nonlinear patch test
//! solved by Newton, VTU cells), while a mesh of quadrilaterals assembles
//! exactly as it did before triangles existed.

use super::*;
use crate::material::PlaneModel;

const MAT: Material = Material {
    young: 50.0,
    poisson: 0.3,
    model: PlaneModel::PlaneStrain,
    kinematics: crate::material::Kinematics::Finite,
};

/// Dispatch through the seam gives the element functions' exact bits.
#[test]
fn dispatch_is_the_element_functions() {
    let xq = [[0.0, 0.0], [1.2, 0.1], [1.0, 0.9], [-0.1, 1.1]];
    let xt = [[0.0, 0.0], [1.2, 0.1], [0.3, 0.8]];
    let u8: [f64; 8] = std::array::from_fn(|k| 0.01 * (k as f64 + 1.0).sin());
    // the seam's buffer: the element's dofs, then zeros
    let u: [f64; MAX_ELEMENT_DOFS] = std::array::from_fn(|k| if k < 8 { u8[k] } else { 0.0 });
    let gq = QuadGeometry::new(&xq).unwrap();
    let gt = TriGeometry::new(&xt).unwrap();
    let eq = ElementGeometry::new(&Element::Quad4(xq)).unwrap();
    let et = ElementGeometry::new(&Element::Tri3(xt)).unwrap();
    assert_eq!(eq.kind(), ElementKind::Quad4);
    assert_eq!(et.kind(), ElementKind::Tri3);
    let rq = gq.response(&u8, &MAT);
    assert_eq!(eq.response(&u, &MAT), ElementResponse::Quad4(rq));
    let ut: [f64; 6] = std::array::from_fn(|k| u8[k]);
    let rt = gt.response(&ut, &MAT);
    let r = et.response(&u, &MAT);
    assert_eq!(r, ElementResponse::Tri3(rt));
    assert_eq!(r.f_int(), &rt.f_int);
    assert_eq!(r.k_row(5), &rt.k[5]);
    assert_eq!(r.energy(), rt.energy);
    assert_eq!(eq.energy(&u, &MAT), gq.energy(&u8, &MAT));
    assert_eq!(et.energy(&u, &MAT), gt.energy(&ut, &MAT));
    assert_eq!(
        eq.mean_stress(&u, &MAT),
        ElementStress::Plane(gq.mean_stress(&u8, &MAT))
    );
    assert_eq!(
        et.mean_stress(&u, &MAT),
        ElementStress::Plane(gt.mean_stress(&ut, &MAT))
    );
    assert_eq!(et.area_ref(), gt.measure_ref());
    // a clockwise triangle is refused with the element's detJ0
    let cw = Element::Tri3([xt[0], xt[2], xt[1]]);
    let Err(ElementError::Invalid(InvalidElement { det_j0 })) = ElementGeometry::new(&cw) else {
        panic!("a clockwise triangle must be invalid");
    };
    assert!(det_j0 < 0.0);
}

#[test]
fn connectivity_views() {
    let e: Element<usize> = [4, 5, 6].into();
    assert_eq!(e.kind(), ElementKind::Tri3);
    assert_eq!(e.len(), 3);
    assert_eq!(e.map_nodes(|n| n + 1).nodes(), [5, 6, 7]);
    let q: Element<usize> = [0, 1, 2, 3].into();
    assert_eq!((&q).into_iter().sum::<usize>(), 6);
    assert_eq!(ElementKind::Tri3.vtk_cell_type(), 5);
    assert_eq!(ElementKind::Quad4.vtk_cell_type(), 9);
    assert_eq!(ElementKind::Tri3.to_string(), "3-node triangle");
}

pub(super) mod mixed {
    use crate::assembly::assemble_solid;
    use crate::element::{Element, ElementKind, SolidElement};
    use crate::ids::{DofId, EquationIndex, NodeId};
    use crate::material::{Material, PlaneModel};
    use crate::mesh::{Mesh, MeshError};
    use crate::model::{Model, Prescribed};
    use crate::system::{DofMap, System};
    use crate::testutil::Lcg;
    use crate::{SolveOptions, solve_model};

    const MAT: Material = Material {
        young: 1.0e6,
        poisson: 0.25,
        model: PlaneModel::PlaneStress,
        kinematics: crate::material::Kinematics::Finite,
    };

    /// The MacNeal–Harder patch (corners 0..3, interior nodes 4..7).
    pub(in crate::element) const NODES: [[f64; 2]; 8] = [
        [0.0, 0.0],
        [0.24, 0.0],
        [0.24, 0.12],
        [0.0, 0.12],
        [0.04, 0.02],
        [0.18, 0.03],
        [0.16, 0.08],
        [0.08, 0.08],
    ];

    /// The patch's five quadrilaterals.
    pub(in crate::element) const QUADS: [[usize; 4]; 5] = [
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
        [4, 5, 6, 7],
    ];

    /// The patch's five quadrilaterals, three of them split into two
    /// triangles each: 2 quadrilaterals and 6 triangles, interleaved.
    fn mixed_elements() -> Vec<Element<usize>> {
        vec![
            Element::Quad4([0, 1, 5, 4]),
            Element::Tri3([1, 2, 6]),
            Element::Tri3([1, 6, 5]),
            Element::Quad4([2, 3, 7, 6]),
            Element::Tri3([3, 0, 4]),
            Element::Tri3([3, 4, 7]),
            Element::Tri3([4, 5, 6]),
            Element::Tri3([4, 6, 7]),
        ]
    }

    fn mixed_mesh(material: Material) -> Mesh {
        let mut mesh = Mesh::new();
        mesh.add_body("patch", material, &NODES, &mixed_elements())
            .unwrap();
        mesh
    }

    /// The mixed patch with the displacements `H X` prescribed on its
    /// four corner nodes.
    fn deformed_patch(h: [[f64; 2]; 2]) -> Model {
        let prescribed = (0..4)
            .flat_map(|n| {
                (0..2).map(move |i| Prescribed {
                    dof: DofId::of(NodeId::new(n), i),
                    value: h[i][0] * NODES[n][0] + h[i][1] * NODES[n][1],
                    amplitude: None,
                })
            })
            .collect();
        Model {
            mesh: mixed_mesh(MAT),
            prescribed,
            loads: Vec::new(),
            contacts: Vec::new(),
            amplitudes: Vec::new(),
            supports: Vec::new(),
            load_factor_end: 1.0,
        }
    }

    #[test]
    fn mixed_bodies_keep_kinds_and_order() {
        let mesh = mixed_mesh(MAT);
        assert_eq!(mesh.element_count(), 8);
        let kinds: Vec<ElementKind> = mesh.elements.iter().map(|e| e.kind()).collect();
        let geometry: Vec<ElementKind> = mesh
            .element_ids()
            .map(|e| mesh.geometry(e).unwrap().kind())
            .collect();
        assert_eq!(kinds, geometry);
        assert_eq!(kinds[1], ElementKind::Tri3);
        assert_eq!(mesh.elements[2].map_nodes(NodeId::index).nodes(), [1, 6, 5]);
        // the elements tile the patch
        let area: f64 = mesh
            .element_ids()
            .map(|e| mesh.geometry(e).unwrap().area_ref())
            .sum();
        assert!((area - 0.24 * 0.12).abs() < 1e-15, "{area}");
        // a triangle's buffer holds its 6 dofs, then zeros
        let u: Vec<f64> = (0..16).map(|k| k as f64 + 1.0).collect();
        let ue = mesh.element_displacements(crate::ids::ElementId::new(2), &u);
        assert_eq!(ue[..6], [3.0, 4.0, 13.0, 14.0, 11.0, 12.0]);
        assert!(ue[6..].iter().all(|&v| v == 0.0));
    }

    /// A clockwise or degenerate triangle is named with its element index
    /// and kind; a triangle with a node outside the body too.
    #[test]
    fn invalid_triangles_are_named() {
        let mut elements = mixed_elements();
        elements[5] = Element::Tri3([3, 7, 4]);
        let err = Mesh::new()
            .add_body("patch", MAT, &NODES, &elements)
            .unwrap_err();
        assert!(
            matches!(
                err,
                MeshError::InvalidElement {
                    element: 5,
                    kind: ElementKind::Tri3,
                    det_j0,
                    ..
                } if det_j0 < 0.0
            ),
            "{err:?}"
        );
        let msg = err.to_string();
        assert!(
            msg.contains("element 5 (3-node triangle) of body `patch` is inverted"),
            "{msg}"
        );
        let collinear = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        let err = Mesh::new()
            .add_body("flat", MAT, &collinear, &[[0, 1, 2]])
            .unwrap_err();
        assert!(matches!(err, MeshError::InvalidElement { element: 0, .. }));
        let err = Mesh::new()
            .add_body("far", MAT, &collinear, &[[0, 1, 3]])
            .unwrap_err();
        assert!(matches!(
            err,
            MeshError::BadConnectivity {
                element: 0,
                node: 3,
                ..
            }
        ));
        // the quadrilateral's message names its kind too
        let err = Mesh::new()
            .add_body("q", MAT, &NODES, &[[0, 4, 5, 1]])
            .unwrap_err();
        assert!(err.to_string().contains("(4-node quadrilateral)"), "{err}");
    }

    /// Residual (free dofs) and dense tangent of the solid alone.
    fn solid_system(model: &Model, dofs: &DofMap, u: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        let mut sys = System::new(dofs.n_eq());
        assemble_solid(model, dofs, u, &mut sys).unwrap();
        let mut k = vec![vec![0.0; dofs.n_eq()]; dofs.n_eq()];
        for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
            k[r as usize][c as usize] += v;
        }
        (sys.residual, k)
    }

    fn fixed_corner(mesh: Mesh) -> Model {
        // node 0 fixed, node 1 held in y: no rigid motion left
        let prescribed = [(0, 0), (0, 1), (1, 1)]
            .map(|(n, i)| Prescribed {
                dof: DofId::of(NodeId::new(n), i),
                value: 0.0,
                amplitude: None,
            })
            .to_vec();
        Model {
            mesh,
            prescribed,
            loads: Vec::new(),
            contacts: Vec::new(),
            amplitudes: Vec::new(),
            supports: Vec::new(),
            load_factor_end: 1.0,
        }
    }

    /// On the mixed mesh, the assembled tangent equals central differences
    /// of the assembled residual in every free dof (h = 1e-8 relative to
    /// the patch, tolerance 1e-7 relative to the largest tangent entry), and
    /// the residual is the gradient of the assembled energy, at random
    /// states with strains of about 10 %, plane stress and plane strain.
    #[test]
    fn mixed_tangent_matches_finite_differences() {
        let mut rng = Lcg::new(23);
        for model_kind in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
            let material = Material {
                model: model_kind,
                ..MAT
            };
            let model = fixed_corner(mixed_mesh(material));
            let dofs = DofMap::new(&model, 0);
            let dof_of: Vec<usize> = (0..16)
                .filter(|&d| dofs.eq(DofId::new(d)).is_some())
                .collect();
            for (j, &d) in dof_of.iter().enumerate() {
                assert_eq!(dofs.eq(DofId::new(d)), Some(EquationIndex::new(j)));
            }
            for _ in 0..3 {
                let mut u: Vec<f64> = (0..16).map(|_| rng.uniform(-0.01, 0.01)).collect();
                for p in &model.prescribed {
                    u[p.dof.index()] = 0.0;
                }
                let (_, k) = solid_system(&model, &dofs, &u);
                let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
                let h = 1e-8;
                let mut worst = 0.0_f64;
                let mut worst_force = 0.0_f64;
                let (r0, _) = solid_system(&model, &dofs, &u);
                let fscale = r0.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (j, &d) in dof_of.iter().enumerate() {
                    let at = |s: f64| {
                        let mut v = u.clone();
                        v[d] += s;
                        let mut sys = System::new(dofs.n_eq());
                        assemble_solid(&model, &dofs, &v, &mut sys).unwrap();
                        sys
                    };
                    let (sp, sm) = (at(h), at(-h));
                    for i in 0..dofs.n_eq() {
                        let fd = (sp.residual[i] - sm.residual[i]) / (2.0 * h);
                        worst = worst.max((fd - k[i][j]).abs() / scale);
                    }
                    let fd_e = (sp.energy - sm.energy) / (2.0 * h);
                    worst_force = worst_force.max((fd_e - r0[j]).abs() / fscale);
                }
                assert!(worst < 1e-7, "relative tangent error {worst:e}");
                assert!(worst_force < 1e-6, "relative force error {worst_force:e}");
                for i in 0..dofs.n_eq() {
                    for j in 0..dofs.n_eq() {
                        assert!((k[i][j] - k[j][i]).abs() <= 1e-12 * scale);
                    }
                }
            }
        }
    }

    /// A mesh of quadrilaterals assembles as before the element seam: the
    /// same triplets and residual bits as the plain loop over
    /// the quadrilateral's response (every element's 8 rows in order, each row's 8
    /// columns in order).
    #[test]
    fn quad_assembly_is_unchanged() {
        let quads = QUADS;
        let mut mesh = Mesh::new();
        mesh.add_body("patch", MAT, &NODES, &quads).unwrap();
        let model = fixed_corner(mesh);
        let dofs = DofMap::new(&model, 0);
        let mut rng = Lcg::new(5);
        let u: Vec<f64> = (0..16).map(|_| rng.uniform(-0.01, 0.01)).collect();
        let mut sys = System::new(dofs.n_eq());
        assemble_solid(&model, &dofs, &u, &mut sys).unwrap();
        let mut old = System::new(dofs.n_eq());
        for (e, el) in quads.iter().enumerate() {
            let Ok(crate::element::ElementGeometry::Quad4(g)) =
                model.mesh.geometry(crate::ids::ElementId::new(e))
            else {
                panic!("element {e} is not a quadrilateral");
            };
            let ue: [f64; 8] = std::array::from_fn(|k| u[2 * el[k / 2] + k % 2]);
            let r = g.response(&ue, &MAT);
            let eqs: [Option<EquationIndex>; 8] =
                std::array::from_fn(|k| dofs.eq(DofId::new(2 * el[k / 2] + k % 2)));
            for p in 0..8 {
                let Some(ep) = eqs[p] else { continue };
                old.residual[ep.index()] += r.f_int[p];
                for q in 0..8 {
                    if let Some(eq) = eqs[q] {
                        old.push(ep, eq, r.k[p][q]);
                    }
                }
            }
            old.energy += r.energy;
        }
        assert_eq!(sys.rows, old.rows);
        assert_eq!(sys.cols, old.cols);
        assert_eq!(sys.vals, old.vals);
        assert_eq!(sys.residual, old.residual);
        assert_eq!(sys.energy, old.energy);
    }

    /// The homogeneous deformation `x = (I + H) X` (strains of about 8 %,
    /// geometrically nonlinear) prescribed on the boundary nodes of the
    /// mixed patch is reproduced at its interior nodes to 1e-12; every
    /// element, quadrilateral or triangle, has the same stresses (1e-10
    /// relative) and the strain energy is the patch's area times the
    /// energy density of the prescribed strain.
    #[test]
    fn mixed_patch_reproduces_homogeneous_deformation() {
        let h = [[0.08, 0.03], [-0.02, 0.05]];
        let exact = |n: usize, i: usize| h[i][0] * NODES[n][0] + h[i][1] * NODES[n][1];
        let model = deformed_patch(h);
        let sol = solve_model(
            &model,
            &SolveOptions {
                steps: 2,
                ..SolveOptions::default()
            },
        )
        .unwrap();
        for n in 4..8 {
            for i in 0..2 {
                let got = sol.displacement(NodeId::new(n))[i];
                assert!((got - exact(n, i)).abs() < 1e-12, "node {n}: {got}");
            }
        }
        let s = sol.element_stresses(&sol.final_state).unwrap();
        assert_eq!(s.len(), 8);
        for (e, st) in s.iter().enumerate() {
            for c in 0..3 {
                assert!(
                    (st.pk2[c] - s[0].pk2[c]).abs() < 1e-10 * s[0].pk2[0].abs(),
                    "element {e}: {st:?} vs {:?}",
                    s[0]
                );
                assert!((st.cauchy[c] - s[0].cauchy[c]).abs() < 1e-10 * s[0].cauchy[0].abs());
            }
        }
        // S = D E of F = I + H
        let f = [[1.0 + h[0][0], h[0][1]], [h[1][0], 1.0 + h[1][1]]];
        let e = [
            (f[0][0] * f[0][0] + f[1][0] * f[1][0] - 1.0) / 2.0,
            (f[0][1] * f[0][1] + f[1][1] * f[1][1] - 1.0) / 2.0,
            f[0][0] * f[0][1] + f[1][0] * f[1][1],
        ];
        let d = MAT.d_matrix();
        let sv: [f64; 3] =
            std::array::from_fn(|r| d[r][0] * e[0] + d[r][1] * e[1] + d[r][2] * e[2]);
        for c in 0..3 {
            assert!((s[0].pk2[c] - sv[c]).abs() < 1e-10 * sv[0].abs(), "S[{c}]");
        }
        let energy = 0.24 * 0.12 * 0.5 * (e[0] * sv[0] + e[1] * sv[1] + e[2] * sv[2]);
        assert!(
            (sol.strain_energy - energy).abs() < 1e-10 * energy,
            "{} vs {energy}",
            sol.strain_energy
        );
    }

    /// The VTU output of a mixed mesh has one cell per element with its own
    /// node count and VTK type (9 quadrilateral, 5 triangle).
    #[test]
    fn vtu_cells_of_a_mixed_mesh() {
        let model = deformed_patch([[0.01, 0.0], [0.0, -0.02]]);
        let sol = solve_model(&model, &SolveOptions::default()).unwrap();
        let text = crate::report::vtu_string(&sol, &sol.final_state).unwrap();
        assert!(text.contains("NumberOfPoints=\"8\" NumberOfCells=\"8\""));
        let array = |name: &str| -> Vec<String> {
            let start = text.find(&format!("Name=\"{name}\"")).unwrap();
            let body = &text[start..];
            let open = body.find('>').unwrap() + 1;
            let close = body.find("</DataArray>").unwrap();
            body[open..close]
                .split_whitespace()
                .map(str::to_owned)
                .collect()
        };
        assert_eq!(array("types"), ["9", "5", "5", "9", "5", "5", "5", "5"]);
        assert_eq!(
            array("offsets"),
            ["4", "7", "10", "14", "17", "20", "23", "26"]
        );
        let conn: Vec<usize> = array("connectivity")
            .iter()
            .map(|v| v.parse().unwrap())
            .collect();
        let expected: Vec<usize> = mixed_elements().iter().flatten().copied().collect();
        assert_eq!(conn, expected);
        assert_eq!(array("cauchy_stress").len(), 24);
        assert_eq!(array("body").len(), 8);
    }
}
