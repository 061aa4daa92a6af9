//! [`FaceLayout`]: the integration points, multipliers and master faces of
//! the 3D contact pairs of a model ([`ContactPair<3>`]), and the kernel each
//! (slave face, master face) pair of kinds takes.
//!
//! # The 3D contact element
//!
//! A pair's slave and master surfaces are lists of tri3 and quad4 faces
//! whose nodes run counter-clockwise seen from outside their bodies. Every
//! slave face of kind `K` carries the rule `gauss_points` gives on `K`
//! ([`face_rule`]: `n x n` Gauss–Legendre points on a quad4, 1, 3, 4, 6 or
//! 7 symmetric points on a tri3; defaults 2 x 2 and 3), integrated in the
//! **reference** configuration: a point `xi_s = (u, v)` with rule weight
//! `w` has
//!
//! ```text
//! w J0 = w |dX/du x dX/dv|(xi_s)
//! ```
//!
//! (`X` the slave face's reference coordinates), so the weights of a face
//! add up to its area (exactly on a flat face). Multipliers live at the
//! slave nodes, one per node however many slave faces share it,
//! `lambda(xi_s) = sum_a N_a(xi_s) l_a` with the slave face's shape
//! functions ([`crate::mesh::face_shape`]), and the element's potential is
//! `Pi_c = sum_points w J0 lambda g` as in 2D ([`super`]): the same
//! residual and tangent, assembled by
//! [`crate::contact::assemble_contact`].
//!
//! The gap `g` of a point paired with a master face is the kernel of the
//! pair's reading for the two faces' kinds ([`face_formulation`]:
//! `tri3-slave-normal`, `tri3-quad4-closest-point`, ...; docs/conventions.md,
//! "3D faces"), on the current coordinates of the slave face's nodes then
//! the master face's. Pairing is `face_pairing`'s.
//!
//! # Segmented integration
//!
//! With [`Integration::Segmented`] each slave face is clipped, in the
//! reference configuration, against every master face that faces it
//! (outward normals `t_1 x t_2` at the faces' centres against each other)
//! and whose box meets the slave face's box inflated by the slave face's
//! size plus its *reach*, each projected onto the slave face's plane ([`SlaveFace`],
//! `clip.rs`: Sutherland–Hodgman, triangulated); every triangle gets the
//! triangle rule of `gauss_points` (1, 3 or 7 points; default 7, degree
//! 5), mapped to the slave's `(u, v)`, with its weight in plane area as
//! `w J0` (exact on a flat slave face). The integrand's kinks where the
//! master shape functions change face are then integrated exactly: the
//! consistent master nodal forces of a uniform pressure are exact on
//! non-matching flat faces (the contact patch test, `face_tests`), where
//! the Gauss rule on the slave face is not. As in 2D the split is taken
//! once, so it is exact while the faces do not slide; a slave face that no
//! master face overlaps gets no points.
//!
//! The reach of a slave face is the largest `|g|` of its Gauss points
//! (the default rule) paired by the pairing's rule in the reference
//! configuration (0 where none pairs): a face apart from the master surface
//! at the start, such as the rim of a curved indenter, is clipped against
//! the faces its points will touch. Without it (the face's size alone) the
//! tetrahedral Hertz mesh at h = 0.07, whose slave faces are 0.046 in size,
//! gave no points to the faces from about r = 0.9 on, where the sphere
//! starts more than 0.04 above the block: their nodes had no tributary
//! area, 53 of the 99 slave nodes between r = 0.8 and 1.0 (inside the
//! contact radius 1.05) carried no pressure and their neighbours up to
//! 5.7 times p0 (docs/benchmarks.md, the 3D Hertz refinement).
//!
//! The active-set constant of a unilateral pair is `c = E / h`, the slave
//! body's Young's modulus over the mean slave face size `h = sqrt(area)`
//! (the 2D layout's `E / h` with `h` the mean segment length).
//!
//! Invariants: built once per solve and never changed; points pair by pair,
//! slave face by slave face, rule point by rule point; multipliers pair by
//! pair in the order their nodes first appear on the slave faces; every
//! point's `w J0` is finite and positive.

use std::collections::HashMap;

use contact_kernels::Formulation;

use crate::element::FaceKind;
use crate::ids::{ContactPointIndex, DofId, MultiplierIndex, NodeId, PairId};
use crate::mesh::Mesh;
use crate::mesh::face_shape::FaceShape;
use crate::mesh::volume::Face;
use crate::model::{ContactMode, ContactPair, Integration, Multipliers};

use crate::contact::MultiplierDof;
use crate::contact::active_set::ActiveSetView;
use crate::contact::clip::{SlaveFace, TriangleRule};
use crate::contact::face_index::{Aabb, FaceIndex};
use crate::contact::face_rules::{default_points, face_rule};
use crate::contact::friction::{Friction, FrictionView};
use crate::contact::layout_error::{DualBasisError, FaceLayoutError};
use crate::contact::space::ContactSpace;
use crate::contact::term::{MAX_POINT_MULTIPLIERS, MultiplierShape, WeightedPoint};

/// Static data of one slave integration point of a 3D pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePoint {
    /// Contact pair.
    pub pair: PairId,
    /// Slave face index within the pair.
    pub slave_face: usize,
    /// Rule point index within the face.
    pub gauss: usize,
    /// Parametric coordinates on the slave face.
    pub xi_s: [f64; 2],
    /// `w J0` (reference area weight).
    pub weight_ref: f64,
    /// The slave face's nodes.
    pub slave: Face<NodeId>,
    /// Global multiplier indices of the slave face's nodes (node order;
    /// a tri3 repeats its last one in the unused slot).
    pub multipliers: [MultiplierIndex; MAX_POINT_MULTIPLIERS],
    /// The multiplier basis at `xi_s`, in node order: the slave face's
    /// shape functions `N_a`, or with `multipliers = "dual"` its dual
    /// basis `psi_a` ([`dual_coefficients`]).
    pub basis: [f64; MAX_POINT_MULTIPLIERS],
}

impl WeightedPoint for FacePoint {
    fn weight_ref(&self) -> f64 {
        self.weight_ref
    }

    fn multiplier_shape(&self) -> MultiplierShape {
        MultiplierShape {
            multipliers: self.multipliers,
            shape: self.basis,
            count: self.slave.nodes().len(),
        }
    }
}

/// The dual basis of a slave face with reference coordinates `x_ref`:
/// `A = D M^-1`, with `M_ab = int N_a N_b` and `D = diag(int N_a)` over
/// the face (a tri3's 7-point rule, a quad4's 4 x 4: exact for the
/// products of its shape functions and area element), so that
/// `psi_a = sum_b A_ab N_b` satisfies `int psi_a N_b = delta_ab int N_b`.
/// On a flat tri3, `A = 4 I - 1` (`psi_a = 4 N_a - 1`). `Err` where the
/// area element is not finite and positive at a rule point, or `M` is not
/// invertible.
pub fn dual_coefficients(x_ref: &Face<[f64; 3]>) -> Result<[[f64; 4]; 4], DualBasisError> {
    let kind = x_ref.kind();
    let n = x_ref.nodes().len();
    let rule = face_rule(kind, if n == 3 { 7 } else { 4 })?;
    let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
    let mut d = vec![0.0; n];
    for (g, &(xi, w)) in rule.points.iter().enumerate() {
        let j0 = x_ref.area_element(xi);
        if !(j0.is_finite() && j0 > 0.0) {
            return Err(DualBasisError::AreaElement {
                gauss: g,
                area_element: j0,
            });
        }
        let s = FaceShape::at(kind, xi);
        for a in 0..n {
            d[a] += w * j0 * s.n[a];
            for b in 0..n {
                m[(a, b)] += w * j0 * s.n[a] * s.n[b];
            }
        }
    }
    let inv = m.try_inverse().ok_or(DualBasisError::SingularMass)?;
    let mut a = [[0.0; 4]; 4];
    for (r, row) in a.iter_mut().enumerate().take(n) {
        for (c, v) in row.iter_mut().enumerate().take(n) {
            *v = d[r] * inv[(r, c)];
        }
    }
    Ok(a)
}

/// The kernel of `reading` (`slave-normal` or `closest-point`) for a slave
/// face of kind `slave` on a master face of kind `master`: named
/// `<slave>-<reading>` when both are of one kind, `<slave>-<master>-<reading>`
/// otherwise (docs/conventions.md, "3D faces"). `None` for another reading.
pub fn face_formulation(
    reading: Formulation,
    slave: FaceKind,
    master: FaceKind,
) -> Option<Formulation> {
    if !matches!(
        reading,
        Formulation::SlaveNormal | Formulation::ClosestPoint
    ) {
        return None;
    }
    let name = if slave == master {
        format!("{slave}-{}", reading.name())
    } else {
        format!("{slave}-{master}-{}", reading.name())
    };
    name.parse().ok()
}

/// The integration points, multipliers and master faces of all 3D contact
/// pairs of a model (module docs).
#[derive(Debug, Clone)]
pub struct FaceLayout {
    /// All slave integration points, pair by pair, face by face.
    pub points: Vec<FacePoint>,
    /// All multiplier dofs, pair by pair.
    pub multipliers: Vec<MultiplierDof>,
    /// The reading of each pair (after an override).
    pub readings: Vec<Formulation>,
    /// The mode of each pair.
    pub modes: Vec<ContactMode>,
    /// Slave faces of each pair.
    pub slaves: Vec<Vec<Face<NodeId>>>,
    /// Master faces of each pair.
    pub masters: Vec<Vec<Face<NodeId>>>,
    /// Active-set constant `c` per pair (unilateral mode).
    pub complementarity: Vec<f64>,
    /// The tangential multipliers of the pairs with friction (two per
    /// node, `slip.rs`).
    pub friction: Friction,
}

/// Per pair and slave face, the reach of segmented integration (module
/// docs): the largest `|g|` of the face's Gauss points paired in the
/// reference configuration, 0 where none pairs. Empty for a pair without
/// segmented integration, and all 0 when the pairing fails (a kernel
/// error the solve itself reports).
fn reference_reach(
    mesh: &Mesh<3>,
    pairs: &[ContactPair<3>],
    reading: Option<Formulation>,
) -> Vec<Vec<f64>> {
    let segmented = |p: &ContactPair<3>| p.integration == Integration::Segmented;
    let mut reach: Vec<Vec<f64>> = pairs
        .iter()
        .map(|p| vec![0.0; if segmented(p) { p.slave.len() } else { 0 }])
        .collect();
    if !pairs.iter().any(segmented) {
        return reach;
    }
    let gauss: Vec<ContactPair<3>> = pairs
        .iter()
        .map(|p| ContactPair {
            integration: Integration::Gauss,
            gauss_points: None,
            ..p.clone()
        })
        .collect();
    let Ok(probe) = FaceLayout::new(mesh, &gauss, reading) else {
        return reach;
    };
    let u = vec![0.0; 3 * mesh.node_count()];
    let unpaired = vec![None; probe.points.len()];
    let Ok((found, _)) = probe.project_all(mesh, &u, &unpaired) else {
        return reach;
    };
    for (pt, f) in probe.points.iter().zip(&found) {
        if let (Some(f), Some(r)) = (f, reach[pt.pair.index()].get_mut(pt.slave_face)) {
            *r = r.max(f.gap.abs());
        }
    }
    reach
}

/// Segmented integration of one pair (module docs): the master faces in
/// the reference configuration with their index, and the triangle rule.
struct Segmenter {
    masters: Vec<Face<[f64; 3]>>,
    index: Option<FaceIndex<3>>,
    rule: TriangleRule,
}

impl Segmenter {
    fn new(mesh: &Mesh<3>, pair: &ContactPair<3>) -> Result<Segmenter, FaceLayoutError> {
        let rule = match pair.gauss_points.unwrap_or(7) {
            1 => TriangleRule::Centroid,
            3 => TriangleRule::Three,
            7 => TriangleRule::Seven,
            requested => {
                return Err(FaceLayoutError::TriangleRule {
                    pair: pair.name.clone(),
                    requested,
                });
            }
        };
        let masters: Vec<Face<[f64; 3]>> = pair
            .master
            .iter()
            .map(|f| f.map_nodes(|n| mesh.node_ref(n)))
            .collect();
        let nodes: Vec<&[[f64; 3]]> = masters.iter().map(|f| f.nodes()).collect();
        Ok(Segmenter {
            index: FaceIndex::from_faces(&nodes, 0.0).ok(),
            masters,
            rule,
        })
    }

    /// The points `(xi_s, w J0)` of slave face `f` (reference coordinates
    /// `x_ref`): every facing master face within its size plus `reach`
    /// (module docs) clipped and triangulated.
    fn points(
        &self,
        pair: &ContactPair<3>,
        f: usize,
        x_ref: &Face<[f64; 3]>,
        reach: f64,
    ) -> Result<Vec<([f64; 2], f64)>, FaceLayoutError> {
        let clip_err = |master, source| FaceLayoutError::Clip {
            pair: pair.name.clone(),
            face: f,
            master,
            source,
        };
        let slave = SlaveFace::new(x_ref.nodes()).map_err(|e| clip_err(0, e))?;
        let candidates: Vec<usize> = match Aabb::around(f, x_ref.nodes(), x_ref.size() + reach)
            .ok()
            .zip(self.index.as_ref())
            .and_then(|(b, index)| index.query_box(&b).ok())
        {
            Some(c) => c,
            None => (0..self.masters.len()).collect(),
        };
        let n_s = x_ref.normal();
        let mut out = Vec::new();
        for m in candidates {
            let master = &self.masters[m];
            if crate::mesh::volume::dot(n_s, master.normal()) >= 0.0 {
                continue;
            }
            for p in slave
                .integration_points(master.nodes(), self.rule)
                .map_err(|e| clip_err(m, e))?
            {
                out.push((p.uv, p.weight));
            }
        }
        Ok(out)
    }
}

impl FaceLayout {
    /// Lays out `pairs` on `mesh`, with every pair's reading replaced by
    /// `reading` when given.
    pub fn new(
        mesh: &Mesh<3>,
        pairs: &[ContactPair<3>],
        reading: Option<Formulation>,
    ) -> Result<FaceLayout, FaceLayoutError> {
        let reach = reference_reach(mesh, pairs, reading);
        let mut points = Vec::new();
        let mut multipliers = Vec::new();
        let mut complementarity = Vec::new();
        let mut readings = Vec::new();
        for (p, pair) in pairs.iter().enumerate() {
            let pid = PairId::new(p);
            let pair_reading = reading.unwrap_or(pair.formulation);
            if face_formulation(pair_reading, FaceKind::Tri3, FaceKind::Tri3).is_none() {
                return Err(FaceLayoutError::Reading {
                    pair: pair.name.clone(),
                    reading: pair_reading,
                });
            }
            readings.push(pair_reading);
            let mut mult_of_node = HashMap::new();
            for face in &pair.slave {
                for &n in face.nodes() {
                    mult_of_node.entry(n).or_insert_with(|| {
                        multipliers.push(MultiplierDof { pair: pid, node: n });
                        MultiplierIndex::new(multipliers.len() - 1)
                    });
                }
            }
            let segmented = match pair.integration {
                Integration::Gauss => None,
                Integration::Segmented => Some(Segmenter::new(mesh, pair)?),
            };
            let mut rules = HashMap::new();
            let mut total_size = 0.0;
            for (f, face) in pair.slave.iter().enumerate() {
                let x_ref = face.map_nodes(|n| mesh.node_ref(n));
                let nodes = face.nodes();
                let mults = std::array::from_fn(|a| mult_of_node[&nodes[a.min(nodes.len() - 1)]]);
                let face_points = match &segmented {
                    Some(seg) => seg.points(pair, f, &x_ref, reach[p][f])?,
                    None => {
                        let kind = face.kind();
                        if let std::collections::hash_map::Entry::Vacant(e) = rules.entry(kind) {
                            let rk = kind;
                            let n = pair.gauss_points.unwrap_or_else(|| default_points(rk));
                            e.insert(face_rule(rk, n).map_err(|source| FaceLayoutError::Rule {
                                pair: pair.name.clone(),
                                source,
                            })?);
                        }
                        let mut out = Vec::new();
                        for (g, &(xi, w)) in rules[&kind].points.iter().enumerate() {
                            let j0 = x_ref.area_element(xi);
                            if !(j0.is_finite() && j0 > 0.0) {
                                return Err(FaceLayoutError::DegenerateSlaveFace {
                                    pair: pair.name.clone(),
                                    face: f,
                                    gauss: g,
                                    area_element: j0,
                                });
                            }
                            out.push((xi, w * j0));
                        }
                        out
                    }
                };
                let dual = match pair.multipliers {
                    Multipliers::Standard => None,
                    Multipliers::Dual => Some(dual_coefficients(&x_ref).map_err(|source| {
                        FaceLayoutError::DualBasis {
                            pair: pair.name.clone(),
                            face: f,
                            source,
                        }
                    })?),
                };
                for (g, (xi, weight_ref)) in face_points.into_iter().enumerate() {
                    let shape = FaceShape::at(face.kind(), xi);
                    let basis = match &dual {
                        None => shape.n,
                        Some(a) => std::array::from_fn(|r| {
                            (0..shape.count).map(|c| a[r][c] * shape.n[c]).sum()
                        }),
                    };
                    points.push(FacePoint {
                        pair: pid,
                        slave_face: f,
                        gauss: g,
                        xi_s: xi,
                        weight_ref,
                        slave: *face,
                        multipliers: mults,
                        basis,
                    });
                }
                total_size += x_ref.size();
            }
            let young = mesh
                .bodies
                .iter()
                .find(|b| pair.slave.first().is_some_and(|f| b.has_node(f.nodes()[0])))
                .map_or(1.0, |b| b.material.young);
            let h = total_size / pair.slave.len().max(1) as f64;
            complementarity.push(young / h);
        }
        Ok(FaceLayout {
            points,
            readings,
            modes: pairs.iter().map(|c| c.mode).collect(),
            slaves: pairs.iter().map(|c| c.slave.clone()).collect(),
            masters: pairs.iter().map(|c| c.master.clone()).collect(),
            complementarity,
            friction: Friction::new(&multipliers, pairs.iter().map(|c| c.friction).collect(), 2),
            multipliers,
        })
    }

    /// The layout as the friction reads it.
    pub fn friction_view(&self) -> FrictionView<'_, FacePoint> {
        FrictionView {
            friction: &self.friction,
            points: &self.points,
            pairs: &self.multipliers,
            complementarity: &self.complementarity,
        }
    }

    /// The layout as the active set reads it.
    pub fn active_set_view(&self) -> ActiveSetView<'_, FacePoint> {
        ActiveSetView {
            points: &self.points,
            multipliers: &self.multipliers,
            modes: &self.modes,
            complementarity: &self.complementarity,
        }
    }

    /// The static data of point `i`.
    pub fn point(&self, i: ContactPointIndex) -> &FacePoint {
        &self.points[i.index()]
    }

    /// The master faces of `pair`.
    pub fn masters_of(&self, pair: PairId) -> &[Face<NodeId>] {
        &self.masters[pair.index()]
    }

    /// The current coordinates of `node` at displacements `u`.
    pub fn current(mesh: &Mesh<3>, u: &[f64], node: NodeId) -> [f64; 3] {
        let x = mesh.node_ref(node);
        std::array::from_fn(|k| x[k] + u[DofId::in_dim::<3>(node, k).index()])
    }

    /// A face's current coordinates at displacements `u`.
    pub fn current_face(mesh: &Mesh<3>, u: &[f64], face: &Face<NodeId>) -> Face<[f64; 3]> {
        face.map_nodes(|n| Self::current(mesh, u, n))
    }
}
