//! The slip term of a 3D point and its anchor (the data of `slip.rs`,
//! which evaluates them; its module docs state the frames).

use nalgebra::{SMatrix, SVector};

use crate::contact::term::{FACE_COORDS, MAX_POINT_MULTIPLIERS, PointSlip, expand_value};
use crate::ids::MasterFaceIndex;

/// A node's two unit tangents (global components).
pub type Frame = [[f64; 3]; 2];

/// A 3D point's slip (module docs): the three global components of
/// `s_m - (n . s_m) n` with their derivatives on the evaluation's
/// [`FACE_COORDS`] coordinates (zero on padding), and the frames of the
/// point's slave face nodes (node order; zero for a frictionless node).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceSlip {
    /// `s_x, s_y, s_z`.
    pub slip: [f64; 3],
    /// Their gradients.
    pub grad: [SVector<f64, FACE_COORDS>; 3],
    /// Their Hessians, `None` when the kernel's type has none.
    pub hess: Option<[SMatrix<f64, FACE_COORDS, FACE_COORDS>; 3]>,
    /// The frames of the slave face's nodes.
    pub frames: [Frame; MAX_POINT_MULTIPLIERS],
}

impl PointSlip<FACE_COORDS> for Box<FaceSlip> {
    fn components(&self) -> usize {
        3
    }

    fn value(&self, c: usize) -> f64 {
        self.slip[c]
    }

    fn grad(&self, c: usize) -> &SVector<f64, FACE_COORDS> {
        &self.grad[c]
    }

    fn hess(&self, c: usize) -> Option<&SMatrix<f64, FACE_COORDS, FACE_COORDS>> {
        self.hess.as_ref().map(|h| &h[c])
    }

    fn direction(&self, j: usize, k: usize) -> [f64; 3] {
        self.frames[j][k]
    }

    fn expanded(&self, d: &SVector<f64, FACE_COORDS>) -> Box<FaceSlip> {
        let mut out = (**self).clone();
        for c in 0..3 {
            let (v, g) = expand_value(
                self.slip[c],
                &self.grad[c],
                self.hess.as_ref().map(|h| &h[c]),
                d,
            );
            out.slip[c] = v;
            out.grad[c] = g;
        }
        Box::new(out)
    }
}

/// Where a 3D point's slip is measured from (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceAnchor {
    /// The master face the point projected into.
    pub master: MasterFaceIndex,
    /// `xi_m0`.
    pub xi_m: [f64; 2],
    /// The frames of the point's slave face nodes at the converged state.
    pub frames: [Frame; MAX_POINT_MULTIPLIERS],
}
