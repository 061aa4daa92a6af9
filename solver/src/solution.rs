//! What a solve returns: the final state, per-step records, cut-backs,
//! contact reports, timings and kernel-call counts.
//!
//! Sign convention of the multipliers: with `Pi_c = sum w J0 lambda g`, a
//! compressive contact has `lambda < 0`; the contact pressure is
//! `p = -lambda`.
//!
//! This is the report boundary: indices here (pairs, segments, Gauss points,
//! nodes) are plain `usize`, converted from the solver's typed indices
//! ([`crate::ids`]) where the reports are written. Apart from
//! [`Timings`], the values do not depend on thread scheduling: parallel maps
//! return in index order and every sum runs sequentially (`crate::par`).

use std::time::Duration;

use contact_kernels::{Formulation, KernelError};

use crate::contact::friction::NodalFriction;
use crate::element::{ElementStress, Stress};
use crate::ids::NodeId;
use crate::linear::KrylovCounts;
use crate::mesh::{Geometries, InvertedElement, Mesh, MeshError};
use crate::model::{ContactPair, Dim, SurfaceDim};
use crate::options::Method;

/// Why a load step was cut back.
#[derive(Debug, Clone, PartialEq)]
pub enum CutbackReason {
    /// No convergence within the iteration limit.
    MaxIterations {
        /// The last residual norm.
        residual: f64,
    },
    /// The residual became NaN or infinite.
    NonFiniteResidual,
    /// The residual grew beyond the divergence bound.
    Diverging {
        /// The residual norm.
        residual: f64,
        /// The bound it exceeded.
        bound: f64,
    },
    /// The linear solve failed: the system was singular (or its solution
    /// not finite), or a fallback factorisation did not fit in memory.
    Singular {
        /// faer's message or the non-finite component.
        message: String,
    },
    /// A contact kernel failed at an integration point.
    Kernel {
        /// The point.
        point: ContactPointId,
        /// The kernel's error.
        error: KernelError,
    },
    /// Complete formulation: an integration point is stuck at a master node
    /// (its pairing cycles between two master segments, or between a
    /// segment and none at the chain's end) and its projection misses the
    /// kept segment by more than [`crate::contact::XI_STUCK_BAND`] (see
    /// [`crate::contact`], "Pairing in the complete formulation").
    StuckAtMasterNode {
        /// The point, with the master segment it was kept on.
        point: ContactPointId,
        /// Its projection coordinate there.
        xi_m: f64,
    },
    /// The iterate inverts an element (`det F <= 0` at an integration
    /// point, [`crate::mesh::inversion`]): rejected, whatever its residual.
    InvertedElement(InvertedElement),
}

impl std::fmt::Display for CutbackReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CutbackReason::MaxIterations { residual } => {
                write!(
                    f,
                    "no convergence within the iteration limit (residual {residual:.3e})"
                )
            }
            CutbackReason::NonFiniteResidual => write!(f, "non-finite residual"),
            CutbackReason::Diverging { residual, bound } => {
                write!(f, "diverging (residual {residual:.3e} above {bound:.3e})")
            }
            CutbackReason::Singular { message } => write!(f, "{message}"),
            CutbackReason::Kernel { point, error } => {
                write!(f, "contact kernel failed at {point}: {error}")
            }
            CutbackReason::InvertedElement(inverted) => write!(f, "{inverted}"),
            CutbackReason::StuckAtMasterNode { point, xi_m } => write!(
                f,
                "{point} is stuck at a master node: its pairing cycles and xi_m = {xi_m:.6} \
                 misses the segment by more than the band"
            ),
        }
    }
}

/// One cut-back (bisection of a load increment).
#[derive(Debug, Clone, PartialEq)]
pub struct Cutback {
    /// The scheduled step (1-based) being solved.
    pub step: usize,
    /// The converged load factor the attempt started from.
    pub from_load_factor: f64,
    /// The load factor the failed attempt aimed at.
    pub attempted_load_factor: f64,
    /// Why it failed.
    pub reason: CutbackReason,
    /// The failed attempt's residual norms.
    pub residuals: Vec<f64>,
}

/// One converged (sub)step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord<const D: usize = 2> {
    /// The scheduled step (1-based) it belongs to.
    pub step: usize,
    /// The load factor reached.
    pub load_factor: f64,
    /// Newton iterations (linear solves) of the converged attempt.
    pub iterations: usize,
    /// Residual norm at each iterate, the last one converged.
    pub residuals: Vec<f64>,
    /// Strain energy at the converged state.
    pub strain_energy: f64,
    /// Integration points projecting into no master segment at the end of
    /// the step.
    pub unpaired: Vec<ContactPointId>,
    /// Complete formulation: integration points held at a master node at
    /// the converged state (`master_segment`: the segment they are paired
    /// with; see [`crate::contact`], "Points stuck at a master node").
    /// Empty for Types 1–6.
    pub node_ties: Vec<ContactPointId>,
    /// Stuck integration points that could not be tied (at the end of a
    /// master chain; in 3D every stuck point), kept on a pairing
    /// (`master_segment`, `None` = inactive) their projection misses by less
    /// than [`crate::contact::XI_STUCK_BAND`]: the complete formulation's
    /// at its converged state, Types 1–6's at the step end (a point cycling
    /// between two masters whose projection onto its expansion's master
    /// lies within the band; see [`crate::newton`], "Re-pairing at the step
    /// end").
    pub kept_outside: Vec<ContactPointId>,
    /// Multipliers carrying a constraint row at the converged state.
    pub active_multipliers: usize,
    /// Accepted at the round-off floor (see [`crate::newton`]) rather than
    /// below the tolerance.
    pub roundoff_floor: bool,
    /// The reaction `[x, y]` (3D: `[x, y, z]`) of each support group at
    /// the converged state,
    /// in [`Solution::support_groups`] order: the force the supports exert
    /// on the body, summed over the group's prescribed dofs (internal plus
    /// contact force, minus loads applied there; see `newton/reactions.rs`).
    pub reactions: Vec<[f64; D]>,
    /// Types 1–6: times the step was solved again because integration
    /// points ended on other master segments than their Taylor expansion's
    /// (see [`crate::newton`], "Re-pairing at the step end"); 0 for the
    /// complete formulation.
    pub repeats: usize,
    /// Types 1–6: the step's largest Taylor remainder, `|g - g~| / L_s`
    /// at the active points (re-projected gap minus the frozen expansion's
    /// gap at the converged end state, over the slave segment's reference
    /// length); `None` for the complete formulation or without active
    /// points.
    pub taylor_remainder: Option<f64>,
    /// Types 1–6: points whose pairing at the accepted end differs from
    /// their expansion's (`master_segment`: the expansion's): cycling at a
    /// master node, still changing after
    /// [`crate::newton::MAX_REPAIR_REPEATS`] repeats, or re-pairing off.
    pub unsettled: Vec<ContactPointId>,
}

/// Types 1–6 with `[newton] taylor_tolerance`: a converged attempt
/// discarded and halved because its Taylor remainder exceeded the
/// tolerance (adaptive stepping; not a divergence, see [`Cutback`]).
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyHalving {
    /// The scheduled step (1-based) being solved.
    pub step: usize,
    /// The converged load factor the attempt started from.
    pub from_load_factor: f64,
    /// The load factor it reached.
    pub attempted_load_factor: f64,
    /// Its largest relative Taylor remainder
    /// ([`StepRecord::taylor_remainder`]).
    pub remainder: f64,
    /// Its Newton iterations (discarded).
    pub iterations: usize,
}

/// Wall-clock time spent, split by phase.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timings {
    /// Solid element evaluation and scatter.
    pub solid_assembly: Duration,
    /// Kernel calls, Taylor expansion, contact scatter and pairing.
    pub contact_evaluation: Duration,
    /// Symbolic and numeric factorisation and solve.
    pub linear_solve: Duration,
    /// The part of `linear_solve` spent in symbolic analysis (only when the
    /// sparsity pattern changed).
    pub symbolic_factorisation: Duration,
    /// The whole solve.
    pub total: Duration,
    /// The support groups' reactions at the converged states (one full
    /// residual assembly per converged step; part of `total`, not of the
    /// phases above).
    pub reactions: Duration,
}

/// Displacements and multipliers at one load factor.
#[derive(Debug, Clone, PartialEq)]
pub struct State<const D: usize = 2> {
    /// The load factor.
    pub load_factor: f64,
    /// Nodal displacements (reference frame, `D` components).
    pub displacements: Vec<[f64; D]>,
    /// Multipliers: the normal ones in [`Solution::multiplier_dofs`] order
    /// (`p = -lambda`), then the tangential ones of the pairs with friction
    /// in [`State::friction`]'s order.
    pub multipliers: Vec<f64>,
    /// Every node of a pair with friction: its state, last step's slip and
    /// accumulated slip, in the order of its tangential multiplier (empty
    /// without friction; [`crate::contact::friction`]).
    pub friction: Vec<NodalFriction>,
}

/// Kernel-call counts, and the contact element's point reports.
pub use crate::contact::{ContactPointId, ContactPointReport, KernelCounts, MultiplierDofInfo};

/// The result of [`crate::solve`] (`D`: the model's dimension).
#[derive(Debug, Clone)]
pub struct Solution<const D: usize = 2>
where
    Dim<D>: SurfaceDim<D>,
{
    /// Complete or an approximation type.
    pub method: Method,
    /// The formulation of each contact pair.
    pub formulations: Vec<Formulation>,
    /// Number of scheduled load steps.
    pub steps: usize,
    /// The final load factor reached (the scheduled end on success).
    pub load_factor: f64,
    /// Strain energy at the final state.
    pub strain_energy: f64,
    /// Newton iterations of all converged attempts.
    pub newton_iterations: usize,
    /// Newton iterations of failed attempts (work spent before cut-backs).
    pub failed_iterations: usize,
    /// Types 1–6: step repeats for pairing changes, over all steps
    /// ([`StepRecord::repeats`]).
    pub repeats: usize,
    /// Types 1–6: Newton iterations of converged attempts discarded, by
    /// the step repeats and the accuracy halvings.
    pub repeated_iterations: usize,
    /// Types 1–6: projection-kernel calls of the step-end checks (the
    /// re-pairing and the Taylor remainder), counted apart from
    /// [`Solution::kernel_counts`] (which counts the scheme's own calls).
    pub step_end_projections: u64,
    /// Types 1–6 with a `taylor_tolerance`: the steps halved for accuracy.
    pub accuracy_halvings: Vec<AccuracyHalving>,
    /// Every converged (sub)step.
    pub step_records: Vec<StepRecord<D>>,
    /// Every cut-back, in order.
    pub cutbacks: Vec<Cutback>,
    /// Timings.
    pub timings: Timings,
    /// Kernel calls.
    pub kernel_counts: KernelCounts,
    /// Symbolic LU factorisations computed (one per sparsity pattern).
    pub symbolic_factorisations: usize,
    /// Linear solves that fell back to LU because the selected solver was
    /// not safe for them (see [`crate::linear::LinearSolver::fallbacks`]);
    /// always 0 with LU.
    pub linear_fallbacks: usize,
    /// Every linear solve that did not pass the LDLᵀ's checks, with the
    /// check it failed and what the LU did (see
    /// [`crate::linear::LinearSolver::fallback_log`]); empty with LU.
    pub linear_fallback_log: Vec<crate::linear::Fallback>,
    /// Every linear solve whose stiffness was indefinite where the active
    /// constraints leave it free (see
    /// [`crate::linear::LinearSolver::indefinite_log`]); empty with LU.
    pub linear_indefinite_log: Vec<crate::linear::IndefiniteSolve>,
    /// Nonzeros of the factor of the last sparsity pattern (the fill; see
    /// [`crate::linear::LinearSolver::factor_nonzeros`]): the lower triangle
    /// of `L`, diagonal included, with LDL^T; `None` with LU, whose factors
    /// faer does not expose.
    pub factor_nonzeros: Option<usize>,
    /// An iterative linear solver's iterations (`None` for a direct one;
    /// [`crate::linear::LinearSolver::krylov`]).
    pub krylov: Option<KrylovCounts>,
    /// Number of equations (free dofs plus multipliers).
    pub equations: usize,
    /// The mesh (reference coordinates, connectivity, bodies, materials).
    pub mesh: Mesh<D>,
    /// The reference geometry of the elements the solve assembled (every
    /// element's on one rank, the rank's own across MPI ranks); the
    /// stresses compute any other element's ([`Geometries::or_compute`]).
    pub geometries: Geometries,
    /// The multiplier dofs.
    pub multiplier_dofs: Vec<MultiplierDofInfo>,
    /// The final state.
    pub final_state: State<D>,
    /// The state after every converged (sub)step, when requested.
    pub snapshots: Vec<State<D>>,
    /// Slave integration points at the final state.
    pub contact_points: Vec<ContactPointReport>,
    /// The contact pairs, in model order, each with the formulation it
    /// was solved with ([`Solution::formulations`]): what the nodal
    /// contact table is taken on ([`crate::report::ContactTable`]).
    pub contact_pairs: Vec<ContactPair<D>>,
    /// The support groups whose reactions each [`StepRecord::reactions`]
    /// holds (a scene's `[[fix]]` and `[[prescribe]]` items: their `group`,
    /// or `fix[i]` / `prescribe[i]`).
    pub support_groups: Vec<String>,
    /// Per mesh node, whether supports hold it: every one of its `D` dofs
    /// is prescribed (fixed or moved by a `[[prescribe]]`). The nodal
    /// contact table marks a slave node held on both sides with it
    /// ([`crate::report::ContactTable::clamped`]).
    pub held_nodes: Vec<bool>,
}

impl Solution<2> {
    /// The stresses at every integration point of every element of the
    /// final state, element after element (four per quadrilateral, one per
    /// triangle).
    pub fn point_stresses(&self) -> Result<Vec<Stress>, MeshError> {
        // a 2D mesh holds 2D elements only (Mesh::add_body), so every
        // stress is a plane one
        Ok(self
            .element_point_stresses()?
            .into_iter()
            .filter_map(ElementStress::plane)
            .collect())
    }

    /// Element stresses (averaged over the Gauss points) in `state`.
    pub fn element_stresses(&self, state: &State) -> Result<Vec<Stress>, MeshError> {
        Ok(self
            .element_mean_stresses(state)?
            .into_iter()
            .filter_map(ElementStress::plane)
            .collect())
    }
}

impl Solution<3> {
    /// The stresses at every integration point of every element of the
    /// final state, element after element (eight per hexahedron, one per
    /// tetrahedron).
    pub fn point_stresses(&self) -> Result<Vec<Stress<6>>, MeshError> {
        // a 3D mesh holds 3D elements only (Mesh::add_body)
        Ok(self
            .element_point_stresses()?
            .into_iter()
            .filter_map(ElementStress::solid)
            .collect())
    }

    /// Element stresses (averaged over the Gauss points) in `state`.
    pub fn element_stresses(&self, state: &State<3>) -> Result<Vec<Stress<6>>, MeshError> {
        Ok(self
            .element_mean_stresses(state)?
            .into_iter()
            .filter_map(ElementStress::solid)
            .collect())
    }
}

impl<const D: usize> Solution<D>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The stresses at every integration point of every element of the
    /// final state, element after element, each in its element's
    /// dimension (an error only when an element's geometry cannot be
    /// computed, [`crate::mesh::Mesh::geometry`]).
    pub fn element_point_stresses(&self) -> Result<Vec<ElementStress>, MeshError> {
        let u: Vec<f64> = self
            .final_state
            .displacements
            .iter()
            .flatten()
            .copied()
            .collect();
        let mut points = Vec::new();
        for e in self.mesh.element_ids() {
            let material = &self.mesh.bodies[self.mesh.element_body[e.index()]].material;
            points.extend(
                self.geometries
                    .or_compute(&self.mesh, e)?
                    .point_stresses(&self.mesh.element_displacements(e, &u), material),
            );
        }
        Ok(points)
    }

    /// Element stresses (averaged over the Gauss points) in `state`, each
    /// in its element's dimension (an error as in
    /// [`Solution::element_point_stresses`]).
    pub fn element_mean_stresses(&self, state: &State<D>) -> Result<Vec<ElementStress>, MeshError> {
        let u: Vec<f64> = state.displacements.iter().flatten().copied().collect();
        self.mesh
            .element_ids()
            .map(|e| {
                let mat = &self.mesh.bodies[self.mesh.element_body[e.index()]].material;
                Ok(self
                    .geometries
                    .or_compute(&self.mesh, e)?
                    .mean_stress(&self.mesh.element_displacements(e, &u), mat))
            })
            .collect()
    }

    /// Newton iterations per scheduled step (sub-steps added up).
    pub fn iterations_per_step(&self) -> Vec<usize> {
        let mut out = vec![0; self.steps];
        for r in &self.step_records {
            if let Some(slot) = out.get_mut(r.step - 1) {
                *slot += r.iterations;
            }
        }
        out
    }

    /// The final displacement of node `node`.
    pub fn displacement(&self, node: NodeId) -> [f64; D] {
        self.final_state.displacements[node.index()]
    }

    /// The node of body `body` nearest to the reference point `at`.
    pub fn node_at(&self, body: &str, at: [f64; D]) -> Option<NodeId> {
        let b = self.mesh.bodies.iter().find(|b| b.name == body)?;
        b.node_ids().min_by(|&i, &j| {
            let d = |n: NodeId| {
                let p = self.mesh.node_ref(n);
                crate::mesh::length(&std::array::from_fn::<f64, D, _>(|c| p[c] - at[c]))
            };
            d(i).total_cmp(&d(j))
        })
    }

    /// The largest `|gap|` over the paired integration points.
    pub fn max_abs_gap(&self) -> f64 {
        self.contact_points
            .iter()
            .filter_map(|p| p.gap)
            .fold(0.0, |m, g| m.max(g.abs()))
    }

    /// The range of `xi_m` over the paired integration points.
    pub fn xi_m_range(&self) -> Option<(f64, f64)> {
        self.contact_points
            .iter()
            .filter_map(|p| p.xi_m)
            .fold(None, |acc, x| match acc {
                None => Some((x, x)),
                Some((lo, hi)) => Some((f64::min(lo, x), f64::max(hi, x))),
            })
    }

    /// Integration points that project into no master segment at the end.
    pub fn unpaired_points(&self) -> Vec<ContactPointId> {
        self.contact_points
            .iter()
            .filter(|p| p.master_segment.is_none())
            .map(|p| ContactPointId {
                pair: p.pair,
                slave_segment: p.slave_segment,
                gauss: p.gauss,
                master_segment: None,
                on_faces: false,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::ContactPointId;

    #[test]
    fn a_contact_point_is_named_by_its_segments_in_2d_and_its_faces_in_3d() {
        let mut p = ContactPointId {
            pair: 0,
            slave_segment: 4,
            gauss: 1,
            master_segment: Some(38),
            on_faces: false,
        };
        assert_eq!(
            p.to_string(),
            "pair 0, slave segment 4, Gauss point 1, master segment 38"
        );
        p.on_faces = true;
        assert_eq!(
            p.to_string(),
            "pair 0, slave face 4, point 1, master face 38"
        );
        p.master_segment = None;
        assert_eq!(p.to_string(), "pair 0, slave face 4, point 1");
    }
}
