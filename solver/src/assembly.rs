//! Global numbering and assembly of the Newton system.
//!
//! Unknowns: the free displacement dofs (in node order) followed by the
//! multipliers. Prescribed dofs are eliminated (their values are set before
//! a step's Newton iterations). The residual is
//!
//! ```text
//! r_u  = f_int(u) + sum_gp w J0 lambda g' - lambda_L f_ref      (free dofs)
//! r_la = sum_gp w J0 N_a g        (active multiplier)  or  l_a  (inactive)
//! ```
//!
//! and the tangent its exact derivative (see [`crate::element::solid`] and
//! [`crate::contact`]). Element matrices are computed in parallel
//! (`crate::par`), collected in element order and scattered sequentially
//! into coordinate triplets, so the result is deterministic. The triplet index order depends
//! only on the mesh, the prescribed set, the pairing and the presence of
//! Hessians, which lets [`crate::linear`] reuse the symbolic factorisation.

use crate::contact::{ContactLayout, GapTerm, NodeTie, PointEval, WeightedPoint};
use crate::element::{ElementResponse, MAX_ELEMENT_DOFS};
use crate::ids::{DofId, ElementId, EquationIndex, MultiplierIndex, NodeId};
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};
use crate::par;

/// Marks a prescribed dof in [`DofMap::eq`].
const PRESCRIBED: usize = usize::MAX;

/// Elements per rayon task.
pub(crate) const PAR_MIN_LEN: usize = 64;

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

/// The assembled Newton system at one state.
#[derive(Debug, Clone, Default)]
pub struct System {
    /// The residual (length [`DofMap::n_eq`]).
    pub residual: Vec<f64>,
    /// Triplet rows.
    pub rows: Vec<usize>,
    /// Triplet columns.
    pub cols: Vec<usize>,
    /// Triplet values.
    pub vals: Vec<f64>,
    /// Strain energy of all solid elements.
    pub energy: f64,
}

impl System {
    /// An empty system with `n` equations.
    pub fn new(n: usize) -> System {
        System {
            residual: vec![0.0; n],
            ..System::default()
        }
    }

    /// Empties `self` into a system of `n` equations with zero residual and
    /// energy and no triplets, keeping its buffers' capacity: the same
    /// system as [`System::new`], without allocating (and touching fresh
    /// pages for) the triplets again every Newton iteration.
    pub fn reset(&mut self, n: usize) {
        self.residual.clear();
        self.residual.resize(n, 0.0);
        self.rows.clear();
        self.cols.clear();
        self.vals.clear();
        self.energy = 0.0;
    }

    /// Appends the triplet `(r, c, v)`.
    pub fn push(&mut self, r: EquationIndex, c: EquationIndex, v: f64) {
        self.rows.push(r.index());
        self.cols.push(c.index());
        self.vals.push(v);
    }

    /// The Euclidean norm of the residual.
    pub fn residual_norm(&self) -> f64 {
        self.residual.iter().map(|v| v * v).sum::<f64>().sqrt()
    }
}

/// Adds the solid elements' internal forces, tangents and energies at
/// displacements `u`, element after element, each through the element seam
/// ([`crate::element::ElementGeometry::response`]): for an element of `n`
/// nodes in `D` dimensions, its `D n` rows in dof order, each row's `D n`
/// columns in order.
pub fn assemble_solid<const D: usize>(model: &Model<D>, dofs: &DofMap, u: &[f64], sys: &mut System)
where
    Dim<D>: SurfaceDim<D>,
{
    assemble_solid_lifted(model, dofs, u, None, sys);
}

/// [`assemble_solid`], and with `lift` (a displacement increment on the
/// prescribed dofs, every dof's entry, zero on the free ones) also the
/// linearised effect of that increment on the free rows, `K_fp du_p`, added
/// to each free row after its internal force: the residual of the Newton
/// step's linearised Dirichlet predictor (see [`crate::newton`],
/// "Prescribed increments"). Without a lift this is [`assemble_solid`] bit
/// for bit.
pub fn assemble_solid_lifted<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    u: &[f64],
    lift: Option<&[f64]>,
    sys: &mut System,
) where
    Dim<D>: SurfaceDim<D>,
{
    let mesh = &model.mesh;
    let responses: Vec<ElementResponse> = par::map(mesh.element_count(), PAR_MIN_LEN, |e| {
        let e = ElementId::new(e);
        let material = &mesh.bodies[mesh.element_body[e.index()]].material;
        mesh.geometry[e.index()].response(&mesh.element_displacements(e, u), material)
    });
    sys.rows.reserve(64 * responses.len());
    sys.cols.reserve(64 * responses.len());
    sys.vals.reserve(64 * responses.len());
    for (el, resp) in mesh.elements.iter().zip(&responses) {
        let eqs = dofs.element_eqs::<D>(el);
        let f_int = resp.f_int();
        let n = f_int.len();
        for p in 0..n {
            let Some(ep) = eqs[p] else { continue };
            sys.residual[ep.index()] += f_int[p];
            let k = resp.k_row(p);
            for q in 0..n {
                if let Some(eq) = eqs[q] {
                    sys.push(ep, eq, k[q]);
                }
            }
            if let Some(du) = lift {
                for q in (0..n).filter(|&q| eqs[q].is_none()) {
                    sys.residual[ep.index()] +=
                        k[q] * du[DofId::in_dim::<D>(el[q / D], q % D).index()];
                }
            }
        }
        sys.energy += resp.energy();
    }
}

/// Adds the contact contributions of the evaluated integration points
/// (`evals[i]`, `None` = inactive) with multipliers `lambda` and the
/// multiplier rows (constraint for `active` multipliers, `l_a = 0` with a
/// unit diagonal for inactive ones).
///
/// A point contributes entries on its slave and paired master nodes only,
/// so the pattern changes when a point is re-paired (then the symbolic
/// factorisation is redone). Reserving the neighbouring master segments in
/// the pattern was tried and measured: on a refined paper scene (26 000
/// equations, complete formulation, 27 iterations) it cut the symbolic
/// analyses from 17 to 6 but made each numeric factorisation about 10 %
/// slower; the two roughly cancel (2 % net), not worth the complexity.
pub fn assemble_contact(
    layout: &ContactLayout,
    evals: &[Option<PointEval>],
    lambda: &[f64],
    active: &[bool],
    dofs: &DofMap,
    sys: &mut System,
) {
    assemble_contact_terms(&layout.points, evals, lambda, active, dofs, sys);
}

/// [`assemble_contact`] for the points and evaluations of any dimension
/// (see [`crate::contact::term`]): 2D segments (`N = 8`) or 3D faces
/// (`N = 24`, padding coordinates skipped). Per point, in this order: the
/// displacement residual `w J0 lambda g'`, the Hessian term
/// `w J0 lambda g''`, then per multiplier `a` of the slave face the
/// constraint residual `w J0 N_a g` (active) and the coupling
/// `w J0 N_a g'` both ways (zero in the inactive row); then the
/// multiplier rows' diagonals.
pub fn assemble_contact_terms<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
    points: &[P],
    evals: &[Option<E>],
    lambda: &[f64],
    active: &[bool],
    dofs: &DofMap,
    sys: &mut System,
) {
    for (pt, ev) in points.iter().zip(evals) {
        let Some(ev) = ev else { continue };
        let shape = pt.multiplier_shape();
        let w = pt.weight_ref();
        let lam = shape.lambda(lambda);
        let eqs: [Option<EquationIndex>; N] =
            std::array::from_fn(|k| ev.dof(k).and_then(|d| dofs.eq(d)));
        let grad = ev.grad();
        for p in 0..N {
            if let Some(ep) = eqs[p] {
                sys.residual[ep.index()] += w * lam * grad[p];
            }
        }
        if let Some(h) = ev.hess() {
            for p in 0..N {
                let Some(ep) = eqs[p] else { continue };
                for q in 0..N {
                    if let Some(eq) = eqs[q] {
                        sys.push(ep, eq, w * lam * h[(p, q)]);
                    }
                }
            }
        }
        for (m, n_a) in shape.iter() {
            let row = dofs.mult_eq(m);
            let on = active[m.index()];
            if on {
                sys.residual[row.index()] += w * n_a * ev.gap();
            }
            for p in 0..N {
                if let Some(ep) = eqs[p] {
                    let v = w * n_a * grad[p];
                    sys.push(ep, row, v);
                    sys.push(row, ep, if on { v } else { 0.0 });
                }
            }
        }
    }
    for (m, &on) in active.iter().enumerate() {
        let row = dofs.mult_eq(MultiplierIndex::new(m));
        if on {
            sys.push(row, row, 0.0);
        } else {
            sys.residual[row.index()] = lambda[m];
            sys.push(row, row, 1.0);
        }
    }
}

/// Adds the node ties of the complete formulation (see
/// [`crate::contact`], "Points stuck at a master node"): tie `k`, with the
/// point's evaluation on its paired segment `evals[point]` (its regular
/// term, added by [`assemble_contact`]) and on the other segment
/// `others[k]`, adds the potential `mu (g_o - g_p)`:
///
/// ```text
/// r_u  += mu (g_o' - g_p')        K_uu += mu (g_o'' - g_p'')
/// r_mu  = g_o - g_p               K_u,mu = K_mu,u = g_o' - g_p'
/// ```
///
/// with the tie's equation [`DofMap::tie_eq`] (after the free dofs and
/// multipliers) and an explicit zero `K_mu,mu`.
pub fn assemble_ties(
    ties: &[NodeTie],
    evals: &[Option<PointEval>],
    others: &[PointEval],
    dofs: &DofMap,
    sys: &mut System,
) {
    for (k, (tie, other)) in ties.iter().zip(others).enumerate() {
        let row = dofs.tie_eq(k);
        let Some(paired) = &evals[tie.point.index()] else {
            // an inactive point cannot be tied; keep the row regular
            sys.residual[row.index()] = tie.mu;
            sys.push(row, row, 1.0);
            continue;
        };
        sys.residual[row.index()] = other.gap - paired.gap;
        for (ev, sign) in [(other, 1.0), (paired, -1.0)] {
            let eqs = dofs.node_eqs(&ev.nodes);
            for p in 0..8 {
                let Some(ep) = eqs[p] else { continue };
                sys.residual[ep.index()] += sign * tie.mu * ev.grad[p];
                sys.push(ep, row, sign * ev.grad[p]);
                sys.push(row, ep, sign * ev.grad[p]);
                if let Some(h) = &ev.hess {
                    for q in 0..8 {
                        if let Some(eq) = eqs[q] {
                            sys.push(ep, eq, sign * tie.mu * h[(p, q)]);
                        }
                    }
                }
            }
        }
        sys.push(row, row, 0.0);
    }
}

/// Subtracts the external force at `load_factor` (`load_factor f_ref`, each
/// load with a curve scaled by it instead, [`Model::factor`]); returns its
/// norm.
pub fn add_external<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    load_factor: f64,
    sys: &mut System,
) -> f64
where
    Dim<D>: SurfaceDim<D>,
{
    let mut f = vec![0.0; model.dof_count()];
    for l in &model.loads {
        f[l.dof.index()] += model.factor(l.amplitude, load_factor) * l.value;
    }
    for (dof, v) in f.iter().enumerate() {
        if let Some(e) = dofs.eq(DofId::new(dof)) {
            sys.residual[e.index()] -= v;
        }
    }
    f.iter().map(|v| v * v).sum::<f64>().sqrt()
}
