//! The scene's entries on nodes and faces of its bodies: supports
//! (`[[fix]]`), point loads (`[[load]]`), prescribed displacements
//! (`[[prescribe]]`), faces (`{ body, side }` or `{ group }`), distributed
//! loads (`[[traction]]`) and contact pairs (`[[contact]]`), with the
//! defaults of their fields.

use contact_kernels::Formulation;
use serde::{Deserialize, Serialize};

use crate::mesh::Side;
use crate::model::{ContactMode, Integration, Multipliers};

use super::values::{
    Coords, Dofs, de_amplitude, de_formulation, de_opt_pair, de_opt_triple, ser_formulation,
};

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
    /// `side`: a block's side ([`Side`]: `bottom`, `right`, `top`,
    /// `left`; in 3D also `front`, `back`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<Side>,
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
///   node on a tri3; see [`crate::scene::traction`]).
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
    pub side: Option<Side>,
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
    /// `friction`: Coulomb's coefficient `mu` between the faces (default
    /// 0: frictionless). A finite number `>= 0`; 0 gives the frictionless
    /// solve bit for bit. Above 0 the pair must be `mode = "unilateral"`
    /// and two-dimensional, and the scene solved with the complete
    /// formulation (see [`crate::contact`], "Coulomb friction"). Not
    /// written when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub friction: f64,
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
    /// `multipliers`: the multiplier basis on the slave faces,
    /// `"standard"` (default: the slave face's shape functions) or, in 3D,
    /// `"dual"`: each slave face's biorthogonal basis (see
    /// [`Multipliers`]), whose nodal multipliers are the nodes' pressures
    /// in the mortar sense. A 2D scene with `"dual"` is refused. Not
    /// written when it is the default.
    #[serde(default, skip_serializing_if = "is_default_multipliers")]
    pub multipliers: Multipliers,
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
    /// `allow_initial_gap`: accept a persistent pair (`mode =
    /// "persistent"`, the default) whose slave nodes start apart from the
    /// master (default `false`). Where a slave node pairs in the reference
    /// configuration (as for `allow_not_facing`), its gap must be at most
    /// [`crate::scene::OPEN_GAP_FRACTION`] (1 %) times the size of its
    /// slave facet: a persistent pair holds `g = 0` at every paired point,
    /// so the first step would pull a wider gap shut. A wider gap is an
    /// error naming the pair and the node with the largest gap relative to
    /// that size, unless this key is `true` or the pair is
    /// `mode = "unilateral"` (contact that opens and closes). Not written
    /// when `false`.
    #[serde(default, skip_serializing_if = "is_false")]
    pub allow_initial_gap: bool,
}

impl ContactSpec {
    /// The pair's name in the model: its `name`, else its field
    /// `contact[i]` (`field`); the one naming of 2D and 3D pairs.
    pub(in crate::scene) fn pair_name(&self, field: &str) -> String {
        self.name.clone().unwrap_or_else(|| field.to_owned())
    }
}

fn is_default_integration(i: &Integration) -> bool {
    *i == Integration::default()
}

fn is_default_multipliers(m: &Multipliers) -> bool {
    *m == Multipliers::default()
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0 && v.is_sign_positive()
}
fn default_formulation() -> Formulation {
    Formulation::SlaveNormal
}
