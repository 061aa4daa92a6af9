//! The scene file's schema: the serde types of a scene (TOML), their
//! defaults and how the non-derived fields read and write.
//!
//! These types are the file format and nothing else: they hold what was
//! written, unvalidated (see `validate.rs` and `build.rs` for what makes
//! sense, and the [module docs](super) for an annotated example). Unknown
//! keys are errors (`deny_unknown_fields` everywhere); every default is
//! written next to its field.

use contact_kernels::Formulation;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::Method;
use crate::material::Material;
use crate::mesh::Side;
use crate::model::ContactMode;

/// A scene (see the module docs for the file format).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// A name for reports.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The default material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<Material>,
    /// The bodies (`[[body]]`).
    #[serde(rename = "body")]
    pub bodies: Vec<BodySpec>,
    /// Supports (`[[fix]]`).
    #[serde(default, rename = "fix")]
    pub fixes: Vec<FixSpec>,
    /// Point loads (`[[load]]`).
    #[serde(default, rename = "load")]
    pub loads: Vec<LoadSpec>,
    /// Prescribed displacements (`[[prescribe]]`).
    #[serde(default, rename = "prescribe")]
    pub prescribes: Vec<PrescribeSpec>,
    /// Contact pairs (`[[contact]]`).
    #[serde(default, rename = "contact")]
    pub contacts: Vec<ContactSpec>,
    /// The load schedule.
    pub loading: LoadingSpec,
    /// Mesh refinement factors.
    #[serde(default)]
    pub refine: RefineSpec,
    /// Newton settings.
    #[serde(default)]
    pub newton: NewtonSpec,
    /// Where the scene came from (file name), for messages.
    #[serde(skip)]
    pub origin: String,
}

/// A body: a structured rectangular block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name.
    pub name: String,
    /// Lower-left corner.
    pub origin: [f64; 2],
    /// Width and height.
    pub size: [f64; 2],
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Material (default: the scene's `[material]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<Material>,
}

/// Which displacement components.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Dofs {
    /// x only.
    #[serde(rename = "x")]
    X,
    /// y only.
    #[serde(rename = "y")]
    Y,
    /// Both.
    #[default]
    #[serde(rename = "xy")]
    XY,
}

impl Dofs {
    /// The displacement components (0 = x, 1 = y) fixed.
    pub(super) fn components(self) -> &'static [usize] {
        match self {
            Dofs::X => &[0],
            Dofs::Y => &[1],
            Dofs::XY => &[0, 1],
        }
    }
}

/// Supports: zero displacement of the selected nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixSpec {
    /// Restrict to this body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Nodes with this reference x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<f64>,
    /// Nodes with this reference y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// The node(s) at this reference point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// Components fixed.
    #[serde(default)]
    pub dofs: Dofs,
}

/// A proportional point force on one node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Restrict to this body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// The node's reference position.
    pub at: [f64; 2],
    /// The force at load factor one.
    pub force: [f64; 2],
}

/// Proportional prescribed displacements.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrescribeSpec {
    /// Restrict to this body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Nodes with this reference x.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<f64>,
    /// Nodes with this reference y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// The node(s) at this reference point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// x displacement at load factor one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ux: Option<f64>,
    /// y displacement at load factor one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uy: Option<f64>,
}

/// A face: one side of a body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceSpec {
    /// The body.
    pub body: String,
    /// The side.
    pub side: Side,
}

/// A contact pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// A name for reports (default `contact[i]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The slave face (carries integration points and multipliers).
    pub slave: FaceSpec,
    /// The master face.
    pub master: FaceSpec,
    /// Gap formulation.
    #[serde(
        default = "default_formulation",
        deserialize_with = "de_formulation",
        serialize_with = "ser_formulation"
    )]
    pub formulation: Formulation,
    /// Persistent or unilateral.
    #[serde(default)]
    pub mode: ContactMode,
    /// Gauss points per slave segment.
    #[serde(default = "default_gauss_points")]
    pub gauss_points: usize,
}

/// The load schedule and default method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadingSpec {
    /// Final load factor (from 0).
    pub load_factor_end: f64,
    /// Step counts for studies.
    pub steps: Vec<usize>,
    /// Step count of a single run (default: the first of `steps`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub default_steps: Option<usize>,
    /// Default method.
    #[serde(
        default = "default_method",
        deserialize_with = "de_method",
        serialize_with = "ser_method"
    )]
    pub method: Method,
}

/// Refinement factors for every body's `nx` and `ny`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineSpec {
    /// Factor on `nx`.
    #[serde(default = "one")]
    pub x: usize,
    /// Factor on `ny`.
    #[serde(default = "one")]
    pub y: usize,
}

impl Default for RefineSpec {
    fn default() -> Self {
        RefineSpec { x: 1, y: 1 }
    }
}

/// Newton settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewtonSpec {
    /// Relative residual tolerance.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Iterations per attempt.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// Cut-backs per scheduled step.
    #[serde(default = "default_max_cutbacks")]
    pub max_cutbacks: usize,
}

impl Default for NewtonSpec {
    fn default() -> Self {
        NewtonSpec {
            tolerance: default_tolerance(),
            max_iterations: default_max_iterations(),
            max_cutbacks: default_max_cutbacks(),
        }
    }
}

fn one() -> usize {
    1
}
fn default_tolerance() -> f64 {
    1e-10
}
fn default_max_iterations() -> usize {
    30
}
fn default_max_cutbacks() -> usize {
    8
}
fn default_gauss_points() -> usize {
    2
}
fn default_formulation() -> Formulation {
    Formulation::SlaveNormal
}
fn default_method() -> Method {
    Method::Complete
}

fn de_formulation<'de, D: Deserializer<'de>>(d: D) -> Result<Formulation, D::Error> {
    let s = String::deserialize(d)?;
    s.parse().map_err(serde::de::Error::custom)
}

fn ser_formulation<S: Serializer>(f: &Formulation, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(f.name())
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
