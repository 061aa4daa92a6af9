//! The kernel evaluations at the integration points: one point on one
//! master segment, and every point at once (in parallel, `crate::par`),
//! with or without re-pairing.
//!
//! Every point at once is batched: the points are taken in chunks of
//! [`BATCH`] (one parallel task each); a chunk's first evaluations (each
//! point on the master its pairing gives it) go through
//! `contact_kernels::Kernel::eval_batch` (4 points per call of the SIMD lane
//! kernels), which gives each point exactly the bits and errors of
//! `contact_kernels::evaluate`; then each point finishes as before (an
//! evaluation outside its master segment or a master-side failure leads to
//! the pairing search, one point at a time).
//!
//! Invariants: results are in point order; kernel calls are counted per
//! point and summed in point order; the first failing point (in point
//! order) is the one reported; the results do not depend on the batching.

use contact_kernels::{ApproxType, Formulation, GapBatch, Kernel, KernelError};
use nalgebra::{SMatrix, SVector};

use crate::ids::{ContactPointIndex, MasterSegmentIndex};
use crate::mesh::Mesh;
use crate::par;

use super::{
    ContactLayout, KernelCounts, PAR_MIN_LEN, PointEval, PointFailure, XI_INSIDE_TOL, slave_side,
};

/// Points per batch: the chunk of one parallel task.
pub const BATCH: usize = PAR_MIN_LEN;

/// A point's first evaluation: its master and the kernel's result there.
type FirstEval = Option<(MasterSegmentIndex, Result<PointEval, KernelError>)>;

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
    fn pair_and_evaluate(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterSegmentIndex>,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<Option<PointEval>, PointFailure> {
        let first = start.map(|m| (m, self.evaluate_on(mesh, u, i, m, ty, counts)));
        self.finish_pairing(mesh, u, i, start, first, ty, counts)
    }

    /// [`pair_and_evaluate`](Self::pair_and_evaluate) after the first
    /// evaluation (`first`: on `start`, when there is one).
    #[allow(clippy::too_many_arguments)]
    fn finish_pairing(
        &self,
        mesh: &Mesh,
        u: &[f64],
        i: ContactPointIndex,
        start: Option<MasterSegmentIndex>,
        first: FirstEval,
        ty: ApproxType,
        counts: &mut KernelCounts,
    ) -> Result<Option<PointEval>, PointFailure> {
        let eval = |master: MasterSegmentIndex, counts: &mut KernelCounts| {
            self.evaluate_on(mesh, u, i, master, ty, counts)
        };
        if let Some((m, result)) = first {
            match result {
                Ok(e) if e.xi_m.abs() <= 1.0 + XI_INSIDE_TOL => return Ok(Some(e)),
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
        match self.find_master(mesh, u, i, start, counts)? {
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
        self.batched(mesh, u, pairing, ty, |i, first, c| {
            self.finish_pairing(mesh, u, i, pairing[i.index()], first, ty, c)
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
        self.batched(mesh, u, pairing, ty, |i, first, c| match first {
            None => Ok(None),
            Some((m, result)) => match result {
                Ok(e) => Ok(Some(e)),
                Err(error) if slave_side(&error) => Err(PointFailure {
                    point: i,
                    master_segment: Some(m),
                    error,
                }),
                Err(_) => self.pair_and_evaluate(mesh, u, i, None, ty, c),
            },
        })
    }

    /// Every point in chunks of [`BATCH`], in parallel: the chunk's points
    /// with a master in `pairing` evaluated there at once
    /// ([`evaluate_batch`](Self::evaluate_batch), counted one evaluation
    /// each), then `finish(point, first evaluation, counts)` point by point.
    /// Results in point order, counts summed, the first failure in point
    /// order: what `par::try_map_counted` of the points gives.
    fn batched<T, F>(
        &self,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
        finish: F,
    ) -> Result<(Vec<T>, KernelCounts), PointFailure>
    where
        T: Send,
        F: Fn(ContactPointIndex, FirstEval, &mut KernelCounts) -> Result<T, PointFailure>
            + Sync
            + Send,
    {
        let n = self.points.len();
        let (chunks, counts) =
            par::try_map_counted(n.div_ceil(BATCH), 1, |c, counts: &mut KernelCounts| {
                let range = c * BATCH..n.min((c + 1) * BATCH);
                let items: Vec<(ContactPointIndex, MasterSegmentIndex)> = range
                    .clone()
                    .filter_map(|i| pairing[i].map(|m| (ContactPointIndex::new(i), m)))
                    .collect();
                let mut firsts = self.evaluate_batch(mesh, u, &items, ty).into_iter();
                range
                    .map(|i| {
                        let first = pairing[i].map(|m| {
                            counts.evaluate += 1;
                            (m, firsts.next().expect("one result per paired point"))
                        });
                        finish(ContactPointIndex::new(i), first, counts)
                    })
                    .collect::<Result<Vec<T>, PointFailure>>()
            })?;
        Ok((chunks.into_iter().flatten().collect(), counts))
    }

    /// The kernel of type `ty` at each `(point, master)` of `items`, as
    /// [`evaluate_on`](Self::evaluate_on) gives it (the same bits and
    /// errors; not counted here), through `Kernel::eval_batch`: the items of
    /// each formulation in one batch.
    pub fn evaluate_batch(
        &self,
        mesh: &Mesh,
        u: &[f64],
        items: &[(ContactPointIndex, MasterSegmentIndex)],
        ty: ApproxType,
    ) -> Vec<Result<PointEval, KernelError>> {
        let formulation = |&(i, _): &(ContactPointIndex, MasterSegmentIndex)| {
            self.formulations[self.point(i).pair.index()]
        };
        let mut out: Vec<Option<Result<PointEval, KernelError>>> = vec![None; items.len()];
        let mut done = 0;
        while done < items.len() {
            let f: Formulation = items
                .iter()
                .zip(&out)
                .find_map(|(item, o)| o.is_none().then(|| formulation(item)))
                .expect("an item left");
            let chosen: Vec<usize> = (0..items.len())
                .filter(|&k| out[k].is_none() && formulation(&items[k]) == f)
                .collect();
            done += chosen.len();
            let kernel = match Kernel::new(f, ty) {
                Ok(kernel) => kernel,
                Err(e) => {
                    for &k in &chosen {
                        out[k] = Some(Err(e));
                    }
                    continue;
                }
            };
            let nodes: Vec<_> = chosen
                .iter()
                .map(|&k| self.nodes(self.point(items[k].0), items[k].1))
                .collect();
            let qs: Vec<f64> = nodes.iter().flat_map(|&n| Self::q(mesh, u, n)).collect();
            let xi_s: Vec<f64> = chosen
                .iter()
                .map(|&k| self.point(items[k].0).xi_s)
                .collect();
            let mut batch = GapBatch::new(&kernel);
            kernel
                .eval_batch(&qs, &xi_s, &mut batch)
                .expect("8 coordinates per point, a batch of the kernel's size");
            for (p, (&k, nodes)) in chosen.iter().zip(nodes).enumerate() {
                out[k] = Some(match batch.status(p) {
                    Err(e) => Err(*e),
                    Ok(()) => {
                        let (gap, xi_m) = batch.gap(p).expect("status ok");
                        Ok(PointEval {
                            master: items[k].1,
                            nodes,
                            gap,
                            xi_m,
                            grad: SVector::from_column_slice(batch.grad(p).expect("status ok")),
                            // Symmetric to the bit: row-major is column-major.
                            hess: batch
                                .hess(p)
                                .expect("status ok")
                                .map(SMatrix::from_column_slice),
                        })
                    }
                });
            }
        }
        out.into_iter()
            .map(|o| o.expect("every item evaluated"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::testutil::Lcg;

    /// The paper scene refined along x (`refine` times the elements, so
    /// `14 refine` integration points: several batches for `refine >= 37`).
    fn layout_of(refine: usize) -> (crate::model::Model, ContactLayout) {
        let scene =
            Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")
                .unwrap()
                .refined(refine, 1);
        let model = scene.build_model().unwrap();
        let layout = ContactLayout::new(&model, None);
        (model, layout)
    }

    /// What `evaluate_all` computed before it was batched: every point
    /// through `pair_and_evaluate`, in parallel.
    fn unbatched(
        layout: &ContactLayout,
        mesh: &Mesh,
        u: &[f64],
        pairing: &[Option<MasterSegmentIndex>],
        ty: ApproxType,
    ) -> Result<(Vec<Option<PointEval>>, KernelCounts), PointFailure> {
        par::try_map_counted(layout.points.len(), PAR_MIN_LEN, |i, c| {
            layout.pair_and_evaluate(mesh, u, ContactPointIndex::new(i), pairing[i], ty, c)
        })
    }

    /// Results compared by their Debug text: every f64 bit shows.
    fn same<T: std::fmt::Debug>(a: &T, b: &T) -> bool {
        format!("{a:?}") == format!("{b:?}")
    }

    #[test]
    fn batched_evaluations_equal_the_point_by_point_ones_bit_for_bit() {
        let (model, layout) = layout_of(40);
        let n = layout.points.len();
        assert!(n > 2 * BATCH, "several batches: {n} points");
        let mut rng = Lcg::new(7);
        let masters = layout.masters_of(crate::ids::PairId::new(0)).len();
        for round in 0..3 {
            let u: Vec<f64> = (0..2 * model.mesh.node_count())
                .map(|_| rng.uniform(-0.05, 0.05))
                .collect();
            // Pairings: none, the right one for some, a neighbour (so the
            // point is outside and searched) or nothing for others.
            let pairing: Vec<Option<MasterSegmentIndex>> = (0..n)
                .map(|i| {
                    let right = masters - 1 - (i / 2) * masters / (n / 2);
                    match (i + round) % 5 {
                        0 => None,
                        1 => Some(MasterSegmentIndex::new((right + 3) % masters)),
                        _ => Some(MasterSegmentIndex::new(right.min(masters - 1))),
                    }
                })
                .collect();
            for ty in ApproxType::ALL {
                let batched = layout.evaluate_all(&model.mesh, &u, &pairing, ty);
                let reference = unbatched(&layout, &model.mesh, &u, &pairing, ty);
                assert!(same(&batched, &reference), "evaluate_all, type {ty}");
                let paired = layout.evaluate_paired(&model.mesh, &u, &pairing, ty);
                let reference = par::try_map_counted(n, PAR_MIN_LEN, |i, c| match pairing[i] {
                    None => Ok(None),
                    Some(m) => {
                        let p = ContactPointIndex::new(i);
                        match layout.evaluate_on(&model.mesh, &u, p, m, ty, c) {
                            Ok(e) => Ok(Some(e)),
                            Err(error) if slave_side(&error) => Err(PointFailure {
                                point: p,
                                master_segment: Some(m),
                                error,
                            }),
                            Err(_) => layout.pair_and_evaluate(&model.mesh, &u, p, None, ty, c),
                        }
                    }
                });
                assert!(same(&paired, &reference), "evaluate_paired, type {ty}");
                let (evals, counts) = paired.unwrap();
                assert!(evals.iter().filter(|e| e.is_some()).count() > n / 2);
                assert!(counts.evaluate > 0);
            }
        }
    }

    #[test]
    fn a_failing_point_is_reported_as_before() {
        let (model, layout) = layout_of(40);
        let n = layout.points.len();
        let mut u = vec![0.0; 2 * model.mesh.node_count()];
        // Collapse the slave segment of a point in the second batch: its
        // two nodes to the same place (a slave-side failure).
        let i = ContactPointIndex::new(BATCH + 5);
        let pt = layout.point(i);
        let nodes = layout.nodes(pt, MasterSegmentIndex::new(0));
        for k in 0..2 {
            let (a, b) = (nodes[0], nodes[1]);
            let target = model.mesh.node_ref(a)[k];
            u[crate::ids::DofId::of(b, k).index()] = target - model.mesh.node_ref(b)[k];
        }
        let pairing: Vec<Option<MasterSegmentIndex>> = vec![None; n];
        let (_, none_counts) = layout
            .evaluate_all(
                &model.mesh,
                &vec![0.0; u.len()],
                &pairing,
                ApproxType::Type3,
            )
            .unwrap();
        assert_eq!(none_counts.evaluate as usize, n);
        let (fresh, _) = layout
            .evaluate_all(
                &model.mesh,
                &vec![0.0; u.len()],
                &pairing,
                ApproxType::Type6,
            )
            .unwrap();
        let pairing: Vec<Option<MasterSegmentIndex>> =
            fresh.iter().map(|e| e.map(|e| e.master)).collect();
        for ty in ApproxType::ALL {
            let batched = layout.evaluate_all(&model.mesh, &u, &pairing, ty);
            let reference = unbatched(&layout, &model.mesh, &u, &pairing, ty);
            assert!(same(&batched, &reference), "type {ty}");
            let failure = batched.expect_err("the collapsed segment fails");
            assert!(matches!(
                failure.error,
                KernelError::DegenerateSegment { .. }
            ));
        }
    }
}
