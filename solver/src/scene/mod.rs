//! Scene files (TOML).
//!
//! A scene describes bodies, 2D or 3D (structured blocks of Q4 or
//! hexahedral elements, or the physical surfaces or volumes of a Gmsh mesh
//! file: Q4 and triangles, hexahedra and tetrahedra), their
//! materials, supports, loads and tractions, prescribed displacements (each
//! proportional to the load factor or following a load curve), contact
//! pairs and the load schedule. Unknown keys are errors. The reference of
//! the format, every key with its type, default, unit and constraints, is
//! `docs/scenes.md` (its examples are solved, and its key tables checked
//! against this schema, by `solver/tests/scene_docs.rs`). The paper scene,
//! `scenes/stacked-cantilever.toml`, reads:
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
//! gauss_points = 2               # per slave segment, 1..=8 (default 2;
//!                                # in 3D per face kind, see docs/scenes.md)
//! integration = "gauss"          # or "segmented": split at the master nodes'
//!                                # projections, gauss_points per piece
//! multipliers = "standard"       # or, in 3D, "dual" (biorthogonal basis)
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
//! name = "top"                # optional: its name in reactions.csv
//! amplitude = [[0.0, 0.0], [0.2, 1.0], [1.0, 1.0]]   # optional load curve
//!                             # [load_factor, a]: a(load_factor) * (ux, uy),
//!                             # piecewise linear, end values held outside
//!                             # (also on [[load]] and [[traction]])
//!
//! [refine]                    # multiply every body's nx and ny
//! x = 4                       # default 1
//! y = 2                       # default 1
//!
//! [newton]
//! tolerance = 1e-10           # |r| <= tolerance * max(1, |f_ext|)
//! max_iterations = 30         # per attempt
//! max_cutbacks = 8            # bisections per scheduled step
//! linear = "lu"               # linear solver: "lu" (default), "ldlt", "petsc" (feature)
//! petsc_options = ""          # PETSc options of "petsc" (docs/petsc.md)
//! repair = true               # Types 1-6: repeat a step whose points end on
//!                             # other master segments (default true; the
//!                             # paper scene sets false, the paper's scheme)
//! taylor_tolerance = 1e-4     # Types 1-6: re-take the expansion of a point
//!                             # whose Taylor remainder / element size
//!                             # exceeds this at a step end, then halve
//!                             # (default none)
//! expand_at = "predictor"     # Types 1-6: expansions at the step's
//!                             # predictor (default) or "start" (the paper's)
//! ```
//!
//! Bodies from a mesh file (`scenes/hertz.toml`, the Hertz quarter model):
//!
//! ```toml
//! [mesh]
//! file = "hertz.msh"          # Gmsh MSH 4.1, ASCII or binary; relative to
//!                             # this file's directory
//!
//! [[body]]                    # no origin/size/nx/ny: a physical surface
//! name = "cylinder"           # of the file, by name
//! # group = "surface_name"    # (optional: a surface of another name)
//!
//! [[body]]                    # blocks and mesh bodies may be mixed;
//! name = "block"              # bodies share no nodes (an error otherwise)
//!
//! [[fix]]                     # [[fix]], [[prescribe]]: `group` (a physical
//! group = "symmetry"          # curve or point) instead of x / y / at
//! dofs = "x"
//!
//! [[load]]                    # a point load: `group` (one node) instead of at
//! group = "tip"
//! force = [0.0, -1.0]
//!
//! [[traction]]                # a dead load per unit reference length on a
//! group = "load_edge"         # physical curve, times the load factor:
//! force_per_length = [0.0, -0.4315]   # t L / 2 to both nodes of a segment
//!                             # (or on a block's side: body = .., side = ..)
//!
//! [[contact]]                 # faces: a physical curve on one body's boundary
//! slave = { group = "cylinder_surface" }      # (optional `body`, checked)
//! master = { group = "block_top" }
//! mode = "unilateral"
//! ```
//!
//! A contact face from a curve is oriented by the element that owns each of
//! its segments (counter-clockwise around the body, outward normal), however
//! the curve was drawn. A mesh body takes the surface's 3-node triangles and
//! 4-node quadrangles, mixed freely, as drawn (an inverted element is an
//! error naming it); `[refine]` applies to blocks only.
//! Group errors name the file and the group: an unknown name lists those
//! that exist, a group of the wrong dimension, a face that is not on a
//! body's boundary, a node of a group in no body.
//!
//! Block sides are ordered counter-clockwise around their body (see
//! [`crate::mesh::block`]). Coordinates select nodes within `1e-9` times the size
//! of the mesh. Errors name the file, the field (e.g. `body[1].nx`) and what
//! is wrong.
//!
//! The module is laid out by concept:
//!
//! * `spec/`: the serde types above (the schema) and their defaults;
//! * `error.rs`: [`SceneError`], and parsing with the position and field
//!   path of a TOML error;
//! * `validate.rs`: the checks of values that need no mesh (counts, finite
//!   numbers, materials, names), each naming its field;
//! * `dimension.rs`: the scene's dimension and the keys only one has;
//! * `source/`: the mesh sources (`Sources<D>`, one for both dimensions),
//!   which make the bodies and resolve the facets that depend on how a
//!   body was made: `source/blocks.rs`, the structured blocks of
//!   `[[body]]`, and `source/gmsh.rs`, the physical surfaces (2D) or
//!   volumes (3D) of the `[mesh]` file and its groups by name; what
//!   differs between the dimensions is `SourceDim<D>`, in `planar.rs` and
//!   `solid.rs`;
//! * `select.rs`: node selection by reference coordinates or group, and
//!   the facets of a side or group, in either dimension;
//! * `build.rs`: [`Scene::build_model`], from a scene to a
//!   [`Model<D>`](crate::model::Model), one code path for both
//!   dimensions ([`SceneDim`]); what it and the sources take from each is
//!   in `planar.rs` (2D: blocks and surfaces, tractions on segments, the
//!   pairs' reference geometry) and `solid.rs` (3D: blocks and volumes,
//!   tractions on faces, the pairs' readings and rules, their layout).

use std::path::Path;

use crate::model::Dim;
use crate::options::{DEFAULT_REGULARIZATION, SolveOptions};

mod build;
mod dimension;
mod error;
mod initial_contact;
mod memory;
mod planar;
mod select;
mod solid;
mod source;
mod spec;
mod supports;
pub mod traction;

pub(crate) use source::MAX_BLOCK_ELEMENTS;
mod validate;

#[cfg(test)]
mod proptests;

#[cfg(test)]
mod bad_input_tests;

#[cfg(test)]
mod tests3d;

pub use build::SceneDim;
pub use dimension::Dimension;
pub use error::SceneError;
pub use initial_contact::{FACING_TOL, OPEN_GAP_FRACTION, PENETRATION_FRACTION};
pub use memory::{check_scene, check_scene_within, scene_equations};
pub use spec::{
    BodySpec, ContactSpec, Coords, Dofs, FaceSpec, FixSpec, LoadSpec, LoadingSpec, MaterialSpec,
    MeshSpec, NewtonSpec, PrescribeSpec, RefineSpec, Scene, TractionSpec,
};

impl Scene {
    /// Parses and validates a scene; `origin` names the text in error
    /// messages (usually the file name). Validating builds the scene's
    /// model once (2D or 3D); a scene that asks for what the solver does
    /// not have yet ([`SceneError::Unsupported`]) would be read, everything
    /// else checked, and fail when its model is built.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let mut scene = error::parse(text, origin)?;
        scene.origin = origin.to_owned();
        match scene.validate() {
            Ok(()) | Err(SceneError::Unsupported { .. }) => Ok(scene),
            Err(e) => Err(e),
        }
    }

    /// Builds the model of the scene's dimension, to check the scene.
    fn validate(&self) -> Result<(), SceneError> {
        let (file, dim) = self.prepare()?;
        match dim {
            Dimension::Two => <Dim<2> as SceneDim<2>>::build(self, file).map(drop),
            Dimension::Three => <Dim<3> as SceneDim<3>>::build(self, file).map(drop),
        }
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
}

impl SolveOptions {
    /// The scene's defaults: its method, default step count and Newton
    /// settings (including `[newton] linear`).
    pub fn from_scene(scene: &Scene) -> SolveOptions {
        SolveOptions {
            method: scene.loading.method,
            steps: scene.default_steps(),
            formulation: None,
            record_steps: false,
            max_iterations: scene.newton.max_iterations,
            max_cutbacks: scene.newton.max_cutbacks,
            tolerance: scene.newton.tolerance,
            regularization: DEFAULT_REGULARIZATION,
            linear: scene.newton.linear,
            petsc_options: scene.newton.petsc_options.clone(),
            repair: scene.newton.repair,
            taylor_tolerance: scene.newton.taylor_tolerance,
            expand_at: scene.newton.expand_at,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Method;
    use crate::ids::{AmplitudeId, DofId, NodeId};
    use crate::model::Model;
    use contact_kernels::Formulation;

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
    /// supports, loads and contact segments in order. The typed ids are
    /// printed as their plain numbers (`NodeId(3)` as `3`), as they were
    /// before the ids had types, so the prints recorded then still hold.
    fn fingerprint(model: &Model) -> u64 {
        untyped(&print(model))
            .bytes()
            .fold(0xcbf2_9ce4_8422_2325, |h, b| {
                (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
            })
    }

    /// An element's reference geometry as the fingerprints recorded it:
    /// `QuadGeometry { grads_ref: .., weight_ref: .. }` (`TriGeometry`,
    /// `HexGeometry`, `TetGeometry`), a one-point element's with the
    /// point's values alone.
    fn geometry(g: &crate::element::ElementGeometry) -> String {
        use crate::element::ElementGeometry as G;
        fn fields<T: std::fmt::Debug, W: std::fmt::Debug>(name: &str, g: &[T], w: &[W]) -> String {
            match (g, w) {
                ([g], [w]) => format!("{name} {{ grads_ref: {g:?}, weight_ref: {w:?} }}"),
                _ => format!("{name} {{ grads_ref: {g:?}, weight_ref: {w:?} }}"),
            }
        }
        match g {
            G::Quad4(g) => fields("QuadGeometry", &g.grads_ref, &g.weight_ref),
            G::Tri3(g) => fields("TriGeometry", &g.grads_ref, &g.weight_ref),
            G::Hex8(g) => fields("HexGeometry", &g.grads_ref, &g.weight_ref),
            G::Tet4(g) => fields("TetGeometry", &g.grads_ref, &g.weight_ref),
        }
    }

    /// The model as the fingerprints recorded it: its fields but
    /// `supports` (report names only), `amplitudes` only when there are
    /// curves, a prescribed dof's or a load's `amplitude` only when it has
    /// one, a material's `kinematics` only when small, a body's
    /// `node_tags` only when it has them, a block's cells as `nx` and `ny`, each pair's `gauss_points` resolved (2 when absent) and its
    /// `integration` only when it is not Gauss.
    fn print(m: &Model) -> String {
        let pairs: Vec<String> = m
            .contacts
            .iter()
            .map(|c| {
                let mut integration = match c.integration {
                    crate::model::Integration::Gauss => String::new(),
                    i => format!(", integration: {i:?}"),
                };
                if c.friction != 0.0 {
                    integration += &format!(", friction: {:?}", c.friction);
                }
                format!(
                    "ContactPair {{ name: {:?}, slave: {:?}, master: {:?}, formulation: {:?}, mode: {:?}, gauss_points: {}{integration} }}",
                    c.name,
                    c.slave,
                    c.master,
                    c.formulation,
                    c.mode,
                    c.gauss_points.unwrap_or(2)
                )
            })
            .collect();
        let amplitudes = if m.amplitudes.is_empty() {
            String::new()
        } else {
            format!(", amplitudes: {:?}", m.amplitudes)
        };
        // a prescribed dof or a load without its curve when it has none
        let item = |kind: &str, dof: DofId, value: f64, amplitude: Option<AmplitudeId>| {
            let curve = amplitude
                .map(|a| format!(", amplitude: {a:?}"))
                .unwrap_or_default();
            format!("{kind} {{ dof: {dof:?}, value: {value:?}{curve} }}")
        };
        let prescribed: Vec<String> = m
            .prescribed
            .iter()
            .map(|p| item("Prescribed", p.dof, p.value, p.amplitude))
            .collect();
        let loads: Vec<String> = m
            .loads
            .iter()
            .map(|l| item("PointLoad", l.dof, l.value, l.amplitude))
            .collect();
        // a material without its kinematics when finite, a body without
        // its node tags when it has none
        let material = |a: &crate::material::Material| {
            let kinematics = match a.kinematics {
                crate::material::Kinematics::Finite => String::new(),
                k => format!(", kinematics: {k:?}"),
            };
            format!(
                "Material {{ young: {:?}, poisson: {:?}, model: {:?}{kinematics} }}",
                a.young, a.poisson, a.model
            )
        };
        let bodies: Vec<String> = m
            .mesh
            .bodies
            .iter()
            .map(|b| {
                let tags = b
                    .node_tags
                    .as_ref()
                    .map(|t| format!(", node_tags: {t:?}"))
                    .unwrap_or_default();
                // a block with its counts by name, as the 2D block had them
                let block = match b.block {
                    Some(k) => format!(
                        "Some(Block {{ origin: {:?}, size: {:?}, nx: {}, ny: {} }})",
                        k.origin, k.size, k.cells[0], k.cells[1]
                    ),
                    None => "None".to_owned(),
                };
                format!(
                    "Body {{ name: {:?}, material: {}, nodes: {:?}, elements: {:?}, block: {block}{tags} }}",
                    b.name,
                    material(&b.material),
                    b.nodes,
                    b.elements,
                )
            })
            .collect();
        let elements: Vec<String> = m
            .mesh
            .elements
            .iter()
            .map(|e| format!("{:?}", e.nodes()))
            .collect();
        let geometry: Vec<String> = m
            .mesh
            .element_ids()
            .map(|e| geometry(&m.mesh.geometry(e).unwrap()))
            .collect();
        let mesh = format!(
            "Mesh {{ nodes_ref: {:?}, elements: [{}], element_body: {:?}, bodies: [{}], geometry: [{}] }}",
            m.mesh.nodes_ref,
            elements.join(", "),
            m.mesh.element_body,
            bodies.join(", "),
            geometry.join(", ")
        );
        format!(
            "Model {{ mesh: {mesh}, prescribed: [{}], loads: [{}], contacts: [{}], load_factor_end: {:?}{amplitudes} }}",
            prescribed.join(", "),
            loads.join(", "),
            pairs.join(", "),
            m.load_factor_end
        )
    }

    /// `text` with every `NodeId(n)`, `ElementId(n)` and `DofId(n)` replaced
    /// by `n`.
    fn untyped(text: &str) -> String {
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        'scan: while !rest.is_empty() {
            for name in ["NodeId(", "ElementId(", "DofId("] {
                if let Some(tail) = rest.strip_prefix(name)
                    && let Some(close) = tail.find(')')
                    && close > 0
                    && tail[..close].bytes().all(|b| b.is_ascii_digit())
                {
                    out.push_str(&tail[..close]);
                    rest = &tail[close + 1..];
                    continue 'scan;
                }
            }
            let c = rest.chars().next().unwrap();
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
        out
    }

    #[test]
    fn untyped_prints_ids_as_numbers() {
        let text = format!("{:?}", ([NodeId::new(3), NodeId::new(40)], DofId::new(7)));
        assert_eq!(untyped(&text), "([3, 40], 7)");
    }

    #[test]
    fn paper_scene_builds_the_same_model() {
        let scene =
            Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")
                .unwrap();
        let m = scene.build_model().unwrap();
        assert_eq!(m.mesh.node_count(), 32);
        assert_eq!(m.mesh.elements.len(), 14);
        let element = |e: usize| m.mesh.elements[e].map_nodes(NodeId::index).to_vec();
        assert_eq!(element(0), [0, 1, 9, 8]);
        assert_eq!(element(6), [6, 7, 15, 14]);
        assert_eq!(element(7), [16, 17, 25, 24]);
        assert_eq!(element(13), [22, 23, 31, 30]);
        assert_eq!(m.mesh.nodes_ref[31], [7.0, 1.0]);
        let fixed: Vec<usize> = m.prescribed.iter().map(|p| p.dof.index()).collect();
        assert_eq!(fixed, [0, 1, 16, 17, 32, 33, 48, 49]);
        assert!(m.prescribed.iter().all(|p| p.value == 0.0));
        let loads: Vec<(usize, f64)> = m.loads.iter().map(|l| (l.dof.index(), l.value)).collect();
        assert_eq!(loads, [(62, 0.0), (63, -0.08)]);
        assert_eq!(m.contacts.len(), 1);
        let c = &m.contacts[0];
        assert_eq!(c.name, "interface");
        let slave: Vec<[usize; 2]> = (16..23).map(|n| [n, n + 1]).collect();
        let master: Vec<[usize; 2]> = (8..15).rev().map(|n| [n + 1, n]).collect();
        let raw = |segs: &[[NodeId; 2]]| -> Vec<[usize; 2]> {
            segs.iter().map(|s| s.map(NodeId::index)).collect()
        };
        assert_eq!(raw(&c.slave), slave);
        assert_eq!(raw(&c.master), master);
        assert_eq!(
            (c.formulation, c.mode, c.gauss_points),
            (
                Formulation::SlaveNormal,
                crate::model::ContactMode::Persistent,
                Some(2)
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

    /// `[newton] linear` selects the linear solver (default LU, not
    /// written back when default); an unknown name is an error.
    #[test]
    fn newton_linear_key_selects_the_solver() {
        use crate::linear::LinearSolverKind;
        let s = Scene::from_toml_str(GOOD, "good.toml").unwrap();
        assert_eq!(s.newton.linear, LinearSolverKind::Lu);
        assert!(!s.to_toml_string().contains("linear"));
        let text = format!("{GOOD}\n[newton]\nlinear = \"ldlt\"\n");
        let s = Scene::from_toml_str(&text, "ldlt.toml").unwrap();
        assert_eq!(s.newton.linear, LinearSolverKind::Ldlt);
        assert_eq!(
            crate::SolveOptions::from_scene(&s).linear,
            LinearSolverKind::Ldlt
        );
        let again = Scene::from_toml_str(&s.to_toml_string(), "round-trip").unwrap();
        assert_eq!(again.newton.linear, LinearSolverKind::Ldlt);
        let bad = format!("{GOOD}\n[newton]\nlinear = \"qr\"\n");
        assert!(Scene::from_toml_str(&bad, "bad.toml").is_err());
    }

    #[test]
    fn minimal_scene_parses_with_defaults() {
        let s = Scene::from_toml_str(GOOD, "good.toml").unwrap();
        assert_eq!(s.loading.method, Method::Complete);
        assert_eq!(s.default_steps(), 2);
        assert_eq!(s.newton.max_iterations, 30);
        let m = s.build_model::<2>().unwrap();
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

    /// A 2D scene's coordinates and vectors take exactly two numbers: a
    /// count other than two or three is a syntax error, three an error
    /// naming the key (they belong to 3D scenes).
    #[test]
    fn coordinate_pairs_take_exactly_two_numbers() {
        for (from, to, field) in [
            ("size = [2.0, 1.0]", "size = [2.0]", "body[0].size"),
            (
                "force = [0.0, -1.0]",
                "force = [0.0, -1.0, 3.0, 4.0]",
                "load[0].force",
            ),
        ] {
            let e = err(&GOOD.replace(from, to));
            assert!(
                matches!(&e, SceneError::Syntax { field: f, message, .. }
                    if f == field && message.starts_with("needs two numbers [x, y] (2D) or three [x, y, z] (3D), got ")),
                "{to}: {e:?}"
            );
        }
        for (from, to, field, says) in [
            (
                "origin = [0.0, 0.0]",
                "origin = [0.0, 0.0, 5.0]",
                "body[0].size",
                "has 2 numbers but `origin` has 3",
            ),
            (
                "at = [2.0, 1.0]",
                "at = [2.0, 1.0, 0.0]",
                "load[0].at",
                "needs two numbers [x, y] in a 2D scene, got 3 numbers",
            ),
            (
                "force = [0.0, -1.0]",
                "force = [0.0, -1.0, 3.0]",
                "load[0].force",
                "needs two numbers [x, y] in a 2D scene, got 3 numbers",
            ),
        ] {
            let e = err(&GOOD.replace(from, to));
            assert!(
                matches!(&e, SceneError::Invalid { field: f, message, .. }
                    if f == field && message.starts_with(says)),
                "{to}: {e:?}"
            );
        }
        // exactly two still parse
        Scene::from_toml_str(GOOD, "good.toml").unwrap();
    }

    /// The dual multiplier basis is built for 3D faces: a 2D pair asking
    /// for it is refused, naming the key.
    #[test]
    fn dual_multipliers_in_2d_are_refused() {
        let text = include_str!("../../../scenes/patch-test.toml");
        let dual = text.replace(
            "integration = \"segmented\"",
            "integration = \"segmented\"\nmultipliers = \"dual\"",
        );
        assert_ne!(dual, text);
        let e = err(&dual);
        assert!(
            matches!(&e, SceneError::Invalid { field, message, .. }
                if field == "contact[0].multipliers" && message.contains("3D faces only")),
            "{e:?}"
        );
        let standard = text.replace(
            "integration = \"segmented\"",
            "integration = \"segmented\"\nmultipliers = \"standard\"",
        );
        Scene::from_toml_str(&standard, "standard.toml").unwrap();
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
