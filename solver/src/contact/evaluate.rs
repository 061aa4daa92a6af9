//! The kernel evaluations at the integration points: one point on one
//! master segment, and every point at once (in parallel, `crate::par`),
//! with or without re-pairing.
//!
//! Invariants: results are in point order; kernel calls are counted per
//! point and summed in point order; the first failing point (in point
//! order) is the one reported.

use contact_kernels::{ApproxType, KernelError};

use crate::ids::{ContactPointIndex, MasterSegmentIndex};
use crate::mesh::Mesh;
use crate::par;

use super::{
    ContactLayout, KernelCounts, PAR_MIN_LEN, PassIndexes, PointEval, PointFailure, XI_INSIDE_TOL,
    slave_side,
};

impl ContactLayout {
    /// Evaluates the kernel of type `ty` for point `i` on master segment
    /// `master`, wherever on the segment's line the point projects.
    pub fn evaluate_on(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterSegmentIndex,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<PointEval, KernelError> {
        let pt = self.point(i);
        counts.evaluate += 1;
        let nodes = self.nodes(pt, master);
        contact_kernels::evaluate(
            self.formulations[pt.pair.index()],
            ty,
            &Self::q(mesh, u, nodes),
            pt.xi_s,
        )
        .map(|k| PointEval {
            master,
            nodes,
            gap: k.gap,
            xi_m: k.xi_m,
            grad: k.grad,
            hess: k.hess,
        })
    }

    /// Pairs point `i` (from its current master `start`) and evaluates the
    /// kernel of type `ty` there. `Ok(None)`: the point projects into no
    /// master segment.
    #[allow(clippy::too_many_arguments)] // the pass's state: mesh, u, indexes, counts
    fn pair_and_evaluate(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterSegmentIndex>,
        ty: ApproxType,
        indexes: &PassIndexes,
        counts: &mut KernelCounts,
    ) -> Result<Option<PointEval>, PointFailure> {
        let eval = |master: MasterSegmentIndex, counts: &mut KernelCounts| {
            self.evaluate_on(mesh, u, i, master, ty, counts)
        };
        if let Some(m) = start {
            match eval(m, counts) {
                Ok(e)
                    if e.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                        && self.faces_each_other(mesh, u, i, m) =>
                {
                    return Ok(Some(e));
                }
                Ok(_) => {}
                Err(e) if slave_side(&e) => {
                    return Err(PointFailure {
                        point: i,
                        master_segment: Some(m),
                        error: e,
                    });
                }
                Err(_) => {}
            }
        }
        match self.find_master(mesh, u, i, start, indexes, counts)? {
            None => Ok(None),
            Some((m, _)) => eval(m, counts).map(Some).map_err(|error| PointFailure {
                point: i,
                master_segment: Some(m),
                error,
            }),
        }
    }

    /// Pairs every point and evaluates type `ty` at displacements `u`, in
    /// parallel; returns the evaluations (None = projects nowhere) and the
    /// kernel-call counts. `pairing` gives each point's current master.
    pub fn evaluate_all(
        &self,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
    ) -> Result<(Vec<Option<PointEval>>, KernelCounts), PointFailure> {
        let indexes = self.pass_indexes();
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |i, c| {
            let start = pairing[i];
            self.pair_and_evaluate(mesh, u, ContactPointIndex::new(i), start, ty, &indexes, c)
        })
    }

    /// Evaluates type `ty` at every point on the master segment `pairing`
    /// gives it, without re-pairing: the projection onto the segment's line
    /// is used also where it falls outside the segment (the complete
    /// formulation's Newton iterations, see the module docs). `None` points
    /// stay inactive. Only when the kernel fails on the given segment for a
    /// master-side reason (e.g. the projection is out of reach) is the point
    /// re-paired by search, as [`evaluate_all`](Self::evaluate_all) does.
    pub fn evaluate_paired(
        &self,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
    ) -> Result<(Vec<Option<PointEval>>, KernelCounts), PointFailure> {
        let indexes = self.pass_indexes();
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |raw, c| {
            match pairing[raw] {
                None => Ok(None),
                Some(m) => match self.evaluate_on(mesh, u, ContactPointIndex::new(raw), m, ty, c) {
                    Ok(e) => Ok(Some(e)),
                    Err(error) if slave_side(&error) => Err(PointFailure {
                        point: ContactPointIndex::new(raw),
                        master_segment: Some(m),
                        error,
                    }),
                    Err(_) => self.pair_and_evaluate(
                        mesh,
                        u,
                        ContactPointIndex::new(raw),
                        None,
                        ty,
                        &indexes,
                        c,
                    ),
                },
            }
        })
    }
}
