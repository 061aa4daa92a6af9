//! Why a contact pair cannot be laid out ([`FaceLayoutError`]; the
//! element's `ContactSpace::build`): today only a 3D pair can be refused,
//! for its rule, a degenerate slave face, a slave face without a dual
//! basis, the clipping of segmented integration or its reading.

use contact_kernels::Formulation;
use thiserror::Error;

use super::clip::ClipError;
use super::face_rules::RuleError;

/// A 3D pair that cannot be laid out.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FaceLayoutError {
    /// `gauss_points` has no rule on one of the pair's slave face kinds.
    #[error("contact pair `{pair}`: {source}")]
    Rule {
        /// The pair's name.
        pair: String,
        /// The rule's error (the counts there are).
        source: RuleError,
    },
    /// A slave face whose reference area element is not positive and
    /// finite at an integration point.
    #[error(
        "contact pair `{pair}`: slave face {face} has area element {area_element:e} at its integration point {gauss}"
    )]
    DegenerateSlaveFace {
        /// The pair's name.
        pair: String,
        /// The slave face's index in the pair.
        face: usize,
        /// The integration point.
        gauss: usize,
        /// `|dX/du x dX/dv|` there.
        area_element: f64,
    },
    /// A slave face whose dual multiplier basis cannot be built
    /// (`multipliers = "dual"`).
    #[error("contact pair `{pair}`: slave face {face} has no dual multiplier basis: {source}")]
    DualBasis {
        /// The pair's name.
        pair: String,
        /// The slave face's index in the pair.
        face: usize,
        /// Why.
        source: DualBasisError,
    },
    /// `gauss_points` is not a triangle rule's count (segmented
    /// integration: 1, 3 or 7).
    #[error(
        "contact pair `{pair}`: segmented integration takes gauss_points = 1, 3 or 7 (points per triangle), got {requested}"
    )]
    TriangleRule {
        /// The pair's name.
        pair: String,
        /// The count asked for.
        requested: usize,
    },
    /// A slave face the clipping refuses (segmented integration).
    #[error("contact pair `{pair}`: slave face {face} against master face {master}: {source}")]
    Clip {
        /// The pair's name.
        pair: String,
        /// The slave face's index in the pair.
        face: usize,
        /// The master face's index in the pair.
        master: usize,
        /// Why.
        source: ClipError,
    },
    /// The pair's reading is not `slave-normal` or `closest-point`.
    #[error(
        "contact pair `{pair}`: `{reading}` is not a reading of 3D faces (slave-normal, closest-point)"
    )]
    Reading {
        /// The pair's name.
        pair: String,
        /// The reading given.
        reading: Formulation,
    },
}

/// Why a slave face has no dual basis (`contact::face::dual_coefficients`).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DualBasisError {
    /// The face's reference area element is not positive and finite at a
    /// point of the rule integrating its mass matrix.
    #[error("area element {area_element:e} at its mass matrix's rule point {gauss}")]
    AreaElement {
        /// The rule point.
        gauss: usize,
        /// `|dX/du x dX/dv|` there.
        area_element: f64,
    },
    /// The face's mass matrix `int N_a N_b` has no inverse in floating point.
    #[error("its mass matrix is singular")]
    SingularMass,
    /// The rule integrating the mass matrix is missing.
    #[error(transparent)]
    Rule(#[from] RuleError),
}
