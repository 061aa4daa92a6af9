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
//!   only repeat its value);
//! * point loads in `[[load]]` order, x then y; then the tractions in
//!   `[[traction]]` order, each curve's segments in file order, each
//!   segment's two nodes in the file's direction, x then y
//!   (`t L / 2` each, `L` the reference length);
//! * contact pairs in `[[contact]]` order, each face's segments as its
//!   source orders them (counter-clockwise around the body).

use super::source::Sources;
use super::{Scene, SceneError};
use crate::ids::DofId;
use crate::mesh::Mesh;
use crate::model::{ContactPair, Model, PointLoad, Prescribed};

impl Scene {
    /// Builds the finite-element model.
    pub fn build_model(&self) -> Result<Model, SceneError> {
        self.check_refine()?;
        let mut sources = Sources::of(self)?;
        let mut mesh = Mesh::new();
        for i in 0..self.bodies.len() {
            let material = self.check_body(i)?;
            sources.add_body(&mut mesh, i, material)?;
        }
        if mesh.bodies.is_empty() {
            return Err(self.invalid("body", "at least one [[body]] is needed"));
        }
        let mut prescribed: Vec<Prescribed> = Vec::new();
        let mut add_prescribed = |field: &str, dof: DofId, value: f64| -> Result<(), SceneError> {
            match prescribed.iter().find(|p| p.dof == dof) {
                Some(p) if p.value != value => Err(self.invalid(
                    field,
                    format!(
                        "node {} component {} is already prescribed to {}",
                        dof.node(),
                        dof.component(),
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
            for n in self.select_in(&mesh, &sources, &f, &fx.body, &fx.group, fx.x, fx.y, fx.at)? {
                for &c in fx.dofs.components() {
                    add_prescribed(&f, DofId::of(n, c), 0.0)?;
                }
            }
        }
        for (i, p) in self.prescribes.iter().enumerate() {
            let f = format!("prescribe[{i}]");
            self.check_prescribe(&f, p)?;
            for n in self.select_in(&mesh, &sources, &f, &p.body, &p.group, p.x, p.y, p.at)? {
                for (c, v) in [(0, p.ux), (1, p.uy)] {
                    if let Some(v) = v {
                        add_prescribed(&f, DofId::of(n, c), v)?;
                    }
                }
            }
        }
        let mut loads = Vec::new();
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}]");
            self.check_load(&f, l)?;
            if l.at.is_none() && l.group.is_none() {
                return Err(self.invalid(&f, "give `at` or `group`"));
            }
            let nodes = self.select_in(&mesh, &sources, &f, &l.body, &l.group, None, None, l.at)?;
            if nodes.len() > 1 {
                return Err(match (&l.group, l.at) {
                    (Some(g), _) => self.invalid(
                        format!("{f}.group"),
                        format!(
                            "physical group `{g}` has {} nodes; a point load needs one (a [[traction]] loads a curve)",
                            nodes.len()
                        ),
                    ),
                    (None, at) => self.invalid(
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
                    value: l.force[c],
                });
            }
        }
        for (i, t) in self.tractions.iter().enumerate() {
            let f = format!("traction[{i}]");
            self.check_traction(&f, t)?;
            let segments = sources.group_segments(&format!("{f}.group"), &t.group)?;
            for seg in segments {
                let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
                let half = (b[0] - a[0]).hypot(b[1] - a[1]) / 2.0;
                for n in seg {
                    for c in 0..2 {
                        loads.push(PointLoad {
                            dof: DofId::of(n, c),
                            value: t.force_per_length[c] * half,
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
            contacts.push(ContactPair {
                name: c.name.clone().unwrap_or_else(|| f.clone()),
                slave,
                master,
                formulation: c.formulation,
                mode: c.mode,
                gauss_points: c.gauss_points,
                integration: c.integration,
            });
        }
        self.check_loading()?;
        self.check_newton()?;
        let model = Model {
            mesh,
            prescribed,
            loads,
            contacts,
            load_factor_end: self.loading.load_factor_end,
        };
        model
            .check()
            .map_err(|e| self.invalid("(model)", e.to_string()))?;
        Ok(model)
    }
}
