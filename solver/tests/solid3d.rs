//! 3D solids through the assembled solver: the patch test on hexahedra,
//! tetrahedra and a mix of both (every dof of the boundary prescribed to a
//! linear field, the interior solved), the assembled tangent against
//! finite differences, a cantilever of hexahedra against beam theory
//! (small and finite kinematics), the 3D outputs and what a 3D model
//! refuses.

use solver::assembly::assemble_solid;
use solver::element::{Element, ElementKind};
use solver::ids::{DofId, NodeId};
use solver::mesh::Block;
use solver::mesh::volume::Cell;
use solver::mesh::{Mesh, MeshError};
use solver::model::{ContactPair, Integration, ModelError, PointLoad, Prescribed, SupportGroup};
use solver::report::{reactions_csv, vtu_string};
use solver::system::{DofMap, System};
use solver::{
    ContactMode, Formulation, Kinematics, Material, Model, PlaneModel, SolveOptions, SolverError,
};

fn material(poisson: f64, kinematics: Kinematics) -> Material {
    Material {
        young: 200.0,
        poisson,
        // not read in 3D
        model: PlaneModel::PlaneStrain,
        kinematics,
    }
}

/// A linear displacement field `u = A X + c` (a uniform stretch with
/// shear and a translation).
const A: [[f64; 3]; 3] = [
    [1.0e-3, 2.0e-4, -1.0e-4],
    [-3.0e-4, -5.0e-4, 4.0e-4],
    [2.5e-4, 1.0e-4, 7.0e-4],
];
const C: [f64; 3] = [0.01, -0.02, 0.005];

fn linear_field(x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| C[i] + (0..3).map(|j| A[i][j] * x[j]).sum::<f64>())
}

/// The nodes of a `2 x 2 x 2` block over `[0, 1.2] x [0, 1] x [0, 0.8]`
/// with its one interior node moved off centre (so the patch is not
/// regular).
fn patch_nodes() -> (Block<3>, Vec<[f64; 3]>) {
    let block = Block {
        origin: [0.0, 0.0, 0.0],
        size: [1.2, 1.0, 0.8],
        cells: [2, 2, 2],
    };
    let mut nodes = block.nodes().unwrap();
    let centre = block.node([1, 1, 1]);
    nodes[centre] = [0.67, 0.46, 0.43];
    (block, nodes)
}

/// The signed volume of a tetrahedron, times 6.
fn tet_volume6(x: &[[f64; 3]], t: [usize; 4]) -> f64 {
    let d = |k: usize| -> [f64; 3] { std::array::from_fn(|i| x[t[k]][i] - x[t[0]][i]) };
    let (a, b, c) = (d(1), d(2), d(3));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// The six tetrahedra (Kuhn's split along the diagonal 0-6) of a
/// hexahedron, each oriented positive.
fn kuhn(x: &[[f64; 3]], h: [usize; 8]) -> Vec<Element<usize>> {
    solver::element::hex::KUHN_TETS
        .iter()
        .map(|l| {
            let mut t = l.map(|k| h[k]);
            if tet_volume6(x, t) < 0.0 {
                t.swap(1, 2);
            }
            Element::Tet4(t)
        })
        .collect()
}

fn hexes(block: &Block<3>) -> Vec<[usize; 8]> {
    block
        .cells()
        .unwrap()
        .into_iter()
        .map(|c| match c {
            Cell::Hex8(h) => h,
            Cell::Tet4(_) => unreachable!("a block has hexahedra"),
        })
        .collect()
}

/// A model whose boundary nodes are all prescribed to the linear field.
fn patch_model(mesh: Mesh<3>) -> Model<3> {
    let tol = 1e-12;
    let lo = [0.0, 0.0, 0.0];
    let hi = [1.2, 1.0, 0.8];
    let mut prescribed = Vec::new();
    for n in mesh.node_ids() {
        let x = mesh.node_ref(n);
        let boundary = (0..3).any(|c| (x[c] - lo[c]).abs() < tol || (x[c] - hi[c]).abs() < tol);
        if boundary {
            let u = linear_field(x);
            for (c, &value) in u.iter().enumerate() {
                prescribed.push(Prescribed {
                    dof: DofId::in_dim::<3>(n, c),
                    value,
                    amplitude: None,
                });
            }
        }
    }
    Model {
        mesh,
        prescribed,
        loads: Vec::new(),
        contacts: Vec::new(),
        load_factor_end: 1.0,
        amplitudes: Vec::new(),
        supports: Vec::new(),
    }
}

/// Solves the patch and returns the largest error of the displacement
/// (over every node) and of the element stresses against the field's
/// uniform ones (relative to the largest stress component).
fn patch_errors(mesh: Mesh<3>, kinematics: Kinematics) -> (f64, f64) {
    let model = patch_model(mesh);
    let solution = solver::solve_model(&model, &SolveOptions::default()).unwrap();
    let mut u_err = 0.0_f64;
    for n in model.mesh.node_ids() {
        let exact = linear_field(model.mesh.node_ref(n));
        let u = solution.displacement(n);
        for c in 0..3 {
            u_err = u_err.max((u[c] - exact[c]).abs());
        }
    }
    let stresses = solution.element_stresses(&solution.final_state).unwrap();
    let first = stresses[0];
    let scale = first.pk2.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    let mut s_err = 0.0_f64;
    for s in &stresses {
        for c in 0..6 {
            s_err = s_err.max((s.pk2[c] - first.pk2[c]).abs() / scale);
        }
    }
    // with small kinematics the stress is D eps of the field, exactly
    if kinematics == Kinematics::Small {
        let d = material(0.3, kinematics).d_matrix_3d();
        let eps = [
            A[0][0],
            A[1][1],
            A[2][2],
            A[1][2] + A[2][1],
            A[0][2] + A[2][0],
            A[0][1] + A[1][0],
        ];
        for (row, s) in d.iter().zip(first.pk2) {
            let exact: f64 = row.iter().zip(&eps).map(|(d, e)| d * e).sum();
            s_err = s_err.max((s - exact).abs() / scale);
        }
    }
    (u_err, s_err)
}

fn hex_mesh(kinematics: Kinematics) -> Mesh<3> {
    let (block, nodes) = patch_nodes();
    let mut mesh = Mesh::<3>::new();
    mesh.add_body("patch", material(0.3, kinematics), &nodes, &hexes(&block))
        .unwrap();
    mesh
}

fn tet_mesh(kinematics: Kinematics) -> Mesh<3> {
    let (block, nodes) = patch_nodes();
    let tets: Vec<Element<usize>> = hexes(&block)
        .into_iter()
        .flat_map(|h| kuhn(&nodes, h))
        .collect();
    let mut mesh = Mesh::<3>::new();
    mesh.add_body("patch", material(0.3, kinematics), &nodes, &tets)
        .unwrap();
    mesh
}

/// Hexahedra below `z = 0.4`, tetrahedra above (the shared faces are
/// quadrilaterals on one side and pairs of triangles on the other: a
/// linear field is exact on both).
fn mixed_mesh(kinematics: Kinematics) -> Mesh<3> {
    let (block, nodes) = patch_nodes();
    let mut elements = Vec::new();
    for (k, h) in hexes(&block).into_iter().enumerate() {
        if k < 4 {
            elements.push(Element::Hex8(h));
        } else {
            elements.extend(kuhn(&nodes, h));
        }
    }
    let mut mesh = Mesh::<3>::new();
    mesh.add_body("patch", material(0.3, kinematics), &nodes, &elements)
        .unwrap();
    mesh
}

#[test]
fn patch_test_on_hexahedra() {
    for kinematics in [Kinematics::Small, Kinematics::Finite] {
        let (u, s) = patch_errors(hex_mesh(kinematics), kinematics);
        assert!(
            u < 1e-12 && s < 1e-10,
            "{kinematics:?}: u {u:e}, stress {s:e}"
        );
    }
}

#[test]
fn patch_test_on_tetrahedra() {
    let mesh = tet_mesh(Kinematics::Small);
    assert_eq!(mesh.element_count(), 48);
    for kinematics in [Kinematics::Small, Kinematics::Finite] {
        let (u, s) = patch_errors(tet_mesh(kinematics), kinematics);
        assert!(
            u < 1e-12 && s < 1e-10,
            "{kinematics:?}: u {u:e}, stress {s:e}"
        );
    }
}

#[test]
fn patch_test_on_a_mix_of_hexahedra_and_tetrahedra() {
    let mesh = mixed_mesh(Kinematics::Small);
    let kinds: Vec<ElementKind> = mesh.elements.iter().map(|e| e.kind()).collect();
    assert_eq!(kinds.iter().filter(|&&k| k == ElementKind::Hex8).count(), 4);
    assert_eq!(
        kinds.iter().filter(|&&k| k == ElementKind::Tet4).count(),
        24
    );
    for kinematics in [Kinematics::Small, Kinematics::Finite] {
        let (u, s) = patch_errors(mixed_mesh(kinematics), kinematics);
        assert!(
            u < 1e-12 && s < 1e-10,
            "{kinematics:?}: u {u:e}, stress {s:e}"
        );
    }
}

/// The assembled residual's derivative by central differences is the
/// assembled tangent, on the mixed mesh at a finite deformation.
#[test]
fn assembled_tangent_is_the_residual_derivative() {
    let model = patch_model(mixed_mesh(Kinematics::Finite));
    let dofs = DofMap::all_free(model.dof_count(), 0);
    let n = model.dof_count();
    let u: Vec<f64> = (0..n).map(|k| 0.05 * ((k as f64) * 0.7).sin()).collect();
    let residual = |u: &[f64]| {
        let mut sys = System::new(n);
        assemble_solid(&model, &dofs, u, &mut sys).unwrap();
        sys
    };
    let at = residual(&u);
    let mut k = vec![vec![0.0; n]; n];
    for ((&r, &c), &v) in at.rows.iter().zip(&at.cols).zip(&at.vals) {
        k[r as usize][c as usize] += v;
    }
    let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let h = 1e-6;
    let mut worst = 0.0_f64;
    for j in (0..n).step_by(7) {
        let (mut up, mut down) = (u.clone(), u.clone());
        up[j] += h;
        down[j] -= h;
        let (rp, rm) = (residual(&up), residual(&down));
        for ((p, m), row) in rp.residual.iter().zip(&rm.residual).zip(&k) {
            let fd = (p - m) / (2.0 * h);
            worst = worst.max((fd - row[j]).abs() / scale);
        }
        // the energy's derivative is the residual
        let de = (rp.energy - rm.energy) / (2.0 * h);
        assert!(
            (de - at.residual[j]).abs() <= 1e-6 * scale,
            "{de} {}",
            at.residual[j]
        );
    }
    assert!(worst < 1e-7, "{worst:e}");
}

/// The cantilever: `L x h x h` with `L = 5`, `h = 1`, `nu = 0`, clamped at
/// `x = 0` (every dof), a tip force `P` along `-z` shared by the tip's
/// nodes as the consistent load of a uniform shear traction.
const L: f64 = 5.0;
const NX: usize = 50;

fn cantilever(kinematics: Kinematics, p: f64) -> (Model<3>, NodeId) {
    let block = Block {
        origin: [0.0, 0.0, 0.0],
        size: [L, 1.0, 1.0],
        cells: [NX, 2, 2],
    };
    let mut mesh = Mesh::<3>::new();
    mesh.add_block("beam", material(0.0, kinematics), block)
        .unwrap();
    let clamped = mesh.select_nodes_at(None, &[Some(0.0)]);
    assert_eq!(clamped.len(), 9);
    let prescribed: Vec<Prescribed> = clamped
        .iter()
        .flat_map(|&n| {
            (0..3).map(move |c| Prescribed {
                dof: DofId::in_dim::<3>(n, c),
                value: 0.0,
                amplitude: None,
            })
        })
        .collect();
    let tip = mesh.select_nodes_at(None, &[Some(L)]);
    assert_eq!(tip.len(), 9);
    // a 2 x 2 grid of bilinear faces: corner 1/16, edge 2/16, centre 4/16
    let loads = tip
        .iter()
        .map(|&n| {
            let x = mesh.node_ref(n);
            let inner = |v: f64| u32::from((v - 0.5).abs() < 1e-9);
            let share = f64::from(1 << (inner(x[1]) + inner(x[2]))) / 16.0;
            PointLoad {
                dof: DofId::in_dim::<3>(n, 2),
                value: -p * share,
                amplitude: None,
            }
        })
        .collect();
    let centre = mesh.select_nodes_at(None, &[Some(L), Some(0.5), Some(0.5)]);
    assert_eq!(centre.len(), 1);
    let supports = vec![SupportGroup {
        name: "clamp".into(),
        prescribed: 0..prescribed.len(),
    }];
    let model = Model {
        mesh,
        prescribed,
        loads,
        contacts: Vec::new(),
        load_factor_end: 1.0,
        amplitudes: Vec::new(),
        supports,
    };
    (model, centre[0])
}

/// Timoshenko's tip deflection of the cantilever (`nu = 0`: `G = E / 2`,
/// shear coefficient 5/6 of a rectangle).
fn timoshenko(p: f64) -> f64 {
    let (e, i, a) = (200.0, 1.0 / 12.0, 1.0);
    p * L.powi(3) / (3.0 * e * i) + p * L / (5.0 / 6.0 * e / 2.0 * a)
}

/// The tolerance from the mesh: a fully integrated trilinear element of
/// length `a` and height `b` in bending is too stiff by the parasitic
/// shear, its deflection `1 / (1 + (1 - nu)/2 (a/b)^2)` of the exact one
/// (2 % at `a/b = 0.1/0.5`, `nu = 0`), plus 1 % for the clamp's warping
/// restraint and the shear coefficient.
fn cantilever_tolerance() -> f64 {
    let ratio: f64 = (L / NX as f64) / 0.5;
    1.0 - 1.0 / (1.0 + 0.5 * ratio * ratio) + 0.01
}

#[test]
fn cantilever_of_hexahedra_matches_beam_theory() {
    let p = 0.01;
    let (model, centre) = cantilever(Kinematics::Small, p);
    let solution = solver::solve_model(&model, &SolveOptions::default()).unwrap();
    let delta = -solution.displacement(centre)[2];
    let exact = timoshenko(p);
    let error = (delta - exact) / exact;
    let tol = cantilever_tolerance();
    assert!(
        error.abs() < tol,
        "delta {delta}, Timoshenko {exact}, error {error:e}, tolerance {tol}"
    );
    // a displacement method errs on the stiff side
    assert!(delta < exact * 1.002, "{delta} {exact}");
    eprintln!(
        "cantilever: delta {delta:e}, Timoshenko {exact:e}, error {error:e}, tolerance {tol:e}"
    );
    // linear: one Newton iteration per step
    assert!(solution.step_records.iter().all(|r| r.iterations == 1));
    // the clamp carries the tip force
    let r = solution.step_records.last().unwrap().reactions[0];
    assert!(
        (r[2] - p).abs() < 1e-9 * p && r[0].abs() < 1e-9 * p && r[1].abs() < 1e-9 * p,
        "{r:?}"
    );
    // reactions.csv has the z column in 3D
    let csv = reactions_csv(&solution);
    assert!(
        csv.starts_with("step,load_factor,clamp_x,clamp_y,clamp_z\n"),
        "{csv}"
    );
    assert_eq!(csv.lines().nth(1).unwrap().split(',').count(), 5);
}

/// With finite kinematics Newton converges quadratically, and at a small
/// load the tip moves as with small kinematics.
#[test]
fn cantilever_with_finite_kinematics_converges() {
    let p = 0.01;
    let (small, centre) = cantilever(Kinematics::Small, p);
    let (finite, _) = cantilever(Kinematics::Finite, p);
    let opts = SolveOptions {
        steps: 2,
        ..SolveOptions::default()
    };
    let s = solver::solve_model(&small, &opts).unwrap();
    let f = solver::solve_model(&finite, &opts).unwrap();
    let (ds, df) = (s.displacement(centre)[2], f.displacement(centre)[2]);
    assert!(((df - ds) / ds).abs() < 0.01, "small {ds}, finite {df}");
    for r in &f.step_records {
        assert!(r.iterations <= 6, "{:?}", r.residuals);
        let last = r.residuals.len() - 1;
        assert!(
            r.residuals[last] < 1e-6 * r.residuals[0],
            "{:?}",
            r.residuals
        );
    }
    assert!(f.strain_energy > 0.0);
}

#[test]
fn vtu_of_a_3d_solution_has_3d_cells_and_six_stresses() {
    let (block, nodes) = patch_nodes();
    let mut elements = vec![Element::Hex8(hexes(&block)[0])];
    elements.extend(kuhn(&nodes, hexes(&block)[7]));
    let mut mesh = Mesh::<3>::new();
    mesh.add_body("m", material(0.3, Kinematics::Small), &nodes, &elements)
        .unwrap();
    // every node prescribed (nodes of no element too)
    let mut model = patch_model(mesh);
    model.prescribed = model
        .mesh
        .node_ids()
        .flat_map(|n| {
            let u = linear_field(model.mesh.node_ref(n));
            (0..3).map(move |c| Prescribed {
                dof: DofId::in_dim::<3>(n, c),
                value: u[c],
                amplitude: None,
            })
        })
        .collect();
    let solution = solver::solve_model(&model, &SolveOptions::default()).unwrap();
    let vtu = vtu_string(&solution, &solution.final_state).unwrap();
    let types = vtu.split("Name=\"types\"").nth(1).unwrap();
    let types = types.split('>').nth(1).unwrap().split('<').next().unwrap();
    let types: Vec<&str> = types.split_whitespace().collect();
    assert_eq!(types, ["12", "10", "10", "10", "10", "10", "10"]);
    assert!(vtu.contains("Name=\"cauchy_stress\" NumberOfComponents=\"6\""));
    assert!(vtu.contains("Name=\"pk2_stress\" NumberOfComponents=\"6\""));
    assert!(vtu.contains("Name=\"displacement\" NumberOfComponents=\"3\""));
    // a node's z and its displacement's z are written
    let n = model.mesh.node_count() - 1;
    let x = model.mesh.nodes_ref[n];
    let u = solution.displacement(NodeId::new(n));
    assert!(vtu.contains(&format!("{:e}", x[2])));
    assert!(vtu.contains(&format!("{:e}", u[2])));
}

#[test]
fn a_3d_model_refuses_a_pair_sharing_nodes_and_nu_one_half_and_2d_elements() {
    let (model, _) = cantilever(Kinematics::Small, 0.01);
    // a 2D pair in a 3D model does not compile (its facets are faces); a
    // pair of faces whose surfaces share a node is refused
    let mut with_contact = model.clone();
    let face = solver::mesh::volume::Face::Tri3([0, 1, 2].map(NodeId::new));
    with_contact.contacts.push(ContactPair {
        name: "c".into(),
        slave: vec![face],
        master: vec![face],
        formulation: Formulation::SlaveNormal,
        mode: ContactMode::Unilateral,
        friction: 0.0,
        gauss_points: None,
        integration: Integration::Gauss,
        multipliers: solver::model::Multipliers::Standard,
    });
    let err = solver::solve_model(&with_contact, &SolveOptions::default()).unwrap_err();
    assert!(
        matches!(
            &err,
            SolverError::Model(ModelError::Contact { pair, message })
                if pair == "c" && message == "the slave and the master surface share a node"
        ),
        "{err:?}"
    );
    let mut incompressible = model.clone();
    incompressible.mesh.bodies[0].material.poisson = 0.5;
    let err = solver::solve_model(&incompressible, &SolveOptions::default()).unwrap_err();
    assert!(
        matches!(&err, SolverError::Model(ModelError::Material { body, .. }) if body == "beam"),
        "{err:?}"
    );
    // a quadrilateral in a 3D mesh, a hexahedron in a 2D one
    let mut mesh = Mesh::<3>::new();
    let err = mesh
        .add_body(
            "q",
            material(0.3, Kinematics::Small),
            &[[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            &[[0, 1, 2, 3]],
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::WrongDimension {
                kind: ElementKind::Quad4,
                dim: 3,
                ..
            }
        ),
        "{err:?}"
    );
    let mut mesh = Mesh::new();
    let err = mesh
        .add_body(
            "h",
            material(0.3, Kinematics::Small),
            &[[0.0, 0.0]; 8],
            &[[0, 1, 2, 3, 4, 5, 6, 7]],
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::WrongDimension {
                kind: ElementKind::Hex8,
                dim: 2,
                ..
            }
        ),
        "{err}"
    );
    assert!(mesh.nodes_ref.is_empty());
}
