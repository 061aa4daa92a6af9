//! Scene files (TOML).
//!
//! A scene describes bodies made of structured rectangular blocks of Q4
//! elements, their materials, supports, proportional loads, prescribed
//! displacements, contact pairs and the load schedule. Unknown keys are
//! errors. The paper scene, `scenes/stacked-cantilever.toml`, reads:
//!
//! ```toml
//! name = "stacked-cantilever"
//!
//! [material]                  # default for bodies without their own
//! young = 1000.0
//! poisson = 0.3
//! model = "plane-stress"      # or "plane-strain"; default plane-stress
//!
//! [[body]]                    # bodies share no nodes
//! name = "master"
//! origin = [0.0, 0.0]         # lower-left corner
//! size = [7.0, 0.5]           # width, height
//! nx = 7                      # elements along x
//! ny = 1                      # elements along y
//! # material = { young = .., poisson = .. }   (optional, per body)
//!
//! [[body]]
//! name = "slave"
//! origin = [0.0, 0.5]
//! size = [7.0, 0.5]
//! nx = 7
//! ny = 1
//!
//! [[fix]]                     # supports (zero displacement)
//! x = 0.0                     # nodes with reference x = 0 (optional `y`,
//!                             # or `at = [x, y]`; optional `body`)
//! dofs = "xy"                 # "x", "y" or "xy" (default)
//!
//! [[load]]                    # point force  load_factor * force
//! body = "slave"              # optional unless the point is ambiguous
//! at = [7.0, 1.0]             # exactly one node must sit there
//! force = [0.0, -0.08]
//!
//! [[contact]]
//! name = "interface"          # optional
//! slave = { body = "slave", side = "bottom" }    # side: bottom|right|top|left
//! master = { body = "master", side = "top" }
//! formulation = "slave-normal"   # or "closest-point" (default slave-normal)
//! mode = "persistent"            # or "unilateral" (default persistent)
//! gauss_points = 2               # per slave segment, 1..=8 (default 2)
//!
//! [loading]
//! load_factor_end = 10.0
//! steps = [4, 6, 8, 10, 12, 14, 16, 18, 20]   # step counts of the study
//! default_steps = 4           # for a single run (default: first of `steps`)
//! method = "complete"         # or 1..6 (an approximation type)
//! ```
//!
//! Optional sections:
//!
//! ```toml
//! [[prescribe]]               # prescribed displacement  load_factor * (ux, uy)
//! body = "block"              # selection as in [[fix]]: x, y or at
//! y = 2.0
//! uy = -0.1                   # ux and/or uy
//!
//! [refine]                    # multiply every body's nx and ny
//! x = 4                       # default 1
//! y = 2                       # default 1
//!
//! [newton]
//! tolerance = 1e-10           # |r| <= tolerance * max(1, |f_ext|)
//! max_iterations = 30         # per attempt
//! max_cutbacks = 8            # bisections per scheduled step
//! ```
//!
//! Block sides are ordered counter-clockwise around their body (see
//! [`crate::mesh`]). Coordinates select nodes within `1e-9` times the size
//! of the mesh. Errors name the file, the field (e.g. `body[1].nx`) and what
//! is wrong.

use std::path::Path;

use contact_kernels::Formulation;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::Method;
use crate::material::Material;
use crate::mesh::{Block, Mesh, Side};
use crate::model::{ContactMode, ContactPair, Model, PointLoad, Prescribed};

/// Why a scene could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{origin}: cannot read the scene: {message}")]
    Io {
        /// The file.
        origin: String,
        /// The operating system's message.
        message: String,
    },
    /// TOML syntax error, unknown or missing key, or a value of the wrong
    /// type.
    #[error("{origin}:{line}:{column}: {field}: {message}")]
    Syntax {
        /// The file (or another name of the text's origin).
        origin: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The dotted path of the field (e.g. `body[1].nx`), as far as it
        /// can be located.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A value that parses but makes no sense (e.g. `nx = 0`, a load point
    /// with no node).
    #[error("{origin}: {field}: {message}")]
    Invalid {
        /// The file.
        origin: String,
        /// The dotted path of the field.
        field: String,
        /// What is wrong.
        message: String,
    },
}

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
    fn components(self) -> &'static [usize] {
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

impl Scene {
    /// Parses and validates a scene; `origin` names the text in error
    /// messages (usually the file name).
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let mut scene: Scene = toml::from_str(text).map_err(|e| {
            let (line, column, field) = match e.span() {
                Some(span) => locate(text, span.start),
                None => (0, 0, String::from("(document)")),
            };
            SceneError::Syntax {
                origin: origin.to_owned(),
                line,
                column,
                field,
                message: e.message().trim().to_owned(),
            }
        })?;
        scene.origin = origin.to_owned();
        scene.build_model()?;
        Ok(scene)
    }

    /// Reads a scene file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let origin = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::Io {
            origin: origin.clone(),
            message: e.to_string(),
        })?;
        Scene::from_toml_str(&text, &origin)
    }

    /// The scene as TOML text (the `origin` is not written).
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).unwrap_or_else(|e| format!("# cannot serialise: {e}"))
    }

    /// A copy with every body's `nx` and `ny` multiplied (on top of the
    /// scene's own `[refine]`).
    pub fn refined(&self, x: usize, y: usize) -> Scene {
        let mut s = self.clone();
        s.refine.x *= x;
        s.refine.y *= y;
        s
    }

    /// The step count of a single run.
    pub fn default_steps(&self) -> usize {
        self.loading
            .default_steps
            .or(self.loading.steps.first().copied())
            .unwrap_or(1)
    }

    fn invalid(&self, field: impl Into<String>, message: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            origin: self.origin.clone(),
            field: field.into(),
            message: message.into(),
        }
    }

    fn body_index(
        &self,
        mesh: &Mesh,
        field: String,
        body: &Option<String>,
    ) -> Result<Option<usize>, SceneError> {
        match body {
            None => Ok(None),
            Some(name) => mesh.body_index(name).map(Some).ok_or_else(|| {
                let names: Vec<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
                self.invalid(
                    field,
                    format!("no body named `{name}` (bodies: {})", names.join(", ")),
                )
            }),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn select(
        &self,
        mesh: &Mesh,
        field: &str,
        body: &Option<String>,
        x: Option<f64>,
        y: Option<f64>,
        at: Option<[f64; 2]>,
    ) -> Result<Vec<usize>, SceneError> {
        let b = self.body_index(mesh, format!("{field}.body"), body)?;
        let (x, y) = match (at, x, y) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                return Err(self.invalid(field, "give either `at` or `x`/`y`, not both"));
            }
            (Some(p), None, None) => (Some(p[0]), Some(p[1])),
            (None, None, None) => {
                return Err(self.invalid(field, "select nodes with `x`, `y` or `at`"));
            }
            (None, x, y) => (x, y),
        };
        let nodes = mesh.select_nodes(b, x, y);
        if nodes.is_empty() {
            return Err(self.invalid(
                field,
                format!("no node at x = {x:?}, y = {y:?}{}", in_body(body)),
            ));
        }
        Ok(nodes)
    }

    /// Builds the finite-element model.
    pub fn build_model(&self) -> Result<Model, SceneError> {
        if self.refine.x == 0 || self.refine.y == 0 {
            return Err(self.invalid("refine", "factors must be at least 1"));
        }
        let mut mesh = Mesh::new();
        for (i, b) in self.bodies.iter().enumerate() {
            let f = format!("body[{i}]");
            if self.bodies[..i].iter().any(|o| o.name == b.name) {
                return Err(self.invalid(
                    format!("{f}.name"),
                    format!("duplicate body name `{}`", b.name),
                ));
            }
            let material = b.material.or(self.material).ok_or_else(|| {
                self.invalid(
                    format!("{f}.material"),
                    "no material (and no default [material])",
                )
            })?;
            material.check().map_err(|m| {
                let field = if b.material.is_some() {
                    format!("{f}.material")
                } else {
                    "material".into()
                };
                self.invalid(field, m)
            })?;
            for (k, v) in [("nx", b.nx), ("ny", b.ny)] {
                if v == 0 {
                    return Err(self.invalid(format!("{f}.{k}"), "must be at least 1"));
                }
            }
            if !(b.size[0] > 0.0 && b.size[1] > 0.0 && b.size.iter().all(|v| v.is_finite())) {
                return Err(self.invalid(
                    format!("{f}.size"),
                    "width and height must be positive and finite",
                ));
            }
            if !b.origin.iter().all(|v| v.is_finite()) {
                return Err(self.invalid(format!("{f}.origin"), "must be finite"));
            }
            let block = Block {
                origin: b.origin,
                size: b.size,
                nx: b.nx * self.refine.x,
                ny: b.ny * self.refine.y,
            };
            mesh.add_block(&b.name, material, block)
                .map_err(|e| self.invalid(f.clone(), e.to_string()))?;
        }
        if mesh.bodies.is_empty() {
            return Err(self.invalid("body", "at least one [[body]] is needed"));
        }
        let mut prescribed: Vec<Prescribed> = Vec::new();
        let mut add_prescribed = |field: &str, dof: usize, value: f64| -> Result<(), SceneError> {
            match prescribed.iter().find(|p| p.dof == dof) {
                Some(p) if p.value != value => Err(self.invalid(
                    field,
                    format!(
                        "node {} component {} is already prescribed to {}",
                        dof / 2,
                        dof % 2,
                        p.value
                    ),
                )),
                Some(_) => Ok(()),
                None => {
                    prescribed.push(Prescribed { dof, value });
                    Ok(())
                }
            }
        };
        for (i, fx) in self.fixes.iter().enumerate() {
            let f = format!("fix[{i}]");
            for n in self.select(&mesh, &f, &fx.body, fx.x, fx.y, fx.at)? {
                for &c in fx.dofs.components() {
                    add_prescribed(&f, 2 * n + c, 0.0)?;
                }
            }
        }
        for (i, p) in self.prescribes.iter().enumerate() {
            let f = format!("prescribe[{i}]");
            if p.ux.is_none() && p.uy.is_none() {
                return Err(self.invalid(&f, "give `ux` and/or `uy`"));
            }
            for (c, v) in [(0, p.ux), (1, p.uy)] {
                if v.is_some_and(|v| !v.is_finite()) {
                    return Err(self.invalid(format!("{f}.{}", ["ux", "uy"][c]), "must be finite"));
                }
            }
            for n in self.select(&mesh, &f, &p.body, p.x, p.y, p.at)? {
                for (c, v) in [(0, p.ux), (1, p.uy)] {
                    if let Some(v) = v {
                        add_prescribed(&f, 2 * n + c, v)?;
                    }
                }
            }
        }
        let mut loads = Vec::new();
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}]");
            if !l.force.iter().all(|v| v.is_finite()) {
                return Err(self.invalid(format!("{f}.force"), "must be finite"));
            }
            let nodes = self.select(&mesh, &f, &l.body, None, None, Some(l.at))?;
            if nodes.len() > 1 {
                return Err(self.invalid(
                    format!("{f}.at"),
                    format!(
                        "{} nodes sit at {:?} (bodies share no nodes); name the `body`",
                        nodes.len(),
                        l.at
                    ),
                ));
            }
            for c in 0..2 {
                loads.push(PointLoad {
                    dof: 2 * nodes[0] + c,
                    value: l.force[c],
                });
            }
        }
        let mut contacts = Vec::new();
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            let face = |which: &str, spec: &FaceSpec| -> Result<Vec<[usize; 2]>, SceneError> {
                let b = self
                    .body_index(&mesh, format!("{f}.{which}.body"), &Some(spec.body.clone()))?
                    .ok_or_else(|| self.invalid(format!("{f}.{which}.body"), "missing"))?;
                mesh.block_side(b, spec.side)
                    .ok_or_else(|| self.invalid(format!("{f}.{which}"), "not a block body"))
            };
            let slave = face("slave", &c.slave)?;
            let master = face("master", &c.master)?;
            if c.slave.body == c.master.body {
                return Err(self.invalid(&f, "slave and master must be different bodies"));
            }
            if !(1..=8).contains(&c.gauss_points) {
                return Err(self.invalid(format!("{f}.gauss_points"), "must be in 1..=8"));
            }
            contacts.push(ContactPair {
                name: c.name.clone().unwrap_or_else(|| f.clone()),
                slave,
                master,
                formulation: c.formulation,
                mode: c.mode,
                gauss_points: c.gauss_points,
            });
        }
        let l = &self.loading;
        if !l.load_factor_end.is_finite() {
            return Err(self.invalid("loading.load_factor_end", "must be finite"));
        }
        if l.steps.is_empty() || l.steps.contains(&0) {
            return Err(self.invalid(
                "loading.steps",
                "needs at least one step count, each at least 1",
            ));
        }
        if l.default_steps == Some(0) {
            return Err(self.invalid("loading.default_steps", "must be at least 1"));
        }
        let n = &self.newton;
        if !(n.tolerance.is_finite() && n.tolerance > 0.0) {
            return Err(self.invalid("newton.tolerance", "must be positive"));
        }
        if n.max_iterations == 0 {
            return Err(self.invalid("newton.max_iterations", "must be at least 1"));
        }
        let model = Model {
            mesh,
            prescribed,
            loads,
            contacts,
            load_factor_end: l.load_factor_end,
        };
        model
            .check()
            .map_err(|e| self.invalid("(model)", e.to_string()))?;
        Ok(model)
    }
}

fn in_body(body: &Option<String>) -> String {
    body.as_ref()
        .map(|b| format!(" in body `{b}`"))
        .unwrap_or_default()
}

/// Line, column and dotted field path of a byte offset in a TOML text:
/// the last table header at or before it (`[[body]]` counted into
/// `body[i]`) and the keys on its line before the offset (inline tables
/// nest).
fn locate(text: &str, offset: usize) -> (usize, usize, String) {
    let offset = offset.min(text.len());
    let mut header = String::new();
    let mut counts: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    let mut line_no = 0;
    let mut line_start = 0;
    let mut current = "";
    for (i, line) in text.split_inclusive('\n').enumerate() {
        line_no = i;
        current = line;
        let t = line.trim();
        if let Some(name) = t.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let k = counts.entry(name.clone()).or_insert(0);
            header = format!("{name}[{k}]");
            *k += 1;
        } else if let Some(name) = t.strip_prefix('[').and_then(|r| r.split(']').next()) {
            header = name.trim().to_owned();
        }
        if offset < line_start + line.len() {
            break;
        }
        line_start += line.len();
    }
    let line = current.trim_end_matches(['\n', '\r']);
    let mut col = offset.saturating_sub(line_start).min(line.len());
    while !line.is_char_boundary(col) {
        col -= 1;
    }
    let mut path: Vec<String> = Vec::new();
    if !header.is_empty() {
        path.push(header);
    }
    if !line.trim_start().starts_with('[') {
        // keys before the offset on this line
        let mut stack: Vec<String> = Vec::new();
        let mut pending: Option<String> = None;
        let mut word = String::new();
        let mut in_str: Option<char> = None;
        for ch in line[..col].chars() {
            if let Some(q) = in_str {
                if ch == q {
                    in_str = None;
                }
                continue;
            }
            match ch {
                '"' | '\'' => in_str = Some(ch),
                '=' => {
                    pending = Some(word.trim().to_owned());
                    word.clear();
                }
                '{' => {
                    if let Some(p) = pending.take() {
                        stack.push(p);
                    }
                    word.clear();
                }
                '}' => {
                    stack.pop();
                    word.clear();
                }
                ',' => {
                    pending = None;
                    word.clear();
                }
                '#' => break,
                c => word.push(c),
            }
        }
        path.extend(stack);
        if let Some(p) = pending.filter(|p| !p.is_empty()) {
            path.push(p);
        }
    }
    let field = if path.is_empty() {
        "(document)".to_owned()
    } else {
        path.join(".")
    };
    (line_no + 1, line[..col].chars().count() + 1, field)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> SceneError {
        Scene::from_toml_str(text, "bad.toml").unwrap_err()
    }

    const GOOD: &str = r#"
[material]
young = 100.0
poisson = 0.25

[[body]]
name = "a"
origin = [0.0, 0.0]
size = [2.0, 1.0]
nx = 2
ny = 1

[[fix]]
x = 0.0

[[load]]
at = [2.0, 1.0]
force = [0.0, -1.0]

[loading]
load_factor_end = 1.0
steps = [2]
"#;

    /// FNV-1a over the model's `Debug` text: node coordinates to the bit
    /// (shortest round-trip), node numbering, element order, body ranges,
    /// supports, loads and contact segments in order.
    fn fingerprint(model: &Model) -> u64 {
        format!("{model:?}")
            .bytes()
            .fold(0xcbf2_9ce4_8422_2325, |h, b| {
                (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
            })
    }

    #[test]
    fn paper_scene_builds_the_same_model() {
        let scene =
            Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")
                .unwrap();
        let m = scene.build_model().unwrap();
        assert_eq!(m.mesh.node_count(), 32);
        assert_eq!(m.mesh.elements.len(), 14);
        assert_eq!(m.mesh.elements[0], [0, 1, 9, 8]);
        assert_eq!(m.mesh.elements[6], [6, 7, 15, 14]);
        assert_eq!(m.mesh.elements[7], [16, 17, 25, 24]);
        assert_eq!(m.mesh.elements[13], [22, 23, 31, 30]);
        assert_eq!(m.mesh.nodes_ref[31], [7.0, 1.0]);
        let fixed: Vec<usize> = m.prescribed.iter().map(|p| p.dof).collect();
        assert_eq!(fixed, [0, 1, 16, 17, 32, 33, 48, 49]);
        assert!(m.prescribed.iter().all(|p| p.value == 0.0));
        let loads: Vec<(usize, f64)> = m.loads.iter().map(|l| (l.dof, l.value)).collect();
        assert_eq!(loads, [(62, 0.0), (63, -0.08)]);
        assert_eq!(m.contacts.len(), 1);
        let c = &m.contacts[0];
        assert_eq!(c.name, "interface");
        let slave: Vec<[usize; 2]> = (16..23).map(|n| [n, n + 1]).collect();
        let master: Vec<[usize; 2]> = (8..15).rev().map(|n| [n + 1, n]).collect();
        assert_eq!(c.slave, slave);
        assert_eq!(c.master, master);
        assert_eq!(
            (c.formulation, c.mode, c.gauss_points),
            (
                Formulation::SlaveNormal,
                crate::model::ContactMode::Persistent,
                2
            )
        );
        assert_eq!(m.load_factor_end, 10.0);
        // the whole model, bit for bit, for the scene and refined variants
        let prints: Vec<u64> = [(1, 1), (2, 1), (4, 2), (3, 3), (16, 1)]
            .map(|(x, y)| fingerprint(&scene.refined(x, y).build_model().unwrap()))
            .to_vec();
        assert_eq!(
            prints,
            [
                8689335778407627383,
                2183681067980692126,
                17199187239843751079,
                3864826904333325836,
                18108556103099798236
            ]
        );
    }

    #[test]
    fn minimal_scene_parses_with_defaults() {
        let s = Scene::from_toml_str(GOOD, "good.toml").unwrap();
        assert_eq!(s.loading.method, Method::Complete);
        assert_eq!(s.default_steps(), 2);
        assert_eq!(s.newton.max_iterations, 30);
        let m = s.build_model().unwrap();
        assert_eq!(m.prescribed.len(), 4);
        assert_eq!(m.loads.len(), 2);
        let again = Scene::from_toml_str(&s.to_toml_string(), "round-trip").unwrap();
        assert_eq!(again.bodies, s.bodies);
    }

    #[test]
    fn wrong_type_names_the_field_and_the_file() {
        let text = GOOD.replace("nx = 2", "nx = \"two\"");
        let e = err(&text);
        let msg = e.to_string();
        assert!(msg.starts_with("bad.toml:"), "{msg}");
        assert!(msg.contains("body[0].nx"), "{msg}");
        assert!(matches!(e, SceneError::Syntax { line: 10, .. }), "{e:?}");
    }

    #[test]
    fn unknown_and_missing_fields_are_named() {
        let msg = err(&GOOD.replace("ny = 1", "ny = 1\nnxx = 3")).to_string();
        assert!(msg.contains("nxx") && msg.contains("body[0]"), "{msg}");
        let msg = err(&GOOD.replace("ny = 1", "")).to_string();
        assert!(
            msg.contains("missing field `ny`") && msg.contains("body[0]"),
            "{msg}"
        );
    }

    #[test]
    fn invalid_values_name_the_field() {
        let msg = err(&GOOD.replace("nx = 2", "nx = 0")).to_string();
        assert_eq!(msg, "bad.toml: body[0].nx: must be at least 1");
        let msg = err(&GOOD.replace("at = [2.0, 1.0]", "at = [2.5, 1.0]")).to_string();
        assert!(msg.contains("load[0]") && msg.contains("no node"), "{msg}");
        let msg = err(&GOOD.replace("poisson = 0.25", "poisson = 1.5")).to_string();
        assert!(msg.contains("material") && msg.contains("Poisson"), "{msg}");
        let text = format!(
            "{GOOD}\n[[contact]]\nslave = {{ body = \"a\", side = \"bottm\" }}\nmaster = {{ body = \"a\", side = \"top\" }}\n"
        );
        let msg = err(&text).to_string();
        assert!(
            msg.contains("contact[0].slave.side") && msg.contains("bottm"),
            "{msg}"
        );
        let msg = err(&GOOD.replace("steps = [2]", "steps = [2]\nmethod = \"seven\"")).to_string();
        assert!(msg.contains("loading.method"), "{msg}");
        // non-ASCII text before the error on the same line
        let msg = err(&GOOD.replace("nx = 2", "name2 = \"Müller\"")).to_string();
        assert!(msg.contains("body[0]") && msg.contains("name2"), "{msg}");
        let msg =
            err(&GOOD.replace("[loading]", "[loading]\nmethod = { x = \"ü\", y = 3 }")).to_string();
        assert!(msg.contains("loading.method"), "{msg}");
    }
}
