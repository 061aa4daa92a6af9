//! [`ContactLayout`]: the integration points, multipliers and master-chain
//! adjacency of all contact pairs of a model, and the node geometry of a
//! (point, master segment) pairing.
//!
//! The integration points of a pair follow its [`Integration`] rule: the
//! Gauss rule on every slave segment, or (segmented) the Gauss rule on
//! every piece of a slave segment split in the reference configuration at
//! the projections of the master nodes, in the pair's formulation after an
//! override (see `segmented`).
//!
//! Invariants: built once per solve from the model and never changed; a
//! slave node shared by neighbouring slave segments carries one multiplier;
//! `adjacency[pair][m]` is `[previous, next]` along the master chain (by the
//! chain's shared nodes).

use contact_kernels::Formulation;

use crate::ids::{ContactPointIndex, DofId, MasterSegmentIndex, MultiplierIndex, NodeId, PairId};
use crate::mesh::Mesh;
use crate::model::{ContactMode, Integration, Model};

use super::segmented::{segmented_rule, split_coordinates};
use crate::contact::active_set::ActiveSetView;
use crate::contact::face_rules::default_points;
use crate::contact::friction::{Friction, FrictionView};
use crate::contact::{ContactPoint, MultiplierDof, gauss_legendre};
use crate::element::FaceKind as RuleKind;

/// The integration points, multipliers and master-chain adjacency of all
/// contact pairs of a model.
#[derive(Debug, Clone)]
pub struct ContactLayout {
    /// All slave integration points, pair by pair, segment by segment.
    pub points: Vec<ContactPoint>,
    /// All multiplier dofs, pair by pair, in slave-face order.
    pub multipliers: Vec<MultiplierDof>,
    /// The formulation of each pair (after an override).
    pub formulations: Vec<Formulation>,
    /// The mode of each pair.
    pub modes: Vec<ContactMode>,
    /// Master segments of each pair.
    pub masters: Vec<Vec<[NodeId; 2]>>,
    /// `[previous, next]` master segment along each pair's chain.
    pub(super) adjacency: Vec<Vec<[Option<MasterSegmentIndex>; 2]>>,
    /// Active-set constant `c` per pair (unilateral mode).
    pub complementarity: Vec<f64>,
    /// The tangential multipliers of the pairs with friction (numbered
    /// after every normal multiplier).
    pub friction: Friction,
    /// Pairs with at least this many master segments search them through
    /// the spatial index (`master_search`; default
    /// [`super::master_search::INDEX_MIN_SEGMENTS`]); the choices are the same either
    /// way.
    pub index_min_segments: usize,
}

impl ContactLayout {
    /// The layout as the active set reads it.
    pub fn active_set_view(&self) -> ActiveSetView<'_, ContactPoint> {
        ActiveSetView {
            points: &self.points,
            multipliers: &self.multipliers,
            modes: &self.modes,
            complementarity: &self.complementarity,
        }
    }

    /// The layout as the friction reads it.
    pub fn friction_view(&self) -> FrictionView<'_, ContactPoint> {
        FrictionView {
            friction: &self.friction,
            points: &self.points,
            pairs: &self.multipliers,
            complementarity: &self.complementarity,
        }
    }

    /// Lays out the contact pairs of `model`, with every pair's
    /// formulation replaced by `formulation` when given.
    pub fn new(model: &Model, formulation: Option<Formulation>) -> ContactLayout {
        let mesh = &model.mesh;
        let mut points = Vec::new();
        let mut multipliers = Vec::new();
        let mut adjacency = Vec::new();
        let mut complementarity = Vec::new();
        for (p, pair) in model.contacts.iter().enumerate() {
            let p = PairId::new(p);
            let mut mult_of_node = std::collections::HashMap::new();
            for seg in &pair.slave {
                for &n in seg {
                    mult_of_node.entry(n).or_insert_with(|| {
                        multipliers.push(MultiplierDof { pair: p, node: n });
                        MultiplierIndex::new(multipliers.len() - 1)
                    });
                }
            }
            let rule = gauss_legendre(
                pair.gauss_points
                    .unwrap_or_else(|| default_points(RuleKind::Segment)),
            );
            let masters_ref: Vec<[[f64; 2]; 2]> = match pair.integration {
                Integration::Gauss => Vec::new(),
                Integration::Segmented => pair
                    .master
                    .iter()
                    .map(|m| m.map(|n| mesh.node_ref(n)))
                    .collect(),
            };
            let pair_formulation = formulation.unwrap_or(pair.formulation);
            let mut total_len = 0.0;
            for (s, seg) in pair.slave.iter().enumerate() {
                let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
                let len = (b[0] - a[0]).hypot(b[1] - a[1]);
                total_len += len;
                // plain Gauss: the rule itself (bit for bit as before)
                let segmented = match pair.integration {
                    Integration::Gauss => None,
                    Integration::Segmented => Some(segmented_rule(
                        &rule,
                        &split_coordinates(pair_formulation, [a, b], &masters_ref),
                    )),
                };
                for (g, &(xi, w)) in segmented.as_deref().unwrap_or(&rule).iter().enumerate() {
                    points.push(ContactPoint {
                        pair: p,
                        slave_segment: s,
                        gauss: g,
                        xi_s: xi,
                        weight_ref: w * len / 2.0,
                        slave_nodes: *seg,
                        multipliers: [mult_of_node[&seg[0]], mult_of_node[&seg[1]]],
                    });
                }
            }
            let mut starts = std::collections::HashMap::new();
            let mut ends = std::collections::HashMap::new();
            for (m, seg) in pair.master.iter().enumerate() {
                starts.insert(seg[0], MasterSegmentIndex::new(m));
                ends.insert(seg[1], MasterSegmentIndex::new(m));
            }
            adjacency.push(
                pair.master
                    .iter()
                    .map(|seg| [ends.get(&seg[0]).copied(), starts.get(&seg[1]).copied()])
                    .collect(),
            );
            let young = mesh
                .bodies
                .iter()
                .find(|b| b.has_node(pair.slave[0][0]))
                .map_or(1.0, |b| b.material.young);
            complementarity.push(young / (total_len / pair.slave.len() as f64));
        }
        let friction = Friction::new(
            &multipliers,
            model.contacts.iter().map(|c| c.friction).collect(),
            1,
        );
        ContactLayout {
            points,
            multipliers,
            friction,
            formulations: model
                .contacts
                .iter()
                .map(|c| formulation.unwrap_or(c.formulation))
                .collect(),
            modes: model.contacts.iter().map(|c| c.mode).collect(),
            masters: model.contacts.iter().map(|c| c.master.clone()).collect(),
            adjacency,
            complementarity,
            index_min_segments: super::master_search::INDEX_MIN_SEGMENTS,
        }
    }

    /// The layout of a model without contact pairs (no points, no
    /// multipliers).
    pub fn empty() -> ContactLayout {
        ContactLayout {
            points: Vec::new(),
            multipliers: Vec::new(),
            formulations: Vec::new(),
            modes: Vec::new(),
            masters: Vec::new(),
            adjacency: Vec::new(),
            complementarity: Vec::new(),
            friction: Friction::default(),
            index_min_segments: super::master_search::INDEX_MIN_SEGMENTS,
        }
    }

    /// Current coordinates `q` of four nodes.
    pub(super) fn q(mesh: &Mesh, u: &[f64], nodes: [NodeId; 4]) -> [f64; 8] {
        std::array::from_fn(|k| {
            mesh.node_ref(nodes[k / 2])[k % 2] + u[DofId::of(nodes[k / 2], k % 2).index()]
        })
    }

    /// The static data of point `i`.
    pub fn point(&self, i: ContactPointIndex) -> &ContactPoint {
        &self.points[i.index()]
    }

    /// The master segments of `pair`.
    pub fn masters_of(&self, pair: PairId) -> &[[NodeId; 2]] {
        &self.masters[pair.index()]
    }

    pub(super) fn nodes(&self, point: &ContactPoint, master: MasterSegmentIndex) -> [NodeId; 4] {
        let m = self.masters_of(point.pair)[master.index()];
        [point.slave_nodes[0], point.slave_nodes[1], m[0], m[1]]
    }

    /// The node that master segments `a` and `b` of `pair` share, if they
    /// are adjacent along the chain.
    pub fn shared_node(
        &self,
        pair: PairId,
        a: MasterSegmentIndex,
        b: MasterSegmentIndex,
    ) -> Option<NodeId> {
        let masters = self.masters_of(pair);
        let (sa, sb) = (masters[a.index()], masters[b.index()]);
        if a == b {
            return None;
        }
        sa.into_iter().find(|n| sb.contains(n))
    }
}
