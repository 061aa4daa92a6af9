//! The model builder of a 3D scene: from a [`Scene`] whose bodies are 3D
//! blocks or physical volumes of a 3D mesh file to a [`Model<3>`].
//!
//! The order of everything the solver sees, as in 2D (`build.rs`):
//!
//! * bodies in `[[body]]` order, each appended with fresh nodes;
//! * prescribed degrees of freedom in the order `[[fix]]` then
//!   `[[prescribe]]`, each item's nodes in increasing index, then its
//!   components x, y, z (`dofs`, default all three); a degree of freedom
//!   appears once (a second item may only repeat its value and, unless it
//!   is zero, its load curve);
//! * support groups, one per `[[fix]]` and `[[prescribe]]`, named as in
//!   2D;
//! * load curves, each distinct table once, in the order items first use
//!   them;
//! * point loads in `[[load]]` order, x, y, z; then the tractions in
//!   `[[traction]]` order: the faces of a block side in the side's order
//!   ([`crate::mesh::block3d`]), of a physical surface in file order; each
//!   face's nodes in its order, each node's components x, y, z, with the
//!   consistent nodal force of [`super::traction::nodal_forces`].
//!
//! Contact between 3D bodies is not supported yet: each `[[contact]]`'s
//! faces are resolved (a side or a physical surface, on two different
//! bodies), then the build fails with [`SceneError::Unsupported`] naming
//! the pair.

use super::dimension::Dimension;
use super::source::Solids;
use super::supports::{Curves, Prescriptions};
use super::traction::nodal_forces;
use super::{Dofs, Scene, SceneError};
use crate::ids::DofId;
use crate::mesh::Mesh;
use crate::mesh::gmsh::AnyMsh;
use crate::model::{Model, PointLoad, SupportGroup};

/// The dof of component `c` of `node` in 3D.
fn dof(node: crate::ids::NodeId, c: usize) -> DofId {
    DofId::in_dim::<3>(node, c)
}

impl Scene {
    /// Builds the finite-element model of a 3D scene (a 2D scene is an
    /// error naming its first body; a 3D scene with contact pairs is
    /// [`SceneError::Unsupported`]).
    pub fn build_model_3d(&self) -> Result<Model<3>, SceneError> {
        let (file, dim) = self.prepare()?;
        if dim == Dimension::Two {
            return Err(self.invalid(
                "body[0]",
                "is a 2D body: a 2D scene's model is built by `Scene::build_model`",
            ));
        }
        self.build_solid(file)
    }

    /// [`Scene::build_model_3d`] after [`Scene::prepare`] found the scene
    /// 3D.
    pub(super) fn build_solid(&self, file: Option<AnyMsh>) -> Result<Model<3>, SceneError> {
        let dim = Dimension::Three;
        let volume = match file {
            None => None,
            Some(AnyMsh::Volume(msh)) => Some(msh),
            Some(AnyMsh::Planar(_)) => {
                return Err(self.invalid(
                    "mesh.file",
                    "is a 2D mesh: a 2D scene's model is built by `Scene::build_model`",
                ));
            }
        };
        let mut sources = Solids::new(self, volume);
        let mut mesh = Mesh::<3>::new();
        for i in 0..self.bodies.len() {
            let material = self.check_body(i, dim)?;
            sources.add_body(&mut mesh, i, material)?;
        }
        if mesh.bodies.is_empty() {
            return Err(self.invalid("body", "at least one [[body]] is needed"));
        }
        let mut curves = Curves::default();
        let mut prescribed = Prescriptions::default();
        let mut supports = Vec::new();
        for (i, fx) in self.fixes.iter().enumerate() {
            let f = format!("fix[{i}]");
            let start = prescribed.list.len();
            let at = fx.at.and_then(|c| c.xyz());
            let xyz = [fx.x, fx.y, fx.z];
            for n in self.select_3d(&mesh, &sources, &f, &fx.body, &fx.group, xyz, at)? {
                for c in fx.dofs.unwrap_or(Dofs::XYZ).components() {
                    prescribed.add(self, &f, n, c, dof(n, c), 0.0, None)?;
                }
            }
            supports.push(SupportGroup {
                name: self.support_name(&fx.name, &fx.group, &f),
                prescribed: start..prescribed.list.len(),
            });
        }
        for (i, p) in self.prescribes.iter().enumerate() {
            let f = format!("prescribe[{i}]");
            self.check_prescribe(&f, p, dim)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &p.amplitude)?);
            let start = prescribed.list.len();
            let at = p.at.and_then(|c| c.xyz());
            let xyz = [p.x, p.y, p.z];
            for n in self.select_3d(&mesh, &sources, &f, &p.body, &p.group, xyz, at)? {
                for (c, v) in [(0, p.ux), (1, p.uy), (2, p.uz)] {
                    if let Some(v) = v {
                        prescribed.add(self, &f, n, c, dof(n, c), v, amplitude)?;
                    }
                }
            }
            supports.push(SupportGroup {
                name: self.support_name(&p.name, &p.group, &f),
                prescribed: start..prescribed.list.len(),
            });
        }
        self.check_support_names(&supports)?;
        let mut loads = Vec::new();
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}]");
            self.check_load(&f, l)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &l.amplitude)?);
            if l.at.is_none() && l.group.is_none() {
                return Err(self.invalid(&f, "give `at` or `group`"));
            }
            let at = l.at.and_then(|c| c.xyz());
            let force = l.force.xyz().ok_or_else(|| {
                self.invalid(format!("{f}.force"), "needs three numbers [x, y, z]")
            })?;
            let nodes = self.select_3d(&mesh, &sources, &f, &l.body, &l.group, [None; 3], at)?;
            if nodes.len() > 1 {
                return Err(match &l.group {
                    Some(g) => self.invalid(
                        format!("{f}.group"),
                        format!(
                            "physical group `{g}` has {} nodes; a point load needs one (a [[traction]] loads a surface)",
                            nodes.len()
                        ),
                    ),
                    None => self.invalid(
                        format!("{f}.at"),
                        format!(
                            "{} nodes sit at {:?} (bodies share no nodes); name the `body`",
                            nodes.len(),
                            at.unwrap_or_default()
                        ),
                    ),
                });
            }
            for (c, &value) in force.iter().enumerate() {
                loads.push(PointLoad {
                    dof: dof(nodes[0], c),
                    value,
                    amplitude,
                });
            }
        }
        for (i, t) in self.tractions.iter().enumerate() {
            let f = format!("traction[{i}]");
            self.check_traction(&f, t)?;
            let force_per_area = t
                .force_per_area
                .ok_or_else(|| self.invalid(&f, "give `force_per_area = [tx, ty, tz]`"))?;
            let amplitude = curves.intern(self.check_amplitude(&f, &t.amplitude)?);
            let (_, faces) = self.faces_3d(&mesh, &sources, &f, &t.body, t.side, &t.group)?;
            for face in faces {
                let x = face.map_nodes(|n| mesh.node_ref(n));
                let forces = nodal_forces(&x, force_per_area);
                for (&n, fa) in face.nodes().iter().zip(forces.nodes()) {
                    for (c, &value) in fa.iter().enumerate() {
                        loads.push(PointLoad {
                            dof: dof(n, c),
                            value,
                            amplitude,
                        });
                    }
                }
            }
        }
        // the first pair is named (each is refused the same way)
        if let Some(c) = self.contacts.first() {
            let f = "contact[0]".to_owned();
            let face = |which: &str, spec: &super::FaceSpec| {
                let field = format!("{f}.{which}");
                self.faces_3d(&mesh, &sources, &field, &spec.body, spec.side, &spec.group)
            };
            let (slave_body, slave) = face("slave", &c.slave)?;
            let (master_body, master) = face("master", &c.master)?;
            if slave_body == master_body {
                return Err(self.invalid(&f, "slave and master must be different bodies"));
            }
            self.check_contact(&f, c)?;
            return Err(SceneError::Unsupported {
                origin: self.origin.clone(),
                field: f,
                message: format!(
                    "contact between 3D bodies is not supported yet (the pair's faces were found: {} slave faces on `{}`, {} master faces on `{}`); without its [[contact]] tables the scene builds and solves",
                    slave.len(),
                    mesh.bodies[slave_body].name,
                    master.len(),
                    mesh.bodies[master_body].name
                ),
            });
        }
        self.check_loading()?;
        self.check_newton()?;
        let model = Model {
            mesh,
            prescribed: prescribed.list,
            loads,
            contacts: Vec::new(),
            face_contacts: Vec::new(),
            load_factor_end: self.loading.load_factor_end,
            amplitudes: curves.0,
            supports,
        };
        model
            .check()
            .map_err(|e| self.invalid("(model)", e.to_string()))?;
        Ok(model)
    }
}
