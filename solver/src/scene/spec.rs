//! The scene file's schema: the serde types of a scene (TOML), their
//! defaults and how the non-derived fields read and write.
//!
//! These types are the file format and nothing else: they hold what was
//! written, unvalidated (see `validate.rs` and `build.rs` for what makes
//! sense, and the [module docs](super) for an annotated example;
//! `docs/scenes.md` is the reference for users, checked against these
//! types by `solver/tests/scene_docs.rs`). Unknown keys are errors
//! (`deny_unknown_fields` everywhere); every default is written next to
//! its field.

use contact_kernels::Formulation;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::linear::LinearSolverKind;
use crate::material::{Kinematics, Material, PlaneModel};
use crate::mesh::Side;
use crate::mesh::block3d::Side3d;
use crate::model::{ContactMode, Integration};
use crate::options::{
    DEFAULT_MAX_CUTBACKS, DEFAULT_MAX_ITERATIONS, DEFAULT_REPAIR, DEFAULT_TOLERANCE, Method,
};

/// A scene (see the module docs for the file format).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// `name`: a name for reports (default: the file name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `description`: free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[material]`: the material of every body without its own
    /// (`young`, `poisson`, `model` = `plane-stress` (default) or
    /// `plane-strain` in 2D, refused in 3D; `kinematics`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
    /// `[mesh]`: a mesh file whose physical surfaces (2D) or volumes (3D)
    /// are bodies (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<MeshSpec>,
    /// The bodies (`[[body]]`, at least one), in mesh order.
    #[serde(rename = "body")]
    pub bodies: Vec<BodySpec>,
    /// Supports (`[[fix]]`, default none).
    #[serde(default, rename = "fix")]
    pub fixes: Vec<FixSpec>,
    /// Point loads (`[[load]]`, default none).
    #[serde(default, rename = "load")]
    pub loads: Vec<LoadSpec>,
    /// Prescribed displacements (`[[prescribe]]`, default none).
    #[serde(default, rename = "prescribe")]
    pub prescribes: Vec<PrescribeSpec>,
    /// Distributed dead loads on block sides or physical curves
    /// (`[[traction]]`, default none).
    #[serde(default, rename = "traction", skip_serializing_if = "Vec::is_empty")]
    pub tractions: Vec<TractionSpec>,
    /// Contact pairs (`[[contact]]`, default none).
    #[serde(default, rename = "contact")]
    pub contacts: Vec<ContactSpec>,
    /// `[loading]`: the load schedule (required).
    pub loading: LoadingSpec,
    /// `[refine]`: refinement factors of the block bodies (default 1 on
    /// every axis).
    #[serde(default)]
    pub refine: RefineSpec,
    /// `[newton]`: Newton settings (defaults as in [`NewtonSpec`]).
    #[serde(default)]
    pub newton: NewtonSpec,
    /// Where the scene came from (file name), for messages; not part of
    /// the file.
    #[serde(skip)]
    pub origin: String,
}

/// The mesh file (`[mesh]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// `file`: a Gmsh MSH 4.1 file (ASCII or binary), relative to the
    /// scene file's directory: a 2D mesh (physical surfaces are bodies)
    /// or, when it holds tetrahedra or hexahedra, a 3D one (physical
    /// volumes are bodies).
    pub file: String,
}

/// A material as written (`[material]`, `[[body]] material`): the
/// [`Material`]'s constants, with `model` kept as given or not, since a
/// 3D scene refuses it ([`MaterialSpec::material`] gives the material,
/// plane stress when `model` is left out).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// `young`: Young's modulus `E` (positive, finite).
    pub young: f64,
    /// `poisson`: Poisson's ratio `nu` (in (-1, 1) in plane stress, in
    /// (-1, 1/2) in plane strain and in 3D).
    pub poisson: f64,
    /// `model`: `plane-stress` (the default) or `plane-strain`; 2D only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<PlaneModel>,
    /// `kinematics`: `finite` (the default) or `small`.
    #[serde(default, skip_serializing_if = "is_finite_kinematics")]
    pub kinematics: Kinematics,
}

fn is_finite_kinematics(k: &Kinematics) -> bool {
    *k == Kinematics::Finite
}

impl MaterialSpec {
    /// The material (plane stress when `model` is left out).
    pub fn material(&self) -> Material {
        Material {
            young: self.young,
            poisson: self.poisson,
            model: self.model.unwrap_or_default(),
            kinematics: self.kinematics,
        }
    }
}

impl From<Material> for MaterialSpec {
    fn from(m: Material) -> MaterialSpec {
        MaterialSpec {
            young: m.young,
            poisson: m.poisson,
            model: Some(m.model),
            kinematics: m.kinematics,
        }
    }
}

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

/// A body (`[[body]]`): either a structured block (see
/// [`crate::mesh::block`] and [`crate::mesh::block3d`]; `origin`, `size`,
/// `nx` and `ny` all given, and `nz` with three numbers in `origin` and
/// `size`: `nx` by `ny` 4-node quadrilaterals in 2D, `nx` by `ny` by `nz`
/// 8-node hexahedra in 3D), or, without any of those fields, the physical
/// group `group` (default: `name`) of the `[mesh]` file: a physical
/// surface of a 2D file (its 3-node triangles and 4-node quadrangles,
/// mixed freely, as drawn: counter-clockwise; an inverted element is an
/// error naming it) or a physical volume of a 3D file (its 4-node
/// tetrahedra and 8-node hexahedra, mixed freely).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// `name`: unique among the bodies; selections and faces refer to it.
    pub name: String,
    /// `origin`: the corner of smallest coordinates of a block, `[x, y]`
    /// or `[x, y, z]` (reference frame, finite).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<Coords>,
    /// `size`: a block's extents along x, y (and z) (positive, finite).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Coords>,
    /// `nx`: a block's elements along x (at least 1; times `[refine] x`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nx: Option<usize>,
    /// `ny`: a block's elements along y (at least 1; times `[refine] y`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ny: Option<usize>,
    /// `nz`: a 3D block's elements along z (at least 1; times
    /// `[refine] z`; refused in 2D).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nz: Option<usize>,
    /// `group`: the physical surface (2D) or volume (3D) of the `[mesh]`
    /// file that is this body (default: `name`; not with the block
    /// fields).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// Material (default: the scene's `[material]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
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

/// Supports (`[[fix]]`): zero displacement of the selected nodes. Select
/// with `at`, or with `x`, `y` and/or `z` (every node on that line or
/// plane), or with a physical `group` of the mesh file; `body` restricts
/// the selection to one body. At least one node must match.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixSpec {
    /// `name`: the support group's name in reports (`reactions.csv`;
    /// default: `group` when no other `[[fix]]`/`[[prescribe]]` has the
    /// same, else `fix[i]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `body`: restrict the selection to this body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// `group`: the nodes of this physical group of the `[mesh]` file (a
    /// point or curve in 2D, also a surface in 3D; instead of
    /// `x`/`y`/`z`/`at`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// `x`: the nodes with this reference x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<f64>,
    /// `y`: the nodes with this reference y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// `z`: the nodes with this reference z (3D only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// `at`: the node(s) at this reference point (not with `x`/`y`/`z`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Coords>,
    /// `dofs`: the components fixed (default: every component, `"xy"` in
    /// 2D, `"xyz"` in 3D; see [`Dofs`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dofs: Option<Dofs>,
}

/// A point force on one node (`[[load]]`): `lambda_L force`, or
/// `a(lambda_L) force` with a load curve `amplitude`.
/// Exactly one node (of `body`, if given) must sit at `at`, or be the
/// physical point `group`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// `body`: restrict to this body (needed where bodies touch).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// `at`: the node's reference position (or `group`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Coords>,
    /// `group`: a physical point (or curve) of the `[mesh]` file with
    /// exactly one node (instead of `at`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// `force`: `[fx, fy]` (2D) or `[fx, fy, fz]` (3D) at load factor one
    /// (finite).
    pub force: Coords,
    /// `amplitude`: a load curve `[[load_factor, value], ...]` (at least
    /// two points, load factors strictly increasing, all finite): at load
    /// factor `L` the force is `a(L)` times the value above, `a` piecewise
    /// linear between the points and held at the end values outside them
    /// (see [`crate::amplitude`]). Default: proportional, `L` times the
    /// value.
    #[serde(
        default,
        deserialize_with = "de_amplitude",
        skip_serializing_if = "Option::is_none"
    )]
    pub amplitude: Option<Vec<[f64; 2]>>,
}

/// Prescribed displacements (`[[prescribe]]`): `lambda_L (ux, uy, uz)`, or
/// `a(lambda_L) (ux, uy, uz)` with a load curve `amplitude`, on the nodes
/// selected as in [`FixSpec`]. A component left out is free; a node's
/// component prescribed twice must agree (the same value and, unless the
/// value is zero, the same curve), and its reaction is reported with the
/// first entry that prescribes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrescribeSpec {
    /// `name`: the support group's name in reports (`reactions.csv`;
    /// default: `group` when no other `[[fix]]`/`[[prescribe]]` has the
    /// same, else `prescribe[i]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `body`: restrict the selection to this body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// `group`: the nodes of this physical group of the `[mesh]` file (as
    /// in [`FixSpec`]; instead of `x`/`y`/`z`/`at`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// `x`: the nodes with this reference x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<f64>,
    /// `y`: the nodes with this reference y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// `z`: the nodes with this reference z (3D only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// `at`: the node(s) at this reference point (not with `x`/`y`/`z`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<Coords>,
    /// `ux`: the x displacement at load factor one (finite).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    /// `uy`: the y displacement at load factor one (finite).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
    /// `uz`: the z displacement at load factor one (finite; 3D only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uz: Option<f64>,
    /// `amplitude`: a load curve `[[load_factor, value], ...]` (at least
    /// two points, load factors strictly increasing, all finite): at load
    /// factor `L` the displacement is `a(L)` times the value above, `a` piecewise
    /// linear between the points and held at the end values outside them
    /// (see [`crate::amplitude`]). Default: proportional, `L` times the
    /// value.
    #[serde(
        default,
        deserialize_with = "de_amplitude",
        skip_serializing_if = "Option::is_none"
    )]
    pub amplitude: Option<Vec<[f64; 2]>>,
}

/// A side of a block as written (`side`): `bottom`, `right`, `top` or
/// `left` of a 2D block ([`Side`]: bottom and top at the smallest and
/// largest y); of a 3D block also `front` and `back` ([`Side3d`]: left and
/// right at the smallest and largest x, front and back y, bottom and top
/// z).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SideName {
    /// 2D: the smallest y; 3D: the smallest z.
    Bottom,
    /// The largest x.
    Right,
    /// 2D: the largest y; 3D: the largest z.
    Top,
    /// The smallest x.
    Left,
    /// The smallest y (3D only).
    Front,
    /// The largest y (3D only).
    Back,
}

impl SideName {
    /// The side of a 2D block; `None` for `front` and `back`.
    pub fn side_2d(self) -> Option<Side> {
        match self {
            SideName::Bottom => Some(Side::Bottom),
            SideName::Right => Some(Side::Right),
            SideName::Top => Some(Side::Top),
            SideName::Left => Some(Side::Left),
            SideName::Front | SideName::Back => None,
        }
    }

    /// The side of a 3D block.
    pub fn side_3d(self) -> Side3d {
        match self {
            SideName::Bottom => Side3d::Bottom,
            SideName::Right => Side3d::Right,
            SideName::Top => Side3d::Top,
            SideName::Left => Side3d::Left,
            SideName::Front => Side3d::Front,
            SideName::Back => Side3d::Back,
        }
    }

    /// The name as written.
    pub fn name(self) -> &'static str {
        self.side_3d().name()
    }
}

impl From<Side> for SideName {
    fn from(side: Side) -> SideName {
        match side {
            Side::Bottom => SideName::Bottom,
            Side::Right => SideName::Right,
            Side::Top => SideName::Top,
            Side::Left => SideName::Left,
        }
    }
}

/// A face (`{ body = .., side = .. }` or `{ group = .. }`): one side of a
/// block body, or a physical group of the `[mesh]` file on the boundary of
/// one body: in 2D a physical curve, as a chain of segments
/// counter-clockwise around the body (resolved by the body's mesh source;
/// a curve's segments are oriented by the element owning each, however the
/// curve was drawn); in 3D a physical surface, its faces oriented outward
/// by their owning elements.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceSpec {
    /// `body`: the body's name (with `side`; optional with `group`, where
    /// it must name the group's body).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// `side`: a block's side ([`SideName`]: `bottom`, `right`, `top`,
    /// `left`; in 3D also `front`, `back`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<SideName>,
    /// `group`: a physical curve (2D) or surface (3D) of the `[mesh]`
    /// file (instead of `side`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
}

/// A distributed dead load (`[[traction]]`) on a side of a block body
/// (`body` and `side`, as a [`FaceSpec`] names it) or on a physical group
/// of the `[mesh]` file (`group`, optionally with its `body`), applied as
/// consistent nodal forces, times the load factor `lambda_L` (or a load
/// curve's `a(lambda_L)` with `amplitude`):
///
/// * 2D: `force_per_length` per unit reference length on a side or a
///   physical curve (`t L / 2` to both nodes of each segment, `L` its
///   reference length);
/// * 3D: `force_per_area` per unit reference area on a side or a physical
///   surface (`t` times the integral of each node's shape function over
///   each face: 2 x 2 Gauss points on a quad4, exactly `t A / 3` per
///   node on a tri3; see [`super::traction`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    /// `body`: the block body whose `side` is loaded (with `side`), or the
    /// body every node of the group must belong to (optional with
    /// `group`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// `side`: a side of the block `body` (instead of `group`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<SideName>,
    /// `group`: the physical curve (2D) or surface (3D) of the `[mesh]`
    /// file loaded (instead of `side`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// `force_per_length`: `[tx, ty]` per unit reference length at load
    /// factor one (finite; 2D only).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_opt_pair"
    )]
    pub force_per_length: Option<[f64; 2]>,
    /// `force_per_area`: `[tx, ty, tz]` per unit reference area at load
    /// factor one (finite; 3D only).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_opt_triple"
    )]
    pub force_per_area: Option<[f64; 3]>,
    /// `amplitude`: a load curve `[[load_factor, value], ...]` (at least
    /// two points, load factors strictly increasing, all finite): at load
    /// factor `L` the load is `a(L)` times the value above, `a` piecewise
    /// linear between the points and held at the end values outside them
    /// (see [`crate::amplitude`]). Default: proportional, `L` times the
    /// value.
    #[serde(
        default,
        deserialize_with = "de_amplitude",
        skip_serializing_if = "Option::is_none"
    )]
    pub amplitude: Option<Vec<[f64; 2]>>,
}

/// A contact pair (`[[contact]]`) between faces of two different bodies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// `name`: a name for reports (default `contact[i]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `slave`: the slave face (carries integration points and
    /// multipliers).
    pub slave: FaceSpec,
    /// `master`: the master face.
    pub master: FaceSpec,
    /// `formulation`: the gap formulation, `slave-normal` (default) or
    /// `closest-point`. (`quadratic-slave-normal`, for 3-node segments, is
    /// refused: the solver's contact faces are two-node segments.) In 3D
    /// it is the pair's reading ([`crate::model::ContactPair::formulation`]): the
    /// kernel of each slave face on a master face is that reading's for
    /// the two faces' kinds.
    #[serde(
        default = "default_formulation",
        deserialize_with = "de_formulation",
        serialize_with = "ser_formulation"
    )]
    pub formulation: Formulation,
    /// `mode`: `persistent` (default) or `unilateral`.
    #[serde(default)]
    pub mode: ContactMode,
    /// `gauss_points`: the rule on each slave face. In 2D, Gauss points
    /// per slave segment, 1..=8, per piece of a slave segment with
    /// `integration = "segmented"`. In 3D, `n x n` points on a quad4 slave
    /// face (1..=8), `n` on a tri3 (1, 3, 4, 6 or 7), and with segmented
    /// integration the rule on each clipped triangle (1, 3 or 7). `None`
    /// (absent, not written): the default of the face kind, 2 on a
    /// segment, 2 x 2 on a quad4, 3 on a tri3 (segmented in 3D: 7), see
    /// [`crate::contact::face_rules::default_points`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gauss_points: Option<usize>,
    /// `integration`: the rule on the slave segments, `"gauss"` (default:
    /// `gauss_points` Gauss points per slave segment) or `"segmented"`:
    /// each slave segment is split at the slave points whose projection
    /// (in the pair's formulation) reaches a master node, and each piece
    /// gets `gauss_points` Gauss points with weights scaled to it, so that
    /// non-matching meshes transmit a uniform pressure exactly (the contact
    /// patch test, `scenes/patch-test.toml`). The split is computed once,
    /// in the reference configuration: exact while the faces do not slide
    /// relative to each other; where they slide, the relative error grows
    /// like `(slip / master segment length)^2`, and after large slips it is
    /// a finer Gauss rule without that guarantee (see [`crate::contact`],
    /// "Integration rule"). Not written when it is the default.
    #[serde(default, skip_serializing_if = "is_default_integration")]
    pub integration: Integration,
    /// `allow_not_facing`: accept slave and master faces that do not face
    /// each other (default `false`). Every slave node is projected onto
    /// the master face in the reference configuration with the pair's
    /// formulation; where it pairs, the outward normals of its slave
    /// segment and of the master segment must be opposed (`n_s . n_m <=`
    /// [`crate::scene::FACING_TOL`]: at most 90 degrees from opposed).
    /// A slave face that looks away from its master (`side = "top"` on a
    /// block resting on a base) is an error naming the pair and the node
    /// with the worst angle, unless this key is `true`. Not written when
    /// `false`.
    #[serde(default, skip_serializing_if = "is_false")]
    pub allow_not_facing: bool,
    /// `allow_initial_penetration`: accept slave nodes that start inside
    /// the master body (default `false`). Where a slave node pairs in the
    /// reference configuration (as for `allow_not_facing`), its gap must be
    /// at least `-`[`crate::scene::PENETRATION_FRACTION`] (1 %) times the
    /// length of its slave segment; a deeper initial penetration is an
    /// error naming the pair and the node with the largest penetration
    /// relative to that length, unless this key is `true` (the solver then
    /// pushes the faces apart in the first step). Not written when
    /// `false`.
    #[serde(default, skip_serializing_if = "is_false")]
    pub allow_initial_penetration: bool,
}

impl ContactSpec {
    /// The pair's name in the model: its `name`, else its field
    /// `contact[i]` (`field`); the one naming of 2D and 3D pairs.
    pub(super) fn pair_name(&self, field: &str) -> String {
        self.name.clone().unwrap_or_else(|| field.to_owned())
    }
}

fn is_default_integration(i: &Integration) -> bool {
    *i == Integration::default()
}

/// The load schedule and default method (`[loading]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadingSpec {
    /// `load_factor_end`: the final load factor (from 0; finite).
    pub load_factor_end: f64,
    /// `steps`: the step counts of a study (at least one, each at least
    /// 1).
    pub steps: Vec<usize>,
    /// `default_steps`: the step count of a single run (at least 1;
    /// default: the first of `steps`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub default_steps: Option<usize>,
    /// `method`: the default method, `"complete"` (default) or an
    /// approximation type 1..6 (a number or its text).
    #[serde(
        default = "default_method",
        deserialize_with = "de_method",
        serialize_with = "ser_method"
    )]
    pub method: Method,
}

/// Refinement factors for every block body's `nx`, `ny` and `nz`
/// (`[refine]`); [`Scene::refined`] multiplies them further.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineSpec {
    /// `x`: the factor on `nx` (at least 1, default 1).
    #[serde(default = "one")]
    pub x: usize,
    /// `y`: the factor on `ny` (at least 1, default 1).
    #[serde(default = "one")]
    pub y: usize,
    /// `z`: the factor on `nz` (at least 1, default 1; 3D only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<usize>,
}

impl RefineSpec {
    /// The factor on `nz` (1 unless given).
    pub fn z_factor(&self) -> usize {
        self.z.unwrap_or(1)
    }
}

impl Default for RefineSpec {
    fn default() -> Self {
        RefineSpec {
            x: 1,
            y: 1,
            z: None,
        }
    }
}

/// Newton settings (`[newton]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewtonSpec {
    /// `tolerance`: converged when `|r| <= tolerance * max(1, |f_ext|)`
    /// (positive, default 1e-10, [`crate::options::DEFAULT_TOLERANCE`]).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// `max_iterations`: Newton iterations per attempt (at least 1,
    /// default 30, [`crate::options::DEFAULT_MAX_ITERATIONS`]).
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// `max_cutbacks`: bisections per scheduled step (default 8,
    /// [`crate::options::DEFAULT_MAX_CUTBACKS`]).
    #[serde(default = "default_max_cutbacks")]
    pub max_cutbacks: usize,
    /// `linear`: the linear solver, `"lu"` (default) or `"ldlt"` (not
    /// written when it is the default).
    #[serde(
        default,
        deserialize_with = "de_linear",
        serialize_with = "ser_linear",
        skip_serializing_if = "is_default_linear"
    )]
    pub linear: LinearSolverKind,
    /// `repair`: Types 1–6 only. At a converged step end every integration
    /// point is re-paired by projection; when a point's master segment
    /// changed (or it became paired or unpaired), the step is repeated from
    /// its start with the Taylor expansion of the new pairing (see
    /// [`crate::newton`], "Re-pairing at the step end"). Default `true`:
    /// without it a point that slides across master nodes during a step
    /// keeps the expansion of the segment it started on and the step
    /// converges to the wrong constraint. `false` is the paper's scheme
    /// (each point keeps its step-start expansion), which the paper scene
    /// sets (`scenes/stacked-cantilever.toml`) to reproduce the paper's
    /// numbers. The Taylor remainder is measured and reported either way.
    /// Not written when it is the default.
    #[serde(default = "default_repair", skip_serializing_if = "is_default_repair")]
    pub repair: bool,
    /// `taylor_tolerance`: Types 1–6 only, adaptive stepping. A converged
    /// (sub)step whose largest Taylor remainder (the re-projected gap minus
    /// the frozen expansion's gap at an active point, over the slave
    /// segment's reference length) exceeds this is halved and redone
    /// (recorded in [`crate::Solution::accuracy_halvings`], apart from the
    /// divergence cut-backs; the halvings share `max_cutbacks`, and a step
    /// that cannot be halved further is accepted). Positive; default none
    /// (no adaptive stepping; not written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub taylor_tolerance: Option<f64>,
}

impl Default for NewtonSpec {
    fn default() -> Self {
        NewtonSpec {
            tolerance: default_tolerance(),
            max_iterations: default_max_iterations(),
            max_cutbacks: default_max_cutbacks(),
            linear: LinearSolverKind::default(),
            repair: default_repair(),
            taylor_tolerance: None,
        }
    }
}

fn one() -> usize {
    1
}
// `[newton]`'s defaults are written once, in `crate::options` (the
// `DEFAULT_` constants, which `SolveOptions::default` takes too)
fn default_repair() -> bool {
    DEFAULT_REPAIR
}
fn is_default_repair(b: &bool) -> bool {
    *b == default_repair()
}
fn is_false(b: &bool) -> bool {
    !*b
}
fn default_tolerance() -> f64 {
    DEFAULT_TOLERANCE
}
fn default_max_iterations() -> usize {
    DEFAULT_MAX_ITERATIONS
}
fn default_max_cutbacks() -> usize {
    DEFAULT_MAX_CUTBACKS
}
fn default_formulation() -> Formulation {
    Formulation::SlaveNormal
}
fn default_method() -> Method {
    Method::Complete
}

/// Exactly two numbers: a plain `[f64; 2]` would take the first two of a
/// longer list silently.
fn pair_from<E: serde::de::Error>(v: &[f64]) -> Result<[f64; 2], E> {
    <[f64; 2]>::try_from(v)
        .map_err(|_| E::custom(format!("needs exactly two numbers [x, y], got {}", v.len())))
}

fn de_opt_pair<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 2]>, D::Error> {
    pair_from(&Vec::<f64>::deserialize(d)?).map(Some)
}

/// Exactly three numbers, as [`pair_from`] two.
fn de_opt_triple<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
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
fn de_amplitude<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vec<[f64; 2]>>, D::Error> {
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

fn de_formulation<'de, D: Deserializer<'de>>(d: D) -> Result<Formulation, D::Error> {
    let s = String::deserialize(d)?;
    let f: Formulation = s.parse().map_err(serde::de::Error::custom)?;
    // Only formulations of two-node segment pairs fit the solver's faces.
    match crate::options::unsupported_formulation(f) {
        Some(why) => Err(serde::de::Error::custom(why)),
        None => Ok(f),
    }
}

fn ser_formulation<S: Serializer>(f: &Formulation, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(f.name())
}

fn de_linear<'de, D: Deserializer<'de>>(d: D) -> Result<LinearSolverKind, D::Error> {
    let s = String::deserialize(d)?;
    s.parse().map_err(serde::de::Error::custom)
}

fn ser_linear<S: Serializer>(k: &LinearSolverKind, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&k.to_string())
}

fn is_default_linear(k: &LinearSolverKind) -> bool {
    *k == LinearSolverKind::default()
}

fn de_method<'de, D: Deserializer<'de>>(d: D) -> Result<Method, D::Error> {
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

fn ser_method<S: Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
    match m {
        Method::Complete => s.serialize_str("complete"),
        Method::Approx(t) => s.serialize_u64(t.index() as u64),
    }
}
