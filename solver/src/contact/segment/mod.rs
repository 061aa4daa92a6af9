//! The 2D contact element: a slave integration point on a 2-node slave
//! segment ([`ContactPoint`]), paired with a master segment and evaluated
//! there ([`PointEval`]), laid out pair by pair ([`ContactLayout`],
//! `layout.rs`, with segmented integration in `segmented.rs`), paired by
//! projection (`search.rs`, through `master_search.rs` on long master
//! faces), tied at master nodes (`ties.rs`), its nodal table of a solved
//! state (`nodal.rs`), and the Newton loop's view of it
//! ([`crate::contact::ContactSpace`], `space.rs`). The mathematics is
//! `crate::contact`'s module docs.

mod layout;
pub mod master_search;
mod nodal;
mod search;
mod segmented;
mod slip;
mod space;

use contact_kernels::Projection;
use nalgebra::{SMatrix, SVector};

use crate::ids::{ContactPointIndex, DofId, MasterSegmentIndex, MultiplierIndex, NodeId, PairId};

use super::friction::SlipTerm;
use super::taylor::Taylor;
use super::term::{GapTerm, MultiplierShape, WeightedPoint};

pub use layout::ContactLayout;
pub use master_search::{INDEX_MIN_SEGMENTS, MasterIndex, Tried, gap_is_distance};
pub use nodal::{NodalContactError, NodalContactRow, NodalProjection, NodalState, nodal_contact};
pub use search::PassIndexes;
pub use segmented::{
    SPLIT_TOL, is_new_split, segmented_rule, slave_coordinate_of_master_end, split_coordinates,
};

/// A 2D point's frozen Taylor expansion (Types 1–6) on its 8 coordinates.
pub type SegmentTaylor = Taylor<PointEval, 8>;

/// Linear shape functions `[N1, N2]` at `xi`.
pub fn shape2(xi: f64) -> [f64; 2] {
    [(1.0 - xi) / 2.0, (1.0 + xi) / 2.0]
}

/// A master segment index with the projection onto it.
pub type Paired = (MasterSegmentIndex, Projection);

/// A due pairing change: the point (index into [`ContactLayout::points`])
/// and its new master segment with the projection onto it (`None`: it
/// projects into no master segment).
pub type PairingUpdate = (ContactPointIndex, Option<Paired>);

/// Static data of one slave integration point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Contact pair.
    pub pair: PairId,
    /// Slave segment index within the pair.
    pub slave_segment: usize,
    /// Integration point index within the segment (with segmented
    /// integration, counted piece by piece).
    pub gauss: usize,
    /// Parametric coordinate on the slave segment.
    pub xi_s: f64,
    /// `w J0` (reference length weight).
    pub weight_ref: f64,
    /// The slave segment's nodes.
    pub slave_nodes: [NodeId; 2],
    /// Global multiplier indices of the slave segment's nodes.
    pub multipliers: [MultiplierIndex; 2],
}

/// The gap and its derivatives at one paired integration point, as used in
/// the assembly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointEval {
    /// Master segment index within the pair.
    pub master: MasterSegmentIndex,
    /// `[slave 1, slave 2, master 1, master 2]` global node indices.
    pub nodes: [NodeId; 4],
    /// Gap (exact or Taylor-approximated).
    pub gap: f64,
    /// The projection coordinate (at the evaluation point of the kernel).
    pub xi_m: f64,
    /// `dg/du` on the 8 dofs of `nodes`.
    pub grad: SVector<f64, 8>,
    /// `d2g/du2`, `None` when the type has none (Type 1).
    pub hess: Option<SMatrix<f64, 8, 8>>,
    /// The slip on the same 8 dofs, when the pair has friction
    /// ([`super::friction`]; added after the gap's evaluation).
    pub slip: Option<SlipTerm<8>>,
}

impl WeightedPoint for ContactPoint {
    fn weight_ref(&self) -> f64 {
        self.weight_ref
    }

    fn multiplier_shape(&self) -> MultiplierShape {
        let n = shape2(self.xi_s);
        MultiplierShape {
            multipliers: [
                self.multipliers[0],
                self.multipliers[1],
                self.multipliers[1],
                self.multipliers[1],
            ],
            shape: [n[0], n[1], 0.0, 0.0],
            count: 2,
        }
    }
}

impl GapTerm<8> for PointEval {
    type Slip = SlipTerm<8>;

    fn gap(&self) -> f64 {
        self.gap
    }

    fn grad(&self) -> &SVector<f64, 8> {
        &self.grad
    }

    fn hess(&self) -> Option<&SMatrix<f64, 8, 8>> {
        self.hess.as_ref()
    }

    fn dof(&self, k: usize) -> Option<DofId> {
        Some(DofId::of(self.nodes[k / 2], k % 2))
    }

    fn with_values(&self, gap: f64, grad: SVector<f64, 8>, slip: Option<SlipTerm<8>>) -> PointEval {
        PointEval {
            gap,
            grad,
            slip,
            ..*self
        }
    }

    fn slip(&self) -> Option<&SlipTerm<8>> {
        self.slip.as_ref()
    }
}
