//! Load stepping, Newton–Raphson and cut-back.
//!
//! The load factor goes from 0 to `lambda_end` in `N` equal scheduled steps.
//! Each step is solved by Newton's method on the free displacements and the
//! multipliers:
//!
//! 1. prescribed dofs are set to `lambda_L u_ref` of the step's target
//!    (`a(lambda_L) u_ref` with a load curve, [`crate::amplitude`]; the
//!    external force likewise), the free dofs start from the converged
//!    state; when prescribed dofs move, through the predictor of the next
//!    section;
//! 2. Types 1–6: at the step start every contact integration point is
//!    re-paired and the type's Taylor coefficients are evaluated, at the
//!    step's predictor (next section) or, without one, at the converged
//!    state `u0` ("Where the expansions are taken"); they stay frozen
//!    during the step. Complete: every iteration
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
//! 5. Types 1–6: at a converged iterate, every point is re-paired by
//!    projection; if one ended on another master segment than its
//!    expansion's, the step is solved again with the expansion of the new
//!    pairing ("Re-pairing at the step end"). Then the step's Taylor
//!    remainder is measured and, with a `taylor_tolerance`, the points
//!    above it get their expansions re-taken there and the step is solved
//!    again; a step still above it is halved.
//!
//! # Prescribed increments
//!
//! Setting the prescribed dofs to their new values with the free dofs at
//! the converged state concentrates the whole increment in the elements at
//! the prescribed boundary. On the ironing scene (`scenes/ironing.toml`, a
//! punch with elements 0.033 high under its pressed top) a press step of
//! 0.025 compresses that row by 75 % and a slide step of 0.31 shears it by
//! 9: St Venant–Kirchhoff elements have no sensible response there (the
//! first residual was 1.2e5), and every step needed 4 to 5 cut-backs (20
//! steps: "singular system" right after the slide started). So when a
//! prescribed dof moves (`Setup::lift`; bit for bit, so a scene whose
//! prescribed dofs stay put, the paper scene among them, iterates exactly
//! as before), the attempt starts from a predictor:
//!
//! * **secant**: when the last converged step moved the prescribed dofs
//!   too, the displacements are extrapolated along that step,
//!   `u + s (u - u_prev)`, with `s` the least-squares fit of this step's
//!   prescribed increment by the last one (`Setup::extrapolation`; `s = 1`
//!   in steady pressing or sliding, none where the direction turns, as from
//!   press to slide). The extrapolated iterate is re-paired at once;
//! * **linearised Dirichlet step**: the first Newton iteration is taken
//!   at the start state with the prescribed dofs where they are and the
//!   rest of their increment `du_p` as the load `K_fp du_p` (the solid
//!   elements' coupling, [`crate::assembly::assemble_solid_lifted`]; a
//!   contact point's coupling to a prescribed dof is left out of this first
//!   step), and the prescribed dofs take their target values with its
//!   correction. That first residual is a linearised one: it is never
//!   taken as converged.
//!
//! On the ironing scene at 20 steps the complete formulation then needs no
//! cut-back (236 iterations, 5 per press step); the sliding scenes' results
//! are unchanged to the solver tolerance, with fewer iterations.
//!
//! # Where the expansions are taken (Types 1–6)
//!
//! The paper expands each point's gap at the step start `u0`
//! (`[newton] expand_at = "start"`). When the step has a secant predictor
//! `u_p` (above: prescribed dofs moving on as in the last step) the
//! default, `expand_at = "predictor"`, takes the expansions there instead:
//! every point re-paired and the type's kernel evaluated at `u_p`, the
//! iterate Newton starts from. The approximation is the same second-order
//! expansion frozen for the step, about a point nearer the step's end, so
//! its Taylor remainder at the end is that of `u - u_p` instead of
//! `u - u0`, and a point that slides across a master node during a steady
//! step is already on its end segment at `u_p`. A step without a predictor
//! (the first step, a load that is not prescribed displacements, a change
//! of direction: the paper scene, a press) is expanded at `u0` as before,
//! and so is one where a point cannot be evaluated at `u_p`. With friction
//! the slip is still measured from the projections at `u0`
//! (docs/conventions.md, "Coulomb friction"): the anchors are taken there.
//!
//! Measured on `scenes/sliding3d.toml` (a block dragged diagonally across
//! 12 x 12 master faces) at 20 steps: expanded at the step start, Types 3
//! and 6 were 0.18 % and 0.19 % off the complete formulation's energy,
//! with 35 and 33 step repeats for re-pairing and 174 and 171 linear
//! solves against the complete formulation's 77; expanded at the
//! predictor, 4.8e-3 % and 3.5e-3 % with 3 repeats and 84 and 83 solves
//! (`solver/tests/contact3d.rs`, docs/benchmarks.md). On the 2D sliding
//! scenes at 20 steps, where every point crosses a node in every step and
//! the re-pairing made each end exact, the predictor gives up that
//! exactness (Type 6 on `scenes/sliding.toml`: 3.0e-2 %, within the 5e-2 %
//! the safety map accepts) for 104 linear solves instead of 238.
//!
//! # Re-pairing at the step end (Types 1–6)
//!
//! The frozen expansion belongs to the master segment a point was paired
//! with at the step start; a point that slides across a master node during
//! the step ends with a gap error of about (kink angle) x (distance past
//! the node), and the step converges to the solution of the wrong
//! constraint (issue #8: on `scenes/sliding.toml`, Type 6 at 20 steps was
//! 20 % off the complete formulation's energy). At a converged step end
//! every point is therefore re-paired (the complete formulation's search);
//! each point whose segment changed (or that became paired or unpaired)
//! gets the expansion of its **new** segment's gap taken at that attempt's
//! converged end (re-taken at each following end until it reproduces the
//! point's gap there, `repair.rs`, "Anchor iteration"), and the step is
//! solved again (Newton warm-started from the discarded attempt's end),
//! until the pairing at the end is the one
//! the expansions were built on (at most [`MAX_REPAIR_REPEATS`] repeats; a
//! point that returns to a pairing it has had in the attempt cycles at a
//! concave master node and is tied to it as in the complete formulation,
//! where no tie is possible (in 3D, always) it keeps its expansion and is
//! listed in [`crate::StepRecord::kept_outside`] when its projection lies
//! within [`crate::contact::XI_STUCK_BAND`] of its expansion's master, in
//! [`crate::StepRecord::unsettled`] otherwise). The alternative of switching a
//! point's pair during the iterations when its predicted `xi_m` leaves
//! `[-1, 1]` was not taken: it makes the frozen problem change within the
//! step (a residual discontinuous in `u`, the cycling the complete
//! formulation's pairing guard was built against), and a frozen expansion
//! has no exact `xi_m` to predict from; the repeat keeps every Newton solve
//! smooth and its cost is one more solve per crossing step. `[newton]
//! repair = false` turns it off ([`crate::SolveOptions::repair`]). The
//! check only projects when no point changes segment (the paper scene):
//! the results and kernel counts are then those without it, and its
//! projection calls are counted apart
//! ([`crate::Solution::step_end_projections`]). Details in `repair.rs`.
//!
//! **Taylor remainder** (error indicator): at the accepted end, over the
//! active points, the largest `|g - g~| / L_s`: the re-projected gap minus
//! the frozen expansion's gap, over the slave segment's reference length
//! ([`crate::StepRecord::taylor_remainder`]). With `[newton]
//! taylor_tolerance` (and `repair`, the default), at a converged end
//! whose pairing stands, each active point whose remainder exceeds the tolerance gets its expansion
//! re-taken there (then followed by the anchor iteration like a point
//! that changed segment) and the step is solved again, the re-takings of
//! one attempt sharing `repair.rs`'s limit of anchor updates; only a step still above the tolerance after them is
//! discarded and its increment halved by the same bisection as a
//! divergence cut-back, recorded apart
//! ([`crate::Solution::accuracy_halvings`]); a step that cannot be halved
//! further (`max_cutbacks`) is accepted as it is. Halving whole steps
//! was the first cure: on `scenes/sliding3d.toml` at 20 steps with the
//! expansions at the step start and `taylor_tolerance = 1e-3` it halved 32
//! steps and took 8x the complete formulation's time; re-taking the
//! points instead halves none (Type 3 then ends within 2e-9 of the
//! complete formulation's energy with 248 linear solves).
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
//! An attempt fails when an iterate inverts an element (`det F <= 0` at an
//! integration point, [`crate::mesh::inversion`]; so no converged state
//! has an inverted element, and a solve that cannot avoid one ends in the
//! error naming it), when the residual is not finite, grows above
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
//! given state, phase by phase, with the same code (for benchmarks; in 2D
//! and 3D, as the solve).
//!
//! # Parts
//!
//! * this module: `Run`, the solve in progress (its converged state and
//!   history), the driver over the schedule, and the [`Solution`] report;
//! * `setup`: `Setup`, the discretised problem (contact layout, equation
//!   numbering, linear solver) and the phases of one Newton iteration on it,
//!   shared by `Run` and [`IterationProbe`];
//! * `schedule`: the scheduled load steps and their bisection cut-backs;
//! * `treatment`: the seam `ContactTreatment`, how contact is treated: its
//!   evaluation at an iterate, its decisions at a converged iterate and at
//!   a converged solve (the module states the mathematics of both);
//! * `complete`: the complete formulation's treatment (re-projection at
//!   every iteration, exact derivatives, the pairing guard);
//! * `frozen`: Types 1–6's treatment (the frozen expansions, built at the
//!   converged state);
//! * `attempt`: one attempt from the converged state to a target load
//!   factor, ending in an `AttemptOutcome`: the Newton loop, the same for
//!   every treatment;
//! * `iterate`: the unknowns an attempt works on (a copy of the converged
//!   state) and Newton's correction of them;
//! * `outcome`: how an attempt ended (`AttemptOutcome`, `Converged`,
//!   `Failed`, Types 1–6's `StepEnd`), shared by `attempt`, the treatments,
//!   `repair` and this module;
//! * `pairing`: the pairing guard of the complete formulation (re-pairing
//!   and node ties at converged iterates);
//! * `repair`: Types 1–6's step-end check (`Frozen::check_end`):
//!   re-pairing, the repeat with the new pairing's expansions, the Taylor
//!   remainder;
//! * `reactions`: the support groups' reaction forces at a converged
//!   state ([`crate::StepRecord::reactions`]);
//! * `regularize`: the tangent-only multiplier regularisation;
//! * `probe`: [`IterationProbe`], one iteration for benchmarks.
//!
//! Invariants: the converged state of `Run` (`u`, `lambda`,
//! `load_factor`) changes only in `Run::commit`, with a converged attempt; a
//! failed attempt leaves it untouched. Its `pairing` and `ties` change
//! there too and otherwise only through the treatment: for Types 1–6 when
//! the Taylor coefficients are built at the converged state (which
//! re-pairs every point and drops the ties), once per converged state, and
//! when a step is repeated with re-paired or tied expansions (`repair.rs`;
//! they are still taken at the converged state).

mod attempt;
mod complete;
mod frozen;
mod iterate;
mod outcome;
mod pairing;
mod probe;
mod reactions;
mod regularize;
mod repair;
mod schedule;
mod setup;
mod treatment;

use std::time::Instant;

use contact_kernels::ApproxType;

use crate::contact::ContactSpace;
use crate::contact::friction::{FrictionState, NodalFriction};
use crate::contact::{KernelCounts, NodeTie};
use crate::error::SolverError;
use crate::model::Model;
use crate::monitor::{Monitor, StepProgress};
use crate::options::{Method, SolveOptions};
use crate::solution::{AccuracyHalving, Cutback, Solution, State, StepRecord, Timings};

use crate::model::{Dim, SurfaceDim};
use complete::Complete;
use frozen::Frozen;
use outcome::{AttemptOutcome, Converged};
use schedule::{ScheduledStep, give_up};
use setup::Setup;
use treatment::ContactTreatment;

pub use crate::options::DEFAULT_REGULARIZATION;
pub use probe::{ContactPhase, IterationProbe, IterationSample};

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

/// Types 1–6: a step is solved again with new expansions at most this many
/// times for pairing changes at its end (see `repair.rs`); points still
/// changing then are accepted and listed in
/// [`crate::StepRecord::kept_outside`] or [`crate::StepRecord::unsettled`]
/// (`repair.rs`, "Termination").
pub const MAX_REPAIR_REPEATS: usize = 4;

/// The solve in progress.
pub(crate) struct Run<'a, const D: usize, S: ContactSpace<D>>
where
    Dim<D>: SurfaceDim<D>,
{
    opts: &'a SolveOptions,
    /// Told of every finished step, cut-back and iterate; asked before
    /// every attempt and iteration whether to stop.
    monitor: &'a dyn Monitor,
    /// When the solve started (the monitor's times).
    started: Instant,
    setup: Setup<'a, D, S>,
    timings: Timings,
    counts: KernelCounts,
    // converged state
    u: Vec<f64>,
    lambda: Vec<f64>,
    pairing: Vec<Option<S::Master>>,
    ties: Vec<NodeTie<S::Master>>,
    load_factor: f64,
    energy: f64,
    /// How contact is treated: the complete formulation, or Types 1–6's
    /// frozen expansions (`treatment.rs`).
    treatment: Box<dyn ContactTreatment<D, S>>,
    /// The converged displacements before the last commit (the secant
    /// predictor's, "Prescribed increments").
    previous_u: Option<Vec<f64>>,
    /// With friction, every frictional node at the converged state (its
    /// accumulated slip).
    friction: Vec<NodalFriction>,
    // history
    records: Vec<StepRecord<D>>,
    cutbacks: Vec<Cutback>,
    snapshots: Vec<State<D>>,
    iterations: usize,
    failed_iterations: usize,
    repeated_iterations: usize,
    accuracy_halvings: Vec<AccuracyHalving>,
}

impl<'a, const D: usize, S: ContactSpace<D>> Run<'a, D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    pub(crate) fn new(
        model: &'a Model<D>,
        opts: &'a SolveOptions,
        monitor: &'a dyn Monitor,
    ) -> Result<Run<'a, D, S>, SolverError> {
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
        // The contact faces are two-node segments: a formulation of 3-node
        // segments (quadratic-slave-normal) cannot evaluate them.
        if let Some(why) = opts
            .formulation
            .and_then(crate::options::unsupported_formulation)
        {
            return Err(SolverError::Options(why));
        }
        let setup = Setup::<D, S>::new(model, opts)?;
        check_friction(model, setup.layout.has_friction(), opts.method, opts.linear)?;
        let n_points = setup.layout.point_count();
        // the one place that matches on the method
        let treatment: Box<dyn ContactTreatment<D, S>> = match opts.method {
            Method::Complete => Box::new(Complete::<S::Master, S::Anchor>::default()),
            Method::Approx(ty) => Box::new(Frozen::<D, S>::new(ty)),
        };
        Ok(Run {
            opts,
            monitor,
            started: Instant::now(),
            timings: Timings::default(),
            counts: KernelCounts::default(),
            u: vec![0.0; model.dof_count()],
            lambda: vec![0.0; setup.layout.multiplier_count()],
            pairing: vec![None; n_points],
            ties: Vec::new(),
            setup,
            load_factor: 0.0,
            energy: 0.0,
            treatment,
            previous_u: None,
            friction: Vec::new(),
            records: Vec::new(),
            cutbacks: Vec::new(),
            snapshots: Vec::new(),
            iterations: 0,
            failed_iterations: 0,
            repeated_iterations: 0,
            accuracy_halvings: Vec::new(),
        })
    }

    fn state(&self) -> State<D> {
        State {
            load_factor: self.load_factor,
            displacements: self
                .u
                .chunks(D)
                .map(|c| std::array::from_fn(|i| c[i]))
                .collect(),
            multipliers: self.lambda.clone(),
            friction: self.friction.clone(),
        }
    }

    /// Runs the whole schedule.
    pub(crate) fn execute(mut self) -> Result<Solution<D>, SolverError> {
        let start = Instant::now();
        self.started = start;
        // initial pairing in the reference configuration
        let t = Instant::now();
        let (initial, counts) = self
            .setup
            .initial_pairing(&self.u)
            .map_err(|f| self.setup.kernel_error(&f, 0.0))?;
        self.counts += counts;
        self.pairing = initial;
        self.timings.contact_evaluation += t.elapsed();
        if self.opts.record_steps {
            self.snapshots.push(self.state());
        }
        let end = self.setup.model.load_factor_end;
        let steps = self.opts.steps;
        for step in 1..=steps {
            let mut schedule = ScheduledStep::new(step, steps, end, self.load_factor);
            let (iterations_before, cutbacks_before) = (self.iterations, self.cutbacks.len());
            while let Some(to) = schedule.next_target(self.load_factor) {
                self.check_stop()?;
                match self.attempt(to)? {
                    AttemptOutcome::Converged(c) => self.commit(step, to, c),
                    AttemptOutcome::TooCoarse(c) => {
                        if schedule.cut_back(self.opts.max_cutbacks).is_ok() {
                            self.repeated_iterations += c.iterations;
                            self.accuracy_halvings.push(AccuracyHalving {
                                step,
                                from_load_factor: self.load_factor,
                                attempted_load_factor: to,
                                remainder: c
                                    .step_end
                                    .as_ref()
                                    .and_then(|e| e.remainder)
                                    .unwrap_or(f64::NAN),
                                iterations: c.iterations,
                            });
                        } else {
                            // cannot be halved further: accept it
                            self.commit(step, to, c);
                        }
                    }
                    AttemptOutcome::CutBack(failed) => {
                        self.failed_iterations += failed.iterations;
                        let cutback = Cutback {
                            step,
                            from_load_factor: self.load_factor,
                            attempted_load_factor: to,
                            reason: failed.reason.clone(),
                            residuals: failed.residuals,
                        };
                        self.monitor.cut_back(&cutback);
                        self.cutbacks.push(cutback);
                        if let Err(cutbacks) = schedule.cut_back(self.opts.max_cutbacks) {
                            return Err(give_up(
                                step,
                                self.load_factor,
                                to,
                                cutbacks,
                                failed.reason,
                            ));
                        }
                    }
                }
            }
            self.monitor.step_done(&StepProgress {
                step,
                steps,
                load_factor: self.load_factor,
                iterations: self.iterations - iterations_before,
                cutbacks: self.cutbacks.len() - cutbacks_before,
                elapsed: start.elapsed(),
            });
        }
        self.finish(start)
    }

    /// `Err(Interrupted)` once the monitor asks the solve to stop.
    fn check_stop(&self) -> Result<(), SolverError> {
        if self.monitor.stop_requested() {
            return Err(SolverError::Interrupted {
                load_factor: self.load_factor,
            });
        }
        Ok(())
    }

    /// Makes a converged attempt towards `to` the converged state.
    fn commit(&mut self, step: usize, to: f64, c: Converged<D, S::Master>) {
        self.previous_u = Some(std::mem::replace(&mut self.u, c.state.u));
        self.lambda = c.state.lambda;
        self.pairing = c.state.pairing;
        self.ties = c.state.ties;
        self.load_factor = to;
        self.energy = c.energy;
        self.iterations += c.iterations;
        let mut friction = c.friction;
        for (k, node) in friction.iter_mut().enumerate() {
            let before = self.friction.get(k).map_or(0.0, |n| n.slip);
            // only a node in contact slips; an open one moves freely
            let step = match node.state {
                FrictionState::Open => 0.0,
                FrictionState::Stick | FrictionState::Slip { .. } => node.step_length(),
            };
            node.slip = before + step;
        }
        self.friction = friction;
        self.treatment.committed();
        let step_end = c.step_end.unwrap_or_default();
        self.records.push(StepRecord {
            step,
            load_factor: to,
            iterations: c.iterations,
            residuals: c.residuals,
            strain_energy: c.energy,
            unpaired: c.points.unpaired,
            node_ties: c.points.node_ties,
            kept_outside: [c.points.kept_outside, step_end.kept_outside].concat(),
            active_multipliers: c.points.active_multipliers,
            roundoff_floor: c.roundoff_floor,
            reactions: c.reactions,
            repeats: step_end.repeats,
            taylor_remainder: step_end.remainder,
            unsettled: step_end.unsettled,
        });
        if self.opts.record_steps {
            self.snapshots.push(self.state());
        }
    }

    fn finish(mut self, start: Instant) -> Result<Solution<D>, SolverError> {
        let layout = &self.setup.layout;
        let (projections, _) = layout
            .project_all(&self.setup.model.mesh, &self.u, &self.pairing)
            .map_err(|f| self.setup.kernel_error(&f, self.load_factor))?;
        let contact_points = layout.reports(&projections);
        let mut timings = self.timings;
        timings.symbolic_factorisation = self.setup.linear.symbolic_time();
        timings.total = start.elapsed();
        Ok(Solution {
            method: self.opts.method,
            formulations: layout.formulations(),
            steps: self.opts.steps,
            load_factor: self.load_factor,
            strain_energy: self.energy,
            newton_iterations: self.iterations,
            failed_iterations: self.failed_iterations,
            repeats: self.records.iter().map(|r| r.repeats).sum(),
            repeated_iterations: self.repeated_iterations,
            step_end_projections: self.treatment.step_end_projections(),
            accuracy_halvings: self.accuracy_halvings.clone(),
            step_records: self.records.clone(),
            cutbacks: self.cutbacks.clone(),
            timings,
            kernel_counts: self.counts,
            symbolic_factorisations: self.setup.linear.symbolic_factorisations(),
            linear_fallbacks: self.setup.linear.fallbacks(),
            linear_fallback_log: self.setup.linear.fallback_log().to_vec(),
            linear_indefinite_log: self.setup.linear.indefinite_log().to_vec(),
            factor_nonzeros: self.setup.linear.factor_nonzeros(),
            krylov: self.setup.linear.krylov(),
            equations: self.setup.dofs.n_eq(),
            mesh: self.setup.model.mesh.clone(),
            geometries: std::mem::take(&mut self.setup.geometries),
            multiplier_dofs: layout.multiplier_dofs(),
            final_state: self.state(),
            snapshots: self.snapshots.clone(),
            contact_points,
            contact_pairs: self
                .setup
                .model
                .contacts
                .iter()
                .zip(layout.formulations())
                .map(|(p, formulation)| crate::model::ContactPair {
                    formulation,
                    ..p.clone()
                })
                .collect(),
            support_groups: self
                .setup
                .model
                .supports
                .iter()
                .map(|g| g.name.clone())
                .collect(),
            held_nodes: held_nodes::<D>(self.setup.model),
        })
    }
}

/// Per node of `model`'s mesh, whether every one of its `D` dofs is
/// prescribed ([`Solution::held_nodes`]).
fn held_nodes<const D: usize>(model: &Model<D>) -> Vec<bool>
where
    Dim<D>: SurfaceDim<D>,
{
    let mut prescribed = vec![0usize; model.mesh.node_count()];
    for p in &model.prescribed {
        prescribed[p.dof.node_in::<D>().index()] += 1;
    }
    prescribed.into_iter().map(|c| c == D).collect()
}

/// The pairs' friction against what the solve can do (see
/// [`crate::contact::friction`]): a coefficient finite and `>= 0`; above 0
/// only on unilateral pairs of an element that solves friction (2D
/// segments), with the complete formulation or Types 2–6 (Type 1 keeps
/// `xi_m` constant, so its slip is zero within a step: it would carry no
/// friction, and its stick rows would be empty), and with a linear solver
/// that takes an unsymmetric matrix (the slip rows are: LDLᵀ would factor
/// one triangle of it).
fn check_friction<const D: usize>(
    model: &Model<D>,
    solves_friction: bool,
    method: Method,
    linear: crate::linear::LinearSolverKind,
) -> Result<(), SolverError>
where
    Dim<D>: SurfaceDim<D>,
{
    for pair in &model.contacts {
        let mu = pair.friction;
        let why = if !(mu.is_finite() && mu >= 0.0) {
            format!("friction must be a finite number >= 0, got {mu}")
        } else if mu == 0.0 {
            continue;
        } else if pair.mode != crate::model::ContactMode::Unilateral {
            "friction needs a unilateral pair".to_owned()
        } else if !solves_friction {
            "its contact element does not solve friction".to_owned()
        } else if method == Method::Approx(ApproxType::Type1) {
            return Err(SolverError::NotApplicable(format!(
                "contact pair `{}`: Type 1 cannot carry friction: it keeps xi_m constant, so its slip is zero within a load step (every point held to the master point it faced, docs/conventions.md, \"The slip\"); use Types 2-6 or the complete formulation",
                pair.name
            )));
        } else if linear == crate::linear::LinearSolverKind::Ldlt {
            "friction makes the Newton matrix unsymmetric (its slip rows), which LDLᵀ cannot factor: use `linear = \"lu\"` (the default) or `petsc`".to_owned()
        } else {
            continue;
        };
        return Err(SolverError::Options(format!(
            "contact pair `{}`: {why}",
            pair.name
        )));
    }
    Ok(())
}
