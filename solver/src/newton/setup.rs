//! The discretised problem a Newton iteration works on, and the phases of
//! one iteration on it.
//!
//! [`Setup`] is built once per solve (and once per [`super::IterationProbe`])
//! from a checked [`Model`] and the [`SolveOptions`]: the contact layout, the
//! equation numbering, the mesh size and the linear solver (which keeps its
//! symbolic analysis across iterations). Its methods are the phases of an
//! iteration, in the order [`super::attempt`] calls them:
//!
//! 1. the contact evaluation, by the treatment of contact
//!    ([`super::treatment`]: the complete formulation re-projects,
//!    `complete::evaluate`; Types 1–6 expand their frozen Taylor
//!    coefficients);
//! 2. the contact system ([`Setup::contact_system`]): active set, contact
//!    and tie contributions into a fresh [`System`];
//! 3. the solid elements and the external force ([`Setup::add_solid`]);
//! 4. the regularised linear solve ([`Setup::solve`]).
//!
//! Across MPI ranks (`crate::partition`) each rank adds its share of the
//! contact element in phase 2 (the points and multipliers of the slave
//! nodes it owns, [`ContactShare`]) and its own elements in phase 3, rank 0
//! alone the friction, the ties, the external force and the
//! regularisation; [`Setup::sum_over_ranks`] then sums the residual and the
//! energy, so that every rank tests convergence on the whole residual, and
//! the linear solver sums the ranks' triplets. On one rank nothing changes.
//!
//! Invariant: the order of the contributions in the system (contact, ties,
//! solid, external force, regularisation) is fixed here, for the solve and
//! the probe alike; it fixes the triplet order and so every floating-point
//! sum of the assembly.

use std::cell::Cell;

use std::sync::Arc;

use crate::assembly::{add_external, assemble_solid_of, external_force_norm, solid_pattern};
use crate::contact::{ContactShare, ContactSpace};
use crate::contact::{KernelCounts, NodeTie, PointFailure};
use crate::error::SolverError;
use crate::ids::ContactPointIndex;
use crate::linear::{BlockPattern, LinearError, LinearSolver};
use crate::mesh::{Geometries, InvertedElement};
use crate::model::Model;
use crate::options::SolveOptions;
use crate::partition::Partition;
use crate::solution::ContactPointId;
use crate::system::{DofMap, MAX_EQUATIONS, System};

use super::regularize::regularize;
use crate::model::{Dim, SurfaceDim};

/// The discretised problem of one solve (module docs).
pub(super) struct Setup<'a, const D: usize, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The model solved.
    pub(super) model: &'a Model<D>,
    /// The contact element: integration points, multipliers and masters
    /// (2D segments or 3D faces, [`ContactSpace`]).
    pub(super) layout: S,
    /// Equation numbers of the free dofs and the multipliers.
    pub(super) dofs: DofMap,
    /// The linear solver, with its cached symbolic analysis.
    pub(super) linear: Box<dyn LinearSolver>,
    /// The mesh size (scales the active-set threshold).
    pub(super) length_scale: f64,
    /// This MPI rank's elements (every element on one rank).
    pub(super) partition: Partition,
    /// This rank's share of the contact element (`None`: one rank, the
    /// whole element).
    contact_share: Option<ContactShare>,
    /// The reference geometry of this rank's elements (every element's on
    /// one rank).
    pub(super) geometries: Geometries,
    /// The pattern of this rank's solid elements' entries, when the linear
    /// solver takes the solid block ([`LinearSolver::takes_block`]): every
    /// system gets a block over it.
    block: Option<Arc<BlockPattern>>,
    /// The buffers of the last solved system, handed back by
    /// [`Setup::recycle`] and reused by the next [`Setup::contact_system`]
    /// (the triplet count barely changes between iterations; at 10^6
    /// equations the fresh pages of a new system cost more than its
    /// assembly's arithmetic).
    spare: Cell<Option<System>>,
}

impl<'a, const D: usize, S: ContactSpace<D>> Setup<'a, D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Checks `model` and lays out its contact pairs and equations with
    /// `options.formulation` and `options.linear`.
    pub(super) fn new(
        model: &'a Model<D>,
        options: &SolveOptions,
    ) -> Result<Setup<'a, D, S>, SolverError> {
        model.check()?;
        let layout = S::build(model, options.formulation)?;
        let dofs = DofMap::new(model, layout.multiplier_count());
        // the node ties come after the multipliers: at most one per dof
        let equations = dofs.n_eq().saturating_add(model.dof_count());
        if equations > MAX_EQUATIONS {
            return Err(SolverError::TooManyEquations { equations });
        }
        let mut linear = options.linear.build(&options.petsc_options);
        let partition = Partition::of(
            model,
            linear.as_ref(),
            layout.multipliers(),
            layout.point_count(),
        )?;
        let mut system_layout = dofs.layout(model);
        system_layout.node_rank = partition.node_rank.clone();
        linear.set_layout(&system_layout);
        let block = if linear.takes_block() {
            Some(Arc::new(solid_pattern(model, &dofs, partition.elements())?))
        } else {
            None
        };
        let contact_share = partition.contact_share(layout.multipliers());
        let geometries = Geometries::of(&model.mesh, partition.elements())?;
        Ok(Setup {
            model,
            contact_share,
            geometries,
            layout,
            dofs,
            linear,
            length_scale: model.mesh.size(),
            partition,
            block,
            spare: Cell::new(None),
        })
    }

    /// Sets the prescribed dofs of `u` to their values at load factor `to`
    /// (`to u_ref`, or `a(to) u_ref` with a load curve; see
    /// [`Model::factor`]). The values are absolute, so the step's predictor
    /// (free dofs at the converged state, prescribed dofs at the target)
    /// carries the prescribed increment whatever its sign: a curve that
    /// goes down, or back, moves the dofs back.
    pub(super) fn prescribe(&self, u: &mut [f64], to: f64) {
        for p in &self.model.prescribed {
            u[p.dof.index()] = self.model.factor(p.amplitude, to) * p.value;
        }
    }

    /// The increment of the prescribed dofs from `u` to load factor `to`
    /// (every dof's entry, zero on the free ones), or `None` when every
    /// prescribed dof of `u` already has its value at `to` (bit for bit):
    /// the lift of the linearised Dirichlet predictor (see [`super`],
    /// "Prescribed increments").
    pub(super) fn lift(&self, u: &[f64], to: f64) -> Option<Vec<f64>> {
        let mut target = u.to_vec();
        self.prescribe(&mut target, to);
        let moved = self
            .model
            .prescribed
            .iter()
            .any(|p| target[p.dof.index()].to_bits() != u[p.dof.index()].to_bits());
        moved.then(|| target.iter().zip(u).map(|(t, u)| t - u).collect())
    }

    /// The factor `s` of the secant predictor (see [`super`], "Prescribed
    /// increments"): the least-squares fit `lift ~ s (u - previous)` on the
    /// prescribed dofs, when it is positive (`None` when the last step moved
    /// no prescribed dof or moved them against or across this one's `lift`).
    pub(super) fn extrapolation(&self, lift: &[f64], u: &[f64], previous: &[f64]) -> Option<f64> {
        let (mut along, mut norm) = (0.0, 0.0);
        for p in &self.model.prescribed {
            let d = u[p.dof.index()] - previous[p.dof.index()];
            along += lift[p.dof.index()] * d;
            norm += d * d;
        }
        let s = along / norm;
        (norm > 0.0 && s > 0.0 && s.is_finite()).then_some(s)
    }

    /// Pairs every point from scratch at displacements `u` (see
    /// [`ContactSpace::initial_pairing`]).
    #[allow(clippy::type_complexity)] // the layouts' own signature
    pub(super) fn initial_pairing(
        &self,
        u: &[f64],
    ) -> Result<(Vec<Option<S::Master>>, KernelCounts), PointFailure<S::Master>> {
        self.layout.initial_pairing(&self.model.mesh, u)
    }

    /// The integration point of a kernel failure.
    pub(super) fn failure_point(&self, f: &PointFailure<S::Master>) -> ContactPointId {
        self.layout.point_id(f.point, f.master_segment)
    }

    /// Integration point `i` (no master segment).
    pub(super) fn point_id(&self, i: ContactPointIndex) -> ContactPointId {
        self.layout.point_id(i, None)
    }

    /// A kernel failure at a state of load factor `load_factor` as the
    /// solve's error.
    pub(super) fn kernel_error(
        &self,
        f: &PointFailure<S::Master>,
        load_factor: f64,
    ) -> SolverError {
        SolverError::Kernel {
            point: self.failure_point(f),
            load_factor,
            error: f.error,
        }
    }

    /// The active multipliers at `(evals, lambda)` (in the `first`
    /// iteration of an attempt also the touching nodes of unilateral pairs
    /// without contact, [`ContactSpace::active`]) and a fresh
    /// system (one equation per free dof, multiplier and tie; in the buffers
    /// [`Setup::recycle`] kept, if any) holding the
    /// contact contributions of `evals` and then those of the `ties` (with
    /// `others`, their evaluations on the other segment).
    pub(super) fn contact_system(
        &self,
        evals: &[Option<S::Eval>],
        others: &[S::Eval],
        lambda: &[f64],
        ties: &[NodeTie<S::Master>],
        first: bool,
    ) -> (System, Vec<bool>) {
        let active = self.layout.active(evals, lambda, self.length_scale, first);
        let n_sys = self.dofs.n_eq() + ties.len();
        let mut sys = match self.spare.take() {
            Some(mut sys) => {
                sys.reset(n_sys);
                sys
            }
            None => match &self.block {
                Some(pattern) => System::with_block(n_sys, pattern.clone()),
                None => System::new(n_sys),
            },
        };
        self.layout.assemble(
            evals,
            lambda,
            &active,
            &self.dofs,
            self.contact_share.as_ref(),
            &mut sys,
        );
        if self.partition.assembles_root_terms() {
            S::assemble_ties(ties, evals, others, &self.dofs, &mut sys);
        }
        (sys, active)
    }

    /// Adds the solid elements at displacements `u` (with a `lift`, the
    /// linearised effect of that prescribed increment,
    /// [`crate::assembly::assemble_solid_lifted`]) and the external force at
    /// load factor `to` to `sys`; returns `|f_ext|`. Across MPI ranks, this
    /// rank's elements, and the external force on rank 0 only
    /// ([`Setup::sum_over_ranks`] then makes the system whole).
    pub(super) fn add_solid(
        &self,
        u: &[f64],
        lift: Option<&[f64]>,
        to: f64,
        sys: &mut System,
    ) -> f64 {
        assemble_solid_of(self.model, &self.geometries, &self.dofs, u, lift, sys);
        if self.partition.assembles_root_terms() {
            add_external(self.model, &self.dofs, to, sys)
        } else {
            external_force_norm(self.model, to)
        }
    }

    /// Sums the residual and the energy of `sys` over the MPI ranks, so
    /// that every rank holds the whole residual (its own triplets stay its
    /// own: the linear solver sums them); nothing on one rank.
    pub(super) fn sum_over_ranks(&self, sys: &mut System) -> Result<(), SolverError> {
        if self.partition.ranks.size <= 1 {
            return Ok(());
        }
        sys.residual.push(sys.energy);
        let summed = self.linear.sum_over_ranks(&mut sys.residual);
        sys.energy = sys.residual.pop().unwrap_or(0.0);
        Ok(summed?)
    }

    /// The element of smallest `det F <= 0` at `u`
    /// ([`Geometries::most_inverted`]), across MPI ranks the worst of every
    /// rank's own elements (the smallest `det F`, the lowest element on a
    /// tie, as on one rank; collective), `None` when no element inverts.
    pub(super) fn most_inverted(&self, u: &[f64]) -> Result<Option<InvertedElement>, LinearError> {
        let mine = self.geometries.most_inverted(&self.model.mesh, u);
        if self.partition.ranks.size <= 1 {
            return Ok(mine);
        }
        // the largest -det F, then the largest -element among the ranks
        // that have it (-inf: none)
        let mut worst = [mine.as_ref().map_or(f64::NEG_INFINITY, |i| -i.det_f)];
        self.linear.max_over_ranks(&mut worst)?;
        let mut first = [mine
            .as_ref()
            .filter(|i| -i.det_f == worst[0])
            .map_or(f64::NEG_INFINITY, |i| -(i.element as f64))];
        self.linear.max_over_ranks(&mut first)?;
        if worst[0] == f64::NEG_INFINITY {
            return Ok(None);
        }
        let element = (-first[0]) as usize;
        Ok(Some(InvertedElement {
            element,
            det_f: -worst[0],
            label: self.model.mesh.element_label(element),
        }))
    }

    /// Keeps `sys`'s buffers for the next [`Setup::contact_system`].
    pub(super) fn recycle(&self, sys: System) {
        self.spare.set(Some(sys));
    }

    /// Adds the multiplier regularisation `delta` (see
    /// [`super::regularize`]) to `sys` and solves `K dx = r`, an iterative
    /// solver to the relative residual [`forcing`] gives for Newton's
    /// residual `norm` against the convergence bound `tol_abs` and the
    /// attempt's first residual `first`.
    pub(super) fn solve(
        &mut self,
        sys: &mut System,
        active: &[bool],
        delta: f64,
        (norm, first, tol_abs): (f64, f64, f64),
    ) -> Result<Vec<f64>, LinearError> {
        regularize(
            sys,
            &self.dofs,
            active,
            delta,
            |m| self.linear.max_over_ranks(m),
            self.partition.assembles_root_terms(),
        )?;
        self.linear.set_forcing(forcing(norm, first, tol_abs));
        self.linear.solve_system_with(
            sys.residual.len(),
            sys.block.as_ref(),
            (&sys.rows, &sys.cols, &sys.vals),
            &sys.residual,
        )
    }
}

/// The largest relative residual asked of an iterative linear solve.
pub(super) const FORCING_MAX: f64 = 1e-6;
/// The smallest (below it a solve is round-off).
pub(super) const FORCING_MIN: f64 = 1e-12;

/// Newton's forcing term: the relative residual `|b - A dx| / |b|` an
/// iterative solve must reach at a Newton residual `norm`, when the
/// attempt started at `first` and converges at `tol_abs`.
///
/// `norm / first`, so that the linear error shrinks with the residual and
/// Newton stays quadratic near the solution (Eisenstat and Walker's
/// choice for quadratic convergence: `eta_k ~ |r_k|`), at most
/// [`FORCING_MAX`]; but never tighter than the `0.1 tol_abs / norm` that
/// already takes the next residual below a tenth of the bound, so the last
/// solve is not over-solved; at least [`FORCING_MIN`].
pub(super) fn forcing(norm: f64, first: f64, tol_abs: f64) -> f64 {
    let quadratic = if first > 0.0 {
        norm / first
    } else {
        FORCING_MAX
    };
    let enough = if norm > 0.0 {
        0.1 * tol_abs / norm
    } else {
        FORCING_MAX
    };
    quadratic
        .min(FORCING_MAX)
        .max(enough.min(FORCING_MAX))
        .max(FORCING_MIN)
}
