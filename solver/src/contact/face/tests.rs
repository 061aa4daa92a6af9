//! The 3D contact element on two stacked hexahedral blocks with
//! non-matching faces: weights, gaps, pairing against the scan, the
//! element's residual and tangent against finite differences of its
//! potential, the frozen expansion and the active set.

use contact_kernels::{ApproxType, Formulation};
use nalgebra::{DMatrix, DVector};

use crate::contact::{ContactShare, ContactSpace, assemble_contact};
use crate::element::material::{Kinematics, Material, PlaneModel};
use crate::ids::{ContactPointIndex, MasterFaceIndex, NodeId};
use crate::mesh::Mesh;
use crate::mesh::volume::Face;
use crate::mesh::{Block, Side};
use crate::model::{ContactMode, ContactPair, Integration};
use crate::system::{DofMap, System};

use crate::contact::term::{GapTerm, WeightedPoint};
use crate::contact::{FaceEval, FaceLayout, KernelCounts, Taylor};

const MATERIAL: Material = Material {
    young: 200.0,
    poisson: 0.3,
    model: PlaneModel::PlaneStrain,
    kinematics: Kinematics::Small,
};

/// A base `[0, 2]^2 x [0, 1]` of 2 x 2 x 1 hexahedra and a cap
/// `[0.3, 1.7]^2 x [1 + gap, 1.5 + gap]` of 3 x 3 x 1 above it; the cap's
/// bottom faces (split into triangles when `tri_slave`) are the slave
/// faces, the base's top faces the master faces.
fn stacked(gap: f64, tri_slave: bool, reading: Formulation) -> (Mesh<3>, ContactPair<3>) {
    stacked_on(2, gap, tri_slave, reading)
}

/// [`stacked`] on a base of `n x n x 1` hexahedra.
fn stacked_on(
    n: usize,
    gap: f64,
    tri_slave: bool,
    reading: Formulation,
) -> (Mesh<3>, ContactPair<3>) {
    let mut mesh = Mesh::<3>::new();
    let base = Block {
        origin: [0.0, 0.0, 0.0],
        size: [2.0, 2.0, 1.0],
        cells: [n, n, 1],
    };
    let cap = Block {
        origin: [0.3, 0.3, 1.0 + gap],
        size: [1.4, 1.4, 0.5],
        cells: [3, 3, 1],
    };
    let b = mesh.add_block("base", MATERIAL, base).unwrap();
    let c = mesh.add_block("cap", MATERIAL, cap).unwrap();
    let global = |body: usize, f: Face| {
        let start = mesh.bodies[body].nodes.start;
        f.map_nodes(|n| NodeId::new(start + n))
    };
    let master = base
        .side(Side::Top)
        .unwrap()
        .into_iter()
        .map(|f| global(b, f))
        .collect();
    let mut slave: Vec<Face<NodeId>> = cap
        .side(Side::Bottom)
        .unwrap()
        .into_iter()
        .map(|f| global(c, f))
        .collect();
    if tri_slave {
        slave = slave
            .into_iter()
            .flat_map(|f| match f {
                Face::Quad4([a, b, c, d]) => [Face::Tri3([a, b, c]), Face::Tri3([a, c, d])],
                Face::Tri3(_) => unreachable!("a block's sides are quad4"),
            })
            .collect();
    }
    let pair = ContactPair {
        name: "cap-on-base".to_owned(),
        slave,
        master,
        formulation: reading,
        mode: ContactMode::Unilateral,
        friction: 0.0,
        gauss_points: None,
        integration: Integration::Gauss,
        multipliers: crate::model::Multipliers::Standard,
    };
    (mesh, pair)
}

/// A smooth displacement field that tilts and warps both surfaces a
/// little (the cap's nodes more than the base's).
fn warp(mesh: &Mesh<3>, scale: f64) -> Vec<f64> {
    let mut u = vec![0.0; 3 * mesh.node_count()];
    for n in mesh.node_ids() {
        let x = mesh.node_ref(n);
        let s = if x[2] > 1.0 { 1.0 } else { 0.4 };
        let d = [
            0.03 * (1.3 * x[1] + 0.4).sin() + 0.01 * x[2],
            -0.02 * (0.9 * x[0]).cos() + 0.015 * x[0] * x[1],
            0.02 * (1.1 * x[0] + 0.7 * x[1]).sin() - 0.01 * x[0] * x[0],
        ];
        for k in 0..3 {
            u[3 * n.index() + k] = scale * s * d[k];
        }
    }
    u
}

#[test]
fn weights_add_up_to_the_slave_area_and_flat_gaps_are_the_offset() {
    for tri in [false, true] {
        for reading in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
            let (mesh, pair) = stacked(0.05, tri, reading);
            let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
            let per_face = if tri { 3 } else { 4 };
            assert_eq!(layout.points.len(), pair.slave.len() * per_face);
            let area: f64 = layout.points.iter().map(|p| p.weight_ref()).sum();
            assert!((area - 1.96).abs() < 1e-13, "{area}");
            // one multiplier per cap bottom node (4 x 4)
            assert_eq!(layout.multipliers.len(), 16);
            let u = vec![0.0; 3 * mesh.node_count()];
            let (pairing, _) = layout.initial_pairing(&mesh, &u).unwrap();
            assert!(pairing.iter().all(Option::is_some));
            let (evals, counts) = layout
                .evaluate_all(&mesh, &u, &pairing, ApproxType::Type6)
                .unwrap();
            assert_eq!(counts.evaluate as usize, layout.points.len());
            for e in evals.iter().map(|e| e.clone().unwrap()) {
                assert!((e.gap - 0.05).abs() < 1e-14, "{}", e.gap);
            }
        }
    }
}

#[test]
fn the_index_pairs_as_the_scan_of_every_master_face() {
    for tri in [false, true] {
        for reading in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
            let (mesh, pair) = stacked(0.02, tri, reading);
            let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
            for scale in [0.0, 1.0, 3.0] {
                let u = warp(&mesh, scale);
                let (by_index, _) = layout.initial_pairing(&mesh, &u).unwrap();
                let (by_scan, _) = layout.pairing_by_scan(&mesh, &u).unwrap();
                assert_eq!(by_index, by_scan, "tri {tri}, {reading}, scale {scale}");
                assert!(by_index.iter().all(Option::is_some));
            }
        }
    }
    // the cap moved off the base: points beyond the base's edge are unpaired
    let (mesh, pair) = stacked(0.02, false, Formulation::SlaveNormal);
    let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
    let mut u = vec![0.0; 3 * mesh.node_count()];
    for n in mesh.node_ids().filter(|&n| mesh.node_ref(n)[2] > 1.0) {
        u[3 * n.index()] = 1.0;
    }
    let (by_index, _) = layout.initial_pairing(&mesh, &u).unwrap();
    let (by_scan, _) = layout.pairing_by_scan(&mesh, &u).unwrap();
    assert_eq!(by_index, by_scan);
    let paired = by_index.iter().filter(|p| p.is_some()).count();
    assert!(paired > 0 && paired < by_index.len(), "{paired}");
}

/// A point past the master's edge projects into no face. The growing ball
/// would try every master face for it; under slave-normal the query along
/// its line (pairing.rs, module docs) tries a few, and the pairing is the
/// scan's either way.
#[test]
fn a_point_past_the_edge_tries_a_few_faces_under_slave_normal() {
    for tri in [false, true] {
        for reading in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
            let (mesh, pair) = stacked_on(24, 0.02, tri, reading);
            let n_faces = pair.master.len();
            let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
            // the cap slid past the base's edge x = 2 by half its width,
            // and tilted a little
            let mut u = warp(&mesh, 1.0);
            for n in mesh.node_ids().filter(|&n| mesh.node_ref(n)[2] > 1.0) {
                u[3 * n.index()] += 1.0;
            }
            let (by_index, counts) = layout.initial_pairing(&mesh, &u).unwrap();
            let (by_scan, scan) = layout.pairing_by_scan(&mesh, &u).unwrap();
            assert_eq!(by_index, by_scan, "tri {tri}, {reading}");
            let unpaired = by_index.iter().filter(|p| p.is_none()).count();
            assert!(unpaired > 0 && unpaired < by_index.len(), "{unpaired}");
            assert_eq!(scan.project as usize, by_index.len() * n_faces);
            // a third of the points are unpaired: the ball's growth to the
            // whole pair would cost them n_faces = 576 projections each
            let per_point = counts.project as f64 / by_index.len() as f64;
            if reading == Formulation::SlaveNormal {
                assert!(per_point < 20.0, "tri {tri}: {per_point} per point");
            }
        }
    }
}

/// The potential `Pi_c = sum w J0 lambda g` of `layout`'s points on the
/// pairing `pairing`, and its assembled residual and tangent (every
/// multiplier active).
fn potential(
    mesh: &Mesh<3>,
    layout: &FaceLayout,
    pairing: &[Option<MasterFaceIndex>],
    u: &[f64],
    lambda: &[f64],
) -> (f64, DVector<f64>, DMatrix<f64>) {
    let (evals, _) = layout
        .evaluate_paired(mesh, u, pairing, ApproxType::Type6)
        .unwrap();
    let mut pi = 0.0;
    for (pt, e) in layout.points.iter().zip(&evals) {
        if let Some(e) = e {
            pi += pt.weight_ref() * pt.multiplier_shape().lambda(lambda) * e.gap();
        }
    }
    let n = u.len() + lambda.len();
    let dofs = DofMap::all_free(u.len(), lambda.len());
    let mut sys = System::new(n);
    let active = vec![true; lambda.len()];
    assemble_contact(&layout.points, &evals, lambda, &active, &dofs, &mut sys);
    let mut k = DMatrix::zeros(n, n);
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        k[(r as usize, c as usize)] += v;
    }
    (pi, DVector::from_vec(sys.residual.clone()), k)
}

#[test]
fn residual_and_tangent_are_the_derivatives_of_the_potential() {
    use crate::model::Multipliers::{Dual, Standard};
    for (tri, reading, basis) in [
        (false, Formulation::SlaveNormal, Standard),
        (true, Formulation::ClosestPoint, Standard),
        (true, Formulation::SlaveNormal, Standard),
        (false, Formulation::SlaveNormal, Dual),
        (true, Formulation::ClosestPoint, Dual),
    ] {
        let (mesh, mut pair) = stacked(0.02, tri, reading);
        pair.multipliers = basis;
        let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
        let u0 = warp(&mesh, 1.0);
        let (pairing, _) = layout.initial_pairing(&mesh, &u0).unwrap();
        let lambda: Vec<f64> = (0..layout.multipliers.len())
            .map(|m| -1.0 - 0.3 * (m as f64 * 0.7).sin())
            .collect();
        let (_, r, k) = potential(&mesh, &layout, &pairing, &u0, &lambda);
        let nu = u0.len();
        let h = 1e-6;
        let mut worst_r: f64 = 0.0;
        let mut worst_k: f64 = 0.0;
        let scale_r = r.amax().max(1e-3);
        let scale_k = k.amax().max(1e-3);
        for j in 0..nu + lambda.len() {
            let shifted = |s: f64| {
                let (mut u, mut l) = (u0.clone(), lambda.clone());
                if j < nu {
                    u[j] += s;
                } else {
                    l[j - nu] += s;
                }
                potential(&mesh, &layout, &pairing, &u, &l)
            };
            let (pp, rp, _) = shifted(h);
            let (pm, rm, _) = shifted(-h);
            worst_r = worst_r.max(((pp - pm) / (2.0 * h) - r[j]).abs() / scale_r);
            let column = (rp - rm) / (2.0 * h);
            for i in 0..nu + lambda.len() {
                // the inactive part of the system aside, K is the Jacobian
                // of r; the multiplier-multiplier block is zero
                worst_k = worst_k.max((column[i] - k[(i, j)]).abs() / scale_k);
            }
        }
        assert!(
            worst_r < 1e-7,
            "tri {tri} {reading} {basis:?}: residual {worst_r:e}"
        );
        assert!(
            worst_k < 1e-6,
            "tri {tri} {reading} {basis:?}: tangent {worst_k:e}"
        );
    }
}

/// A slave face without area has no dual basis: the error names the rule
/// point, never a NaN coefficient.
#[test]
fn a_degenerate_slave_face_has_no_dual_basis() {
    use super::layout::dual_coefficients;
    use crate::contact::DualBasisError;
    // collinear corners: zero area element everywhere
    let x = Face::Tri3([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
    match dual_coefficients(&x) {
        Err(DualBasisError::AreaElement {
            gauss: 0,
            area_element,
        }) => {
            assert_eq!(area_element, 0.0)
        }
        other => panic!("expected the area element's error, got {other:?}"),
    }
    let x = Face::Tri3([[0.0, 0.0, 0.0], [1.0, 0.0, f64::NAN], [0.0, 1.0, 0.0]]);
    assert!(matches!(
        dual_coefficients(&x),
        Err(DualBasisError::AreaElement { gauss: 0, .. })
    ));
}

/// The dual basis of a slave face is biorthogonal to its shape functions,
/// `int psi_a N_b = delta_ab int N_b` (checked with another exact rule
/// than the one that built it: a tri3's 6 points, a planar quad4's 6 x 6),
/// adds up to 1 (constants are in the multiplier space, so a uniform
/// pressure is one), and is `4 N_a - 1` on a tri3.
#[test]
fn the_dual_basis_is_biorthogonal_to_the_slave_shape_functions() {
    use super::layout::dual_coefficients;
    use crate::contact::face_rules::face_rule;
    use crate::mesh::face_shape::FaceShape;
    let faces = [
        Face::Tri3([[0.0, 0.0, 0.0], [1.3, 0.2, 0.1], [0.2, 0.9, -0.2]]),
        // planar (z = 0.1 x - 0.2 y), not a parallelogram
        Face::Quad4([
            [0.0, 0.0, 0.0],
            [1.2, 0.1, 0.1],
            [1.0, 0.9, -0.08],
            [-0.1, 1.1, -0.23],
        ]),
    ];
    for x in faces {
        let n = x.nodes().len();
        let a = dual_coefficients(&x).unwrap();
        if n == 3 {
            for (r, row) in a.iter().enumerate().take(3) {
                for (c, v) in row.iter().enumerate().take(3) {
                    let want = if r == c { 3.0 } else { -1.0 };
                    assert!((v - want).abs() < 1e-12, "A[{r}][{c}] = {v}");
                }
            }
        }
        let rule = face_rule(x.kind(), 6).unwrap();
        let mut product = [[0.0; 4]; 4];
        let mut integral = [0.0; 4];
        for &(xi, w) in &rule.points {
            let j0 = x.area_element(xi);
            let s = FaceShape::at(x.kind(), xi);
            let psi: Vec<f64> = (0..n)
                .map(|r| (0..n).map(|c| a[r][c] * s.n[c]).sum())
                .collect();
            assert!((psi.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            for r in 0..n {
                integral[r] += w * j0 * s.n[r];
                for b in 0..n {
                    product[r][b] += w * j0 * psi[r] * s.n[b];
                }
            }
        }
        for r in 0..n {
            for b in 0..n {
                let want = if r == b { integral[b] } else { 0.0 };
                assert!(
                    (product[r][b] - want).abs() < 1e-12,
                    "{n} nodes: int psi_{r} N_{b} = {} (want {want})",
                    product[r][b]
                );
            }
        }
    }
}

#[test]
fn the_frozen_expansion_in_3d_is_exact_at_its_point_with_its_own_gradient() {
    let (mesh, pair) = stacked(0.02, true, Formulation::SlaveNormal);
    let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
    let u0 = warp(&mesh, 1.0);
    let (pairing, _) = layout.initial_pairing(&mesh, &u0).unwrap();
    let i = ContactPointIndex::new(5);
    let m = pairing[5].unwrap();
    for ty in [ApproxType::Type1, ApproxType::Type3, ApproxType::Type6] {
        let at = layout
            .evaluate_on(&mesh, &u0, i, m, ty, &mut KernelCounts::default())
            .unwrap();
        let t: Taylor<FaceEval, 24> = Taylor::at(at.clone(), &u0);
        assert_eq!(t.expand(&u0).gap, at.gap);
        let u1 = warp(&mesh, 1.3);
        let e = t.expand(&u1);
        let h = 1e-6;
        for k in 0..24 {
            let Some(d) = e.dof(k) else {
                assert_eq!(e.grad[k], 0.0);
                continue;
            };
            let (mut up, mut um) = (u1.clone(), u1.clone());
            up[d.index()] += h;
            um[d.index()] -= h;
            let fd = (t.expand(&up).gap - t.expand(&um).gap) / (2.0 * h);
            assert!(
                (fd - e.grad[k]).abs() < 1e-8,
                "{ty:?} {k}: {fd} {}",
                e.grad[k]
            );
        }
    }
}

#[test]
fn penetrating_nodes_are_active_and_open_ones_are_not() {
    for (gap, expect) in [(-0.01, true), (0.01, false)] {
        let (mesh, pair) = stacked(gap, false, Formulation::SlaveNormal);
        let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
        let u = vec![0.0; 3 * mesh.node_count()];
        let (pairing, _) = layout.initial_pairing(&mesh, &u).unwrap();
        let (evals, _) = layout
            .evaluate_all(&mesh, &u, &pairing, ApproxType::Type6)
            .unwrap();
        let view = layout.active_set_view();
        let lambda = vec![0.0; layout.multipliers.len()];
        let active = view.active_multipliers(&evals, &lambda, 1.0);
        assert!(active.iter().all(|&a| a == expect), "gap {gap}");
    }
}

#[test]
fn a_gauss_count_without_a_rule_and_a_segment_reading_are_refused() {
    let (mesh, mut pair) = stacked(0.0, true, Formulation::SlaveNormal);
    pair.gauss_points = Some(2);
    let err = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap_err();
    assert!(err.to_string().contains("tri3"), "{err}");
    pair.gauss_points = None;
    let err = FaceLayout::new(
        &mesh,
        std::slice::from_ref(&pair),
        Some(Formulation::Tri3SlaveNormal),
    )
    .unwrap_err();
    assert!(err.to_string().contains("not a reading"), "{err}");
}

/// The contact patch test of the element: a uniform pressure on the cap's
/// flat bottom loads the base's top nodes with the consistent nodal forces
/// `p int N_b dA` over the overlap `[0.3, 1.7]^2`, which are exact with
/// segmented integration and not with the Gauss rule on the (non-matching)
/// slave faces. With unit spacing the base's hat functions integrate to
/// `a(x) a(y)`, `a = 0.91` at the middle node and `0.245` at an edge node.
#[test]
fn segmented_integration_gives_the_exact_master_forces_of_a_uniform_pressure() {
    let a = |k: usize| if k == 1 { 0.91 } else { 0.245 };
    let mut gauss_error: f64 = 0.0;
    for tri in [false, true] {
        for integration in [Integration::Segmented, Integration::Gauss] {
            for reading in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
                let (mesh, mut pair) = stacked(0.0, tri, reading);
                pair.integration = integration;
                let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
                let area: f64 = layout.points.iter().map(|p| p.weight_ref()).sum();
                assert!((area - 1.96).abs() < 1e-12, "{area}");
                let u = vec![0.0; 3 * mesh.node_count()];
                let (pairing, _) = layout.initial_pairing(&mesh, &u).unwrap();
                let (evals, _) = layout
                    .evaluate_all(&mesh, &u, &pairing, ApproxType::Type6)
                    .unwrap();
                // the force on node dof d: sum w lambda dg/du_d with lambda = 1
                let mut force = vec![0.0; u.len()];
                for (pt, e) in layout.points.iter().zip(&evals) {
                    let e = e.as_ref().expect("every point is over the base");
                    for k in 0..24 {
                        if let Some(d) = e.dof(k) {
                            force[d.index()] += pt.weight_ref() * e.grad[k];
                        }
                    }
                }
                let mut worst: f64 = 0.0;
                for face in &pair.master {
                    for &n in face.nodes() {
                        let x = mesh.node_ref(n);
                        let exact = -a(x[0].round() as usize) * a(x[1].round() as usize);
                        let fz = force[3 * n.index() + 2];
                        worst = worst.max((fz - exact).abs());
                        assert!(force[3 * n.index()].abs() < 1e-12);
                    }
                }
                match integration {
                    Integration::Segmented => {
                        assert!(worst < 1e-12, "tri {tri} {reading}: {worst:e}")
                    }
                    Integration::Gauss => gauss_error = gauss_error.max(worst),
                }
            }
        }
    }
    // the Gauss rule on non-matching faces misses the master kinks
    eprintln!("plain Gauss: largest master nodal force error {gauss_error:e} (exact: 1.96 in all)");
    assert!(gauss_error > 1e-3, "{gauss_error:e}");
}

#[test]
fn segmented_integration_refuses_a_count_without_a_triangle_rule() {
    let (mesh, mut pair) = stacked(0.02, false, Formulation::SlaveNormal);
    pair.integration = Integration::Segmented;
    pair.gauss_points = Some(4);
    let err = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap_err();
    assert!(err.to_string().contains("1, 3 or 7"), "{err}");
}

#[test]
fn the_nodal_table_gives_each_slave_node_its_gap_pressure_and_area() {
    let (mesh, pair) = stacked(0.05, false, Formulation::SlaveNormal);
    let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
    let u = vec![0.0; 3 * mesh.node_count()];
    let lambda: Vec<f64> = (0..layout.multipliers.len()).map(|m| -(m as f64)).collect();
    let (rows, counts) = layout.nodal_table(&mesh, &u, &lambda).unwrap();
    assert_eq!(rows.len(), 16);
    assert!(counts.project > 0);
    let h = 1.4 / 3.0;
    let mut area = 0.0;
    for (m, r) in rows.iter().enumerate() {
        assert_eq!(r.node, layout.multipliers[m].node);
        assert_eq!(r.pressure, m as f64);
        assert!((r.gap.unwrap() - 0.05).abs() < 1e-14);
        let (face, nodes) = r.master.unwrap();
        assert!(nodes.nodes().len() == 4 && face.index() < 4);
        // a corner node carries a quarter face, an edge node half of two,
        // an inner node four quarters
        let x = r.x;
        let on_edge = |c: f64| (c - 0.3).abs() < 1e-12 || (c - 1.7).abs() < 1e-12;
        let expect = match (on_edge(x[0]), on_edge(x[1])) {
            (true, true) => h * h / 4.0,
            (true, false) | (false, true) => h * h / 2.0,
            (false, false) => h * h,
        };
        assert!((r.tributary_area - expect).abs() < 1e-13, "{x:?}");
        area += r.tributary_area;
    }
    assert!((area - 1.96).abs() < 1e-13);
    // off the base: no gap, never NaN
    let mut moved = u.clone();
    for n in mesh.node_ids().filter(|&n| mesh.node_ref(n)[2] > 1.0) {
        moved[3 * n.index()] = 5.0;
    }
    let (rows, _) = layout.nodal_table(&mesh, &moved, &lambda).unwrap();
    assert!(rows.iter().all(|r| r.gap.is_none() && r.master.is_none()));
}

/// The contact system with friction of `layout` at `(u, lambda)`: the
/// Type 6 gap and slip on `pairing`, the slips from `anchors`, the normal
/// and tangential active flags `active` (held fixed), assembled by the
/// layout (`assemble_contact` and the friction).
fn friction_system(
    mesh: &Mesh<3>,
    layout: &FaceLayout,
    pairing: &[Option<MasterFaceIndex>],
    anchors: &[Option<crate::contact::face::FaceAnchor>],
    u: &[f64],
    lambda: &[f64],
    active: &[bool],
) -> (DVector<f64>, DMatrix<f64>) {
    let (r, k, _) = friction_system_of(mesh, layout, (pairing, anchors), u, lambda, active, None);
    (r, k)
}

/// [`friction_system`], only `share`'s part of the element, and the
/// number of triplets it pushed.
fn friction_system_of(
    mesh: &Mesh<3>,
    layout: &FaceLayout,
    (pairing, anchors): (
        &[Option<MasterFaceIndex>],
        &[Option<crate::contact::face::FaceAnchor>],
    ),
    u: &[f64],
    lambda: &[f64],
    active: &[bool],
    share: Option<&ContactShare>,
) -> (DVector<f64>, DMatrix<f64>, usize) {
    let (mut evals, mut counts) = layout
        .evaluate_paired(mesh, u, pairing, ApproxType::Type6)
        .unwrap();
    layout
        .add_slips(mesh, u, &mut evals, anchors, ApproxType::Type6, &mut counts)
        .unwrap();
    let n = u.len() + lambda.len();
    let dofs = DofMap::all_free(u.len(), lambda.len());
    let mut sys = System::new(n);
    layout.assemble(&evals, lambda, active, &dofs, share, &mut sys);
    let mut k = DMatrix::zeros(n, n);
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        k[(r as usize, c as usize)] += v;
    }
    (DVector::from_vec(sys.residual.clone()), k, sys.vals.len())
}

/// Sixteen quad4 faces with friction 0.4 pressed and shifted over their
/// base: the mesh, the layout, the pairing, the anchors, `u`, the
/// multipliers (every other node sticking, the rest slipping) and the
/// active set (every multiplier).
#[allow(clippy::type_complexity)] // one test state
fn sliding_with_friction() -> (
    Mesh<3>,
    FaceLayout,
    Vec<Option<MasterFaceIndex>>,
    Vec<Option<crate::contact::face::FaceAnchor>>,
    Vec<f64>,
    Vec<f64>,
    Vec<bool>,
) {
    let (mesh, mut pair) = stacked(0.02, false, Formulation::SlaveNormal);
    pair.friction = 0.4;
    let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
    assert_eq!(layout.multiplier_count(), 16 * 3);
    // the anchors at a warped state, the iterate shifted from it
    let u0 = warp(&mesh, 1.0);
    let (pairing0, _) = layout.initial_pairing(&mesh, &u0).unwrap();
    let (evals0, _) = layout
        .evaluate_paired(&mesh, &u0, &pairing0, ApproxType::Type6)
        .unwrap();
    let anchors = layout.anchors(&mesh, &u0, &evals0);
    let mut u = u0.clone();
    for n in mesh.node_ids().filter(|&n| mesh.node_ref(n)[2] > 1.0) {
        u[3 * n.index()] += 0.01;
        u[3 * n.index() + 1] += 0.006;
    }
    let (pairing, _) = layout.initial_pairing(&mesh, &u).unwrap();
    let (mut evals, mut counts) = layout
        .evaluate_paired(&mesh, &u, &pairing, ApproxType::Type6)
        .unwrap();
    layout
        .add_slips(
            &mesh,
            &u,
            &mut evals,
            &anchors,
            ApproxType::Type6,
            &mut counts,
        )
        .unwrap();
    // pressed nodes; every other one sticks (its tangential multipliers
    // nearly cancel the trial slip), the rest slip (no tangential load)
    let normal = layout.multipliers.len();
    let mut lambda: Vec<f64> = (0..normal)
        .map(|m| -1.0 - 0.3 * (m as f64 * 0.7).sin())
        .collect();
    let (weight, slip) = layout.friction.nodal_slips(&layout.points, &evals);
    let c = layout.complementarity[0];
    for k in 0..layout.friction.normal.len() {
        for d in 0..2 {
            let trial = c * slip[2 * k + d] / weight[k];
            lambda.push(if k % 2 == 0 { -0.99 * trial } else { 0.0 });
        }
    }
    // every node in contact (the normal active set is not under test)
    let active = vec![true; lambda.len()];
    let states = layout.friction_states(&evals, &lambda, &active);
    let sticking = states
        .iter()
        .filter(|s| **s == crate::contact::friction::FrictionState::Stick)
        .count();
    assert_eq!(sticking, 8, "{states:?}");
    (mesh, layout, pairing, anchors, u, lambda, active)
}

#[test]
fn the_friction_tangent_is_the_jacobian_of_its_residual_in_stick_and_in_slip() {
    let (mesh, layout, pairing, anchors, u, lambda, active) = sliding_with_friction();
    let (_, k) = friction_system(&mesh, &layout, &pairing, &anchors, &u, &lambda, &active);
    let nu = u.len();
    let h = 1e-7;
    let scale = k.amax();
    let mut worst: f64 = 0.0;
    for j in 0..nu + lambda.len() {
        let shifted = |s: f64| {
            let (mut u, mut l) = (u.clone(), lambda.clone());
            if j < nu {
                u[j] += s;
            } else {
                l[j - nu] += s;
            }
            friction_system(&mesh, &layout, &pairing, &anchors, &u, &l, &active).0
        };
        let column = (shifted(h) - shifted(-h)) / (2.0 * h);
        for i in 0..nu + lambda.len() {
            worst = worst.max((column[i] - k[(i, j)]).abs() / scale);
        }
    }
    assert!(
        worst < 1e-6,
        "tangent against the residual's derivative: {worst:e}"
    );
}

/// The slip pass (each chunk's points of one formulation in one
/// `Slip::eval_batch`) gives every point the bits `Slip::eval` gives it
/// alone, on quad4 and on tri3 slave faces.
#[test]
fn the_batched_slip_pass_gives_each_point_the_bits_of_its_own_evaluation() {
    use contact_kernels::{Kernel, SlipOut};
    for tri_slave in [false, true] {
        let (mesh, mut pair) = stacked(0.02, tri_slave, Formulation::SlaveNormal);
        pair.friction = 0.4;
        let layout = FaceLayout::new(&mesh, std::slice::from_ref(&pair), None).unwrap();
        let u0 = warp(&mesh, 1.0);
        let (pairing0, _) = layout.initial_pairing(&mesh, &u0).unwrap();
        let (evals0, _) = layout
            .evaluate_paired(&mesh, &u0, &pairing0, ApproxType::Type6)
            .unwrap();
        let anchors = layout.anchors(&mesh, &u0, &evals0);
        let mut u = u0.clone();
        for n in mesh.node_ids().filter(|&n| mesh.node_ref(n)[2] > 1.0) {
            u[3 * n.index()] += 0.3;
            u[3 * n.index() + 1] -= 0.2;
        }
        for ty in [ApproxType::Type3, ApproxType::Type6] {
            let (pairing, _) = layout.initial_pairing(&mesh, &u).unwrap();
            let (mut evals, mut counts) = layout.evaluate_paired(&mesh, &u, &pairing, ty).unwrap();
            layout
                .add_slips(&mesh, &u, &mut evals, &anchors, ty, &mut counts)
                .unwrap();
            let (mut checked, mut moved) = (0, 0);
            for (k, (e, anchor)) in evals.iter().zip(&anchors).enumerate() {
                let (Some(e), Some(anchor)) = (e, anchor) else {
                    continue;
                };
                let probe = layout.probe(ContactPointIndex::new(k));
                let f = layout.formulation_of(&probe, e.master).unwrap();
                let slip = Kernel::new(f, ty).unwrap().slip().unwrap();
                let mut out = SlipOut::new(&slip);
                let xi_m0 = if anchor.master == e.master {
                    anchor.xi_m
                } else {
                    moved += 1;
                    layout.face_anchor_on(&mesh, &probe, anchor.master, anchor.xi_m, e.master)
                };
                let n = 3 * e.node_count;
                let q = FaceLayout::q(&mesh, &u, &e.nodes[..e.node_count]);
                slip.eval(&q[..n], probe.xi_s, xi_m0, &mut out).unwrap();
                let got = e.slip.as_ref().expect("a slip at every anchored point");
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&got.slip), bits(out.slip()), "point {k}");
                for c in 0..3 {
                    assert_eq!(bits(&got.grad[c].as_slice()[..n]), bits(out.grad(c)));
                    let h = out.hess(c).unwrap();
                    let mine = &got.hess.as_ref().unwrap()[c];
                    for r in 0..n {
                        for s in 0..n {
                            assert_eq!(mine[(r, s)].to_bits(), h[r * n + s].to_bits());
                        }
                    }
                }
                assert_eq!(got.frames, anchor.frames);
                checked += 1;
            }
            assert!(checked >= 16, "{checked} points checked");
            assert!(moved > 0, "some points crossed a master edge");
        }
    }
}

/// The shares of three MPI ranks (`ContactShare`: the multipliers by
/// their node's rank, here the node index modulo 3, rank 0 also the
/// friction) sum to the whole contact element, every entry pushed exactly
/// once: residual and tangent with friction, stick and slip.
#[test]
fn the_ranks_contact_shares_sum_to_the_whole_element() {
    let (mesh, layout, pairing, anchors, u, lambda, active) = sliding_with_friction();
    let system = |share: Option<&ContactShare>| {
        friction_system_of(
            &mesh,
            &layout,
            (&pairing, &anchors),
            &u,
            &lambda,
            &active,
            share,
        )
    };
    let (r, k, pushed) = system(None);
    let (mut r_sum, mut k_sum, mut pushed_sum) = (r.clone() * 0.0, k.clone() * 0.0, 0);
    let mut owned = vec![0; lambda.len()];
    for rank in 0..3 {
        let share = ContactShare {
            multipliers: layout
                .multipliers()
                .iter()
                .map(|m| m.node.index() % 3 == rank)
                .collect(),
            root: rank == 0,
        };
        for (m, o) in owned.iter_mut().enumerate() {
            *o += usize::from(share.multiplier(m));
        }
        let (r, k, pushed) = system(Some(&share));
        r_sum += r;
        k_sum += k;
        pushed_sum += pushed;
    }
    assert!(owned.iter().all(|&o| o == 1), "{owned:?}");
    assert_eq!(pushed_sum, pushed);
    assert!((r_sum - &r).amax() <= 1e-14 * r.amax(), "residual");
    assert!((k_sum - &k).amax() <= 1e-14 * k.amax(), "tangent");
}
