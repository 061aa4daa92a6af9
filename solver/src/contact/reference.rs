//! How a slave node meets its master surface in the reference
//! configuration: what a scene's checks of a contact pair read before a
//! solve (faces that do not face each other, initial penetration, a
//! persistent pair that starts open; `crate::scene`'s `initial_contact`).
//!
//! Each dimension pairs a slave node the way its contact element pairs an
//! integration point, but without asking the faces to face each other: the
//! master facet it projects into (`xi_m` inside within
//! [`super::XI_INSIDE_TOL`]) with the smallest `|g|`, in the pair's
//! formulation (2D: on the slave segment that starts at the node, the last
//! node of an open chain on the one ending there; 3D: at the node's corner
//! of the first slave face that has it, as the nodal table takes it). A
//! node that projects into no master facet has no [`ReferencePairing`].
//!
//! Sign convention: `cos = n_s . n_m` of the **unit outward** normals of
//! the slave facet at the node and of the master facet at the projection:
//! `-1` for faces that face each other squarely, `+1` for a slave face
//! looking the same way as its master (the far side of one of the bodies).

use crate::ids::NodeId;

/// One slave node paired in the reference configuration (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferencePairing<const D: usize> {
    /// The slave node.
    pub node: NodeId,
    /// Its gap `g` (positive open, negative penetrating).
    pub gap: f64,
    /// The size `h` of its slave facet: a segment's length, a face's
    /// `sqrt` of its area ([`crate::mesh::volume::Face::size`]).
    pub size: f64,
    /// `n_s . n_m` of the unit outward normals (module docs).
    pub cos: f64,
    /// The unit outward normals `[n_s, n_m]`.
    pub normals: [[f64; D]; 2],
}
