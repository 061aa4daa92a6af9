//! The discrete model the solver works on: mesh, boundary conditions,
//! proportional loads and contact pairs (a [`crate::Scene`] builds one).
//!
//! Loads and prescribed displacements are proportional to the load factor
//! `lambda_L`: the external force is `lambda_L f_ref` and a prescribed degree
//! of freedom has the value `lambda_L u_ref` (a fixed one has `u_ref = 0`).
//!
//! Invariants after [`Model::check`] (which every solve runs first): every
//! dof and node index is in range, a dof is prescribed at most once (or
//! twice to the same value), every value is finite, every node with a free
//! dof belongs to an element, and every contact pair has non-empty slave and
//! master faces of non-degenerate segments that share no node. Nodes are
//! [`NodeId`]s and dofs [`DofId`]s (`2 node + component`); the error
//! variants carry their plain numbers.

use contact_kernels::Formulation;
use serde::{Deserialize, Serialize};

use crate::contact::Integration;
use crate::ids::{DofId, NodeId};
use crate::mesh::Mesh;

/// How a contact pair's constraint is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactMode {
    /// Equality `g = 0` at every paired integration point (frictionless
    /// sliding; the paper's contact).
    #[default]
    Persistent,
    /// Inequality `g >= 0` with compressive pressure `p = -lambda >= 0`
    /// and an active set of multiplier nodes (see [`crate::contact`]).
    Unilateral,
}

impl ContactMode {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            ContactMode::Persistent => "persistent",
            ContactMode::Unilateral => "unilateral",
        }
    }
}

/// One contact pair: a slave face and a master face, each a list of 2-node
/// segments (global node indices) ordered counter-clockwise around its
/// body.
#[derive(Clone, PartialEq)]
pub struct ContactPair {
    /// A name for reports.
    pub name: String,
    /// Slave segments.
    pub slave: Vec<[NodeId; 2]>,
    /// Master segments.
    pub master: Vec<[NodeId; 2]>,
    /// The gap formulation.
    pub formulation: Formulation,
    /// Persistent or unilateral.
    pub mode: ContactMode,
    /// Gauss points per slave segment (1..=8), per piece of it with
    /// segmented integration.
    pub gauss_points: usize,
    /// The integration rule on the slave segments (see
    /// [`crate::contact::Integration`]).
    pub integration: Integration,
}

/// As derived, except that the default integration rule is not printed, so
/// that the `Debug` text of every model without segmented integration (and
/// the fingerprints of it that tests keep) is what it was before the rule
/// existed.
impl std::fmt::Debug for ContactPair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("ContactPair");
        d.field("name", &self.name)
            .field("slave", &self.slave)
            .field("master", &self.master)
            .field("formulation", &self.formulation)
            .field("mode", &self.mode)
            .field("gauss_points", &self.gauss_points);
        if self.integration != Integration::Gauss {
            d.field("integration", &self.integration);
        }
        d.finish()
    }
}

/// A prescribed displacement degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prescribed {
    /// Global degree of freedom (`2 node + component`).
    pub dof: DofId,
    /// Its value at load factor one (zero for a fixed support).
    pub value: f64,
}

/// A proportional point force component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    /// Global degree of freedom (`2 node + component`).
    pub dof: DofId,
    /// Its value at load factor one.
    pub value: f64,
}

/// Everything the solver needs.
#[derive(Debug, Clone)]
pub struct Model {
    /// The mesh with materials.
    pub mesh: Mesh,
    /// Prescribed degrees of freedom (each at most once).
    pub prescribed: Vec<Prescribed>,
    /// Reference point loads (a dof may appear several times; they add).
    pub loads: Vec<PointLoad>,
    /// Contact pairs.
    pub contacts: Vec<ContactPair>,
    /// The final load factor.
    pub load_factor_end: f64,
}

/// A model inconsistency found by [`Model::check`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// A degree of freedom index beyond the mesh.
    #[error("{what}: degree of freedom {dof} does not exist (the mesh has {count})")]
    DofOutOfRange {
        /// Which list.
        what: &'static str,
        /// The index.
        dof: usize,
        /// Number of dofs.
        count: usize,
    },
    /// The same dof prescribed twice with different values.
    #[error("degree of freedom {dof} (node {node}) is prescribed twice, to {a} and {b}")]
    ConflictingPrescribed {
        /// The dof.
        dof: usize,
        /// Its node.
        node: usize,
        /// First value.
        a: f64,
        /// Second value.
        b: f64,
    },
    /// A node with free dofs that belongs to no element.
    #[error(
        "node {node} belongs to no element and is not fully prescribed (its equations would be empty)"
    )]
    OrphanNode {
        /// The node.
        node: usize,
    },
    /// A contact pair problem.
    #[error("contact pair `{pair}`: {message}")]
    Contact {
        /// The pair's name.
        pair: String,
        /// What is wrong.
        message: String,
    },
    /// A non-finite load, prescribed value or load factor.
    #[error("{what} is not finite")]
    NonFinite {
        /// What.
        what: &'static str,
    },
}

impl Model {
    /// Checks indices, duplicates and contact pairs.
    pub fn check(&self) -> Result<(), ModelError> {
        let ndof = 2 * self.mesh.node_count();
        if !self.load_factor_end.is_finite() {
            return Err(ModelError::NonFinite {
                what: "the final load factor",
            });
        }
        let mut prescribed: Vec<Option<f64>> = vec![None; ndof];
        for p in &self.prescribed {
            if p.dof.index() >= ndof {
                return Err(ModelError::DofOutOfRange {
                    what: "prescribed",
                    dof: p.dof.index(),
                    count: ndof,
                });
            }
            if !p.value.is_finite() {
                return Err(ModelError::NonFinite {
                    what: "a prescribed displacement",
                });
            }
            if let Some(a) = prescribed[p.dof.index()]
                && a != p.value
            {
                return Err(ModelError::ConflictingPrescribed {
                    dof: p.dof.index(),
                    node: p.dof.node().index(),
                    a,
                    b: p.value,
                });
            }
            prescribed[p.dof.index()] = Some(p.value);
        }
        for l in &self.loads {
            if l.dof.index() >= ndof {
                return Err(ModelError::DofOutOfRange {
                    what: "load",
                    dof: l.dof.index(),
                    count: ndof,
                });
            }
            if !l.value.is_finite() {
                return Err(ModelError::NonFinite { what: "a load" });
            }
        }
        let mut in_element = vec![false; self.mesh.node_count()];
        for el in &self.mesh.elements {
            for &n in el {
                in_element[n.index()] = true;
            }
        }
        if let Some(node) = self.mesh.node_ids().find(|&n| {
            !in_element[n.index()]
                && (prescribed[DofId::of(n, 0).index()].is_none()
                    || prescribed[DofId::of(n, 1).index()].is_none())
        }) {
            return Err(ModelError::OrphanNode { node: node.index() });
        }
        for pair in &self.contacts {
            let err = |message: String| ModelError::Contact {
                pair: pair.name.clone(),
                message,
            };
            if pair.slave.is_empty() || pair.master.is_empty() {
                return Err(err(
                    "the slave and the master face need at least one segment each".into(),
                ));
            }
            if !(1..=8).contains(&pair.gauss_points) {
                return Err(err(format!(
                    "gauss_points must be in 1..=8, got {}",
                    pair.gauss_points
                )));
            }
            for seg in pair.slave.iter().chain(&pair.master) {
                // printed as the plain `[a, b]` it always was
                let raw = seg.map(NodeId::index);
                if raw.iter().any(|&n| n >= self.mesh.node_count()) {
                    return Err(err(format!("segment {raw:?} refers to a missing node")));
                }
                let (a, b) = (self.mesh.node_ref(seg[0]), self.mesh.node_ref(seg[1]));
                if !((a[0] - b[0]).hypot(a[1] - b[1]) > self.mesh.coordinate_tolerance()) {
                    return Err(err(format!("segment {raw:?} has zero length")));
                }
            }
            let slave_nodes: std::collections::HashSet<NodeId> =
                pair.slave.iter().flatten().copied().collect();
            if pair
                .master
                .iter()
                .flatten()
                .any(|n| slave_nodes.contains(n))
            {
                return Err(err("the slave and the master face share a node".into()));
            }
        }
        Ok(())
    }
}
