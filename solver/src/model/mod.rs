//! The discrete model the solver works on: mesh, boundary conditions,
//! proportional loads and contact pairs (a [`crate::Scene`] builds one).
//!
//! Loads and prescribed displacements are proportional to the load factor
//! `lambda_L`: the external force is `lambda_L f_ref` and a prescribed degree
//! of freedom has the value `lambda_L u_ref` (a fixed one has `u_ref = 0`),
//! unless the item carries a load curve ([`Prescribed::amplitude`],
//! [`PointLoad::amplitude`], an index into [`Model::amplitudes`]): then its
//! value is `a(lambda_L) u_ref` (resp. `f_ref`), see [`crate::amplitude`].
//! [`Model::factor`] gives the factor of either kind; without a curve it is
//! `lambda_L` itself, so proportional loading computes `lambda_L * value`
//! exactly as before curves existed.
//!
//! [`Model::supports`] names groups of prescribed dofs (contiguous ranges
//! of [`Model::prescribed`]; a scene makes one per `[[fix]]` and
//! `[[prescribe]]`) whose reaction forces the solve reports.
//!
//! Invariants after [`Model::check`] (which every solve runs first): every
//! dof and node index is in range, a dof is prescribed at most once (or
//! twice to the same value and curve), every value is finite, every
//! amplitude index is in range, every support group is a range of
//! `prescribed`, every node with a free
//! dof belongs to an element, and every contact pair has non-empty slave and
//! master surfaces of facets that share no node (segments of non-zero
//! length in 2D) and `gauss_points`, if given, in 1..=8. Nodes are
//! [`NodeId`]s and dofs [`DofId`]s (`D node + component`); the error
//! variants carry their plain numbers.
//!
//! A model lives in the dimension of its mesh (`Model<D>`, 2 by default;
//! one type and one solver for both). Its contact pairs are
//! [`ContactPair<D>`]s of the dimension's facets (`pair.rs`: segments in
//! 2D, tri3/quad4 faces in 3D); [`Model::check`] refuses a 3D body whose
//! material is not admissible in 3D ([`ModelError::Material`]: Poisson's
//! ratio must be below 1/2; a 2D model's materials are checked where they
//! are read).

mod pair;

use std::ops::Range;

use crate::amplitude::Amplitude;
use crate::ids::{AmplitudeId, DofId, NodeId};
use crate::mesh::Mesh;

pub use pair::{
    ContactMode, ContactPair, Dim, Facet, FacetOf, Integration, Multipliers, SurfaceDim,
};

/// A prescribed displacement degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prescribed {
    /// Global degree of freedom (`D node + component`,
    /// [`DofId::in_dim`]).
    pub dof: DofId,
    /// Its value at load factor one (zero for a fixed support), or the
    /// value its curve scales.
    pub value: f64,
    /// Its load curve (`None`: proportional, `lambda_L value`).
    pub amplitude: Option<AmplitudeId>,
}

/// A point force component (proportional, or scaled by a load curve).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    /// Global degree of freedom (`D node + component`,
    /// [`DofId::in_dim`]).
    pub dof: DofId,
    /// Its value at load factor one, or the value its curve scales.
    pub value: f64,
    /// Its load curve (`None`: proportional, `lambda_L value`).
    pub amplitude: Option<AmplitudeId>,
}

/// A named group of prescribed dofs whose reaction force is reported.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SupportGroup {
    /// Its name in reports (a scene's `group`, or `fix[i]`/`prescribe[i]`).
    pub name: String,
    /// Its entries of [`Model::prescribed`].
    pub prescribed: Range<usize>,
}

/// Everything the solver needs.
#[derive(Debug, Clone)]
pub struct Model<const D: usize = 2>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The mesh with materials.
    pub mesh: Mesh<D>,
    /// Prescribed degrees of freedom (each at most once).
    pub prescribed: Vec<Prescribed>,
    /// Reference point loads (a dof may appear several times; they add).
    pub loads: Vec<PointLoad>,
    /// Contact pairs.
    pub contacts: Vec<ContactPair<D>>,
    /// The final load factor.
    pub load_factor_end: f64,
    /// Load curves, referred to by [`Prescribed::amplitude`] and
    /// [`PointLoad::amplitude`].
    pub amplitudes: Vec<Amplitude>,
    /// Groups of prescribed dofs whose reactions are reported, in report
    /// order (may be empty: no reactions reported).
    pub supports: Vec<SupportGroup>,
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
    /// The same dof prescribed twice to the same non-zero value but with
    /// different load curves.
    #[error(
        "degree of freedom {dof} (node {node}) is prescribed twice, with different load curves"
    )]
    ConflictingAmplitude {
        /// The dof.
        dof: usize,
        /// Its node.
        node: usize,
    },
    /// A load curve index beyond [`Model::amplitudes`].
    #[error("{what}: load curve {amplitude} does not exist (the model has {count})")]
    AmplitudeOutOfRange {
        /// Which list.
        what: &'static str,
        /// The index.
        amplitude: usize,
        /// Number of curves.
        count: usize,
    },
    /// A support group that is not a range of the prescribed dofs.
    #[error("support group `{name}`: {start}..{end} is not a range of the {count} prescribed dofs")]
    SupportOutOfRange {
        /// The group's name.
        name: String,
        /// Range start.
        start: usize,
        /// Range end.
        end: usize,
        /// Number of prescribed dofs.
        count: usize,
    },
    /// A non-finite load, prescribed value or load factor.
    #[error("{what} is not finite")]
    NonFinite {
        /// What.
        what: &'static str,
    },
    /// A body of a 3D model whose material is not admissible for a 3D
    /// solid ([`crate::material::Material::check_3d`]: `nu` below 1/2).
    #[error("body `{body}`: {error}")]
    Material {
        /// The body.
        body: String,
        /// Why.
        error: crate::material::MaterialError,
    },
}

impl<const D: usize> Model<D>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The factor of an item with load curve `amplitude` at load factor
    /// `load_factor`: `load_factor` itself without a curve (so the item's
    /// value is `load_factor * value`, as for proportional loading), else
    /// the curve's value there.
    pub fn factor(&self, amplitude: Option<AmplitudeId>, load_factor: f64) -> f64 {
        match amplitude {
            None => load_factor,
            Some(a) => self.amplitudes[a.index()].at(load_factor),
        }
    }

    /// The number of displacement dofs, `D` per node.
    pub fn dof_count(&self) -> usize {
        D * self.mesh.node_count()
    }

    /// Checks indices, duplicates and contact pairs (module docs).
    pub fn check(&self) -> Result<(), ModelError> {
        let ndof = self.dof_count();
        if !self.load_factor_end.is_finite() {
            return Err(ModelError::NonFinite {
                what: "the final load factor",
            });
        }
        let curve_in_range = |what: &'static str, a: Option<AmplitudeId>| match a {
            Some(a) if a.index() >= self.amplitudes.len() => Err(ModelError::AmplitudeOutOfRange {
                what,
                amplitude: a.index(),
                count: self.amplitudes.len(),
            }),
            _ => Ok(()),
        };
        for g in &self.supports {
            if g.prescribed.start > g.prescribed.end || g.prescribed.end > self.prescribed.len() {
                return Err(ModelError::SupportOutOfRange {
                    name: g.name.clone(),
                    start: g.prescribed.start,
                    end: g.prescribed.end,
                    count: self.prescribed.len(),
                });
            }
        }
        let mut curves: Vec<Option<AmplitudeId>> = vec![None; ndof];
        let mut prescribed: Vec<Option<f64>> = vec![None; ndof];
        for p in &self.prescribed {
            curve_in_range("prescribed", p.amplitude)?;
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
            if prescribed[p.dof.index()].is_some()
                && p.value != 0.0
                && curves[p.dof.index()] != p.amplitude
            {
                return Err(ModelError::ConflictingAmplitude {
                    dof: p.dof.index(),
                    node: p.dof.node().index(),
                });
            }
            prescribed[p.dof.index()] = Some(p.value);
            curves[p.dof.index()] = p.amplitude;
        }
        for l in &self.loads {
            curve_in_range("load", l.amplitude)?;
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
                && (0..D).any(|c| prescribed[DofId::in_dim::<D>(n, c).index()].is_none())
        }) {
            return Err(ModelError::OrphanNode { node: node.index() });
        }
        if D == 3 {
            for b in &self.mesh.bodies {
                b.material
                    .check_3d()
                    .map_err(|error| ModelError::Material {
                        body: b.name.clone(),
                        error,
                    })?;
            }
        }
        for pair in &self.contacts {
            self.check_pair(pair)
                .map_err(|message| ModelError::Contact {
                    pair: pair.name.clone(),
                    message,
                })?;
        }
        Ok(())
    }

    /// What is wrong with `pair` (module docs), if anything.
    fn check_pair(&self, pair: &ContactPair<D>) -> Result<(), String> {
        let (facet, surface) = (FacetOf::<D>::NAME, FacetOf::<D>::SURFACE);
        if pair.slave.is_empty() || pair.master.is_empty() {
            return Err(format!(
                "the slave and the master {surface} need at least one {facet} each"
            ));
        }
        if let Some(n) = pair.gauss_points
            && !(1..=8).contains(&n)
        {
            return Err(format!("gauss_points must be in 1..=8, got {n}"));
        }
        for f in pair.slave.iter().chain(&pair.master) {
            if f.nodes()
                .iter()
                .any(|n| n.index() >= self.mesh.node_count())
            {
                let raw: Vec<usize> = f.nodes().iter().map(|n| n.index()).collect();
                return Err(format!("{facet} {raw:?} refers to a missing node"));
            }
            if let Some(m) = <Dim<D> as SurfaceDim<D>>::degenerate(&self.mesh, f) {
                return Err(m);
            }
        }
        let slave_nodes: std::collections::HashSet<NodeId> = pair
            .slave
            .iter()
            .flat_map(|f| f.nodes().iter().copied())
            .collect();
        if pair
            .master
            .iter()
            .any(|f| f.nodes().iter().any(|n| slave_nodes.contains(n)))
        {
            return Err(format!("the slave and the master {surface} share a node"));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, PlaneModel};
    use crate::mesh::Block;

    /// One element, fixed at node 0, a curve on a load.
    fn model() -> Model {
        let mut mesh = Mesh::new();
        let material = Material {
            young: 100.0,
            poisson: 0.3,
            model: PlaneModel::PlaneStress,
            kinematics: crate::material::Kinematics::Finite,
        };
        let block = Block {
            origin: [0.0, 0.0],
            size: [1.0, 1.0],
            cells: [1, 1],
        };
        mesh.add_block("a", material, block).unwrap();
        let fixed = |c| Prescribed {
            dof: DofId::of(NodeId::new(0), c),
            value: 0.0,
            amplitude: None,
        };
        Model {
            mesh,
            prescribed: vec![fixed(0), fixed(1)],
            loads: vec![PointLoad {
                dof: DofId::new(5),
                value: 2.0,
                amplitude: Some(AmplitudeId::new(0)),
            }],
            contacts: Vec::new(),
            load_factor_end: 1.0,
            amplitudes: vec![Amplitude::new(vec![[0.0, 0.0], [0.5, 1.0]]).unwrap()],
            supports: vec![SupportGroup {
                name: "corner".into(),
                prescribed: 0..2,
            }],
        }
    }

    #[test]
    fn factor_is_the_load_factor_or_the_curve() {
        let m = model();
        assert_eq!(m.factor(None, 0.3), 0.3);
        assert_eq!(m.factor(Some(AmplitudeId::new(0)), 0.25), 0.5);
        assert_eq!(m.factor(Some(AmplitudeId::new(0)), 2.0), 1.0);
    }

    #[test]
    fn check_rejects_bad_curves_and_groups() {
        model().check().unwrap();
        let mut m = model();
        m.loads[0].amplitude = Some(AmplitudeId::new(1));
        assert_eq!(
            m.check(),
            Err(ModelError::AmplitudeOutOfRange {
                what: "load",
                amplitude: 1,
                count: 1
            })
        );
        let mut m = model();
        m.supports[0].prescribed = 1..3;
        assert!(
            matches!(
                m.check(),
                Err(ModelError::SupportOutOfRange {
                    end: 3,
                    count: 2,
                    ..
                })
            ),
            "{:?}",
            m.check()
        );
        // the same dof twice: same value and curve agree; a zero value
        // agrees whatever the curve; a non-zero one with another curve not
        let mut m = model();
        let p = Prescribed {
            dof: DofId::new(7),
            value: 0.1,
            amplitude: Some(AmplitudeId::new(0)),
        };
        m.prescribed.extend([p, p]);
        m.check().unwrap();
        m.prescribed[3].amplitude = None;
        assert_eq!(
            m.check(),
            Err(ModelError::ConflictingAmplitude { dof: 7, node: 3 })
        );
        m.prescribed[0].amplitude = Some(AmplitudeId::new(0));
        m.prescribed.truncate(2);
        m.check().unwrap();
    }
}
