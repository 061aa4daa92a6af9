//! The model builder: from a [`Scene`] to the [`Model<D>`] the solver
//! works on, one code path for both dimensions; what differs between them
//! comes from the dimension ([`Build`], implemented in `planar.rs` and
//! `solid.rs`).
//!
//! The order of everything the solver sees is fixed here and is part of the
//! results (assembly and the contact points follow it):
//!
//! * bodies in `[[body]]` order, each appended by its mesh source with
//!   fresh nodes (bodies share no nodes);
//! * prescribed degrees of freedom in the order `[[fix]]` then
//!   `[[prescribe]]`, each item's nodes in increasing index, then its
//!   components x, y (, z) (`dofs`, default all); a degree of freedom
//!   appears once (a second item may only repeat its value and, unless it
//!   is zero, its load curve);
//! * support groups, one per `[[fix]]` and `[[prescribe]]` in that order,
//!   named by the item's `name`, else its `group` when no other item has
//!   the same `group`, else `fix[i]` / `prescribe[i]`; each holds the dofs
//!   its item added (a dof prescribed twice belongs to the first item, so
//!   the groups' reactions add up to the total support force);
//! * load curves, each distinct table once, in the order items first use
//!   them;
//! * point loads in `[[load]]` order, one per component; then the
//!   tractions in `[[traction]]` order, each facet's nodes in order, each
//!   node's components in order ([`Build::traction_forces`]: in 2D
//!   `t L / 2` per node of a segment of reference length `L`, a block
//!   side's segments counter-clockwise around the body, a curve's in file
//!   order and direction; in 3D the consistent nodal forces of
//!   [`super::traction::nodal_forces`], a block side's faces in the side's
//!   order, a physical surface's in file order);
//! * contact pairs in `[[contact]]` order, named by `name`, else
//!   `contact[i]`: its slave and master facets (a block side's in the
//!   side's order, a physical group's in file order; outward, see
//!   [`crate::model::ContactPair`]), on two different bodies, each with at
//!   least one facet, checked by the dimension ([`Build::check_pair`]: in
//!   2D the reference geometry, `initial_contact.rs`; in 3D the reading
//!   and the `gauss_points` on the slave faces' kinds) and, once the model
//!   is checked, laid out ([`Build::check_model`]: in 3D every pair once,
//!   so that what the solve's layout refuses is a scene error naming
//!   `contact[i]`).

use super::dimension::Dimension;
use super::source::{SourceDim, Sources};
use super::supports::{Curves, Prescriptions};
use super::{ContactSpec, Dofs, FaceSpec, Scene, SceneError, TractionSpec};
use crate::dim::SpaceDim;
use crate::ids::{DofId, NodeId};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::mesh::gmsh::AnyMsh;
use crate::model::{ContactPair, Dim, Facet, FacetOf, Model, PointLoad, SupportGroup, SurfaceDim};

/// A scene's dimension as a type: `Dim<2>` builds the model of a 2D
/// scene, `Dim<3>` of a 3D one ([`Scene::build_model`]).
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
        scene.build_in::<2>(file)
    }
}

impl SceneDim<3> for Dim<3> {
    const DIMENSION: Dimension = Dimension::Three;

    fn build(scene: &Scene, file: Option<AnyMsh>) -> Result<Model<3>, SceneError> {
        scene.build_in::<3>(file)
    }
}

/// What the builder takes from the dimension (module docs), beyond what
/// its mesh sources take ([`SourceDim`]).
pub(super) trait Build<const D: usize>: SceneDim<D> + SourceDim<D> {
    /// `traction[i]`'s force per reference length or area (named `f`).
    fn traction_force(scene: &Scene, f: &str, t: &TractionSpec) -> Result<[f64; D], SceneError>;

    /// The nodal forces of the traction `t` (named `f`) of force `force`:
    /// each node of each loaded facet, in order (module docs).
    fn traction_forces(
        scene: &Scene,
        mesh: &Mesh<D>,
        sources: &Sources<'_, D>,
        f: &str,
        t: &TractionSpec,
        force: [f64; D],
    ) -> Result<Vec<(NodeId, [f64; D])>, SceneError>
    where
        Dim<D>: SourceDim<D>;

    /// Checks `contact[i]` (named `f`, `c`) on its `slave` facets before
    /// its pair is made.
    fn check_spec(
        scene: &Scene,
        f: &str,
        c: &ContactSpec,
        slave: &[FacetOf<D>],
    ) -> Result<(), SceneError>
    where
        Dim<D>: SurfaceDim<D>;

    /// Checks the pair `pair` of `contact[i]` (named `f`, `c`) on `mesh`.
    fn check_pair(
        scene: &Scene,
        mesh: &Mesh<D>,
        f: &str,
        c: &ContactSpec,
        pair: &ContactPair<D>,
    ) -> Result<(), SceneError>
    where
        Dim<D>: SurfaceDim<D>;

    /// Checks the checked `model` as a whole.
    fn check_model(scene: &Scene, model: &Model<D>) -> Result<(), SceneError>
    where
        Dim<D>: SurfaceDim<D>;
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

    /// [`Scene::build_model`] after [`Scene::prepare`] found the scene of
    /// dimension `D` (module docs).
    fn build_in<const D: usize>(&self, file: Option<AnyMsh>) -> Result<Model<D>, SceneError>
    where
        Dim<D>: Build<D>,
    {
        let dim = <Dim<D> as SceneDim<D>>::DIMENSION;
        let mut sources = Sources::<D>::new(self, file)?;
        let mut mesh = Mesh::<D>::new();
        for i in 0..self.bodies.len() {
            let material: Material = self.check_body(i, dim)?;
            sources.add_body(&mut mesh, i, material)?;
        }
        if mesh.bodies.is_empty() {
            return Err(self.invalid("body", "at least one [[body]] is needed"));
        }
        let dof = |n: NodeId, c: usize| DofId::in_dim::<D>(n, c);
        let mut curves = Curves::default();
        let mut prescribed = Prescriptions::default();
        let mut supports = Vec::new();
        for (i, fx) in self.fixes.iter().enumerate() {
            let f = format!("fix[{i}]");
            let start = prescribed.list.len();
            let at = fx.at.and_then(|c| c.point::<D>());
            let axes = [fx.x, fx.y, fx.z];
            for n in self.select(&mesh, &sources, &f, &fx.body, &fx.group, &axes, at)? {
                for c in fx.dofs.unwrap_or(Dofs::all(D)).components() {
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
            let at = p.at.and_then(|c| c.point::<D>());
            let axes = [p.x, p.y, p.z];
            for n in self.select(&mesh, &sources, &f, &p.body, &p.group, &axes, at)? {
                for (c, v) in [p.ux, p.uy, p.uz].into_iter().take(D).enumerate() {
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
            let at = l.at.and_then(|c| c.point::<D>());
            let force = l.force.point::<D>().ok_or_else(|| {
                self.invalid(
                    format!("{f}.force"),
                    format!(
                        "needs {} numbers [{}]",
                        <Dim<D> as SourceDim<D>>::NUMBERS,
                        <Dim<D> as SpaceDim<D>>::AXES.join(", ")
                    ),
                )
            })?;
            let nodes = self.select(&mesh, &sources, &f, &l.body, &l.group, &[None; 3], at)?;
            if nodes.len() > 1 {
                return Err(match &l.group {
                    Some(g) => self.invalid(
                        format!("{f}.group"),
                        format!(
                            "physical group `{g}` has {} nodes; a point load needs one (a [[traction]] loads a {})",
                            nodes.len(),
                            <Dim<D> as SourceDim<D>>::GROUP
                        ),
                    ),
                    None => self.invalid(
                        format!("{f}.at"),
                        format!(
                            "{} nodes sit at {:?} (bodies share no nodes); name the `body`",
                            nodes.len(),
                            at.unwrap_or([0.0; D])
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
            let force = <Dim<D> as Build<D>>::traction_force(self, &f, t)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &t.amplitude)?);
            let forces =
                <Dim<D> as Build<D>>::traction_forces(self, &mesh, &sources, &f, t, force)?;
            for (n, fa) in forces {
                for (c, &value) in fa.iter().enumerate() {
                    loads.push(PointLoad {
                        dof: dof(n, c),
                        value,
                        amplitude,
                    });
                }
            }
        }
        let mut contacts = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            contacts.push(self.contact_pair(&mesh, &sources, &f, c)?);
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
        <Dim<D> as Build<D>>::check_model(self, &model)?;
        Ok(model)
    }

    /// The pair of `contact[i]` (named `f`, `c`): its two surfaces
    /// resolved, on two different bodies, each with at least one facet,
    /// checked by the dimension (module docs).
    fn contact_pair<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        sources: &Sources<'_, D>,
        f: &str,
        c: &ContactSpec,
    ) -> Result<ContactPair<D>, SceneError>
    where
        Dim<D>: Build<D>,
    {
        let facets = |which: &str, spec: &FaceSpec| {
            let field = format!("{f}.{which}");
            let (body, facets) =
                self.facets(mesh, sources, &field, &spec.body, spec.side, &spec.group)?;
            if facets.is_empty() {
                return Err(self.invalid(field, format!("has no {}s", FacetOf::<D>::NAME)));
            }
            Ok((body, facets))
        };
        let (slave_body, slave) = facets("slave", &c.slave)?;
        let (master_body, master) = facets("master", &c.master)?;
        if slave_body == master_body {
            return Err(self.invalid(f, "slave and master must be different bodies"));
        }
        self.check_friction(f, c)?;
        <Dim<D> as Build<D>>::check_spec(self, f, c, &slave)?;
        let pair = ContactPair {
            name: c.pair_name(f),
            slave,
            master,
            formulation: c.formulation,
            mode: c.mode,
            friction: c.friction,
            gauss_points: c.gauss_points,
            integration: c.integration,
            multipliers: c.multipliers,
        };
        <Dim<D> as Build<D>>::check_pair(self, mesh, f, c, &pair)?;
        Ok(pair)
    }
}
