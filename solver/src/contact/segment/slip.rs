//! The slip of the 2D points of pairs with friction ([`crate::contact::friction`]):
//! the generated slip kernel of the pair's formulation on the point's
//! master segment, from the master point the slave point faced at the last
//! converged state (its *anchor*, a master segment and `xi_m0`).
//!
//! A point evaluated on another master segment than its anchor's (it
//! crossed a master node in the step) takes as `xi_m0` the anchor's
//! material point expressed on the new segment's line: the reference
//! position `X0` of the anchor on its segment, projected onto the new
//! segment's reference line, `xi_m0 = 2 (X0 - X_c) . (X_b - X_a) / |X_b -
//! X_a|^2` with `X_c` the new segment's midpoint. On a master face that
//! deforms little along itself this is the anchor's current position to
//! the strain of the two segments; it is exact for a rigid or uniformly
//! stretched straight master.
//!
//! Invariant: a formulation without a slip is `NotCompiled` (every
//! shipped formulation defines one).

use contact_kernels::{ApproxType, Formulation, Kernel, KernelError, Slip, SlipOut};
use nalgebra::{SMatrix, SVector};

use crate::contact::friction::{Anchor, SlipTerm};
use crate::contact::{ContactLayout, PointEval};
use crate::ids::{ContactPointIndex, MasterSegmentIndex, PairId};
use crate::mesh::Mesh;

/// The slip kernel of one formulation and type with its output buffers,
/// kept across the points of a pass ([`ContactLayout::slip_with`]).
#[derive(Debug, Default)]
pub(super) struct SlipBuffers(Option<(Formulation, ApproxType, Slip, SlipOut)>);

impl ContactLayout {
    /// See [`crate::contact::ContactSpace::add_slip`]: the slip of point
    /// `i` evaluated as `e`, with kernel type `ty` at displacements `u`,
    /// from `anchor`, stored in `e`; the slip kernel and its output
    /// buffers of the last call kept in `buffers` (a pass over every point
    /// reuses them while the formulation and type stay).
    #[allow(clippy::too_many_arguments)] // one point's inputs and the buffers
    pub(super) fn slip_with(
        &self,
        mesh: &Mesh<2>,
        u: &[f64],
        i: ContactPointIndex,
        e: &mut PointEval,
        anchor: Anchor<MasterSegmentIndex>,
        ty: ApproxType,
        buffers: &mut SlipBuffers,
    ) -> Result<(), KernelError> {
        let pt = self.point(i);
        let formulation = self.formulations[pt.pair.index()];
        let xi_m0 = if anchor.master == e.master {
            anchor.xi_m
        } else {
            self.anchor_on(mesh, pt.pair, anchor.master, anchor.xi_m, e.master)
        };
        let (slip, out) = match &mut buffers.0 {
            Some((f, t, slip, out)) if *f == formulation && *t == ty => (*slip, out),
            cached => {
                let Some(slip) = Kernel::new(formulation, ty)?.slip() else {
                    return Err(KernelError::NotCompiled(formulation));
                };
                let (_, _, _, out) = cached.insert((formulation, ty, slip, SlipOut::new(&slip)));
                (slip, out)
            }
        };
        slip.eval(&Self::q(mesh, u, e.nodes), pt.xi_s, xi_m0, out)?;
        e.slip = Some(SlipTerm {
            slip: out.slip()[0],
            grad: SVector::<f64, 8>::from_column_slice(out.grad(0)),
            hess: out.hess(0).map(SMatrix::<f64, 8, 8>::from_row_slice),
        });
        Ok(())
    }

    /// The anchor at `xi0` on master segment `from` of `pair`, as a
    /// parameter on the line of master segment `to` (module docs).
    fn anchor_on(
        &self,
        mesh: &Mesh<2>,
        pair: PairId,
        from: MasterSegmentIndex,
        xi0: f64,
        to: MasterSegmentIndex,
    ) -> f64 {
        let masters = self.masters_of(pair);
        let [a0, b0] = masters[from.index()].map(|n| mesh.node_ref(n));
        let [a, b] = masters[to.index()].map(|n| mesh.node_ref(n));
        let [na, nb] = crate::contact::shape2(xi0);
        let x0 = [na * a0[0] + nb * b0[0], na * a0[1] + nb * b0[1]];
        let d = [b[0] - a[0], b[1] - a[1]];
        let c = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        2.0 * ((x0[0] - c[0]) * d[0] + (x0[1] - c[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])
    }
}
