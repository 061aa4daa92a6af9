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
//! the point lies on the new segment), and the step is solved again: the
//! same equations (load factor `to`, the other points' step-start
//! expansions), Newton started from the discarded attempt's converged
//! displacements and multipliers (a warm start: the frozen problem has no
//! history, so only the iteration count changes; on the sliding scenes
//! the errors agree to four digits with a start from the step start and
//! the repeats cost 40 % fewer iterations). This repeats until the pairing
//! at the end is the one the expansion was built on, so that each point's
//! constraint belongs to the segment it ends on — the same condition the
//! complete formulation imposes at a converged iterate.
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
//! **Points cycling at a node.** A point may go back to a pairing it has
//! already been given in the attempt: converged on segment A it projects
//! into B, converged on B back into A. That is a point at a concave master
//! node, where neither side is consistent and the discrete solution holds
//! the point at the node (the complete formulation ties it, see
//! [`crate::contact`], "Points stuck at a master node"). Such a point is
//! tied the same way ([`NodeTie`]: potential `lambda w J0 g_A + mu (g_B -
//! g_A)`, the equation `g_B = g_A`), with the expansions of both segments
//! taken at the attempt's end (re-taken by the anchor iteration, kept in
//! `Frozen::ties`), and the step is solved again. A tie whose weight
//! `theta = mu / (lambda w J0)` leaves `[0, 1]` at a converged end is
//! released (to A for `theta < 0`, to B for `theta > 1`) and the point is
//! never tied again in that attempt. Ties last one step: the next step's
//! expansions are built without them (a point still stuck is tied again
//! at that step's end). Measured on `scenes/sliding.toml` at 160 steps,
//! where the complete formulation ties 18 points: before the ties every
//! type had 40 unsettled points and reactions 1.52 % off (one step,
//! load factor 0.26875, the tangential reaction of a point kept on one
//! segment's line past a concave node); with them, 0.010–0.021 %.
//!
//! Termination: a point cycling where no tie is possible (between a
//! segment and none; in 3D between any two faces, see [`crate::contact`],
//! "Points stuck at a master node"), or still changing after
//! [`MAX_REPAIR_REPEATS`] pairing repeats, keeps its current expansion.
//! It is listed as kept outside ([`crate::StepRecord::kept_outside`]) when
//! its projection onto its expansion's master at the end misses that
//! master by less than [`crate::contact::XI_STUCK_BAND`] (the complete
//! formulation's rule for a stuck point it cannot tie), as unsettled
//! otherwise. With re-pairing off (`[newton] repair = false`) no point is
//! moved or tied, nothing above runs, and every point that ends on
//! another master is listed as unsettled. A repeat that fails to converge is cut back like any
//! attempt, keeping the new expansions (the shorter step re-pairs again at
//! its end; an expansion taken elsewhere than at the step start counts as
//! moved there).
//!
//! The **Taylor remainder** of an accepted step is, at every active point
//! (paired in the expansion and at the end, with at least one of its
//! multipliers carrying a constraint row), the re-projected gap minus the
//! expansion's gap at the end state, over the slave segment's reference
//! length; the step reports its largest magnitude. With a `taylor_tolerance`
//! the points above it (at an end whose pairing stands) get their
//! expansions re-taken there like a moved point's, within the same
//! [`MAX_ANCHOR_UPDATES`], and the step is solved again; a step still above
//! it is halved ([`AttemptOutcome::TooCoarse`]).
//!
//! Invariant: the check changes nothing when every point ends on the
//! segment its expansion was built on (the paper scene): the Newton
//! iterations and results are those without it; its projection calls are
//! counted apart ([`crate::Solution::step_end_projections`]).

use std::time::Instant;

use crate::contact::ContactSpace;
use crate::contact::NodeTie;
use crate::error::SolverError;
use crate::ids::ContactPointIndex;
use crate::solution::CutbackReason;

use super::MAX_REPAIR_REPEATS;
use super::frozen::Frozen;
use super::outcome::{AttemptOutcome, Converged};
use super::setup::Setup;
use super::treatment::{Context, SolveEnd, StepStart};
use crate::model::{Dim, SurfaceDim};

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

impl<const D: usize, S: ContactSpace<D>> Frozen<D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The step-end check of the converged solve `c` (module docs): the
    /// attempt's outcome, or a repeat of the step with new expansions
    /// while the pairing changes.
    pub(super) fn check_end(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        mut start: StepStart<'_, S::Master>,
        mut c: Converged<D, S::Master>,
    ) -> Result<SolveEnd<D, S::Master>, SolverError> {
        let found = match self.project_end(cx, start.pairing, &c.state.u) {
            Ok(f) => f,
            Err(reason) => {
                let failed = AttemptOutcome::cut_back(reason, c.residuals, c.iterations);
                return Ok(SolveEnd::Done(Box::new(failed)));
            }
        };
        // ties whose weight left [0, 1]: released to that side
        let mut changed = self.release_ties(cx.setup, &mut start, &c);
        let layout = &cx.setup.layout;
        let mut switch = Vec::new();
        let mut tie = Vec::new();
        let mut unsettled = Vec::new();
        let mut kept = Vec::new();
        let mesh = &cx.setup.model.mesh;
        for (i, (t, f)) in self.points.iter().zip(&found).enumerate() {
            let built = t.as_ref().map(|t| S::master(S::expanded(t)));
            let now = f.as_ref().map(S::found_master);
            let i = ContactPointIndex::new(i);
            if now == built || start.ties.iter().any(|t| t.point == i) {
                continue;
            }
            let repeats_left = self.check.switches < MAX_REPAIR_REPEATS;
            if !cx.opts.repair {
                // listed below
            } else if repeats_left && !self.check.tried[i.index()].contains(&now) {
                switch.push((i, now));
                continue;
            } else if let (Some(p), Some(o)) = (built, now)
                && repeats_left
                && !self.check.released.contains(&i)
                && layout.can_tie(i, p, o)
            {
                // cycling at the node between two segments: tie it
                tie.push((i, p, o));
                continue;
            } else if let Some(p) = built
                && layout
                    .evaluate_on(mesh, &c.state.u, i, p, self.ty, cx.counts)
                    .is_ok_and(|e| layout.within_band(&e))
            {
                // stuck where no tie is made: kept on its expansion's
                // master, which its projection misses by less than the
                // band, as the complete formulation keeps it
                kept.push(layout.point_id(i, built));
                continue;
            }
            unsettled.push(layout.point_id(i, built));
        }
        if !switch.is_empty() || !tie.is_empty() {
            self.check.switches += 1;
        } else if cx.opts.repair && !changed && self.check.updates < MAX_ANCHOR_UPDATES {
            // the moved points whose expansion misses their end gap and,
            // with a `taylor_tolerance`, the others whose remainder exceeds
            // it: re-taken at this end
            switch = self.unconverged_anchors(
                cx.setup,
                start.ties,
                &c,
                &found,
                cx.opts.taylor_tolerance,
            );
            let retied = self.reanchor_ties(cx, start.ties, &c)?;
            if !switch.is_empty() || retied {
                self.check.updates += 1;
                changed = true;
            }
        }
        if !switch.is_empty() || !tie.is_empty() || changed {
            // tied points too: released later in the attempt, they keep
            // an end-taken expansion and must be re-anchored like a
            // switched point
            for i in switch
                .iter()
                .map(|(i, _)| i)
                .chain(tie.iter().map(|(i, ..)| i))
            {
                self.check.moved[i.index()] = true;
            }
            self.switch_expansions(cx, start.pairing, &switch, &c.state.u)?;
            self.tie_points(cx, &mut start, &tie, &c.state.u)?;
            self.check.end.repeats += 1;
            // the repeat starts Newton from the discarded solve's end
            return Ok(SolveEnd::Again {
                warm: (c.state.u, c.state.lambda),
                spent: c.iterations,
            });
        }
        let mut end = std::mem::take(&mut self.check.end);
        end.unsettled = unsettled;
        end.kept_outside = kept;
        end.remainder = self.remainder(cx.setup, &c, &found);
        let too_coarse = matches!(
            (end.remainder, cx.opts.taylor_tolerance),
            (Some(r), Some(tol)) if r > tol
        );
        c.step_end = Some(end);
        Ok(SolveEnd::Done(Box::new(if too_coarse {
            AttemptOutcome::TooCoarse(c)
        } else {
            AttemptOutcome::Converged(c)
        })))
    }

    /// Per point: whether its expansion was taken elsewhere than at the
    /// converged state `start` (its anchor's nodal displacements differ
    /// from the step start's), or the point is tied.
    pub(super) fn anchored_elsewhere(&self, start: &StepStart<'_, S::Master>) -> Vec<bool> {
        let mut moved: Vec<bool> = self
            .points
            .iter()
            .map(|t| t.as_ref().is_some_and(|t| S::moved(t, &self.built_at)))
            .collect();
        for tie in start.ties.iter() {
            moved[tie.point.index()] = true;
        }
        moved
    }

    /// Releases the ties whose weight `theta` at the end of `c` left
    /// `[0, 1]`: to the paired segment for `theta < 0`, to the other one
    /// (its expansion becomes the point's) for `theta > 1`, as the
    /// complete formulation does; records them in the check's
    /// `released`. Returns whether any was released.
    fn release_ties(
        &mut self,
        setup: &Setup<'_, D, S>,
        start: &mut StepStart<'_, S::Master>,
        c: &Converged<D, S::Master>,
    ) -> bool {
        let layout = &setup.layout;
        let mut keep = Vec::with_capacity(start.ties.len());
        let mut changed = false;
        for (k, tie) in c.state.ties.iter().enumerate() {
            let theta = layout.tie_theta(tie, &c.state.lambda).unwrap_or(-1.0);
            if (0.0..=1.0).contains(&theta) {
                keep.push(k);
                continue;
            }
            if theta > 1.0 {
                self.points[tie.point.index()] = Some(self.ties[k].clone());
                start.pairing[tie.point.index()] = Some(tie.other);
            }
            self.check.released.push(tie.point);
            changed = true;
        }
        if changed {
            *start.ties = keep.iter().map(|&k| start.ties[k]).collect();
            self.ties = keep.iter().map(|&k| self.ties[k].clone()).collect();
        }
        changed
    }

    /// Ties each point of `tie` (`(point, paired, other)`) to the node
    /// between its two segments, with both segments' expansions taken at
    /// `anchor` (module docs, "Points cycling at a node").
    fn tie_points(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        start: &mut StepStart<'_, S::Master>,
        tie: &[(ContactPointIndex, S::Master, S::Master)],
        anchor: &[f64],
    ) -> Result<(), SolverError> {
        let mesh = &cx.setup.model.mesh;
        let layout = &cx.setup.layout;
        for &(i, p, o) in tie {
            let (Ok(on_p), Ok(on_o)) = (
                layout.evaluate_on(mesh, anchor, i, p, self.ty, cx.counts),
                layout.evaluate_on(mesh, anchor, i, o, self.ty, cx.counts),
            ) else {
                continue;
            };
            let (Ok(on_p), Ok(on_o)) = (
                self.with_slip(cx, anchor, i, on_p),
                self.with_slip(cx, anchor, i, on_o),
            ) else {
                continue;
            };
            self.points[i.index()] = Some(S::expand_at(on_p, anchor));
            start.pairing[i.index()] = Some(p);
            start.ties.push(NodeTie {
                point: i,
                paired: p,
                other: o,
                mu: 0.0,
            });
            self.ties.push(S::expand_at(on_o, anchor));
        }
        Ok(())
    }

    /// Re-takes both expansions of every tied point at the end of `c`
    /// when either misses that segment's gap there by more than
    /// [`ANCHOR_TOLERANCE`] (relative); returns whether any was re-taken.
    fn reanchor_ties(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        ties: &[NodeTie<S::Master>],
        c: &Converged<D, S::Master>,
    ) -> Result<bool, SolverError> {
        let setup = cx.setup;
        let mesh = &setup.model.mesh;
        let layout = &setup.layout;
        let u = &c.state.u;
        let mut changed = false;
        for (k, tie) in ties.iter().enumerate() {
            let i = tie.point;
            let Some(on_p_taylor) = self.points[i.index()].clone() else {
                continue;
            };
            let (Ok(on_p), Ok(on_o)) = (
                layout.evaluate_on(mesh, u, i, tie.paired, self.ty, cx.counts),
                layout.evaluate_on(mesh, u, i, tie.other, self.ty, cx.counts),
            ) else {
                continue;
            };
            let (Ok(on_p), Ok(on_o)) = (
                self.with_slip(cx, u, i, on_p),
                self.with_slip(cx, u, i, on_o),
            ) else {
                continue;
            };
            let off = |t: &S::Expansion, gap: f64| {
                point_remainder(setup, c, i, t, gap).is_some_and(|r| r > ANCHOR_TOLERANCE)
            };
            if off(&on_p_taylor, S::gap(&on_p)) || off(&self.ties[k], S::gap(&on_o)) {
                self.points[i.index()] = Some(S::expand_at(on_p, u));
                self.ties[k] = S::expand_at(on_o, u);
                changed = true;
            }
        }
        Ok(changed)
    }

    /// Re-pairs every point at the end state `u` by projection, searching
    /// from its expansion's segment (`pairing`; counted in
    /// `step_end_projections`).
    fn project_end(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        pairing: &[Option<S::Master>],
        u: &[f64],
    ) -> Result<Vec<Option<S::Found>>, CutbackReason> {
        let t = Instant::now();
        let result = cx
            .setup
            .layout
            .project_all(&cx.setup.model.mesh, u, pairing);
        cx.timings.contact_evaluation += t.elapsed();
        match result {
            Ok((found, counts)) => {
                self.step_end_projections += counts.project + counts.evaluate;
                Ok(found)
            }
            Err(f) => Err(CutbackReason::Kernel {
                point: cx.setup.failure_point(&f),
                error: f.error,
            }),
        }
    }

    /// The points that end active on the segment of their expansion with
    /// a relative remainder above their bound, each with that segment:
    /// their expansion is to be re-taken at this end (module docs). The
    /// bound is [`ANCHOR_TOLERANCE`] for a point moved at an earlier
    /// attempt's end (the check's `moved`) and `taylor_tolerance` for the
    /// others (none without it).
    fn unconverged_anchors(
        &self,
        setup: &Setup<'_, D, S>,
        ties: &[NodeTie<S::Master>],
        c: &Converged<D, S::Master>,
        found: &[Option<S::Found>],
        taylor_tolerance: Option<f64>,
    ) -> Vec<(ContactPointIndex, Option<S::Master>)> {
        let mut again = Vec::new();
        for (i, (t, f)) in self.points.iter().zip(found).enumerate() {
            let (Some(t), Some(f)) = (t, f) else {
                continue;
            };
            let Some(bound) = (if self.check.moved[i] {
                Some(ANCHOR_TOLERANCE)
            } else {
                taylor_tolerance
            }) else {
                continue;
            };
            let i = ContactPointIndex::new(i);
            let m = S::found_master(f);
            if m == S::master(S::expanded(t))
                && ties.iter().all(|t| t.point != i)
                && point_remainder(setup, c, i, t, S::found_gap(f)).is_some_and(|r| r > bound)
            {
                again.push((i, Some(m)));
            }
        }
        again
    }

    /// Replaces the expansions of the points in `switch` by those of their
    /// new pairing taken at the state `anchor` (the end of the attempt
    /// that found it; `None`: no expansion, the point is inactive); a
    /// point whose new segment the kernel cannot evaluate there keeps its
    /// expansion. Records every new pairing in the check's `tried`.
    fn switch_expansions(
        &mut self,
        cx: &mut Context<'_, '_, D, S>,
        pairing: &mut [Option<S::Master>],
        switch: &[(ContactPointIndex, Option<S::Master>)],
        anchor: &[f64],
    ) -> Result<(), SolverError> {
        let t = Instant::now();
        let mesh = &cx.setup.model.mesh;
        let u0 = anchor;
        for &(i, now) in switch {
            let tried = &mut self.check.tried[i.index()];
            if !tried.contains(&now) {
                tried.push(now);
            }
            let new = match now {
                None => None,
                Some(m) => {
                    match cx
                        .setup
                        .layout
                        .evaluate_on(mesh, u0, i, m, self.ty, cx.counts)
                    {
                        Ok(at_start) => match self.with_slip(cx, u0, i, at_start) {
                            Ok(at_start) => Some(S::expand_at(at_start, u0)),
                            Err(_) => continue,
                        },
                        Err(_) => continue,
                    }
                }
            };
            self.points[i.index()] = new;
            pairing[i.index()] = now;
        }
        cx.timings.contact_evaluation += t.elapsed();
        Ok(())
    }

    /// The largest relative Taylor remainder of the converged attempt `c`
    /// over its active points, with `found` the re-projection at its end
    /// (module docs).
    fn remainder(
        &self,
        setup: &Setup<'_, D, S>,
        c: &Converged<D, S::Master>,
        found: &[Option<S::Found>],
    ) -> Option<f64> {
        let mut worst: Option<f64> = None;
        for (i, (t, f)) in self.points.iter().zip(found).enumerate() {
            let (Some(t), Some(f)) = (t, f) else {
                continue;
            };
            let gap = S::found_gap(f);
            if let Some(r) = point_remainder(setup, c, ContactPointIndex::new(i), t, gap) {
                worst = Some(worst.map_or(r, |w| w.max(r)));
            }
        }
        worst
    }
}

/// The relative Taylor remainder `|g - g~| / L_s` of point `i` with
/// expansion `t` and re-projected gap `gap` at the end of `c`; `None`
/// when none of its multipliers carries a constraint row.
fn point_remainder<const D: usize, S: ContactSpace<D>>(
    setup: &Setup<'_, D, S>,
    c: &Converged<D, S::Master>,
    i: ContactPointIndex,
    t: &S::Expansion,
    gap: f64,
) -> Option<f64>
where
    Dim<D>: SurfaceDim<D>,
{
    let length = setup
        .layout
        .remainder_length(&setup.model.mesh, i, &c.active)?;
    Some((gap - S::gap(&S::expand(t, &c.state.u))).abs() / length)
}
