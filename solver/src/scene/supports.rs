//! What the 2D and 3D model builders share: load curves stored once, the
//! prescribed degrees of freedom with their agreement rule, and the names
//! of the support groups.

use std::collections::HashMap;

use super::{Scene, SceneError};
use crate::amplitude::Amplitude;
use crate::ids::{AmplitudeId, DofId, NodeId};
use crate::model::{Prescribed, SupportGroup};

/// The load curves of a model, each stored once (equal tables share an
/// index, so that two entries prescribing a dof with equal curves agree).
#[derive(Default)]
pub(super) struct Curves(pub(super) Vec<Amplitude>);

impl Curves {
    /// The index of `curve` (`None` for none), adding it if new.
    pub(super) fn intern(&mut self, curve: Option<Amplitude>) -> Option<AmplitudeId> {
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

/// The prescribed degrees of freedom of a model, in the order first
/// prescribed, each once.
#[derive(Default)]
pub(super) struct Prescriptions {
    pub(super) list: Vec<Prescribed>,
    /// The index in `list` of each dof.
    index: HashMap<DofId, usize>,
}

impl Prescriptions {
    /// Prescribes component `c` of `node` (its dof `dof`) to `value` with
    /// the curve `amplitude`, for the item `field` of `scene`; a dof
    /// prescribed before must agree: the same value and, unless it is
    /// zero, the same curve.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn add(
        &mut self,
        scene: &Scene,
        field: &str,
        node: NodeId,
        c: usize,
        dof: DofId,
        value: f64,
        amplitude: Option<AmplitudeId>,
    ) -> Result<(), SceneError> {
        match self.index.get(&dof).map(|&k| &self.list[k]) {
            Some(p) if p.value != value => Err(scene.invalid(
                field,
                format!(
                    "node {} component {c} is already prescribed to {}",
                    node.index(),
                    p.value
                ),
            )),
            Some(p) if value != 0.0 && p.amplitude != amplitude => Err(scene.invalid(
                field,
                format!(
                    "node {} component {c} is already prescribed with another load curve",
                    node.index(),
                ),
            )),
            Some(_) => Ok(()),
            None => {
                self.index.insert(dof, self.list.len());
                self.list.push(Prescribed {
                    dof,
                    value,
                    amplitude,
                });
                Ok(())
            }
        }
    }
}

impl Scene {
    /// A support group's name: the item's `name`, else its `group` unless
    /// another `[[fix]]`/`[[prescribe]]` has it, else its field `f`.
    pub(super) fn support_name(
        &self,
        name: &Option<String>,
        group: &Option<String>,
        f: &str,
    ) -> String {
        match group {
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
        }
    }

    /// The support groups `supports` (one per `[[fix]]`, then per
    /// `[[prescribe]]`) have unique names; the error names the first item
    /// whose name an earlier one has.
    pub(super) fn check_support_names(&self, supports: &[SupportGroup]) -> Result<(), SceneError> {
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
        Ok(())
    }
}
