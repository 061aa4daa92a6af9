//! The values of the formulation language (scalars, 2-vectors, 3-vectors:
//! [`Value`]) and the scalar arithmetic the interpreter computes them in
//! ([`Domain`]): the DAG for the expressions themselves, truncated jets
//! (`crate::jet`) for the derivatives of the gap.

use crate::expr::{Dag, Id};

/// A value of the formulation language.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value<S> {
    /// A scalar.
    Scalar(S),
    /// A 2-vector.
    Vec2([S; 2]),
    /// A 3-vector (points and vectors of 3D faces).
    Vec3([S; 3]),
}

impl<S: Copy> Value<S> {
    /// The scalar components (one, two or three).
    pub fn components(&self) -> Vec<S> {
        match *self {
            Value::Scalar(s) => vec![s],
            Value::Vec2([a, b]) => vec![a, b],
            Value::Vec3([a, b, c]) => vec![a, b, c],
        }
    }

    /// The value of the same kind as `self` with components `c` (as many
    /// as `self` has).
    pub fn like<T: Copy>(&self, c: &[T]) -> Value<T> {
        match self {
            Value::Scalar(_) => Value::Scalar(c[0]),
            Value::Vec2(_) => Value::Vec2([c[0], c[1]]),
            Value::Vec3(_) => Value::Vec3([c[0], c[1], c[2]]),
        }
    }

    /// The vector of components `c` (one: a scalar).
    pub fn from_components(c: &[S]) -> Value<S> {
        match *c {
            [a] => Value::Scalar(a),
            [a, b] => Value::Vec2([a, b]),
            [a, b, c] => Value::Vec3([a, b, c]),
            _ => panic!("values have one to three components, not {}", c.len()),
        }
    }
}

/// Scalar arithmetic the interpreter needs; implemented by the DAG (values)
/// and by truncated jets (derivatives of the gap).
pub trait Domain {
    /// The scalar type.
    type S: Copy;
    /// A constant.
    fn constant(&mut self, c: f64) -> Self::S;
    /// `a + b`.
    fn add(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a - b`.
    fn sub(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a * b`.
    fn mul(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `a / b`.
    fn div(&mut self, a: Self::S, b: Self::S) -> Self::S;
    /// `-a`.
    fn neg(&mut self, a: Self::S) -> Self::S;
    /// `sqrt(a)`.
    fn sqrt(&mut self, a: Self::S) -> Self::S;
    /// `a^n`.
    fn powi(&mut self, a: Self::S, n: i32) -> Self::S;
    /// The first non-finite constant a fold produced, if the domain folds
    /// constants (the DAG does: [`Dag::non_finite`]).
    fn non_finite(&self) -> Option<f64> {
        None
    }
}

impl Domain for Dag {
    type S = Id;
    fn constant(&mut self, c: f64) -> Id {
        Dag::constant(self, c)
    }
    fn add(&mut self, a: Id, b: Id) -> Id {
        Dag::add(self, a, b)
    }
    fn sub(&mut self, a: Id, b: Id) -> Id {
        Dag::sub(self, a, b)
    }
    fn mul(&mut self, a: Id, b: Id) -> Id {
        Dag::mul(self, a, b)
    }
    fn div(&mut self, a: Id, b: Id) -> Id {
        Dag::div(self, a, b)
    }
    fn neg(&mut self, a: Id) -> Id {
        Dag::neg(self, a)
    }
    fn sqrt(&mut self, a: Id) -> Id {
        Dag::sqrt(self, a)
    }
    fn powi(&mut self, a: Id, n: i32) -> Id {
        Dag::powi(self, a, n)
    }
    fn non_finite(&self) -> Option<f64> {
        Dag::non_finite(self)
    }
}
