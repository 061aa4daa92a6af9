//! [`IterationProbe`]: one Newton iteration of the complete formulation at a
//! fixed state, phase by phase, for benchmarks and profiling.
//!
//! The probe builds the same [`Setup`] as a solve and runs the same phase
//! methods on it, so what it times is what a solve runs. Invariant: the
//! probe's state is never updated, so every call repeats the same
//! iteration (only the first linear solve does the symbolic analysis).

use std::time::Instant;

use crate::contact::ContactSpace;
use crate::contact::KernelCounts;
use crate::dim::SpaceDim;
use crate::error::SolverError;
use crate::model::Dim;
use crate::model::Model;
use crate::options::{Method, SolveOptions};
use crate::solution::State;
use crate::system::System;

use super::complete;
use super::setup::Setup;

/// The contact phase of one Newton iteration ([`IterationProbe::contact`]):
/// a fresh system holding the contact contributions, and which multipliers
/// carry a constraint row.
#[derive(Debug, Clone)]
pub struct ContactPhase {
    /// Residual and triplets with the contact terms only.
    pub system: System,
    /// Active multipliers (see [`ActiveSetView::active_multipliers`](crate::contact::ActiveSetView::active_multipliers)).
    pub active: Vec<bool>,
}

/// Wall-clock time of the phases of one probed iteration, split as in
/// [`Timings`](crate::Timings), and the residual norm at the probed state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IterationSample {
    /// Re-projection, Type 6 kernel, active set and contact scatter.
    pub contact_evaluation: std::time::Duration,
    /// Solid elements and external force.
    pub solid_assembly: std::time::Duration,
    /// Regularisation, numeric LU (symbolic analysis only when the pattern
    /// changed) and solve.
    pub linear_solve: std::time::Duration,
    /// `|r|` at the probed state.
    pub residual_norm: f64,
}

impl IterationSample {
    /// The sum of the three phases.
    pub fn total(&self) -> std::time::Duration {
        self.contact_evaluation + self.solid_assembly + self.linear_solve
    }
}

/// One Newton iteration of the **complete** formulation at a fixed state,
/// split into the phases that [`Timings`](crate::Timings) reports — for benchmarks and
/// profiling (`benches/solver_scaling.rs`, `examples/scaling_table/`).
///
/// Each phase calls the same setup and phase code as an iteration of
/// [`crate::solve`]:
/// [`contact`](Self::contact) re-projects every slave integration point
/// onto its paired master segment (the probe pairs from scratch at its
/// state and has no node ties), evaluates the Type 6 kernel and scatters
/// the contact terms into a fresh
/// [`System`]; [`solid`](Self::solid) adds the solid elements and the
/// external force; [`linear_solve`](Self::linear_solve) adds the multiplier
/// regularisation and solves with the probe's [`LinearSolver`](crate::linear::LinearSolver), whose
/// symbolic factorisation is computed on the first call and reused after.
/// The state is never updated, so every call repeats the same iteration.
///
/// Generic over the dimension `D` as the solve is, with the dimension's
/// contact element ([`SpaceDim::Contact`]); a 3D model without face pairs
/// has an empty contact phase, and the probe times the solid assembly and
/// the linear solve.
pub struct IterationProbe<'a, const D: usize = 2>
where
    Dim<D>: SpaceDim<D>,
{
    setup: Setup<'a, D, ContactOf<D>>,
    regularization: f64,
    u: Vec<f64>,
    lambda: Vec<f64>,
    pairing: Vec<Option<<ContactOf<D> as ContactSpace<D>>::Master>>,
    /// With friction, every point's anchor at the probe's state (as at a
    /// step's start: the slips are zero there, their derivatives are not).
    anchors: Vec<Option<<ContactOf<D> as ContactSpace<D>>::Anchor>>,
    load_factor: f64,
}

/// The contact element of dimension `D`.
type ContactOf<const D: usize> = <Dim<D> as SpaceDim<D>>::Contact;

impl<'a, const D: usize> IterationProbe<'a, D>
where
    Dim<D>: SpaceDim<D>,
{
    /// The iteration from `state` (e.g. a converged
    /// [`Solution::final_state`](crate::Solution::final_state)) towards load factor `load_factor`: the
    /// prescribed dofs are set to `load_factor u_ref` and the external force
    /// is `load_factor f_ref` (each item with a load curve scaled by it
    /// instead), as in the first iteration of a step ending there. The points are paired from scratch at `state`. Uses
    /// `options.formulation` and `options.regularization`; `options.method`
    /// must be [`Method::Complete`].
    pub fn new(
        model: &'a Model<D>,
        options: &SolveOptions,
        state: &State<D>,
        load_factor: f64,
    ) -> Result<IterationProbe<'a, D>, SolverError> {
        if options.method != Method::Complete {
            return Err(SolverError::Options(format!(
                "the iteration probe evaluates the complete formulation, not `{}`",
                options.method
            )));
        }
        let setup = Setup::<D, ContactOf<D>>::new(model, options)?;
        if setup.partition.ranks.size > 1 {
            return Err(SolverError::Options(format!(
                "the iteration probe measures one process, and this one is rank {} of {} (mpiexec): \
                 run it without mpiexec",
                setup.partition.ranks.rank, setup.partition.ranks.size
            )));
        }
        let n_mult = setup.dofs.n_mult;
        let nodes = model.mesh.node_count();
        if state.displacements.len() != nodes || state.multipliers.len() != n_mult {
            return Err(SolverError::Options(format!(
                "state has {} displacements and {} multipliers, the model {} nodes and {} multipliers",
                state.displacements.len(),
                state.multipliers.len(),
                nodes,
                n_mult
            )));
        }
        let mut u: Vec<f64> = state.displacements.iter().flatten().copied().collect();
        setup.prescribe(&mut u, load_factor);
        let (pairing, _) = setup
            .initial_pairing(&u)
            .map_err(|f| setup.kernel_error(&f, load_factor))?;
        let anchors = if setup.layout.has_friction() {
            let (found, _) = setup
                .layout
                .project_all(&model.mesh, &u, &pairing)
                .map_err(|f| setup.kernel_error(&f, load_factor))?;
            setup.layout.found_anchors(&model.mesh, &u, &found)
        } else {
            Vec::new()
        };
        Ok(IterationProbe {
            regularization: options.regularization,
            u,
            lambda: state.multipliers.clone(),
            pairing,
            anchors,
            load_factor,
            setup,
        })
    }

    /// Number of equations (free dofs plus multipliers).
    pub fn equations(&self) -> usize {
        self.setup.dofs.n_eq()
    }

    /// Number of slave integration points.
    pub fn contact_points(&self) -> usize {
        self.setup.layout.point_count()
    }

    /// Symbolic factorisations computed so far (1 after the first
    /// [`linear_solve`](Self::linear_solve)).
    pub fn symbolic_factorisations(&self) -> usize {
        self.setup.linear.symbolic_factorisations()
    }

    /// Time spent in symbolic analysis so far.
    pub fn symbolic_time(&self) -> std::time::Duration {
        self.setup.linear.symbolic_time()
    }

    /// Linear solves so far that fell back to LU (see
    /// [`crate::linear::LinearSolver::fallbacks`]).
    pub fn linear_fallbacks(&self) -> usize {
        self.setup.linear.fallbacks()
    }

    /// Nonzeros of the factor (see
    /// [`crate::linear::LinearSolver::factor_nonzeros`]); `None` before the
    /// first [`linear_solve`](Self::linear_solve) or with LU.
    pub fn factor_nonzeros(&self) -> Option<usize> {
        self.setup.linear.factor_nonzeros()
    }

    /// Phase 1: re-projection and Type 6 kernel at every integration point
    /// (with friction, the Type 6 slip too, from the anchors at the probe's
    /// state), active set, and the contact scatter into a fresh system.
    pub fn contact(&self) -> Result<ContactPhase, SolverError> {
        let mut counts = KernelCounts::default();
        let (mut evals, others) =
            complete::evaluate(&self.setup, &self.u, &self.pairing, &[], false, &mut counts)
                .map_err(|f| self.setup.kernel_error(&f, self.load_factor))?;
        if !self.anchors.is_empty() {
            self.setup
                .layout
                .add_slips(
                    &self.setup.model.mesh,
                    &self.u,
                    &mut evals,
                    &self.anchors,
                    complete::DERIVATIVES,
                    &mut counts,
                )
                .map_err(|f| self.setup.kernel_error(&f, self.load_factor))?;
        }
        let (system, active) = self
            .setup
            .contact_system(&evals, &others, &self.lambda, &[], false);
        Ok(ContactPhase { system, active })
    }

    /// Phase 2: adds the solid elements' forces and tangents and the
    /// external force to `system`; returns `|f_ext|`.
    pub fn solid(&self, system: &mut System) -> f64 {
        self.setup
            .add_solid(&self.u, None, self.load_factor, system)
    }

    /// Phase 3: regularisation and the linear solve of the assembled
    /// system (contact then solid, as in a solve); returns the Newton
    /// correction `dx` with `K dx = r` (an iterative solver to the forcing
    /// term of an attempt's first iteration, as a Newton step from this
    /// state would ask).
    pub fn linear_solve(&mut self, assembled: ContactPhase) -> Result<Vec<f64>, SolverError> {
        let ContactPhase { mut system, active } = assembled;
        let norm = system.residual_norm();
        let solved = self
            .setup
            .solve(&mut system, &active, self.regularization, (norm, norm, 0.0));
        self.setup.recycle(system);
        solved.map_err(|e| SolverError::Singular {
            load_factor: self.load_factor,
            attempted: self.load_factor,
            cutbacks: 0,
            message: e.to_string(),
        })
    }

    /// The three phases in order, timed.
    pub fn iteration(&mut self) -> Result<IterationSample, SolverError> {
        let t = Instant::now();
        let mut phase = self.contact()?;
        let contact_evaluation = t.elapsed();
        let t = Instant::now();
        self.solid(&mut phase.system);
        let solid_assembly = t.elapsed();
        let residual_norm = phase.system.residual_norm();
        let t = Instant::now();
        self.linear_solve(phase)?;
        let linear_solve = t.elapsed();
        Ok(IterationSample {
            contact_evaluation,
            solid_assembly,
            linear_solve,
            residual_norm,
        })
    }
}

#[cfg(test)]
mod tests {
    use contact_kernels::ApproxType;

    use super::*;
    use crate::Scene;
    use crate::ids::{DofId, MultiplierIndex};
    use crate::system::DofMap;

    /// The probe reproduces the solver's own iterates: from the reference
    /// state towards the first step's load factor, its residual norm is the
    /// step's first one, and after applying its correction the second.
    #[test]
    fn probe_matches_the_first_newton_iterations() {
        let scene = Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "paper")
            .unwrap()
            .refined(2, 1);
        let mut model = scene.build_model().unwrap();
        // the first of four steps only
        model.load_factor_end /= 4.0;
        let opts = SolveOptions {
            steps: 1,
            ..SolveOptions::default()
        };
        let solution = crate::solve_model(&model, &opts).unwrap();
        let first = &solution.step_records[0];
        let to = first.load_factor;
        let n = model.mesh.node_count();
        let zero = State {
            load_factor: 0.0,
            friction: Vec::new(),
            displacements: vec![[0.0; 2]; n],
            multipliers: vec![0.0; solution.multiplier_dofs.len()],
        };
        let mut probe = IterationProbe::new(&model, &opts, &zero, to).unwrap();
        assert_eq!(probe.equations(), solution.equations);
        let sample = probe.iteration().unwrap();
        let r0 = first.residuals[0];
        assert!((sample.residual_norm - r0).abs() <= 1e-12 * r0);
        // apply the correction as the solver does
        let mut phase = probe.contact().unwrap();
        probe.solid(&mut phase.system);
        let dx = probe.linear_solve(phase).unwrap();
        assert_eq!(probe.symbolic_factorisations(), 1);
        let dofs = DofMap::new(&model, zero.multipliers.len());
        let mut u = vec![0.0; 2 * n];
        for (dof, ud) in u.iter_mut().enumerate() {
            if let Some(e) = dofs.eq(DofId::new(dof)) {
                *ud -= dx[e.index()];
            }
        }
        let next = State {
            load_factor: 0.0,
            friction: Vec::new(),
            displacements: u.chunks(2).map(|c| [c[0], c[1]]).collect(),
            multipliers: (0..dofs.n_mult)
                .map(|m| -dx[dofs.mult_eq(MultiplierIndex::new(m)).index()])
                .collect(),
        };
        let probe = IterationProbe::new(&model, &opts, &next, to).unwrap();
        let mut phase = probe.contact().unwrap();
        probe.solid(&mut phase.system);
        let r1 = first.residuals[1];
        assert!((phase.system.residual_norm() - r1).abs() <= 1e-9 * r0);
        // only the complete formulation is probed
        let approx = SolveOptions {
            method: Method::Approx(ApproxType::Type3),
            ..opts.clone()
        };
        assert!(IterationProbe::new(&model, &approx, &zero, to).is_err());
    }

    /// In 3D (no contact) the probe's first residual is the solve's, its
    /// contact phase is empty, and its correction gives the solve's second
    /// residual.
    #[test]
    fn probe_matches_the_first_newton_iterations_in_3d() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/block3d.toml");
        let scene = Scene::from_file(&path).unwrap();
        let mut model = scene.build_model::<3>().unwrap();
        model.load_factor_end /= 2.0;
        let opts = SolveOptions {
            steps: 1,
            ..SolveOptions::from_scene(&scene)
        };
        let solution = crate::solve_model(&model, &opts).unwrap();
        let first = &solution.step_records[0];
        let n = model.mesh.node_count();
        let zero = State::<3> {
            load_factor: 0.0,
            friction: Vec::new(),
            displacements: vec![[0.0; 3]; n],
            multipliers: Vec::new(),
        };
        let mut probe = IterationProbe::new(&model, &opts, &zero, first.load_factor).unwrap();
        assert_eq!(probe.equations(), solution.equations);
        assert_eq!(probe.contact_points(), 0);
        let sample = probe.iteration().unwrap();
        let r0 = first.residuals[0];
        assert!((sample.residual_norm - r0).abs() <= 1e-12 * r0);
        let mut phase = probe.contact().unwrap();
        assert!(phase.system.vals.is_empty() && phase.active.is_empty());
        probe.solid(&mut phase.system);
        let dx = probe.linear_solve(phase).unwrap();
        assert_eq!(probe.symbolic_factorisations(), 1);
        assert_eq!(probe.linear_fallbacks(), 0);
        let dofs = DofMap::new(&model, 0);
        let mut u = vec![0.0; 3 * n];
        for (dof, ud) in u.iter_mut().enumerate() {
            if let Some(e) = dofs.eq(DofId::new(dof)) {
                *ud -= dx[e.index()];
            }
        }
        let next = State::<3> {
            load_factor: 0.0,
            friction: Vec::new(),
            displacements: u.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
            multipliers: Vec::new(),
        };
        let probe = IterationProbe::new(&model, &opts, &next, first.load_factor).unwrap();
        let mut phase = probe.contact().unwrap();
        probe.solid(&mut phase.system);
        let r1 = first.residuals[1];
        assert!((phase.system.residual_norm() - r1).abs() <= 1e-9 * r0);
    }
}
