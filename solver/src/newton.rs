//! Load stepping, Newton–Raphson and cut-back.
//!
//! The load factor goes from 0 to `lambda_end` in `N` equal scheduled steps.
//! Each step is solved by Newton's method on the free displacements and the
//! multipliers:
//!
//! 1. prescribed dofs are set to `lambda_L u_ref` of the step's target;
//! 2. Types 1–6: at the step start (converged state `u0`) every contact
//!    integration point is re-paired and the type's Taylor coefficients are
//!    evaluated; they stay frozen during the step. Complete: every iteration
//!    re-projects and evaluates the exact kernel on the paired master
//!    segments;
//! 3. iterate `K du = -r` until `|r| <= tol max(1, |lambda_L f_ref|)`
//!    (Euclidean norms; `r` over the free dofs and the multipliers;
//!    `tol = 1e-10` by default);
//! 4. complete formulation: at a converged iterate, re-pair the points
//!    whose projection left their master segment (and tie or release the
//!    points stuck at a master node); if anything changed, evaluate the
//!    same iterate again and go on with step 3. The pairing changes only
//!    there, apart from the first [`REPAIR_AT_ONCE_ITERATIONS`] iterates;
//!    see [`crate::contact`], "Pairing in the complete formulation", for
//!    why (re-pairing at every iteration made Newton cycle on refined
//!    meshes). Each tie adds one equation after the multipliers.
//!
//! A step's residual history ([`crate::StepRecord::residuals`]) then holds
//! one more entry per pairing change (the same iterate, evaluated again);
//! the iteration count is the number of linear solves.
//!
//! Round-off floor: the residual of a fine mesh with large displacements
//! cannot be evaluated more accurately than about
//! `eps E |u| / h` per element (absolute displacements over small elements),
//! which may exceed `1e-10 |f|`. From the third iterate on (of the current
//! pairing), a residual below `100 tol max(1, |f|)` that no longer halves
//! per iteration is accepted as converged and the step is flagged
//! (`StepRecord::roundoff_floor`); Newton's quadratic convergence makes this
//! unambiguous. The paper scene converges far below the tolerance and never
//! uses it.
//!
//! Multiplier regularisation (tangent only): the linearised constraints can
//! be rank deficient. In the paper scene, both layers are clamped at
//! `x = 0`, so in the reference configuration the interface gap is a
//! function of the 7 free interface offsets while there are 8 multiplier
//! rows: the saddle-point matrix is exactly singular in one multiplier
//! direction, the LU's round-off picks an arbitrary (load-proportional)
//! component there, and with a gap Hessian (Types 2–6, complete) Newton
//! stalls in the first step. Each linear solve therefore uses the tangent
//! with `-eps` on the diagonal of the active multiplier rows,
//! `eps = delta max|G|^2 / max|K_uu|` (`delta` =
//! [`DEFAULT_REGULARIZATION`], [`crate::SolveOptions::regularization`]),
//! which selects the minimum-norm multiplier in a null direction. The
//! residual is not modified, so converged states are those of the
//! unregularised problem; for `delta` in `[1e-12, 1e-8]` the paper scene's
//! results and iteration counts do not depend on `delta`.
//!
//! An attempt fails when the residual is not finite, grows above
//! `1e10 max(|r_0|, 1)`, the iteration limit is reached, the linear system is
//! singular (see [`crate::linear`]), a kernel fails during the iterations
//! or (complete formulation) a point stuck at the end of a master chain
//! misses it by more than the band. A failed attempt is discarded (the
//! converged state is restored) and the increment is halved; the rest of
//! the scheduled step is
//! then done with the halved increment. Each cut-back is recorded; after
//! `max_cutbacks` cut-backs within one scheduled step (or when a further
//! halving could not advance the load factor) the solve stops with a
//! [`SolverError`]. A kernel failure at a converged state (step start) stops
//! the solve at once, since a smaller increment cannot change that state.
//!
//! [`IterationProbe`] runs one iteration of the complete formulation at a
//! given state, phase by phase, with the same code (for benchmarks).

use std::time::Instant;

use contact_kernels::ApproxType;

use crate::assembly::{
    DofMap, System, add_external, assemble_contact, assemble_solid, assemble_ties,
};
use crate::contact::{
    ContactLayout, KernelCounts, NodeTie, PairingUpdate, PointEval, PointFailure, Taylor,
    XI_STUCK_BAND,
};
use crate::error::SolverError;
use crate::linear::LinearSolver;
use crate::model::Model;
use crate::options::{Method, SolveOptions};
use crate::solution::{
    ContactPointId, ContactPointReport, Cutback, CutbackReason, MultiplierDofInfo, Solution, State,
    StepRecord, Timings,
};

/// The residual may grow to this factor times `max(|r_0|, 1)` before an
/// attempt counts as diverging.
pub const DIVERGENCE_FACTOR: f64 = 1e10;

/// An iterate whose residual is within this factor of the tolerance and no
/// longer halves per iteration has reached the round-off floor of the
/// residual evaluation and is accepted (and flagged in the step record).
pub const STAGNATION_FACTOR: f64 = 100.0;

/// Complete formulation: in this many first iterates of an attempt
/// (iterates 1 and 2, after the first corrections), a point whose
/// projection leaves its master segment is re-paired at once; from then on
/// the pairing only changes at converged iterates (module docs).
pub const REPAIR_AT_ONCE_ITERATIONS: usize = 2;

pub use crate::options::DEFAULT_REGULARIZATION;

/// The integration point of a kernel failure.
fn failure_point(layout: &ContactLayout, f: &PointFailure) -> ContactPointId {
    let p = &layout.points[f.point];
    ContactPointId {
        pair: p.pair,
        slave_segment: p.slave_segment,
        gauss: p.gauss,
        master_segment: f.master_segment,
    }
}

/// Adds the tangent-only multiplier regularisation (module docs): `-eps` on
/// the diagonal of the active multiplier rows (an explicit zero on the
/// inactive ones, so the pattern does not depend on the active set), with
/// `eps = delta max|G|^2 / max|K_uu|`. Nothing when `delta` is 0 or there
/// are no multipliers.
fn regularize(sys: &mut System, dofs: &DofMap, active: &[bool], delta: f64) {
    if !(delta > 0.0) || dofs.n_mult == 0 {
        return;
    }
    let n_free = dofs.n_free;
    let (mut k_max, mut g_max) = (0.0_f64, 0.0_f64);
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        if r < n_free && c < n_free {
            k_max = k_max.max(v.abs());
        } else if r < n_free || c < n_free {
            g_max = g_max.max(v.abs());
        }
    }
    let eps = if k_max > 0.0 {
        delta * g_max * g_max / k_max
    } else {
        0.0
    };
    for (m, &on) in active.iter().enumerate() {
        let row = dofs.mult_eq(m);
        sys.rows.push(row);
        sys.cols.push(row);
        sys.vals.push(if on { -eps } else { 0.0 });
    }
}

/// What [`PairingGuard::apply`] decided at a converged iterate.
#[derive(Debug, Clone, PartialEq)]
enum GuardOutcome {
    /// Some points were re-paired or tied: iterate on.
    Changed,
    /// The pairing stands. Lists the points kept on a pairing their
    /// projection misses by less than [`XI_STUCK_BAND`].
    Settled(Vec<usize>),
    /// A point's pairing cycles and its projection misses by more than the
    /// band.
    Stuck {
        /// The point.
        point: usize,
        /// Its projection coordinate (on its master segment, or for an
        /// inactive point on the segment it projects into).
        xi_m: f64,
    },
}

/// The pairing changes of one attempt of the complete formulation (module
/// docs of [`crate::contact`], "Pairing in the complete formulation" and
/// "Points stuck at a master node").
#[derive(Debug, Default)]
struct PairingGuard {
    /// `(point, pairing)` the point has been switched away from.
    left: Vec<(usize, Option<usize>)>,
    /// Points released from a tie in this attempt: one more switch (the
    /// side `theta` chose may be wrong when other points moved meanwhile).
    released: Vec<usize>,
    /// Points that made their last allowed switch in this attempt.
    settled: Vec<usize>,
}

impl PairingGuard {
    /// Applies the pairing `updates` due at a converged iterate with
    /// contact evaluations `evals` (see
    /// [`ContactLayout::pairing_updates`]; tied points excluded) to
    /// `pairing`, tying a point whose pairing cycles between two adjacent
    /// master segments (appended to `ties`).
    fn apply(
        &mut self,
        layout: &ContactLayout,
        updates: &[PairingUpdate],
        evals: &[Option<PointEval>],
        pairing: &mut [Option<usize>],
        ties: &mut Vec<NodeTie>,
    ) -> GuardOutcome {
        let mut changed = false;
        let mut kept = Vec::new();
        for &(i, target) in updates {
            let current = pairing[i];
            let to = target.map(|(m, _)| m);
            // how far the projection misses the current pairing
            let (xi_m, within) = match (&evals[i], target) {
                (Some(e), _) => (e.xi_m, e.xi_m.abs() <= 1.0 + XI_STUCK_BAND),
                (None, Some((_, p))) => (p.xi_m, p.xi_m.abs() >= 1.0 - XI_STUCK_BAND),
                (None, None) => (f64::NAN, true),
            };
            if self.settled.contains(&i) {
                if !within {
                    return GuardOutcome::Stuck { point: i, xi_m };
                }
                kept.push(i);
                continue;
            }
            if let Some(k) = self.released.iter().position(|&j| j == i) {
                self.released.swap_remove(k);
                self.settled.push(i);
            } else if self.left.contains(&(i, to)) {
                // back to a pairing the point has left: stuck at the node
                // between the two (or at the chain's end)
                let pair = layout.points[i].pair;
                if let (Some(p), Some(o)) = (current, to)
                    && layout.shared_node(pair, p, o).is_some()
                {
                    ties.push(NodeTie {
                        point: i,
                        paired: p,
                        other: o,
                        mu: 0.0,
                    });
                    changed = true;
                    continue;
                }
                self.settled.push(i);
                if within {
                    kept.push(i);
                    continue;
                }
                // no tie possible: back to the other side, once
            }
            self.left.push((i, current));
            pairing[i] = to;
            changed = true;
        }
        if changed {
            GuardOutcome::Changed
        } else {
            GuardOutcome::Settled(kept)
        }
    }
}

/// A converged attempt.
struct Converged {
    u: Vec<f64>,
    lambda: Vec<f64>,
    pairing: Vec<Option<usize>>,
    iterations: usize,
    residuals: Vec<f64>,
    energy: f64,
    active_multipliers: usize,
    ties: Vec<NodeTie>,
    unpaired: Vec<ContactPointId>,
    node_ties: Vec<ContactPointId>,
    kept_outside: Vec<ContactPointId>,
    roundoff_floor: bool,
}

/// The solve in progress.
pub(crate) struct Run<'a> {
    model: &'a Model,
    opts: &'a SolveOptions,
    layout: ContactLayout,
    dofs: DofMap,
    linear: Box<dyn LinearSolver>,
    timings: Timings,
    counts: KernelCounts,
    length_scale: f64,
    // converged state
    u: Vec<f64>,
    lambda: Vec<f64>,
    pairing: Vec<Option<usize>>,
    ties: Vec<NodeTie>,
    load_factor: f64,
    energy: f64,
    taylor: Option<Vec<Option<Taylor>>>,
    // history
    records: Vec<StepRecord>,
    cutbacks: Vec<Cutback>,
    snapshots: Vec<State>,
    iterations: usize,
    failed_iterations: usize,
}

impl<'a> Run<'a> {
    pub(crate) fn new(model: &'a Model, opts: &'a SolveOptions) -> Result<Run<'a>, SolverError> {
        if opts.steps == 0 {
            return Err(SolverError::Options("steps must be at least 1".into()));
        }
        if opts.max_iterations == 0 {
            return Err(SolverError::Options(
                "max_iterations must be at least 1".into(),
            ));
        }
        if !(opts.tolerance.is_finite() && opts.tolerance > 0.0) {
            return Err(SolverError::Options(format!(
                "tolerance must be positive, got {}",
                opts.tolerance
            )));
        }
        model.check()?;
        let layout = ContactLayout::new(model, opts.formulation);
        let dofs = DofMap::new(model, layout.multipliers.len());
        let n_points = layout.points.len();
        Ok(Run {
            model,
            opts,
            dofs,
            linear: opts.linear.build(),
            timings: Timings::default(),
            counts: KernelCounts::default(),
            length_scale: model.mesh.size(),
            u: vec![0.0; 2 * model.mesh.node_count()],
            lambda: vec![0.0; layout.multipliers.len()],
            pairing: vec![None; n_points],
            ties: Vec::new(),
            layout,
            load_factor: 0.0,
            energy: 0.0,
            taylor: None,
            records: Vec::new(),
            cutbacks: Vec::new(),
            snapshots: Vec::new(),
            iterations: 0,
            failed_iterations: 0,
        })
    }

    fn point_id(&self, f: &PointFailure) -> ContactPointId {
        failure_point(&self.layout, f)
    }

    /// Integration point `i` (no master segment).
    fn point_index_id(&self, i: usize) -> ContactPointId {
        let p = &self.layout.points[i];
        ContactPointId {
            pair: p.pair,
            slave_segment: p.slave_segment,
            gauss: p.gauss,
            master_segment: None,
        }
    }

    fn state(&self) -> State {
        State {
            load_factor: self.load_factor,
            displacements: self.u.chunks(2).map(|c| [c[0], c[1]]).collect(),
            multipliers: self.lambda.clone(),
        }
    }

    /// Runs the whole schedule.
    pub(crate) fn execute(mut self) -> Result<Solution, SolverError> {
        let start = Instant::now();
        // initial pairing in the reference configuration
        let t = Instant::now();
        let (initial, counts) = self
            .layout
            .initial_pairing(&self.model.mesh, &self.u)
            .map_err(|f| SolverError::Kernel {
                point: self.point_id(&f),
                load_factor: 0.0,
                error: f.error,
            })?;
        self.counts += counts;
        self.pairing = initial;
        self.timings.contact_evaluation += t.elapsed();
        if self.opts.record_steps {
            self.snapshots.push(self.state());
        }
        let end = self.model.load_factor_end;
        let steps = self.opts.steps;
        for step in 1..=steps {
            let target = end * step as f64 / steps as f64;
            let mut increment = target - self.load_factor;
            let mut cuts = 0;
            while (target - self.load_factor).abs() > 1e-12 * end.abs().max(f64::MIN_POSITIVE) {
                let remaining = target - self.load_factor;
                let to = if increment / remaining >= 1.0 - 1e-9 {
                    target
                } else {
                    self.load_factor + increment
                };
                match self.attempt(to)? {
                    Ok(c) => self.commit(step, to, c),
                    Err((reason, residuals, iterations)) => {
                        self.failed_iterations += iterations;
                        cuts += 1;
                        self.cutbacks.push(Cutback {
                            step,
                            from_load_factor: self.load_factor,
                            attempted_load_factor: to,
                            reason: reason.clone(),
                            residuals,
                        });
                        // a further halving could not advance the load factor
                        let exhausted = (increment / 2.0).abs() <= 1e-12 * end.abs();
                        if cuts > self.opts.max_cutbacks || exhausted {
                            return Err(self.give_up(step, to, cuts - 1, reason));
                        }
                        increment /= 2.0;
                    }
                }
            }
        }
        self.finish(start)
    }

    fn give_up(
        &self,
        step: usize,
        attempted: f64,
        cutbacks: usize,
        reason: CutbackReason,
    ) -> SolverError {
        match reason {
            CutbackReason::Singular { message } => SolverError::Singular {
                load_factor: self.load_factor,
                attempted,
                cutbacks,
                message,
            },
            CutbackReason::Kernel { point, error } => SolverError::Kernel {
                point,
                load_factor: attempted,
                error,
            },
            reason => SolverError::Diverged {
                step,
                load_factor: self.load_factor,
                attempted,
                cutbacks,
                reason,
            },
        }
    }

    fn commit(&mut self, step: usize, to: f64, c: Converged) {
        self.u = c.u;
        self.lambda = c.lambda;
        self.pairing = c.pairing;
        self.ties = c.ties;
        self.load_factor = to;
        self.energy = c.energy;
        self.iterations += c.iterations;
        self.taylor = None;
        self.records.push(StepRecord {
            step,
            load_factor: to,
            iterations: c.iterations,
            residuals: c.residuals,
            strain_energy: c.energy,
            unpaired: c.unpaired,
            node_ties: c.node_ties,
            kept_outside: c.kept_outside,
            active_multipliers: c.active_multipliers,
            roundoff_floor: c.roundoff_floor,
        });
        if self.opts.record_steps {
            self.snapshots.push(self.state());
        }
    }

    /// Builds the frozen Taylor coefficients at the converged state (Types
    /// 1–6), re-pairing every point.
    fn ensure_taylor(&mut self, ty: ApproxType) -> Result<(), SolverError> {
        if self.taylor.is_some() {
            return Ok(());
        }
        let t = Instant::now();
        let (evals, counts) = self
            .layout
            .evaluate_all(&self.model.mesh, &self.u, &self.pairing, ty)
            .map_err(|f| SolverError::Kernel {
                point: self.point_id(&f),
                load_factor: self.load_factor,
                error: f.error,
            })?;
        self.counts += counts;
        self.pairing = evals.iter().map(|e| e.map(|e| e.master)).collect();
        let taylor = evals
            .into_iter()
            .map(|e| {
                e.map(|at_start| Taylor {
                    u0: nalgebra::SVector::<f64, 8>::from_fn(|k, _| {
                        self.u[2 * at_start.nodes[k / 2] + k % 2]
                    }),
                    at_start,
                })
            })
            .collect();
        self.taylor = Some(taylor);
        self.timings.contact_evaluation += t.elapsed();
        Ok(())
    }

    /// One Newton solve from the converged state to load factor `to`. The
    /// outer `Err` stops the solve; the inner one asks for a cut-back (with
    /// the iterations spent).
    #[allow(clippy::type_complexity)]
    fn attempt(
        &mut self,
        to: f64,
    ) -> Result<Result<Converged, (CutbackReason, Vec<f64>, usize)>, SolverError> {
        if let Method::Approx(ty) = self.opts.method {
            self.ensure_taylor(ty)?;
        }
        let mut u = self.u.clone();
        for p in &self.model.prescribed {
            u[p.dof] = to * p.value;
        }
        let mut lambda = self.lambda.clone();
        let mut pairing = self.pairing.clone();
        let mut ties = self.ties.clone();
        let mut guard = PairingGuard::default();
        let mut residuals = Vec::new();
        // index into `residuals` of the first iterate with the current pairing
        let mut phase_start = 0;
        let n_eq = self.dofs.n_eq();
        let mut it = 0;
        loop {
            // contact
            let t = Instant::now();
            let (evals, others) = match self.opts.method {
                Method::Approx(_) => {
                    let taylor = self.taylor.as_deref().unwrap_or(&[]);
                    let evals: Vec<Option<PointEval>> =
                        taylor.iter().map(|t| t.map(|t| t.expand(&u))).collect();
                    (evals, Vec::new())
                }
                Method::Complete => {
                    // re-pair at once in the first iterates, until the first
                    // pairing change at a converged iterate
                    let at_once = (1..=REPAIR_AT_ONCE_ITERATIONS).contains(&it) && phase_start == 0;
                    match self.evaluate_complete(&u, &mut pairing, &ties, at_once) {
                        Ok(e) => e,
                        Err(f) => {
                            self.timings.contact_evaluation += t.elapsed();
                            let point = self.point_id(&f);
                            return Ok(Err((
                                CutbackReason::Kernel {
                                    point,
                                    error: f.error,
                                },
                                residuals,
                                it,
                            )));
                        }
                    }
                }
            };
            let active = self
                .layout
                .active_multipliers(&evals, &lambda, self.length_scale);
            let n_sys = n_eq + ties.len();
            let mut sys = System::new(n_sys);
            assemble_contact(&self.layout, &evals, &lambda, &active, &self.dofs, &mut sys);
            assemble_ties(&ties, &evals, &others, &self.dofs, n_eq, &mut sys);
            self.timings.contact_evaluation += t.elapsed();
            // solid
            let t = Instant::now();
            assemble_solid(self.model, &self.dofs, &u, &mut sys);
            let f_ext = add_external(self.model, &self.dofs, to, &mut sys);
            self.timings.solid_assembly += t.elapsed();

            let norm = sys.residual_norm();
            residuals.push(norm);
            if !norm.is_finite() {
                return Ok(Err((CutbackReason::NonFiniteResidual, residuals, it)));
            }
            let tol_abs = self.opts.tolerance * f_ext.max(1.0);
            let last = residuals.len() - 1;
            let at_floor = last >= phase_start + 2
                && norm <= STAGNATION_FACTOR * tol_abs
                && norm >= 0.5 * residuals[last - 1];
            if norm <= tol_abs || at_floor {
                let mut kept = Vec::new();
                if self.opts.method == Method::Complete {
                    let t = Instant::now();
                    let outcome = self.update_pairing(
                        &u,
                        &lambda,
                        &evals,
                        &mut pairing,
                        &mut ties,
                        &mut guard,
                    );
                    self.timings.contact_evaluation += t.elapsed();
                    match outcome {
                        Ok(GuardOutcome::Changed) => {
                            // the same iterate again, with the new pairing
                            phase_start = residuals.len();
                            continue;
                        }
                        Ok(GuardOutcome::Settled(k)) => kept = k,
                        Ok(GuardOutcome::Stuck { point, xi_m }) => {
                            let point = ContactPointId {
                                master_segment: pairing[point],
                                ..self.point_index_id(point)
                            };
                            return Ok(Err((
                                CutbackReason::StuckAtMasterNode { point, xi_m },
                                residuals,
                                it,
                            )));
                        }
                        Err(f) => {
                            let point = self.point_id(&f);
                            return Ok(Err((
                                CutbackReason::Kernel {
                                    point,
                                    error: f.error,
                                },
                                residuals,
                                it,
                            )));
                        }
                    }
                }
                let unpaired = self
                    .layout
                    .points
                    .iter()
                    .zip(&evals)
                    .filter(|(_, e)| e.is_none())
                    .map(|(p, _)| ContactPointId {
                        pair: p.pair,
                        slave_segment: p.slave_segment,
                        gauss: p.gauss,
                        master_segment: None,
                    })
                    .collect();
                // inactive rows read l_a = 0 (satisfied to round-off): make it exact
                for (l, &on) in lambda.iter_mut().zip(&active) {
                    if !on {
                        *l = 0.0;
                    }
                }
                let with_master = |i: usize| ContactPointId {
                    master_segment: pairing[i],
                    ..self.point_index_id(i)
                };
                let node_ties = ties.iter().map(|t| with_master(t.point)).collect();
                let kept_outside = kept.into_iter().map(with_master).collect();
                return Ok(Ok(Converged {
                    u,
                    lambda,
                    pairing,
                    ties,
                    iterations: it,
                    residuals,
                    energy: sys.energy,
                    active_multipliers: active.iter().filter(|a| **a).count(),
                    unpaired,
                    node_ties,
                    kept_outside,
                    roundoff_floor: norm > tol_abs,
                }));
            }
            if it == self.opts.max_iterations {
                return Ok(Err((
                    CutbackReason::MaxIterations { residual: norm },
                    residuals,
                    it,
                )));
            }
            let bound = DIVERGENCE_FACTOR * residuals[0].max(1.0);
            if norm > bound {
                return Ok(Err((
                    CutbackReason::Diverging {
                        residual: norm,
                        bound,
                    },
                    residuals,
                    it,
                )));
            }
            let t = Instant::now();
            regularize(&mut sys, &self.dofs, &active, self.opts.regularization);
            let solved =
                self.linear
                    .solve_system(n_sys, &sys.rows, &sys.cols, &sys.vals, &sys.residual);
            self.timings.linear_solve += t.elapsed();
            let dx = match solved {
                Ok(dx) => dx,
                Err(e) => {
                    return Ok(Err((
                        CutbackReason::Singular {
                            message: e.to_string(),
                        },
                        residuals,
                        it,
                    )));
                }
            };
            for (dof, ud) in u.iter_mut().enumerate() {
                if let Some(e) = self.dofs.eq(dof) {
                    *ud -= dx[e];
                }
            }
            for (m, l) in lambda.iter_mut().enumerate() {
                *l -= dx[self.dofs.mult_eq(m)];
            }
            for (k, tie) in ties.iter_mut().enumerate() {
                tie.mu -= dx[n_eq + k];
            }
            it += 1;
        }
    }

    /// The complete formulation's contact evaluation at one iterate: the
    /// Type 6 kernel of every point on its paired master segment (see
    /// [`ContactLayout::evaluate_paired`]; `pairing` is updated where a
    /// kernel failure forced a re-pairing) and of every tied point on its
    /// other segment.
    fn evaluate_complete(
        &mut self,
        u: &[f64],
        pairing: &mut Vec<Option<usize>>,
        ties: &[NodeTie],
        at_once: bool,
    ) -> Result<(Vec<Option<PointEval>>, Vec<PointEval>), PointFailure> {
        let mesh = &self.model.mesh;
        let (mut evals, counts) = if at_once {
            self.layout
                .evaluate_all(mesh, u, pairing, ApproxType::Type6)?
        } else {
            self.layout
                .evaluate_paired(mesh, u, pairing, ApproxType::Type6)?
        };
        self.counts += counts;
        let mut counts = KernelCounts::default();
        for t in ties {
            if evals[t.point].is_none_or(|e| e.master != t.paired) {
                evals[t.point] = Some(
                    self.layout
                        .evaluate_on(mesh, u, t.point, t.paired, ApproxType::Type6, &mut counts)
                        .map_err(|error| PointFailure {
                            point: t.point,
                            master_segment: Some(t.paired),
                            error,
                        })?,
                );
            }
        }
        *pairing = evals.iter().map(|e| e.map(|e| e.master)).collect();
        let others = ties
            .iter()
            .map(|t| {
                self.layout
                    .evaluate_on(mesh, u, t.point, t.other, ApproxType::Type6, &mut counts)
                    .map_err(|error| PointFailure {
                        point: t.point,
                        master_segment: Some(t.other),
                        error,
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        self.counts += counts;
        Ok((evals, others))
    }

    /// The pairing update of the complete formulation at a converged
    /// iterate (module docs of [`crate::contact`]): releases the ties whose
    /// `theta` left `[0, 1]` (to the paired segment for `theta < 0`, to the
    /// other one for `theta > 1`), then re-pairs the untied points whose
    /// projection left their segment, tying those that cycle.
    fn update_pairing(
        &mut self,
        u: &[f64],
        lambda: &[f64],
        evals: &[Option<PointEval>],
        pairing: &mut [Option<usize>],
        ties: &mut Vec<NodeTie>,
        guard: &mut PairingGuard,
    ) -> Result<GuardOutcome, PointFailure> {
        let (updates, counts) = self.layout.pairing_updates(&self.model.mesh, u, evals)?;
        self.counts += counts;
        let updates: Vec<_> = updates
            .into_iter()
            .filter(|(i, _)| ties.iter().all(|t| t.point != *i))
            .collect();
        let mut released = false;
        ties.retain(|t| {
            let theta = t.theta(&self.layout, lambda).unwrap_or(-1.0);
            if (0.0..=1.0).contains(&theta) {
                return true;
            }
            if theta > 1.0 {
                pairing[t.point] = Some(t.other);
            }
            guard.released.push(t.point);
            released = true;
            false
        });
        let outcome = guard.apply(&self.layout, &updates, evals, pairing, ties);
        Ok(match outcome {
            GuardOutcome::Settled(_) if released => GuardOutcome::Changed,
            o => o,
        })
    }

    fn finish(self, start: Instant) -> Result<Solution, SolverError> {
        let (projections, _) = self
            .layout
            .project_all(&self.model.mesh, &self.u, &self.pairing)
            .map_err(|f| SolverError::Kernel {
                point: self.point_id(&f),
                load_factor: self.load_factor,
                error: f.error,
            })?;
        let contact_points = self
            .layout
            .points
            .iter()
            .zip(&projections)
            .map(|(p, proj)| ContactPointReport {
                pair: p.pair,
                slave_segment: p.slave_segment,
                gauss: p.gauss,
                xi_s: p.xi_s,
                slave_nodes: p.slave_nodes,
                master_segment: proj.map(|(m, _)| m),
                master_nodes: proj.map(|(m, _)| self.layout.masters[p.pair][m]),
                xi_m: proj.map(|(_, pr)| pr.xi_m),
                gap: proj.map(|(_, pr)| pr.gap),
            })
            .collect();
        let mut timings = self.timings;
        timings.symbolic_factorisation = self.linear.symbolic_time();
        timings.total = start.elapsed();
        Ok(Solution {
            method: self.opts.method,
            formulations: self.layout.formulations.clone(),
            steps: self.opts.steps,
            load_factor: self.load_factor,
            strain_energy: self.energy,
            newton_iterations: self.iterations,
            failed_iterations: self.failed_iterations,
            step_records: self.records.clone(),
            cutbacks: self.cutbacks.clone(),
            timings,
            kernel_counts: self.counts,
            symbolic_factorisations: self.linear.symbolic_factorisations(),
            equations: self.dofs.n_eq(),
            mesh: self.model.mesh.clone(),
            multiplier_dofs: self
                .layout
                .multipliers
                .iter()
                .map(|m| MultiplierDofInfo {
                    pair: m.pair,
                    node: m.node,
                })
                .collect(),
            final_state: self.state(),
            snapshots: self.snapshots.clone(),
            contact_points,
        })
    }
}

/// The contact phase of one Newton iteration ([`IterationProbe::contact`]):
/// a fresh system holding the contact contributions, and which multipliers
/// carry a constraint row.
#[derive(Debug, Clone)]
pub struct ContactPhase {
    /// Residual and triplets with the contact terms only.
    pub system: System,
    /// Active multipliers (see [`ContactLayout::active_multipliers`]).
    pub active: Vec<bool>,
}

/// Wall-clock time of the phases of one probed iteration, split as in
/// [`Timings`], and the residual norm at the probed state.
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
/// split into the phases that [`Timings`] reports — for benchmarks and
/// profiling (`benches/solver_scaling.rs`, `examples/scaling_table.rs`).
///
/// Each phase runs the same code as an iteration of [`crate::solve`]:
/// [`contact`](Self::contact) re-projects every slave integration point
/// onto its paired master segment (the probe pairs from scratch at its
/// state and has no node ties), evaluates the Type 6 kernel and scatters
/// the contact terms into a fresh
/// [`System`]; [`solid`](Self::solid) adds the solid elements and the
/// external force; [`linear_solve`](Self::linear_solve) adds the multiplier
/// regularisation and solves with the probe's [`LinearSolver`], whose
/// symbolic factorisation is computed on the first call and reused after.
/// The state is never updated, so every call repeats the same iteration.
pub struct IterationProbe<'a> {
    model: &'a Model,
    regularization: f64,
    layout: ContactLayout,
    dofs: DofMap,
    linear: Box<dyn LinearSolver>,
    length_scale: f64,
    u: Vec<f64>,
    lambda: Vec<f64>,
    pairing: Vec<Option<usize>>,
    load_factor: f64,
}

impl<'a> IterationProbe<'a> {
    /// The iteration from `state` (e.g. a converged
    /// [`Solution::final_state`]) towards load factor `load_factor`: the
    /// prescribed dofs are set to `load_factor u_ref` and the external force
    /// is `load_factor f_ref`, as in the first iteration of a step ending
    /// there. The points are paired from scratch at `state`. Uses
    /// `options.formulation` and `options.regularization`; `options.method`
    /// must be [`Method::Complete`].
    pub fn new(
        model: &'a Model,
        options: &SolveOptions,
        state: &State,
        load_factor: f64,
    ) -> Result<IterationProbe<'a>, SolverError> {
        if options.method != Method::Complete {
            return Err(SolverError::Options(format!(
                "the iteration probe evaluates the complete formulation, not `{}`",
                options.method
            )));
        }
        model.check()?;
        let layout = ContactLayout::new(model, options.formulation);
        let dofs = DofMap::new(model, layout.multipliers.len());
        let nodes = model.mesh.node_count();
        if state.displacements.len() != nodes || state.multipliers.len() != dofs.n_mult {
            return Err(SolverError::Options(format!(
                "state has {} displacements and {} multipliers, the model {} nodes and {} multipliers",
                state.displacements.len(),
                state.multipliers.len(),
                nodes,
                dofs.n_mult
            )));
        }
        let mut u: Vec<f64> = state.displacements.iter().flatten().copied().collect();
        for p in &model.prescribed {
            u[p.dof] = load_factor * p.value;
        }
        let (pairing, _) =
            layout
                .initial_pairing(&model.mesh, &u)
                .map_err(|f| SolverError::Kernel {
                    point: failure_point(&layout, &f),
                    load_factor,
                    error: f.error,
                })?;
        Ok(IterationProbe {
            model,
            regularization: options.regularization,
            length_scale: model.mesh.size(),
            u,
            lambda: state.multipliers.clone(),
            pairing,
            load_factor,
            layout,
            dofs,
            linear: options.linear.build(),
        })
    }

    /// Number of equations (free dofs plus multipliers).
    pub fn equations(&self) -> usize {
        self.dofs.n_eq()
    }

    /// Number of slave integration points.
    pub fn contact_points(&self) -> usize {
        self.layout.points.len()
    }

    /// Symbolic factorisations computed so far (1 after the first
    /// [`linear_solve`](Self::linear_solve)).
    pub fn symbolic_factorisations(&self) -> usize {
        self.linear.symbolic_factorisations()
    }

    /// Time spent in symbolic analysis so far.
    pub fn symbolic_time(&self) -> std::time::Duration {
        self.linear.symbolic_time()
    }

    /// Phase 1: re-projection and Type 6 kernel at every integration point,
    /// active set, and the contact scatter into a fresh system.
    pub fn contact(&self) -> Result<ContactPhase, SolverError> {
        let (evals, _) = self
            .layout
            .evaluate_paired(&self.model.mesh, &self.u, &self.pairing, ApproxType::Type6)
            .map_err(|f| SolverError::Kernel {
                point: failure_point(&self.layout, &f),
                load_factor: self.load_factor,
                error: f.error,
            })?;
        let active = self
            .layout
            .active_multipliers(&evals, &self.lambda, self.length_scale);
        let mut system = System::new(self.dofs.n_eq());
        assemble_contact(
            &self.layout,
            &evals,
            &self.lambda,
            &active,
            &self.dofs,
            &mut system,
        );
        Ok(ContactPhase { system, active })
    }

    /// Phase 2: adds the solid elements' forces and tangents and the
    /// external force to `system`; returns `|f_ext|`.
    pub fn solid(&self, system: &mut System) -> f64 {
        assemble_solid(self.model, &self.dofs, &self.u, system);
        add_external(self.model, &self.dofs, self.load_factor, system)
    }

    /// Phase 3: regularisation and the sparse LU solve of the assembled
    /// system (contact then solid, as in a solve); returns the Newton
    /// correction `dx` with `K dx = r`.
    pub fn linear_solve(&mut self, assembled: ContactPhase) -> Result<Vec<f64>, SolverError> {
        let ContactPhase { mut system, active } = assembled;
        regularize(&mut system, &self.dofs, &active, self.regularization);
        self.linear
            .solve_system(
                self.dofs.n_eq(),
                &system.rows,
                &system.cols,
                &system.vals,
                &system.residual,
            )
            .map_err(|e| SolverError::Singular {
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
mod probe_tests {
    use super::*;
    use crate::Scene;

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
            if let Some(e) = dofs.eq(dof) {
                *ud -= dx[e];
            }
        }
        let next = State {
            load_factor: 0.0,
            displacements: u.chunks(2).map(|c| [c[0], c[1]]).collect(),
            multipliers: (0..dofs.n_mult).map(|m| -dx[dofs.mult_eq(m)]).collect(),
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
}
