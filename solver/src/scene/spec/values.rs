//! The values written inside the scene's tables: points and vectors
//! ([`Coords`]) and sets of displacement components ([`Dofs`]) (a block's
//! side is a [`crate::mesh::Side`]), and the serde helpers that the other
//! files' fields name (`deserialize_with = "de_..."`, `serialize_with = "ser_..."`):
//! number lists of an exact length, load curves, formulations, linear
//! solvers and methods.

use contact_kernels::Formulation;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::linear::LinearSolverKind;
use crate::options::Method;

/// A point or a vector as written: two numbers `[x, y]` in a 2D scene,
/// three `[x, y, z]` in a 3D one (any other count is a syntax error; which
/// of the two a scene takes is checked with its dimension).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Coords {
    /// `[x, y]`.
    Xy([f64; 2]),
    /// `[x, y, z]`.
    Xyz([f64; 3]),
}

impl Coords {
    /// How many numbers were written (2 or 3).
    pub fn len(&self) -> usize {
        self.as_slice().len()
    }

    /// Never empty (for clippy's `len` rule).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The numbers, as written.
    pub fn as_slice(&self) -> &[f64] {
        match self {
            Coords::Xy(v) => v,
            Coords::Xyz(v) => v,
        }
    }

    /// The point `[x, y]` (`D` = 2) or `[x, y, z]` (`D` = 3), if `D`
    /// numbers were written.
    pub fn point<const D: usize>(&self) -> Option<[f64; D]> {
        self.as_slice().try_into().ok()
    }
}

impl Serialize for Coords {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.as_slice().serialize(s)
    }
}

impl<'de> Deserialize<'de> for Coords {
    /// Exactly two or three numbers: a plain array would take the first
    /// ones of a longer list silently.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Coords, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        match *v.as_slice() {
            [x, y] => Ok(Coords::Xy([x, y])),
            [x, y, z] => Ok(Coords::Xyz([x, y, z])),
            _ => Err(serde::de::Error::custom(format!(
                "needs two numbers [x, y] (2D) or three [x, y, z] (3D), got {}",
                v.len()
            ))),
        }
    }
}

/// Which displacement components (`dofs`: any non-empty set of the
/// letters `x`, `y` and, in 3D, `z`, each at most once, in any order:
/// `"x"`, `"yz"`, `"xyz"`, ...). Written back in the order x, y, z.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dofs {
    /// Whether x, y, z are in the set.
    axes: [bool; 3],
}

impl Dofs {
    /// x only.
    pub const X: Dofs = Dofs {
        axes: [true, false, false],
    };
    /// y only.
    pub const Y: Dofs = Dofs {
        axes: [false, true, false],
    };
    /// z only.
    pub const Z: Dofs = Dofs {
        axes: [false, false, true],
    };
    /// x and y (every component in 2D).
    pub const XY: Dofs = Dofs {
        axes: [true, true, false],
    };
    /// x, y and z (every component in 3D).
    pub const XYZ: Dofs = Dofs {
        axes: [true, true, true],
    };

    /// Every component of a scene of dimension `dim` (2 or 3): what a
    /// `[[fix]]` without `dofs` fixes.
    pub fn all(dim: usize) -> Dofs {
        if dim == 3 { Dofs::XYZ } else { Dofs::XY }
    }

    /// The displacement components (0 = x, 1 = y, 2 = z), ascending.
    pub fn components(self) -> impl Iterator<Item = usize> {
        (0..3).filter(move |&c| self.axes[c])
    }

    /// Whether z is in the set.
    pub fn has_z(self) -> bool {
        self.axes[2]
    }

    /// The set as written back: its letters in the order x, y, z.
    pub fn name(self) -> String {
        self.components().map(|c| ['x', 'y', 'z'][c]).collect()
    }
}

impl std::str::FromStr for Dofs {
    type Err = String;

    fn from_str(s: &str) -> Result<Dofs, String> {
        let bad = || {
            format!(
                "`dofs` is a non-empty set of the letters x, y, z, each at most once (\"x\", \"xy\", \"xyz\", ...), got \"{s}\""
            )
        };
        let mut axes = [false; 3];
        for ch in s.chars() {
            let c = match ch {
                'x' => 0,
                'y' => 1,
                'z' => 2,
                _ => return Err(bad()),
            };
            if axes[c] {
                return Err(bad());
            }
            axes[c] = true;
        }
        if axes == [false; 3] {
            return Err(bad());
        }
        Ok(Dofs { axes })
    }
}

impl Serialize for Dofs {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

impl<'de> Deserialize<'de> for Dofs {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Dofs, D::Error> {
        String::deserialize(d)?
            .parse()
            .map_err(serde::de::Error::custom)
    }
}

/// Exactly two numbers: a plain `[f64; 2]` would take the first two of a
/// longer list silently.
fn pair_from<E: serde::de::Error>(v: &[f64]) -> Result<[f64; 2], E> {
    <[f64; 2]>::try_from(v)
        .map_err(|_| E::custom(format!("needs exactly two numbers [x, y], got {}", v.len())))
}

pub(super) fn de_opt_pair<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 2]>, D::Error> {
    pair_from(&Vec::<f64>::deserialize(d)?).map(Some)
}

/// Exactly three numbers, as [`pair_from`] two.
pub(super) fn de_opt_triple<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
    let v = Vec::<f64>::deserialize(d)?;
    <[f64; 3]>::try_from(v.as_slice()).map(Some).map_err(|_| {
        serde::de::Error::custom(format!(
            "needs exactly three numbers [x, y, z], got {}",
            v.len()
        ))
    })
}

/// A load curve's points, each exactly two numbers (a `[f64; 2]` alone
/// would take the first two of a longer list silently).
pub(super) fn de_amplitude<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<Vec<[f64; 2]>>, D::Error> {
    let points = Vec::<Vec<f64>>::deserialize(d)?;
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            <[f64; 2]>::try_from(p.as_slice()).map_err(|_| {
                serde::de::Error::custom(format!(
                    "point {i}: needs two numbers [load_factor, value], got {}",
                    p.len()
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

pub(super) fn de_formulation<'de, D: Deserializer<'de>>(d: D) -> Result<Formulation, D::Error> {
    let s = String::deserialize(d)?;
    let f: Formulation = s.parse().map_err(serde::de::Error::custom)?;
    // Only formulations of two-node segment pairs fit the solver's faces.
    match crate::options::unsupported_formulation(f) {
        Some(why) => Err(serde::de::Error::custom(why)),
        None => Ok(f),
    }
}

pub(super) fn ser_formulation<S: Serializer>(f: &Formulation, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(f.name())
}

/// A value written as a string its `FromStr` reads (the linear solver,
/// the expansion point).
pub(super) fn de_from_str<'de, D, T>(d: D) -> Result<T, D::Error>
where
    D: Deserializer<'de>,
    T: std::str::FromStr<Err: std::fmt::Display>,
{
    let s = String::deserialize(d)?;
    s.parse().map_err(serde::de::Error::custom)
}

/// A value written as its `Display` string (read back by [`de_from_str`]).
pub(super) fn ser_display<S: Serializer, T: std::fmt::Display>(
    k: &T,
    s: S,
) -> Result<S::Ok, S::Error> {
    s.serialize_str(&k.to_string())
}

pub(super) fn is_default_linear(k: &LinearSolverKind) -> bool {
    *k == LinearSolverKind::default()
}

pub(super) fn de_method<'de, D: Deserializer<'de>>(d: D) -> Result<Method, D::Error> {
    struct V;
    impl serde::de::Visitor<'_> for V {
        type Value = Method;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("\"complete\" or an approximation type 1..6")
        }
        fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Method, E> {
            v.parse().map_err(E::custom)
        }
        fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Method, E> {
            self.visit_str(&v.to_string())
        }
        fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Method, E> {
            self.visit_str(&v.to_string())
        }
    }
    d.deserialize_any(V)
}

pub(super) fn ser_method<S: Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
    match m {
        Method::Complete => s.serialize_str("complete"),
        Method::Approx(t) => s.serialize_u64(t.index() as u64),
    }
}
