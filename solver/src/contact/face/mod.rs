//! The 3D contact element: slave integration points on tri3 and quad4
//! slave faces ([`FacePoint`], laid out pair by pair by [`FaceLayout`],
//! `layout.rs`; segmented integration over the triangles of
//! `crate::contact::clip`), paired by projection with a master face and
//! evaluated there ([`FaceEval`], `pairing.rs`), the nodal table of a solved state
//! (`nodal.rs`), and the Newton loop's view of it
//! ([`crate::contact::ContactSpace`], `space.rs`). The mathematics is
//! `crate::contact`'s module docs and `layout.rs`'s.

mod layout;
mod nodal;
mod pairing;
mod reference;
mod slip;
mod slip_term;
mod space;
#[cfg(test)]
mod tests;

pub use layout::{FaceLayout, FacePoint, face_formulation};
pub use nodal::{FaceNodalError, FaceNodalRow};
pub use pairing::{FACE_COORDS, FaceEval, FaceFound, MasterFaces};
pub use slip::frame_of;
pub use slip_term::{FaceAnchor, FaceSlip, Frame};
