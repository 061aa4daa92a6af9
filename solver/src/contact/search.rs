//! Pairing by projection (see [`super`], "Pairing"): which master segment a
//! slave integration point projects into.
//!
//! Invariants: a point is paired only with a segment it projects into
//! (`|xi_m| <= 1 +` [`XI_INSIDE_TOL`]), found by walking along the master
//! chain from its current segment and, failing that, among all segments by
//! the smallest `|g|`; a point that projects into none is inactive, never
//! extrapolated. Slave-side kernel failures are errors (no master segment
//! can cure them); master-side ones mean "not this segment".

use contact_kernels::Projection;

use crate::ids::{ContactPointIndex, MasterSegmentIndex, PairId};
use crate::mesh::Mesh;
use crate::par;

use super::{
    ContactLayout, KernelCounts, PAR_MIN_LEN, Paired, PairingUpdate, PointEval, PointFailure,
    XI_INSIDE_TOL, slave_side,
};

impl ContactLayout {
    /// Whether point `i`'s slave segment and master segment `master` face
    /// each other at displacements `u`: their outward normals point against
    /// each other, `n_s . n_m < 0`. Both faces run counter-clockwise around
    /// their bodies and the outward normal is the tangent turned clockwise,
    /// so `n_s . n_m` is the dot product of the two tangents (see the
    /// module docs).
    pub fn faces_each_other(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterSegmentIndex,
    ) -> bool {
        let q = Self::q(mesh, u, self.nodes(self.point(i), master));
        (q[2] - q[0]) * (q[6] - q[4]) + (q[3] - q[1]) * (q[7] - q[5]) < 0.0
    }

    /// Projects onto one master segment. `Ok(None)` when the two segments
    /// do not face each other ([`Self::faces_each_other`]; no kernel call)
    /// or the kernel reports a master-side or projection problem (the point
    /// does not project into this segment); `Err` for slave-side problems,
    /// which no other master segment can cure.
    pub(super) fn project_on(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        master: MasterSegmentIndex,
        counts: &mut KernelCounts,
    ) -> Result<Option<Projection>, PointFailure> {
        if !self.faces_each_other(mesh, u, i, master) {
            return Ok(None);
        }
        let pt = self.point(i);
        counts.project += 1;
        match contact_kernels::project(
            self.formulations[pt.pair.index()],
            &Self::q(mesh, u, self.nodes(pt, master)),
            pt.xi_s,
        ) {
            Ok(p) => Ok(Some(p)),
            Err(e) if slave_side(&e) => Err(PointFailure {
                point: i,
                master_segment: Some(master),
                error: e,
            }),
            Err(_) => Ok(None),
        }
    }

    /// The master segment point `i` projects into, searching from `start`
    /// (see the module docs), or `None`.
    pub fn find_master(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterSegmentIndex>,
        counts: &mut KernelCounts,
    ) -> Result<Option<Paired>, PointFailure> {
        let pair = self.point(i).pair.index();
        let n_master = self.masters[pair].len();
        if let Some(mut cur) = start {
            let mut previous = None;
            for _ in 0..n_master {
                let Some(p) = self.project_on(mesh, u, i, cur, counts)? else {
                    break;
                };
                if p.xi_m.abs() <= 1.0 + XI_INSIDE_TOL {
                    return Ok(Some((cur, p)));
                }
                let next = self.adjacency[pair][cur.index()][usize::from(p.xi_m > 0.0)];
                match next {
                    Some(n) if Some(n) != previous => {
                        previous = Some(cur);
                        cur = n;
                    }
                    _ => break,
                }
            }
        }
        let mut best: Option<Paired> = None;
        for m in (0..n_master).map(MasterSegmentIndex::new) {
            if let Some(p) = self.project_on(mesh, u, i, m, counts)?
                && p.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                && best.is_none_or(|(_, b)| p.gap.abs() < b.gap.abs())
            {
                best = Some((m, p));
            }
        }
        Ok(best)
    }

    /// The pairing changes due at a converged iterate of the complete
    /// formulation (module docs, "Complete formulation"): every active point
    /// whose projection has left its master segment (`|xi_m| > 1 +`
    /// [`XI_INSIDE_TOL`] in `evals`) is searched for from that segment, every
    /// inactive point from scratch. Returns `(point, new pairing)` for the
    /// points whose master segment changes, in point order, with the
    /// projection onto the new segment (`None`: the point now projects into
    /// no master segment).
    pub fn pairing_updates(
        &self,
        mesh: &Mesh,
        u: &[f64],
        evals: &[Option<PointEval>],
    ) -> Result<(Vec<PairingUpdate>, KernelCounts), PointFailure> {
        let mut counts = KernelCounts::default();
        let mut out = Vec::new();
        for (i, ev) in evals.iter().enumerate() {
            let i = ContactPointIndex::new(i);
            let current = match ev {
                Some(e)
                    if e.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                        && self.faces_each_other(mesh, u, i, e.master) =>
                {
                    continue;
                }
                Some(e) => Some(e.master),
                None => None,
            };
            let found = self.find_master(mesh, u, i, current, &mut counts)?;
            if found.map(|(m, _)| m) != current {
                out.push((i, found));
            }
        }
        Ok((out, counts))
    }

    /// Pairs every point from scratch (sequentially): each point's search
    /// starts from the master segment found for the previous point of the
    /// same pair, so along a face the walk usually finds it in a step or
    /// two instead of trying every master segment.
    pub fn initial_pairing(
        &self,
        mesh: &Mesh,
        u: &[f64],
    ) -> Result<(Vec<Option<MasterSegmentIndex>>, KernelCounts), PointFailure> {
        let mut counts = KernelCounts::default();
        let mut out = Vec::with_capacity(self.points.len());
        let mut seed: Option<(PairId, MasterSegmentIndex)> = None;
        for (i, pt) in self.points.iter().enumerate() {
            let i = ContactPointIndex::new(i);
            let start = seed.filter(|(pair, _)| *pair == pt.pair).map(|(_, m)| m);
            let found = self
                .find_master(mesh, u, i, start, &mut counts)?
                .map(|(m, _)| m);
            if let Some(m) = found {
                seed = Some((pt.pair, m));
            }
            out.push(found);
        }
        Ok((out, counts))
    }

    /// Re-pairs every point by projection only (no derivatives): the exact
    /// gap and `xi_m` at displacements `u`, for reports.
    pub fn project_all(
        &self,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
    ) -> Result<(Vec<Option<Paired>>, KernelCounts), PointFailure> {
        par::try_map_counted(self.points.len(), PAR_MIN_LEN, |i, c| {
            let start = pairing[i];
            self.find_master(mesh, u, ContactPointIndex::new(i), start, c)
        })
    }
}
