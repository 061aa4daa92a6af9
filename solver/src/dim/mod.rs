//! The seam over the spatial dimension above the contact element: the
//! trait [`SpaceDim`], implemented for `Dim<2>` and `Dim<3>`
//! ([`crate::model::Dim`]).
//!
//! The solver's core (mesh, model, dofs, elements, assembly, Newton,
//! solution, output) is one code path generic over a `const D: usize`.
//! What exists only in some dimensions goes through traits on `Dim<D>`,
//! so that the generic code names it without branching on `D`: the facet
//! of a contact pair ([`crate::model::SurfaceDim`]: a segment in 2D, a
//! tri3/quad4 face in 3D), and here the axis names and the contact
//! element, whose mathematics is the same in both dimensions
//! ([`ContactSpace`], the trait the Newton loop reads, which the 2D
//! [`ContactLayout`] and the 3D [`FaceLayout`] implement in
//! `crate::contact`). Above it the scene builder
//! (`crate::scene::SceneDim`) and the nodal contact table
//! (`crate::report::ContactTable`) are traits of the same kind. A generic
//! function that builds a solve (Newton's `Setup`, [`crate::solve_model`])
//! carries the bound `where Dim<D>: SpaceDim<D>`, which also restricts `D`
//! to 2 and 3; a function that only reads a model or a solution carries
//! `Dim<D>: SurfaceDim<D>` (what `Model<D>` needs to name its pairs).

use crate::contact::{ContactLayout, ContactSpace, FaceLayout};
use crate::model::{Dim, SurfaceDim};

/// What differs between the dimensions beyond the sizes `D` fixes, above
/// the facets of a contact pair ([`SurfaceDim`]).
pub trait SpaceDim<const D: usize>: SurfaceDim<D> {
    /// The names of the coordinates, `x`, `y` (and `z`).
    const AXES: [&'static str; D];

    /// The contact element of the dimension: [`ContactLayout`] in 2D,
    /// [`FaceLayout`] in 3D.
    type Contact: ContactSpace<D>;
}

impl SpaceDim<2> for Dim<2> {
    const AXES: [&'static str; 2] = ["x", "y"];
    type Contact = ContactLayout;
}

impl SpaceDim<3> for Dim<3> {
    const AXES: [&'static str; 3] = ["x", "y", "z"];
    type Contact = FaceLayout;
}
