//! The seam over the spatial dimension: `Dim<D>` and the trait
//! [`SpaceDim`], implemented for `Dim<2>` and `Dim<3>`.
//!
//! The solver's core (mesh, model, dofs, elements, assembly, Newton,
//! solution, output) is one code path generic over a `const D: usize`.
//! What exists only in some dimensions goes through this trait, so that
//! the generic code names it without branching on `D`: today contact,
//! whose layout, kernels and pairing work on 2D segments. A generic
//! function that builds a solve (Newton's `Setup`, [`crate::solve_model`])
//! carries the bound `where Dim<D>: SpaceDim<D>`, which also restricts `D`
//! to 2 and 3; the functions it calls need no bound.

use crate::model::Model;
use crate::solution::{Solution, State};

/// The spatial dimension `D` as a type (see [`SpaceDim`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dim<const D: usize>;

/// What differs between the dimensions beyond the sizes `D` fixes.
pub trait SpaceDim<const D: usize> {
    /// The names of the coordinates, `x`, `y` (and `z`).
    const AXES: [&'static str; D];

    /// The model as the 2D contact layer sees it: the model itself in 2D;
    /// `None` in 3D, where contact is not available yet (a 3D model with
    /// a contact pair is refused by [`Model::check`], so Newton treats a
    /// 3D model as one without contact).
    fn planar(model: &Model<D>) -> Option<&Model<2>>;

    /// A solution and one of its states as the 2D contact report sees
    /// them (the nodal contact table): themselves in 2D, `None` in 3D
    /// (no contact).
    fn planar_solution<'s>(
        solution: &'s Solution<D>,
        state: &'s State<D>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)>;
}

impl SpaceDim<2> for Dim<2> {
    const AXES: [&'static str; 2] = ["x", "y"];

    fn planar(model: &Model<2>) -> Option<&Model<2>> {
        Some(model)
    }

    fn planar_solution<'s>(
        solution: &'s Solution<2>,
        state: &'s State<2>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)> {
        Some((solution, state))
    }
}

impl SpaceDim<3> for Dim<3> {
    const AXES: [&'static str; 3] = ["x", "y", "z"];

    fn planar(_: &Model<3>) -> Option<&Model<2>> {
        None
    }

    fn planar_solution<'s>(
        _: &'s Solution<3>,
        _: &'s State<3>,
    ) -> Option<(&'s Solution<2>, &'s State<2>)> {
        None
    }
}
