//! The model builder: from a [`Scene`] to the [`Model`] the solver works on.
//!
//! The order of everything the solver sees is fixed here and is part of the
//! results (assembly and the contact points follow it):
//!
//! * bodies in `[[body]]` order, each appended by its mesh source with
//!   fresh nodes (bodies share no nodes);
//! * prescribed degrees of freedom in the order `[[fix]]` then
//!   `[[prescribe]]`, each item's nodes in increasing index, then its
//!   components x, y; a degree of freedom appears once (a second item may
//!   only repeat its value and, unless it is zero, its load curve);
//! * support groups, one per `[[fix]]` and `[[prescribe]]` in that order,
//!   named by the item's `name`, else its `group` when no other item has
//!   the same `group`, else `fix[i]` / `prescribe[i]`; each holds the dofs its item added
//!   (a dof prescribed twice belongs to the first item, so the groups'
//!   reactions add up to the total support force);
//! * load curves, each distinct table once, in the order items first use
//!   them;
//! * point loads in `[[load]]` order, x then y; then the tractions in
//!   `[[traction]]` order: a block side's segments counter-clockwise
//!   around the body (as a contact face), a curve's segments in file order
//!   with each segment's two nodes in the file's direction; each segment's
//!   nodes x then y (`t L / 2` each, `L` the reference length);
//! * contact pairs in `[[contact]]` order, each face's segments as its
//!   source orders them (counter-clockwise around the body); each pair's
//!   reference geometry checked (`initial_contact`: faces that face each
//!   other, no initial penetration, unless the `[[contact]]` allows it).

use super::dimension::Dimension;
use super::initial_contact::check_initial_contact;
use super::source::Sources;
use super::supports::{Curves, Prescriptions};
use super::{Dofs, Scene, SceneError};
use crate::dim::SpaceDim;
use crate::ids::DofId;
use crate::mesh::Mesh;
use crate::mesh::gmsh::AnyMsh;
use crate::model::{ContactPair, Dim, Model, PointLoad, SupportGroup, SurfaceDim};

/// A scene's dimension as a type: what the model builder takes from it.
pub trait SceneDim<const D: usize>: SpaceDim<D> {
    /// The scene dimension it builds.
    const DIMENSION: Dimension;

    /// The model of `scene`, whose `[mesh] file` is `file` (read), after
    /// [`Scene::prepare`] found it of this dimension.
    fn build(scene: &Scene, file: Option<AnyMsh>) -> Result<Model<D>, SceneError>
    where
        Dim<D>: SurfaceDim<D>;
}

impl SceneDim<2> for Dim<2> {
    const DIMENSION: Dimension = Dimension::Two;

    fn build(scene: &Scene, file: Option<AnyMsh>) -> Result<Model<2>, SceneError> {
        scene.build_planar(file, Dimension::Two)
    }
}

impl SceneDim<3> for Dim<3> {
    const DIMENSION: Dimension = Dimension::Three;

    fn build(scene: &Scene, file: Option<AnyMsh>) -> Result<Model<3>, SceneError> {
        scene.build_solid(file)
    }
}

impl Scene {
    /// The checks before any body is made: `[refine]`, the memory
    /// estimate, the `[mesh] file` (read), the scene's dimension and the
    /// keys it has (`dimension.rs`).
    pub(super) fn prepare(&self) -> Result<(Option<AnyMsh>, Dimension), SceneError> {
        self.check_refine()?;
        super::memory::check_scene(self).map_err(|e| self.invalid("body", e.to_string()))?;
        let file = self.read_mesh_file()?;
        let dim = self.dimension_with(file.as_ref())?;
        self.check_dimension(dim)?;
        Ok((file, dim))
    }

    /// Builds the finite-element model of the scene in dimension `D`
    /// (`build_model::<2>()` of a 2D scene, `build_model::<3>()` of a 3D
    /// one); a scene of the other dimension is an error naming its first
    /// body.
    pub fn build_model<const D: usize>(&self) -> Result<Model<D>, SceneError>
    where
        Dim<D>: SceneDim<D>,
    {
        let (file, dim) = self.prepare()?;
        if dim != <Dim<D> as SceneDim<D>>::DIMENSION {
            return Err(self.invalid(
                "body[0]",
                format!(
                    "is a {} body: build the model of a {} scene with `Scene::build_model::<{}>`",
                    dim.name(),
                    dim.name(),
                    dim.count()
                ),
            ));
        }
        <Dim<D> as SceneDim<D>>::build(self, file)
    }

    /// [`Scene::build_model`] after [`Scene::prepare`].
    pub(super) fn build_planar(
        &self,
        file: Option<AnyMsh>,
        dim: Dimension,
    ) -> Result<Model, SceneError> {
        let planar = match file {
            None => None,
            Some(AnyMsh::Planar(msh)) => Some(msh),
            // `prepare` found the scene 2D, so its mesh file is 2D
            Some(AnyMsh::Volume(_)) => {
                return Err(self.invalid("mesh.file", "is a 3D mesh in a 2D scene"));
            }
        };
        let mut sources = Sources::of(self, planar);
        let mut mesh = Mesh::new();
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
            let at = fx.at.and_then(|c| c.point::<2>());
            for n in self.select_in(&mesh, &sources, &f, &fx.body, &fx.group, fx.x, fx.y, at)? {
                for c in fx.dofs.unwrap_or(Dofs::XY).components() {
                    prescribed.add(self, &f, n, c, DofId::of(n, c), 0.0, None)?;
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
            let at = p.at.and_then(|c| c.point::<2>());
            for n in self.select_in(&mesh, &sources, &f, &p.body, &p.group, p.x, p.y, at)? {
                for (c, v) in [(0, p.ux), (1, p.uy)] {
                    if let Some(v) = v {
                        prescribed.add(self, &f, n, c, DofId::of(n, c), v, amplitude)?;
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
            let at = l.at.and_then(|c| c.point::<2>());
            let force = l
                .force
                .point::<2>()
                .ok_or_else(|| self.invalid(format!("{f}.force"), "needs two numbers [x, y]"))?;
            let nodes = self.select_in(&mesh, &sources, &f, &l.body, &l.group, None, None, at)?;
            if nodes.len() > 1 {
                return Err(match (&l.group, l.at) {
                    (Some(g), _) => self.invalid(
                        format!("{f}.group"),
                        format!(
                            "physical group `{g}` has {} nodes; a point load needs one (a [[traction]] loads a curve)",
                            nodes.len()
                        ),
                    ),
                    (None, _) => self.invalid(
                        format!("{f}.at"),
                        format!(
                            "{} nodes sit at {:?} (bodies share no nodes); name the `body`",
                            nodes.len(),
                            at.unwrap_or_default()
                        ),
                    ),
                });
            }
            for c in 0..2 {
                loads.push(PointLoad {
                    dof: DofId::of(nodes[0], c),
                    value: force[c],
                    amplitude,
                });
            }
        }
        for (i, t) in self.tractions.iter().enumerate() {
            let f = format!("traction[{i}]");
            self.check_traction(&f, t)?;
            let force_per_length = t
                .force_per_length
                .ok_or_else(|| self.invalid(&f, "give `force_per_length = [tx, ty]`"))?;
            let amplitude = curves.intern(self.check_amplitude(&f, &t.amplitude)?);
            let segments = self.traction_segments(&mesh, &sources, &f, t)?;
            for seg in segments {
                let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
                let half = (b[0] - a[0]).hypot(b[1] - a[1]) / 2.0;
                for n in seg {
                    for c in 0..2 {
                        loads.push(PointLoad {
                            dof: DofId::of(n, c),
                            value: force_per_length[c] * half,
                            amplitude,
                        });
                    }
                }
            }
        }
        let mut contacts = Vec::new();
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            let (slave_body, slave) = self.face(&mesh, &sources, &f, "slave", &c.slave)?;
            let (master_body, master) = self.face(&mesh, &sources, &f, "master", &c.master)?;
            if slave_body == master_body {
                return Err(self.invalid(&f, "slave and master must be different bodies"));
            }
            self.check_contact(&f, c)?;
            let pair = ContactPair {
                name: c.pair_name(&f),
                slave,
                master,
                formulation: c.formulation,
                mode: c.mode,
                gauss_points: c.gauss_points,
                integration: c.integration,
            };
            check_initial_contact(
                &mesh,
                &pair,
                c.allow_not_facing,
                c.allow_initial_penetration,
            )
            .map_err(|m| self.invalid(&f, m))?;
            contacts.push(pair);
        }
        self.check_loading()?;
        self.check_newton()?;
        let model = Model {
            mesh,
            prescribed: prescribed.list,
            loads,
            contacts,
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
