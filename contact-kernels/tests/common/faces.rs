//! The face configurations the C comparison and the lane tests share: per
//! formulation of 3D faces, the verifier's face families
//! (`gapsim_families::faces::faces` for its pair of kinds) and degenerate,
//! folded, outside, non-finite, unprojectable, out-of-reach and extreme
//! input built around the pair's worked example.

use contact_kernels::Formulation;
use gapsim_families::faces::{FaceKind, faces};

/// Every formulation of faces: the formulation, its C identifier, the slave
/// and the master kind (the C driver's order).
pub const FACES: [(Formulation, &str, FaceKind, FaceKind); 8] = [
    (
        Formulation::Tri3SlaveNormal,
        "tri3_slave_normal",
        FaceKind::Tri3,
        FaceKind::Tri3,
    ),
    (
        Formulation::Tri3ClosestPoint,
        "tri3_closest_point",
        FaceKind::Tri3,
        FaceKind::Tri3,
    ),
    (
        Formulation::Quad4SlaveNormal,
        "quad4_slave_normal",
        FaceKind::Quad4,
        FaceKind::Quad4,
    ),
    (
        Formulation::Quad4ClosestPoint,
        "quad4_closest_point",
        FaceKind::Quad4,
        FaceKind::Quad4,
    ),
    (
        Formulation::Tri3Quad4SlaveNormal,
        "tri3_quad4_slave_normal",
        FaceKind::Tri3,
        FaceKind::Quad4,
    ),
    (
        Formulation::Tri3Quad4ClosestPoint,
        "tri3_quad4_closest_point",
        FaceKind::Tri3,
        FaceKind::Quad4,
    ),
    (
        Formulation::Quad4Tri3SlaveNormal,
        "quad4_tri3_slave_normal",
        FaceKind::Quad4,
        FaceKind::Tri3,
    ),
    (
        Formulation::Quad4Tri3ClosestPoint,
        "quad4_tri3_closest_point",
        FaceKind::Quad4,
        FaceKind::Tri3,
    ),
];

/// One face configuration: its label, `q` (slave nodes then master nodes,
/// three coordinates each) and `xi_s`.
pub struct FaceConfig {
    /// Family and index, or the kind of special input.
    pub label: String,
    /// The coordinates.
    pub q: Vec<f64>,
    /// The slave point.
    pub xi_s: [f64; 2],
}

/// A flat face of `kind` in a plane: its nodes `origin + a e1 + b e2` at
/// the kind's reference corners (tri3: (0,0), (1,0), (0,1); quad4: the
/// corners of [-1, 1]^2), counter-clockwise about `e1 x e2`.
fn flat(kind: FaceKind, origin: [f64; 3], e1: [f64; 3], e2: [f64; 3]) -> Vec<f64> {
    let corners: &[[f64; 2]] = match kind {
        FaceKind::Tri3 => &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        FaceKind::Quad4 => &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
    };
    corners
        .iter()
        .flat_map(|[a, b]| (0..3).map(move |k| origin[k] + a * e1[k] + b * e2[k]))
        .collect()
}

/// The configurations of a slave face of kind `s` on a master of kind `m`:
/// the verifier's families, then the special input (module docs).
pub fn face_configurations(s: FaceKind, m: FaceKind) -> Vec<FaceConfig> {
    let families = faces(s, m);
    let worked = families[0].q.clone();
    assert_eq!(families[0].label, "worked");
    let worked_xi = [families[0].params[0], families[0].params[1]];
    let mut out: Vec<FaceConfig> = families
        .into_iter()
        .map(|c| FaceConfig {
            label: format!("verifier {}", c.label),
            q: c.q,
            xi_s: [c.params[0], c.params[1]],
        })
        .collect();
    let (ns, n) = (s.nodes(), 3 * (s.nodes() + m.nodes()));
    let mut push = |label: &str, q: Vec<f64>, xi_s: [f64; 2]| {
        assert_eq!(q.len(), n);
        out.push(FaceConfig {
            label: label.to_owned(),
            q,
            xi_s,
        })
    };
    let with = |changes: &[(usize, f64)]| {
        let mut q = worked.clone();
        for &(i, v) in changes {
            q[i] = v;
        }
        q
    };
    // Non-finite input: coordinates of both faces, each component of xi_s.
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for i in [0, 3 * ns - 1, 3 * ns, n - 1] {
            push("non-finite input", with(&[(i, bad)]), worked_xi);
        }
        push("non-finite input", worked.clone(), [bad, worked_xi[1]]);
        push("non-finite input", worked.clone(), [worked_xi[0], bad]);
    }
    // The slave point just outside its face, and on its edges and corners.
    let (outside, edges): (&[[f64; 2]], &[[f64; 2]]) = match s {
        FaceKind::Tri3 => (
            &[[-1e-12, 0.3], [0.3, -0.1], [0.6, 0.5], [0.5, 0.5 + 1e-12]],
            &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5]],
        ),
        FaceKind::Quad4 => (
            &[[1.0 + 1e-12, 0.0], [0.0, -1.5], [-1.2, 1.2]],
            &[[1.0, 1.0], [-1.0, 1.0], [1.0, -0.3], [0.0, -1.0]],
        ),
    };
    for &xi in outside {
        push("slave point outside", worked.clone(), xi);
    }
    for &xi in edges {
        push("slave point on the boundary", worked.clone(), xi);
    }
    // Degenerate faces: a node on the first (corner 0 vanishes), and all
    // nodes on a line.
    for (label, first, nodes) in [
        ("degenerate slave", 0, ns),
        ("degenerate master", ns, m.nodes()),
    ] {
        let node = |q: &[f64], a: usize, k: usize| q[3 * (first + a) + k];
        let coincident: Vec<(usize, f64)> = (0..3)
            .map(|k| (3 * (first + 1) + k, node(&worked, 0, k)))
            .collect();
        push(label, with(&coincident), worked_xi);
        let line: Vec<(usize, f64)> = (2..nodes)
            .flat_map(|a| {
                let t = a as f64 - 0.5;
                (0..3).map(move |k| (a, k, t))
            })
            .map(|(a, k, t)| {
                let (p0, p1) = (node(&worked, 0, k), node(&worked, 1, k));
                (3 * (first + a) + k, p0 + t * (p1 - p0))
            })
            .collect();
        push(label, with(&line), worked_xi);
        // Nearly degenerate: a tri3's third node, a quad4's last, 1e-6 of
        // the face off the line through the first two.
        let (a, p0, p1) = (nodes - 1, 0, 1);
        let near: Vec<(usize, f64)> = (0..3)
            .map(|k| {
                let (x0, x1) = (node(&worked, p0, k), node(&worked, p1, k));
                let off = if k == 2 { 1e-6 } else { 0.0 };
                (3 * (first + a) + k, 0.5 * (x0 + x1) + off)
            })
            .collect();
        push(label, with(&near), worked_xi);
    }
    // Folded quad4 faces: two nodes swapped (a bow tie), a node pulled
    // across the diagonal of its neighbours (a dart), onto the opposite
    // node and beyond it.
    for (label, first, kind) in [("folded slave", 0, s), ("folded master", ns, m)] {
        if kind != FaceKind::Quad4 {
            continue;
        }
        let at = |a: usize, k: usize| 3 * (first + a) + k;
        let node = |a: usize, k: usize| worked[at(a, k)];
        let swap: Vec<(usize, f64)> = (0..3)
            .flat_map(|k| [(at(2, k), node(3, k)), (at(3, k), node(2, k))])
            .collect();
        push(label, with(&swap), worked_xi);
        for t in [0.3, 0.5, 0.7] {
            // Node 3 moved the fraction 2t of the way to node 1: past the
            // diagonal from node 2 to node 4 (a dart) at 2t = 0.6, onto
            // node 1 (degenerate) at 2t = 1, beyond it at 2t = 1.4.
            let dart: Vec<(usize, f64)> = (0..3)
                .map(|k| (at(2, k), node(2, k) + t * 2.0 * (node(0, k) - node(2, k))))
                .collect();
            push(label, with(&dart), worked_xi);
        }
    }
    // No projection (slave-normal): the master face contains the slave's
    // normal direction, so det A = 0 exactly.
    let slave_flat = match s {
        FaceKind::Tri3 => flat(s, [0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        FaceKind::Quad4 => flat(s, [0.0; 3], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0]),
    };
    for e2 in [[0.0, 0.0, 1.0], [0.0, 1e-13, 1.0]] {
        let mut q = slave_flat.clone();
        q.extend(flat(m, [0.2, 0.1, 0.5], [0.0, 1.0, 0.0], e2));
        push("master along the slave normal", q, worked_xi);
    }
    // Projections out of reach: the master moved far along the slave.
    for shift in [1e5, 1e7, 1e12] {
        let q: Vec<f64> = (0..n)
            .map(|i| {
                let master_x = i >= 3 * ns && i % 3 == 0;
                worked[i] + if master_x { shift } else { 0.0 }
            })
            .collect();
        push("master far along the slave", q, worked_xi);
    }
    // Scales where squares and their reciprocals underflow or overflow.
    for e in (-170..=-90).chain(90..=170).step_by(10) {
        let scale = 10f64.powi(e);
        push(
            "extreme scale",
            worked.iter().map(|v| v * scale).collect(),
            worked_xi,
        );
    }
    out
}
