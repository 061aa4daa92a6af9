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
//!   consistent nodal force of [`super::traction::nodal_forces`];
//! * contact pairs in `[[contact]]` order, each a [`ContactPair<3>`] of
//!   [`Model::contacts`] named as in 2D (`name`, else `contact[i]`):
//!   its slave and master faces (a block side's in the side's order, a
//!   physical surface's in file order; each counter-clockwise seen from
//!   outside its body), on two different bodies; its reading the
//!   `formulation` (`slave-normal` or `closest-point`: any other is
//!   refused naming `contact[i].formulation`); `gauss_points` as given
//!   (absent: `None`, the face kind's default, 2 x 2 on a quad4, 3 on a
//!   tri3, 7 per clipped triangle with segmented integration), checked
//!   against the kinds of the slave faces ([`face_rule`]) or the
//!   clipped triangles' rules (1, 3, 7), and every pair laid out once
//!   ([`FaceLayout::new`]) so that what the solve's layout refuses is a
//!   scene error naming `contact[i]`.
//!
//! The pairs become [`Model::contacts`], which Newton solves with the
//! 3D contact element ([`crate::dim::ContactSpace`]). The 2D reference checks of a pair (faces facing each other, no initial
//! penetration: `initial_contact.rs`) are not made in 3D.

use contact_kernels::Formulation;

use super::dimension::Dimension;
use super::source::Solids;
use super::supports::{Curves, Prescriptions};
use super::traction::nodal_forces;
use super::{ContactSpec, Dofs, FaceSpec, Scene, SceneError};
use crate::contact::FaceLayout;
use crate::contact::face_rules::{FaceKind as RuleKind, face_rule};
use crate::ids::{DofId, NodeId};
use crate::mesh::Mesh;
use crate::mesh::gmsh::AnyMsh;
use crate::mesh::volume::{Face, FaceKind};
use crate::model::{ContactPair, Integration, Model, PointLoad, SupportGroup};

/// The dof of component `c` of `node` in 3D.
fn dof(node: crate::ids::NodeId, c: usize) -> DofId {
    DofId::in_dim::<3>(node, c)
}

impl Scene {
    /// [`Scene::build_model`] of a 3D scene after [`Scene::prepare`].
    pub(super) fn build_solid(&self, file: Option<AnyMsh>) -> Result<Model<3>, SceneError> {
        let dim = Dimension::Three;
        let volume = match file {
            None => None,
            Some(AnyMsh::Volume(msh)) => Some(msh),
            // `prepare` found the scene 3D, so its mesh file is 3D
            Some(AnyMsh::Planar(_)) => {
                return Err(self.invalid("mesh.file", "is a 2D mesh in a 3D scene"));
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
            let at = fx.at.and_then(|c| c.point::<3>());
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
            let at = p.at.and_then(|c| c.point::<3>());
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
            let at = l.at.and_then(|c| c.point::<3>());
            let force = l.force.point::<3>().ok_or_else(|| {
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
        let mut contacts = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            contacts.push(self.face_pair(&mesh, &sources, &f, c)?);
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
        if let Err(e) = model.check() {
            return Err(self.invalid("(model)", e.to_string()));
        }
        // what the solve's layout of the pairs refuses (a clipping that
        // fails, a degenerate slave face) is refused here, by pair
        for (i, pair) in model.contacts.iter().enumerate() {
            FaceLayout::new(&model.mesh, std::slice::from_ref(pair), None)
                .map_err(|e| self.invalid(format!("contact[{i}]"), e.to_string()))?;
        }
        Ok(model)
    }

    /// The [`ContactPair<3>`] of `contact[i]` (named `f`, `c`): its two faces
    /// resolved (a block side's faces in the side's order, a physical
    /// surface's in file order), on two different bodies, each with at
    /// least one face; its `formulation` a reading of 3D faces; its
    /// `gauss_points` a rule on each kind of its slave faces (or, with
    /// segmented integration, on the clipped triangles). Named, and its
    /// mode and integration taken, as a 2D pair (`build.rs`).
    fn face_pair(
        &self,
        mesh: &Mesh<3>,
        sources: &Solids,
        f: &str,
        c: &ContactSpec,
    ) -> Result<ContactPair<3>, SceneError> {
        let faces = |which: &str, spec: &FaceSpec| {
            let field = format!("{f}.{which}");
            let (body, faces) =
                self.faces_3d(mesh, sources, &field, &spec.body, spec.side, &spec.group)?;
            if faces.is_empty() {
                return Err(self.invalid(field, "has no faces"));
            }
            Ok((body, faces))
        };
        let (slave_body, slave) = faces("slave", &c.slave)?;
        let (master_body, master) = faces("master", &c.master)?;
        if slave_body == master_body {
            return Err(self.invalid(f, "slave and master must be different bodies"));
        }
        if !matches!(
            c.formulation,
            Formulation::SlaveNormal | Formulation::ClosestPoint
        ) {
            return Err(self.invalid(
                format!("{f}.formulation"),
                format!(
                    "`{}` is not a reading of 3D faces: a 3D pair takes `slave-normal` or `closest-point` (the kernel of each slave face on a master face is the reading's for the two faces' kinds)",
                    c.formulation
                ),
            ));
        }
        self.check_face_gauss_points(f, c, &slave)?;
        Ok(ContactPair {
            name: c.pair_name(f),
            slave,
            master,
            formulation: c.formulation,
            mode: c.mode,
            gauss_points: c.gauss_points,
            integration: c.integration,
        })
    }

    /// `gauss_points` of the 3D pair `f` (`c`), if given: with Gauss
    /// integration a rule on every kind of its `slave` faces
    /// ([`face_rule`]: 1..=8 per direction on a quad4, 1, 3, 4, 6 or 7 on
    /// a tri3), with segmented integration a rule on the clipped triangles
    /// (1, 3 or 7); an error names `{f}.gauss_points` and the counts
    /// there are.
    fn check_face_gauss_points(
        &self,
        f: &str,
        c: &ContactSpec,
        slave: &[Face<NodeId>],
    ) -> Result<(), SceneError> {
        let Some(n) = c.gauss_points else {
            return Ok(());
        };
        let field = format!("{f}.gauss_points");
        match c.integration {
            Integration::Segmented => {
                if !SEGMENTED_POINTS.contains(&n) {
                    return Err(self.invalid(
                        field,
                        format!(
                            "segmented integration takes a rule of 1, 3 or 7 points on each clipped triangle, got {n}"
                        ),
                    ));
                }
            }
            Integration::Gauss => {
                let mut kinds: Vec<FaceKind> = Vec::new();
                for face in slave {
                    if !kinds.contains(&face.kind()) {
                        kinds.push(face.kind());
                    }
                }
                for kind in kinds {
                    let (rule, per) = match kind {
                        FaceKind::Quad4 => (RuleKind::Quad4, " per direction (n x n points)"),
                        FaceKind::Tri3 => (RuleKind::Tri3, ""),
                    };
                    face_rule(rule, n).map_err(|e| {
                        self.invalid(
                            &field,
                            format!("{e}{per}, for the pair's {rule} slave faces"),
                        )
                    })?;
                }
            }
        }
        Ok(())
    }
}

/// The point counts of the triangle rules of segmented integration
/// (`contact::clip::TriangleRule`: centroid, three points, Radon's seven).
const SEGMENTED_POINTS: [usize; 3] = [1, 3, 7];
