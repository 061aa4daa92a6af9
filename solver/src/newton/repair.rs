//! Types 1–6 at a converged step end: re-pairing, the repeat with the new
//! pairing's Taylor expansion, and the Taylor remainder (see [`super`],
//! "Re-pairing at the step end").
//!
//! The frozen expansion of a point is that of the gap on the master segment
//! the point was paired with at the step start. When the point slides
//! across a master node during the step, its true gap at the end is that of
//! the next segment, and the expansion misses it by about (kink angle) x
//! (distance past the node): the step's solution is that of the wrong
//! constraint. At a converged step end every point is therefore re-paired
//! by projection (the complete formulation's search, [`ContactLayout::
//! project_all`](crate::contact::ContactLayout::project_all), starting from
//! the expansion's segment). If a point now projects into another segment
//! (or became paired, or unpaired), its expansion is replaced by that of
//! the **new** segment's gap, taken at that attempt's converged end (where
//! the point lies on the new segment), and the step is solved again from
//! its start. This repeats until the pairing at the end is the one the
//! expansion was built on, so that each point's constraint belongs to the
//! segment it ends on — the same condition the complete formulation
//! imposes at a converged iterate.
//!
//! **Anchor iteration.** A point that crossed a node has no expansion on
//! its end segment at the step start. The first implementation took the
//! new segment's expansion at the step start `u0`, on the segment's line
//! one or two segments away; on `scenes/sliding.toml` at 20 steps every
//! point crosses a node in every sliding step and that expansion's
//! remainder (1e-2 of the element size for Types 4/6, 2e-3 for 3/5) left
//! the normal reaction 0.5 % low during the whole slide: -0.50 % energy
//! for Types 4/6, the same at 10 and 20 steps because the end state only
//! depends on the last step's expansions. The expansion of a moved point
//! is therefore taken at the converged end of the attempt that found the
//! new segment, and re-taken at each following end while its relative
//! remainder there exceeds [`ANCHOR_TOLERANCE`] (at most
//! [`MAX_ANCHOR_UPDATES`] times per attempt): a fixed-point iteration
//! whose limit is the point's exact gap at the step end. A point that
//! stays on its segment keeps the type's expansion at the step start.
//!
//! Termination: within one attempt a point never goes back to a pairing it
//! has already been given (that is a point cycling at a master node, where
//! neither side is consistent; the complete formulation ties it). Such a
//! point keeps its current expansion and is listed as unsettled, as is
//! every point still changing after [`MAX_REPAIR_REPEATS`] repeats or when
//! re-pairing is off (`[newton] repair = false`). A repeat that fails to
//! converge is cut back like any attempt, keeping the new expansions (the
//! shorter step re-pairs again at its end).
//!
//! The **Taylor remainder** of an accepted step is, at every active point
//! (paired in the expansion and at the end, with at least one of its
//! multipliers carrying a constraint row), the re-projected gap minus the
//! expansion's gap at the end state, over the slave segment's reference
//! length; the step reports its largest magnitude. With a `taylor_tolerance`
//! a step above it is halved ([`AttemptOutcome::TooCoarse`]).
//!
//! Invariant: the check changes nothing when every point ends on the
//! segment its expansion was built on (the paper scene): the Newton
//! iterations and results are those without it; its projection calls are
//! counted apart ([`crate::Solution::step_end_projections`]).

use contact_kernels::ApproxType;
use nalgebra::SVector;

use crate::contact::{Paired, Taylor};
use crate::error::SolverError;
use crate::ids::{ContactPointIndex, DofId, MasterSegmentIndex};
use crate::solution::{ContactPointId, CutbackReason};

use super::attempt::{AttemptOutcome, Converged};
use super::{MAX_REPAIR_REPEATS, Run};

/// A point whose expansion was re-taken at an attempt's end (it crossed a
/// master node) gets it re-taken at the next end while its relative Taylor
/// remainder there exceeds this: the anchor iteration has converged when
/// the expansion reproduces the point's true gap at the end it describes
/// (module docs).
pub(super) const ANCHOR_TOLERANCE: f64 = 1e-8;

/// At most this many anchor updates per attempt (each one more solve of
/// the step); a point still above [`ANCHOR_TOLERANCE`] then shows in the
/// step's Taylor remainder.
pub(super) const MAX_ANCHOR_UPDATES: usize = 4;

/// What the step-end check found for an accepted attempt.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct StepEnd {
    /// Times the step was solved again with a new pairing.
    pub(super) repeats: usize,
    /// Largest `|g_true - g~| / L_s` over the active points; `None` when
    /// no point is active.
    pub(super) remainder: Option<f64>,
    /// Points whose pairing at the end differs from their expansion's
    /// (`master_segment`: the expansion's).
    pub(super) unsettled: Vec<ContactPointId>,
}

impl Run<'_> {
    /// Newton's method to `to` with the current expansions, then the
    /// step-end check, repeated with new expansions while the pairing
    /// changes (module docs).
    pub(super) fn repaired_attempt(
        &mut self,
        ty: ApproxType,
        to: f64,
    ) -> Result<AttemptOutcome, SolverError> {
        let mut tried: Vec<Vec<Option<MasterSegmentIndex>>> =
            self.pairing.iter().map(|p| vec![*p]).collect();
        let mut end = StepEnd::default();
        // points whose expansion was re-taken at an attempt's end
        let mut moved = vec![false; tried.len()];
        let (mut switches, mut updates) = (0, 0);
        loop {
            let outcome = self.newton(to)?;
            let AttemptOutcome::Converged(mut c) = outcome else {
                return Ok(outcome);
            };
            let found = match self.project_end(&c.state.u) {
                Ok(f) => f,
                Err(reason) => {
                    return Ok(AttemptOutcome::cut_back(reason, c.residuals, c.iterations));
                }
            };
            let taylor = self.taylor.as_deref().unwrap_or(&[]);
            let mut switch = Vec::new();
            let mut unsettled = Vec::new();
            for (i, (t, f)) in taylor.iter().zip(&found).enumerate() {
                let built = t.map(|t| t.at_start.master);
                let now = f.map(|(m, _)| m);
                if now == built {
                    continue;
                }
                let i = ContactPointIndex::new(i);
                if self.opts.repair
                    && switches < MAX_REPAIR_REPEATS
                    && !tried[i.index()].contains(&now)
                {
                    switch.push((i, now));
                } else {
                    unsettled.push(ContactPointId {
                        master_segment: built.map(MasterSegmentIndex::index),
                        ..self.setup.point_id(i)
                    });
                }
            }
            if switch.is_empty() && updates < MAX_ANCHOR_UPDATES {
                // the moved points whose expansion misses their end gap
                switch = self.unconverged_anchors(&c, &found, &moved);
                if !switch.is_empty() {
                    updates += 1;
                }
            } else if !switch.is_empty() {
                switches += 1;
            }
            if !switch.is_empty() {
                for (i, _) in &switch {
                    moved[i.index()] = true;
                }
                self.switch_expansions(ty, &switch, &mut tried, &c.state.u)?;
                end.repeats += 1;
                self.repeated_iterations += c.iterations;
                continue;
            }
            end.unsettled = unsettled;
            end.remainder = self.remainder(&c, &found);
            let too_coarse = matches!(
                (end.remainder, self.opts.taylor_tolerance),
                (Some(r), Some(tol)) if r > tol
            );
            c.step_end = Some(end);
            return Ok(if too_coarse {
                AttemptOutcome::TooCoarse(c)
            } else {
                AttemptOutcome::Converged(c)
            });
        }
    }

    /// Re-pairs every point at the end state `u` by projection, searching
    /// from its expansion's segment (counted in `step_end_projections`).
    fn project_end(&mut self, u: &[f64]) -> Result<Vec<Option<Paired>>, CutbackReason> {
        let t = std::time::Instant::now();
        let result = self
            .setup
            .layout
            .project_all(&self.setup.model.mesh, u, &self.pairing);
        self.timings.contact_evaluation += t.elapsed();
        match result {
            Ok((found, counts)) => {
                self.step_end_projections += counts.project + counts.evaluate;
                Ok(found)
            }
            Err(f) => Err(CutbackReason::Kernel {
                point: self.setup.failure_point(&f),
                error: f.error,
            }),
        }
    }

    /// The points `moved` at an earlier attempt's end that end active on
    /// the segment of their expansion with a relative remainder above
    /// [`ANCHOR_TOLERANCE`], each with that segment: their expansion is to
    /// be re-taken at this end (module docs).
    fn unconverged_anchors(
        &self,
        c: &Converged,
        found: &[Option<Paired>],
        moved: &[bool],
    ) -> Vec<(ContactPointIndex, Option<MasterSegmentIndex>)> {
        let taylor = self.taylor.as_deref().unwrap_or(&[]);
        let mut again = Vec::new();
        for (i, (t, f)) in taylor.iter().zip(found).enumerate() {
            let (true, Some(t), Some((m, p))) = (moved[i], t, f) else {
                continue;
            };
            let i = ContactPointIndex::new(i);
            if *m == t.at_start.master
                && self
                    .point_remainder(c, i, t, p.gap)
                    .is_some_and(|r| r > ANCHOR_TOLERANCE)
            {
                again.push((i, Some(*m)));
            }
        }
        again
    }

    /// The relative Taylor remainder `|g - g~| / L_s` of point `i` with
    /// expansion `t` and re-projected gap `gap` at the end of `c`; `None`
    /// when none of its multipliers carries a constraint row.
    fn point_remainder(
        &self,
        c: &Converged,
        i: ContactPointIndex,
        t: &Taylor,
        gap: f64,
    ) -> Option<f64> {
        let pt = self.setup.layout.point(i);
        if !pt.multipliers.iter().any(|m| c.active[m.index()]) {
            return None;
        }
        let mesh = &self.setup.model.mesh;
        let [a, b] = pt.slave_nodes.map(|n| mesh.node_ref(n));
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        Some((gap - t.expand(&c.state.u).gap).abs() / length)
    }

    /// Replaces the expansions of the points in `switch` by those of their
    /// new pairing taken at the state `anchor` (the end of the attempt
    /// that found it; `None`: no expansion, the point is inactive); a
    /// point whose new segment the kernel cannot evaluate there keeps its
    /// expansion. Records every new pairing in `tried`.
    fn switch_expansions(
        &mut self,
        ty: ApproxType,
        switch: &[(ContactPointIndex, Option<MasterSegmentIndex>)],
        tried: &mut [Vec<Option<MasterSegmentIndex>>],
        anchor: &[f64],
    ) -> Result<(), SolverError> {
        let t = std::time::Instant::now();
        let mesh = &self.setup.model.mesh;
        let u0 = anchor;
        let taylor = self.taylor.get_or_insert_with(Vec::new);
        for &(i, now) in switch {
            if !tried[i.index()].contains(&now) {
                tried[i.index()].push(now);
            }
            let new = match now {
                None => None,
                Some(m) => {
                    match self
                        .setup
                        .layout
                        .evaluate_on(mesh, u0, i, m, ty, &mut self.counts)
                    {
                        Ok(at_start) => Some(Taylor {
                            u0: SVector::<f64, 8>::from_fn(|k, _| {
                                u0[DofId::of(at_start.nodes[k / 2], k % 2).index()]
                            }),
                            at_start,
                        }),
                        Err(_) => continue,
                    }
                }
            };
            taylor[i.index()] = new;
            self.pairing[i.index()] = now;
        }
        self.timings.contact_evaluation += t.elapsed();
        Ok(())
    }

    /// The largest relative Taylor remainder of the converged attempt `c`
    /// over its active points, with `found` the re-projection at its end
    /// (module docs).
    fn remainder(&self, c: &Converged, found: &[Option<Paired>]) -> Option<f64> {
        let taylor = self.taylor.as_deref()?;
        let mut worst: Option<f64> = None;
        for (i, (t, f)) in taylor.iter().zip(found).enumerate() {
            let (Some(t), Some((_, p))) = (t, f) else {
                continue;
            };
            if let Some(r) = self.point_remainder(c, ContactPointIndex::new(i), t, p.gap) {
                worst = Some(worst.map_or(r, |w| w.max(r)));
            }
        }
        worst
    }
}
