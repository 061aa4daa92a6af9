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

use super::initial_contact::check_initial_contact;
use super::source::Sources;
use super::{Scene, SceneError};
use crate::amplitude::Amplitude;
use crate::ids::{AmplitudeId, DofId};
use crate::mesh::Mesh;
use crate::model::{ContactPair, Model, PointLoad, Prescribed, SupportGroup};

/// The load curves of a model, each stored once (equal tables share an
/// index, so that two entries prescribing a dof with equal curves agree).
#[derive(Default)]
struct Curves(Vec<Amplitude>);

impl Curves {
    /// The index of `curve` (`None` for none), adding it if new.
    fn intern(&mut self, curve: Option<Amplitude>) -> Option<AmplitudeId> {
        let curve = curve?;
        let i = match self.0.iter().position(|c| *c == curve) {
            Some(i) => i,
            None => {
                self.0.push(curve);
                self.0.len() - 1
            }
        };
        Some(AmplitudeId::new(i))
    }
}

impl Scene {
    /// Builds the finite-element model.
    pub fn build_model(&self) -> Result<Model, SceneError> {
        self.check_refine()?;
        super::memory::check_scene(self).map_err(|e| self.invalid("body", e.to_string()))?;
        let mut sources = Sources::of(self)?;
        let mut mesh = Mesh::new();
        for i in 0..self.bodies.len() {
            let material = self.check_body(i)?;
            sources.add_body(&mut mesh, i, material)?;
        }
        if mesh.bodies.is_empty() {
            return Err(self.invalid("body", "at least one [[body]] is needed"));
        }
        let mut curves = Curves::default();
        let mut prescribed: Vec<Prescribed> = Vec::new();
        let add_prescribed = |prescribed: &mut Vec<Prescribed>,
                              field: &str,
                              dof: DofId,
                              value: f64,
                              amplitude: Option<AmplitudeId>|
         -> Result<(), SceneError> {
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
                Some(p) if value != 0.0 && p.amplitude != amplitude => Err(self.invalid(
                    field,
                    format!(
                        "node {} component {} is already prescribed with another load curve",
                        dof.node(),
                        dof.component(),
                    ),
                )),
                Some(_) => Ok(()),
                None => {
                    prescribed.push(Prescribed {
                        dof,
                        value,
                        amplitude,
                    });
                    Ok(())
                }
            }
        };
        // a support group's name: its `name`, else its `group` unless
        // another item has it, else its field
        let group_name = |name: &Option<String>, group: &Option<String>, f: &str| match group {
            _ if name.is_some() => name.clone().unwrap_or_default(),
            Some(g)
                if self
                    .fixes
                    .iter()
                    .map(|x| &x.group)
                    .chain(self.prescribes.iter().map(|p| &p.group))
                    .filter(|o| o.as_ref() == Some(g))
                    .count()
                    == 1 =>
            {
                g.clone()
            }
            _ => f.to_owned(),
        };
        let mut supports = Vec::new();
        for (i, fx) in self.fixes.iter().enumerate() {
            let f = format!("fix[{i}]");
            let start = prescribed.len();
            for n in self.select_in(&mesh, &sources, &f, &fx.body, &fx.group, fx.x, fx.y, fx.at)? {
                for &c in fx.dofs.components() {
                    add_prescribed(&mut prescribed, &f, DofId::of(n, c), 0.0, None)?;
                }
            }
            supports.push(SupportGroup {
                name: group_name(&fx.name, &fx.group, &f),
                prescribed: start..prescribed.len(),
            });
        }
        for (i, p) in self.prescribes.iter().enumerate() {
            let f = format!("prescribe[{i}]");
            self.check_prescribe(&f, p)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &p.amplitude)?);
            let start = prescribed.len();
            for n in self.select_in(&mesh, &sources, &f, &p.body, &p.group, p.x, p.y, p.at)? {
                for (c, v) in [(0, p.ux), (1, p.uy)] {
                    if let Some(v) = v {
                        add_prescribed(&mut prescribed, &f, DofId::of(n, c), v, amplitude)?;
                    }
                }
            }
            supports.push(SupportGroup {
                name: group_name(&p.name, &p.group, &f),
                prescribed: start..prescribed.len(),
            });
        }
        for (k, g) in supports.iter().enumerate() {
            if supports[..k].iter().any(|o| o.name == g.name) {
                let f = match k.checked_sub(self.fixes.len()) {
                    None => format!("fix[{k}]"),
                    Some(i) => format!("prescribe[{i}]"),
                };
                return Err(self.invalid(
                    format!("{f}.name"),
                    format!(
                        "support group name `{}` is already used (name each [[fix]] and [[prescribe]] uniquely)",
                        g.name
                    ),
                ));
            }
        }
        let mut loads = Vec::new();
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}]");
            self.check_load(&f, l)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &l.amplitude)?);
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
                    amplitude,
                });
            }
        }
        for (i, t) in self.tractions.iter().enumerate() {
            let f = format!("traction[{i}]");
            self.check_traction(&f, t)?;
            let amplitude = curves.intern(self.check_amplitude(&f, &t.amplitude)?);
            let segments = self.traction_segments(&mesh, &sources, &f, t)?;
            for seg in segments {
                let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
                let half = (b[0] - a[0]).hypot(b[1] - a[1]) / 2.0;
                for n in seg {
                    for c in 0..2 {
                        loads.push(PointLoad {
                            dof: DofId::of(n, c),
                            value: t.force_per_length[c] * half,
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
                name: c.name.clone().unwrap_or_else(|| f.clone()),
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
            prescribed,
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
