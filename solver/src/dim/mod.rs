//! The seam over the spatial dimension: `Dim<D>` and the trait
//! [`SpaceDim`], implemented for `Dim<2>` and `Dim<3>`.
//!
//! The solver's core (mesh, model, dofs, elements, assembly, Newton,
//! solution, output) is one code path generic over a `const D: usize`.
//! What exists only in some dimensions goes through this trait, so that
//! the generic code names it without branching on `D`: the axis names, and
//! contact, whose element is 2D segments in 2D and tri3/quad4 faces in 3D
//! ([`ContactSpace`], `space.rs`: the trait the Newton loop reads,
//! implemented for the 2D [`ContactLayout`] in `planar.rs` and the 3D
//! [`FaceLayout`] in `faces.rs`). A generic
//! function that builds a solve (Newton's `Setup`, [`crate::solve_model`])
//! carries the bound `where Dim<D>: SpaceDim<D>`, which also restricts `D`
//! to 2 and 3; the functions it calls need no bound.

mod faces;
mod planar;
mod space;

use crate::contact::{ContactLayout, FaceLayout};
use crate::solution::{Solution, State};

pub use space::{ContactSpace, EvalsResult, FoundResult, Update};

/// The spatial dimension `D` as a type (see [`SpaceDim`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dim<const D: usize>;

/// What differs between the dimensions beyond the sizes `D` fixes.
pub trait SpaceDim<const D: usize> {
    /// The names of the coordinates, `x`, `y` (and `z`).
    const AXES: [&'static str; D];

    /// The contact element of the dimension: [`ContactLayout`] in 2D,
    /// [`FaceLayout`] in 3D.
    type Contact: ContactSpace<D>;

    /// A solution and one of its states as the 2D contact report sees
    /// them (the nodal contact table): themselves in 2D, `None` in 3D
    /// (no contact).
    fn planar_solution<'s>(
        solution: &'s Solution<D>,
        state: &'s State<D>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)>;

    /// The same as the 3D contact report sees them (the face pairs'
    /// nodal table): themselves in 3D, `None` in 2D.
    fn solid_solution<'s>(
        solution: &'s Solution<D>,
        state: &'s State<D>,
    ) -> Option<(&'s Solution<3>, &'s State<3>)>;
}

impl SpaceDim<2> for Dim<2> {
    const AXES: [&'static str; 2] = ["x", "y"];
    type Contact = ContactLayout;

    fn planar_solution<'s>(
        solution: &'s Solution<2>,
        state: &'s State<2>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)> {
        Some((solution, state))
    }

    fn solid_solution<'s>(
        _: &'s Solution<2>,
        _: &'s State<2>,
    ) -> Option<(&'s Solution<3>, &'s State<3>)> {
        None
    }
}

impl SpaceDim<3> for Dim<3> {
    const AXES: [&'static str; 3] = ["x", "y", "z"];
    type Contact = FaceLayout;

    fn planar_solution<'s>(
        _: &'s Solution<3>,
        _: &'s State<3>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)> {
        None
    }

    fn solid_solution<'s>(
        solution: &'s Solution<3>,
        state: &'s State<3>,
    ) -> Option<(&'s Solution<3>, &'s State<3>)> {
        Some((solution, state))
    }
}
