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
//!
//! The schema is laid out by concept:
//!
//! * `mod.rs`: [`Scene`] and its top-level tables (`[mesh]`,
//!   `[material]`, `[[body]]`, `[loading]`, `[refine]`, `[newton]`) and
//!   their defaults;
//! * `items.rs`: the entries that select nodes or faces of the bodies
//!   (`[[fix]]`, `[[load]]`, `[[prescribe]]`, `[[traction]]`,
//!   `[[contact]]` and its faces);
//! * `values.rs`: the values written inside them ([`Coords`], [`Dofs`];
//!   a block's side is a [`crate::mesh::Side`]) and the serde helpers of the fields that do not derive
//!   their reading or writing.
//!
//! Everything is re-exported here: `spec::X` names every type.

use serde::{Deserialize, Serialize};

use crate::linear::LinearSolverKind;
use crate::material::{Kinematics, Material, PlaneModel};
use crate::options::{
    DEFAULT_EXPAND_AT, DEFAULT_MAX_CUTBACKS, DEFAULT_MAX_ITERATIONS, DEFAULT_REPAIR,
    DEFAULT_TOLERANCE, ExpansionPoint, Method,
};

mod items;
mod values;

pub use items::{ContactSpec, FaceSpec, FixSpec, LoadSpec, PrescribeSpec, TractionSpec};
pub use values::{Coords, Dofs};
use values::{de_from_str, de_method, is_default_linear, ser_display, ser_method};

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

/// A body (`[[body]]`): either a structured block (see
/// [`crate::mesh::block`]; `origin`, `size`,
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    /// `linear`: the linear solver, `"lu"` (default), `"ldlt"` or, in a
    /// build with the `petsc` feature, `"petsc"` (not written when it is the
    /// default).
    #[serde(
        default,
        deserialize_with = "de_from_str",
        serialize_with = "ser_display",
        skip_serializing_if = "is_default_linear"
    )]
    pub linear: LinearSolverKind,
    /// `petsc_options`: PETSc options of `linear = "petsc"`, in PETSc's
    /// syntax (`"-fieldsplit_u_pc_type hypre"`), applied after the defaults
    /// and the `PETSC_OPTIONS` environment (docs/petsc.md); default none
    /// (not written).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub petsc_options: String,
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
    /// `expand_at`: Types 1–6 only, where a load step's Taylor expansions
    /// are taken: `"predictor"` (default; not written), the step's secant
    /// predictor where prescribed displacements move on as in the last
    /// step and the step start otherwise, or `"start"`, the converged state
    /// (the paper's scheme). See [`crate::newton`], "Where the expansions
    /// are taken".
    #[serde(
        default,
        deserialize_with = "de_from_str",
        serialize_with = "ser_display",
        skip_serializing_if = "is_default_expand_at"
    )]
    pub expand_at: ExpansionPoint,
}

impl Default for NewtonSpec {
    fn default() -> Self {
        NewtonSpec {
            tolerance: default_tolerance(),
            max_iterations: default_max_iterations(),
            max_cutbacks: default_max_cutbacks(),
            linear: LinearSolverKind::default(),
            petsc_options: String::new(),
            repair: default_repair(),
            taylor_tolerance: None,
            expand_at: DEFAULT_EXPAND_AT,
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
fn is_default_expand_at(e: &ExpansionPoint) -> bool {
    *e == DEFAULT_EXPAND_AT
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
fn default_method() -> Method {
    Method::Complete
}
