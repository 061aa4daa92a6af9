//! Reaction forces of the support groups at a converged state.
//!
//! The reaction at a prescribed dof is the force the support exerts on the
//! body there: with the residual of the assembly,
//!
//! ```text
//! R = f_int(u) + sum_gp w J0 lambda g' (+ node ties) - f_ext(lambda_L)
//! ```
//!
//! evaluated at the prescribed dof (the free dofs' entries are the
//! converged residual, zero to the tolerance). A load applied at a
//! prescribed dof goes straight into the support. Summed over the dofs of a
//! group ([`crate::model::SupportGroup`]), per component x and y.
//!
//! Equilibrium: the internal force and the contact potential's gradient are
//! invariant under rigid translation, so their x (and y) entries sum to
//! zero over all dofs; hence at a converged state the reactions of all
//! groups plus all applied loads sum to zero (to the Newton tolerance),
//! bodies in contact included. A dof belongs to one group only (the first
//! item that prescribes it, see `scene/build.rs`), so nothing is counted
//! twice.
//!
//! The residual is assembled with [`DofMap::all_free`] by the same
//! assembly functions as the Newton system (so every element kind and the
//! contact contributions are included as the solve sees them), into a
//! [`System::forces_only`] that keeps no tangent entry, once per
//! converged state of a model with support groups. Of the solid elements
//! only those with a prescribed dof are assembled, and only their forces
//! are scattered (their tangents are computed by the element but not
//! kept): the other elements add nothing to the entries read, and
//! the kept ones add in the same order as in the full assembly, so the
//! reactions are the full residual's entries to the bit. Their geometry is
//! the solve's, or across MPI ranks computed for an element another rank
//! owns ([`Geometries::or_compute`]: the supported elements are a layer at
//! the supports, every rank computes all of them).

use crate::assembly::{PAR_MIN_LEN, add_external};
use crate::contact::ContactSpace;
use crate::contact::NodeTie;
use crate::ids::ElementId;
use crate::mesh::{Geometries, MeshError};
use crate::model::Model;
use crate::par;
use crate::system::{DofMap, System};

use super::setup::Setup;
use crate::model::{Dim, SurfaceDim};

impl<const D: usize, S: ContactSpace<D>> Setup<'_, D, S>
where
    Dim<D>: SurfaceDim<D>,
{
    /// The reaction `[x, y(, z)]` of every support group of the model at the
    /// converged state `(u, lambda, ties)` of load factor `to`, with the
    /// contact evaluations `evals` (`others`: the ties' second evaluations)
    /// and active set `active` it converged with (module docs). Empty when
    /// the model names no groups.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn reactions(
        &self,
        u: &[f64],
        lambda: &[f64],
        ties: &[NodeTie<S::Master>],
        evals: &[Option<S::Eval>],
        others: &[S::Eval],
        active: &[bool],
        to: f64,
    ) -> Result<Vec<[f64; D]>, MeshError> {
        let model = self.model;
        if model.supports.is_empty() {
            return Ok(Vec::new());
        }
        let all = DofMap::all_free(u.len(), self.dofs.n_mult);
        let mut sys = System::forces_only(all.n_eq() + ties.len());
        self.layout
            .assemble(evals, lambda, active, &all, None, &mut sys);
        S::assemble_ties(ties, evals, others, &all, &mut sys);
        add_supported_element_forces(model, &self.geometries, &all, u, &mut sys.residual)?;
        add_external(model, &all, to, &mut sys);
        Ok(model
            .supports
            .iter()
            .map(|g| {
                let mut r = [0.0; D];
                for p in &model.prescribed[g.prescribed.clone()] {
                    r[p.dof.component_in::<D>()] += sys.residual[p.dof.index()];
                }
                r
            })
            .collect())
    }
}

/// Adds the internal forces of the elements with a prescribed dof to
/// `residual`, in element order (module docs: the prescribed entries equal
/// the full solid assembly's).
fn add_supported_element_forces<const D: usize>(
    model: &Model<D>,
    geometries: &Geometries,
    all: &DofMap,
    u: &[f64],
    residual: &mut [f64],
) -> Result<(), MeshError>
where
    Dim<D>: SurfaceDim<D>,
{
    let mesh = &model.mesh;
    let mut prescribed = vec![false; u.len()];
    for p in &model.prescribed {
        prescribed[p.dof.index()] = true;
    }
    let supported: Vec<usize> = (0..mesh.element_count())
        .filter(|&e| {
            let eqs = all.element_eqs::<D>(&mesh.elements[e]);
            eqs.iter().flatten().any(|eq| prescribed[eq.index()])
        })
        .collect();
    let forces: Vec<Vec<f64>> = par::map(supported.len(), PAR_MIN_LEN, |i| {
        let e = ElementId::new(supported[i]);
        let material = &mesh.bodies[mesh.element_body[e.index()]].material;
        let geometry = geometries.or_compute(mesh, e)?;
        let response = geometry.response(&mesh.element_displacements(e, u), material);
        Ok(response.f_int().to_vec())
    })
    .into_iter()
    .collect::<Result<_, MeshError>>()?;
    for (&e, f_int) in supported.iter().zip(&forces) {
        let eqs = all.element_eqs::<D>(&mesh.elements[e]);
        for (eq, f) in eqs.iter().zip(f_int) {
            if let Some(eq) = eq {
                residual[eq.index()] += f;
            }
        }
    }
    Ok(())
}
