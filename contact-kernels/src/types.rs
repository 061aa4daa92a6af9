//! The vocabulary shared by all kernels: formulations, approximation types,
//! the truncation table and operation counts.

pub use crate::generated::Formulation;

/// How an entity (xi_m, x_ms or n) depends on the displacements within a
/// load step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EntityOrder {
    /// Held constant: first and second derivatives dropped.
    Constant,
    /// Linear: second derivative dropped.
    Linear,
    /// Quadratic: first and second derivatives kept.
    Quadratic,
}

/// One of the six approximation types: a row of the truncation table.
///
/// | type | xi_m | x_ms | n |
/// |---|---|---|---|
/// | 1 | constant | linear | constant |
/// | 2 | linear | linear | linear |
/// | 3 | linear | quadratic | linear |
/// | 4 | quadratic | quadratic | linear |
/// | 5 | linear | quadratic | quadratic |
/// | 6 | quadratic | quadratic | quadratic |
///
/// Type 6 keeps everything: the exact gradient and Hessian.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ApproxType {
    /// xi_m constant, x_ms linear, n constant (no Hessian).
    Type1,
    /// xi_m, x_ms and n linear.
    Type2,
    /// xi_m linear, x_ms quadratic, n linear.
    Type3,
    /// xi_m quadratic, x_ms quadratic, n linear.
    Type4,
    /// xi_m linear, x_ms quadratic, n quadratic.
    Type5,
    /// Everything quadratic: exact derivatives.
    Type6,
}

impl ApproxType {
    /// All six types in order.
    pub const ALL: [ApproxType; 6] = [
        ApproxType::Type1,
        ApproxType::Type2,
        ApproxType::Type3,
        ApproxType::Type4,
        ApproxType::Type5,
        ApproxType::Type6,
    ];

    /// The type's number, 1..=6.
    pub fn index(self) -> usize {
        self as usize + 1
    }

    /// The type with number `n` (1..=6), if any.
    pub fn from_index(n: usize) -> Option<ApproxType> {
        n.checked_sub(1).and_then(|i| Self::ALL.get(i).copied())
    }

    /// The orders kept for `[xi_m, x_ms, n]` (the generator's truncation
    /// table, written into the generated code).
    pub fn orders(self) -> [EntityOrder; 3] {
        crate::generated::TRUNCATION[self as usize]
    }

    /// Whether the type has a second-order term.
    pub fn has_hessian(self) -> bool {
        self != ApproxType::Type1
    }
}

impl std::fmt::Display for ApproxType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.index())
    }
}

/// Error parsing a formulation or type name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} `{given}` (expected one of: {expected})")]
pub struct ParseNameError {
    what: &'static str,
    given: String,
    expected: String,
}

impl std::str::FromStr for ApproxType {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s
            .trim()
            .trim_start_matches("type")
            .trim_start_matches("Type");
        t.parse::<usize>()
            .ok()
            .and_then(ApproxType::from_index)
            .ok_or_else(|| ParseNameError {
                what: "approximation type",
                given: s.to_owned(),
                expected: "1, 2, 3, 4, 5, 6".to_owned(),
            })
    }
}

impl std::str::FromStr for Formulation {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Formulation::ALL
            .into_iter()
            .find(|f| f.name() == s.trim())
            .ok_or_else(|| ParseNameError {
                what: "formulation",
                given: s.to_owned(),
                expected: Formulation::ALL.map(|f| f.name()).join(", "),
            })
    }
}

impl Formulation {
    /// The coordinate count `n` of the formulation's kernels (8 for
    /// two-node segment pairs, 12 for three-node ones, 18 to 24 for face
    /// pairs); `None` when it was not compiled in.
    pub fn coords(self) -> Option<usize> {
        match crate::generated::face_kernel_set(self) {
            Some(f) => Some(f.coords),
            None => crate::generated::kernel_set(self).map(|s| s.coords),
        }
    }

    /// The node counts `(slave, master)` of a formulation of 3D faces (3:
    /// tri3, 4: quad4); `None` for segments or when not compiled in.
    pub fn face_nodes(self) -> Option<(usize, usize)> {
        crate::generated::face_kernel_set(self).map(|f| (f.slave_nodes, f.master_nodes))
    }

    /// The parametric dimension of the formulation's faces (1 for
    /// segments, 2 for tri3 and quad4 faces): the length of `xi_s` and
    /// `xi_m`; `None` when it was not compiled in.
    pub fn param_dim(self) -> Option<usize> {
        match crate::generated::face_kernel_set(self) {
            Some(_) => Some(2),
            None => crate::generated::kernel_set(self).map(|_| 1),
        }
    }
}

impl std::fmt::Display for Formulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Floating-point operations in a generated kernel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: u32,
    /// Multiplications.
    pub mul: u32,
    /// Divisions.
    pub div: u32,
    /// Square roots.
    pub sqrt: u32,
    /// Negations.
    pub neg: u32,
}

impl OpCount {
    /// All operations together (each counts one).
    pub fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.sqrt + self.neg
    }
}
