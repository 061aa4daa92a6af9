//! The Newton system's numbering and sink: [`DofMap`] (the equation of
//! every free displacement dof, multiplier and node tie) and [`System`]
//! (the residual and the tangent: coordinate triplets, and for a solver
//! that takes it the solid elements' entries in a compressed [`Block`]),
//! filled by the solid elements (`crate::assembly`) and the contact element
//! (`crate::contact`).
//!
//! Unknowns: the free displacement dofs (in node order) followed by the
//! multipliers, then the node ties. Prescribed dofs are eliminated (their
//! values are set before a step's Newton iterations).

use crate::element::MAX_ELEMENT_DOFS;
use crate::ids::{DofId, EquationIndex, MultiplierIndex, NodeId};
use crate::linear::SystemLayout;
use crate::linear::{Block, BlockPattern};
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};

/// Marks a prescribed dof in [`DofMap::eq`].
const PRESCRIBED: usize = usize::MAX;

/// Equation numbers of the dofs, multipliers and node ties.
///
/// Invariant: equations `0..n_free` are the free dofs in dof order,
/// `n_free..n_eq()` the multipliers in [`MultiplierIndex`] order, and tie
/// `k` of the complete formulation is equation `n_eq() + k`.
#[derive(Debug, Clone)]
pub struct DofMap {
    eq: Vec<usize>,
    /// Number of free displacement dofs.
    pub n_free: usize,
    /// Number of multipliers.
    pub n_mult: usize,
}

impl DofMap {
    /// Numbers the free dofs of `model` (`D` per node) and `n_mult`
    /// multipliers.
    pub fn new<const D: usize>(model: &Model<D>, n_mult: usize) -> DofMap
    where
        Dim<D>: SurfaceDim<D>,
    {
        let ndof = model.dof_count();
        let mut eq = vec![0; ndof];
        for p in &model.prescribed {
            eq[p.dof.index()] = PRESCRIBED;
        }
        let mut n_free = 0;
        for e in eq.iter_mut() {
            if *e != PRESCRIBED {
                *e = n_free;
                n_free += 1;
            }
        }
        DofMap { eq, n_free, n_mult }
    }

    /// Every one of `ndof` displacement dofs free (equation = dof), then
    /// `n_mult` multipliers: assembling into it gives the residual at every
    /// dof, prescribed or not (for reaction forces).
    pub fn all_free(ndof: usize, n_mult: usize) -> DofMap {
        DofMap {
            eq: (0..ndof).collect(),
            n_free: ndof,
            n_mult,
        }
    }

    /// What the equations are, for the linear solver: the dof of each free
    /// equation and `model`'s reference coordinates (no node ranks: one
    /// rank's layout).
    pub fn layout<const D: usize>(&self, model: &Model<D>) -> SystemLayout
    where
        Dim<D>: SurfaceDim<D>,
    {
        let mut free_dofs = vec![0; self.n_free];
        for (dof, &e) in self.eq.iter().enumerate() {
            if e != PRESCRIBED {
                free_dofs[e] = dof;
            }
        }
        SystemLayout {
            dim: D,
            free_dofs,
            coordinates: model.mesh.nodes_ref.iter().flatten().copied().collect(),
            node_rank: Vec::new(),
        }
    }

    /// The equation of displacement dof `dof`, `None` if prescribed.
    pub fn eq(&self, dof: DofId) -> Option<EquationIndex> {
        let e = self.eq[dof.index()];
        (e != PRESCRIBED).then_some(EquationIndex::new(e))
    }

    /// The equations of the 8 dofs of the 2D contact element `nodes` (`x`
    /// then `y` of each node, in node order), `None` for prescribed ones.
    pub fn node_eqs(&self, nodes: &[NodeId; 4]) -> [Option<EquationIndex>; 8] {
        std::array::from_fn(|k| self.eq(DofId::of(nodes[k / 2], k % 2)))
    }

    /// The equations of the `D n` dofs of an element's `n` nodes in `D`
    /// dimensions (`x`, `y` (and `z`) of each node, in node order), `None`
    /// for prescribed ones, then `None` up to [`MAX_ELEMENT_DOFS`].
    pub fn element_eqs<const D: usize>(
        &self,
        nodes: &[NodeId],
    ) -> [Option<EquationIndex>; MAX_ELEMENT_DOFS] {
        std::array::from_fn(|k| {
            nodes
                .get(k / D)
                .and_then(|&n| self.eq(DofId::in_dim::<D>(n, k % D)))
        })
    }

    /// The equation of multiplier `m`.
    pub fn mult_eq(&self, m: MultiplierIndex) -> EquationIndex {
        EquationIndex::new(self.n_free + m.index())
    }

    /// The equation of node tie `k` (after the multipliers).
    pub fn tie_eq(&self, k: usize) -> EquationIndex {
        EquationIndex::new(self.n_eq() + k)
    }

    /// Total number of equations.
    pub fn n_eq(&self) -> usize {
        self.n_free + self.n_mult
    }
}

/// The most equations a [`System`] holds (its triplet indices are 32-bit).
pub const MAX_EQUATIONS: usize = u32::MAX as usize;

/// The assembled Newton system at one state.
#[derive(Debug, Clone, Default)]
pub struct System {
    /// The residual (length [`DofMap::n_eq`]).
    pub residual: Vec<f64>,
    /// Triplet rows (32-bit: the triplets are the largest buffer of a 3D
    /// run; a system of more equations is refused when Newton sets up,
    /// [`MAX_EQUATIONS`]).
    pub rows: Vec<u32>,
    /// Triplet columns (32-bit, as the rows).
    pub cols: Vec<u32>,
    /// Triplet values.
    pub vals: Vec<f64>,
    /// The solid block: with one, every contribution to an entry of its
    /// pattern is added there instead of becoming a triplet ([`Block`]).
    pub block: Option<Block>,
    /// Strain energy of all solid elements.
    pub energy: f64,
    /// The forces only: [`System::push`] drops the tangent's entries
    /// ([`System::forces_only`]).
    pub forces_only: bool,
}

impl System {
    /// An empty system with `n` equations.
    pub fn new(n: usize) -> System {
        System {
            residual: vec![0.0; n],
            ..System::default()
        }
    }

    /// An empty system with `n` equations that keeps the residual and the
    /// energy and drops every tangent entry: what the reactions read at a
    /// converged state, without the triplets of the contact's tangent
    /// (tens of MB on a 3D contact surface of a few thousand points).
    pub fn forces_only(n: usize) -> System {
        System {
            forces_only: true,
            ..System::new(n)
        }
    }

    /// An empty system with `n` equations and a zero solid block over
    /// `pattern`.
    pub fn with_block(n: usize, pattern: std::sync::Arc<BlockPattern>) -> System {
        System {
            block: Some(Block::new(pattern)),
            ..System::new(n)
        }
    }

    /// Empties `self` into a system of `n` equations with zero residual and
    /// energy, no triplets and a zero block (if it has one), keeping its
    /// buffers' capacity: the same system as [`System::new`] (or
    /// [`System::with_block`]), without allocating (and touching fresh
    /// pages for) the triplets again every Newton iteration.
    pub fn reset(&mut self, n: usize) {
        self.residual.clear();
        self.residual.resize(n, 0.0);
        self.rows.clear();
        self.cols.clear();
        self.vals.clear();
        if let Some(b) = &mut self.block {
            b.clear();
        }
        self.energy = 0.0;
    }

    /// Adds `v` to entry `(r, c)`: into the block when its pattern holds
    /// the entry, otherwise as the triplet `(r, c, v)`; nothing in a
    /// [`System::forces_only`].
    pub fn push(&mut self, r: EquationIndex, c: EquationIndex, v: f64) {
        if self.forces_only {
            return;
        }
        if let Some(b) = &mut self.block
            && b.add(r, c, v)
        {
            return;
        }
        // below MAX_EQUATIONS (checked when Newton sets up): exact
        self.rows.push(r.index() as u32);
        self.cols.push(c.index() as u32);
        self.vals.push(v);
    }

    /// The Euclidean norm of the residual.
    pub fn residual_norm(&self) -> f64 {
        self.residual.iter().map(|v| v * v).sum::<f64>().sqrt()
    }
}
