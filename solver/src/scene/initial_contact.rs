//! The reference geometry of a contact pair, checked before a solve, the
//! same three checks in 2D and 3D: faces that do not face each other,
//! initial penetration, and a persistent pair that starts open are errors
//! unless the `[[contact]]` acknowledges them (`allow_not_facing`,
//! `allow_initial_penetration`, `allow_initial_gap`; see
//! [`super::ContactSpec`]).
//!
//! Every slave node is paired in the reference configuration as
//! [`crate::contact::reference`] describes it (2D: the pair's formulation on
//! the slave segment that starts at the node, every master segment tried;
//! 3D: [`crate::contact::FaceLayout::reference_pairings`]), facing or not,
//! the smallest `|g|` among the master facets the node projects into. A
//! node that projects into none is not checked (it does not pair). Where a
//! node pairs, with `h` the size of its slave facet (a segment's length, a
//! face's square root of its area):
//!
//! * **facing**: the unit outward normals of its slave facet and of the
//!   master facet (each face runs counter-clockwise around its body, so
//!   the outward normal of a segment `a -> b` is `(b - a)` turned
//!   clockwise, of a face `t_1 x t_2`) must be opposed,
//!   `n_s . n_m <= FACING_TOL`; a slave face looking away from its master
//!   (the far side of the slave body) has `n_s . n_m` near 1;
//! * **penetration**: `g >= -PENETRATION_FRACTION h`;
//! * **open persistent pair**: in `mode = "persistent"` (the default),
//!   `g <= OPEN_GAP_FRACTION h`: a persistent pair holds `g = 0` at every
//!   paired point, so the first step would pull an open gap shut with
//!   whatever force that takes (contact that may open and close is
//!   `mode = "unilateral"`).
//!
//! The error names the pair and its worst node (largest `n_s . n_m`; most
//! negative or most positive `g / h`) by its reference coordinates, and
//! the key that acknowledges it.

use contact_kernels::{Formulation, PAIR_COORDS};

use crate::contact::{ReferencePairing, XI_INSIDE_TOL};
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::model::{ContactMode, ContactPair};

/// The largest `n_s . n_m` of faces that face each other (the normals at
/// most 90 degrees from opposed; the slack is round-off).
pub const FACING_TOL: f64 = 1e-9;

/// The largest initial penetration accepted, as a fraction of the slave
/// facet's size.
pub const PENETRATION_FRACTION: f64 = 1e-2;

/// The largest initial gap of a persistent pair accepted, as a fraction of
/// the slave facet's size.
pub const OPEN_GAP_FRACTION: f64 = 1e-2;

/// The outward unit normal of segment `a -> b` of a counter-clockwise
/// face (zero for a zero-length segment).
fn outward(a: [f64; 2], b: [f64; 2]) -> ([f64; 2], f64) {
    let t = [b[0] - a[0], b[1] - a[1]];
    let len = t[0].hypot(t[1]);
    if len > 0.0 {
        ([t[1] / len, -t[0] / len], len)
    } else {
        ([0.0, 0.0], 0.0)
    }
}

/// Every slave node of the 2D `pair` that pairs in the reference
/// configuration, with `formulation` (module docs).
pub(super) fn reference_pairings_2d(
    mesh: &Mesh,
    pair: &ContactPair,
    formulation: Formulation,
) -> Vec<ReferencePairing<2>> {
    let mut nodes: Vec<NodeId> = Vec::new();
    for seg in &pair.slave {
        for &n in seg {
            if !nodes.contains(&n) {
                nodes.push(n);
            }
        }
    }
    let mut out = Vec::new();
    for node in nodes {
        let slave = pair
            .slave
            .iter()
            .find(|s| s[0] == node)
            .map(|s| (*s, -1.0))
            .or_else(|| pair.slave.iter().find(|s| s[1] == node).map(|s| (*s, 1.0)));
        let Some((slave, xi_s)) = slave else { continue };
        let mut best: Option<(f64, [NodeId; 2])> = None;
        for master in &pair.master {
            let q_nodes = [slave[0], slave[1], master[0], master[1]];
            let q: [f64; PAIR_COORDS] =
                std::array::from_fn(|k| mesh.node_ref(q_nodes[k / 2])[k % 2]);
            let Ok(pr) = contact_kernels::project(formulation, &q, xi_s) else {
                continue;
            };
            if pr.xi_m.abs() <= 1.0 + XI_INSIDE_TOL
                && best.is_none_or(|(g, _)| pr.gap.abs() < g.abs())
            {
                best = Some((pr.gap, *master));
            }
        }
        let Some((gap, master)) = best else { continue };
        let (n_s, slave_length) = outward(mesh.node_ref(slave[0]), mesh.node_ref(slave[1]));
        let (n_m, _) = outward(mesh.node_ref(master[0]), mesh.node_ref(master[1]));
        out.push(ReferencePairing {
            node,
            gap,
            size: slave_length,
            cos: n_s[0] * n_m[0] + n_s[1] * n_m[1],
            normals: [n_s, n_m],
        });
    }
    out
}

/// A point or vector written for a message: `(x, y)` or `(x, y, z)`.
fn point<const D: usize>(x: [f64; D]) -> String {
    let parts: Vec<String> = x.iter().map(|c| format!("{c}")).collect();
    format!("({})", parts.join(", "))
}

/// What a [`ContactSpec`](super::ContactSpec) acknowledges of its pair's
/// reference geometry, and the pair's mode.
#[derive(Debug, Clone, Copy)]
pub(super) struct Acknowledged {
    /// `allow_not_facing`.
    pub not_facing: bool,
    /// `allow_initial_penetration`.
    pub penetration: bool,
    /// `allow_initial_gap`.
    pub open_gap: bool,
    /// The pair's mode.
    pub mode: ContactMode,
}

impl Acknowledged {
    /// What `spec` acknowledges.
    pub(super) fn of(spec: &super::ContactSpec) -> Acknowledged {
        Acknowledged {
            not_facing: spec.allow_not_facing,
            penetration: spec.allow_initial_penetration,
            open_gap: spec.allow_initial_gap,
            mode: spec.mode,
        }
    }

    /// Whether no check is left to make.
    pub(super) fn everything(&self) -> bool {
        self.not_facing
            && self.penetration
            && (self.open_gap || self.mode != ContactMode::Persistent)
    }
}

/// Checks the reference pairings `paired` of the pair named `name`
/// (module docs) against what `ack` acknowledges; the message names the
/// pair and its worst node.
pub(super) fn check_initial_contact<const D: usize>(
    mesh: &Mesh<D>,
    name: &str,
    paired: &[ReferencePairing<D>],
    ack: Acknowledged,
) -> Result<(), String> {
    let facet = if D == 2 {
        "slave segment's length"
    } else {
        "slave face's size"
    };
    if !ack.not_facing {
        let worst = paired
            .iter()
            .filter(|p| p.cos > FACING_TOL)
            .max_by(|a, b| a.cos.total_cmp(&b.cos));
        if let Some(w) = worst {
            let angle = w.cos.clamp(-1.0, 1.0).acos().to_degrees();
            return Err(format!(
                "contact pair `{name}`: the slave and master faces do not face each other: at the \
                 slave node at {} the outward normals of the slave face {} and of the master \
                 face {} are {angle:.1} degrees apart (facing faces have opposed normals, 180 \
                 degrees; the slave face may be the far side of its body); set \
                 `allow_not_facing = true` in this [[contact]] if that is intended",
                point(mesh.node_ref(w.node)),
                point(w.normals[0]),
                point(w.normals[1]),
            ));
        }
    }
    if !ack.penetration {
        let worst = paired
            .iter()
            .filter(|p| p.gap < -PENETRATION_FRACTION * p.size)
            .min_by(|a, b| (a.gap / a.size).total_cmp(&(b.gap / b.size)));
        if let Some(w) = worst {
            return Err(format!(
                "contact pair `{name}`: initial penetration {} at the slave node at {}, beyond the \
                 tolerance {} ({} of the {facet} {}); set \
                 `allow_initial_penetration = true` in this [[contact]] if that is intended",
                -w.gap,
                point(mesh.node_ref(w.node)),
                PENETRATION_FRACTION * w.size,
                PENETRATION_FRACTION,
                w.size,
            ));
        }
    }
    if !ack.open_gap && ack.mode == ContactMode::Persistent {
        let worst = paired
            .iter()
            .filter(|p| p.gap > OPEN_GAP_FRACTION * p.size)
            .max_by(|a, b| (a.gap / a.size).total_cmp(&(b.gap / b.size)));
        if let Some(w) = worst {
            return Err(format!(
                "contact pair `{name}`: initial gap {} at the slave node at {}, beyond the \
                 tolerance {} ({} of the {facet} {}), and the pair is persistent (the default \
                 `mode`: g = 0 at every paired point), so the first step would pull the gap \
                 shut; set `mode = \"unilateral\"` for contact that opens and closes, or \
                 `allow_initial_gap = true` in this [[contact]] if the pair is meant to be \
                 pulled shut",
                w.gap,
                point(mesh.node_ref(w.node)),
                OPEN_GAP_FRACTION * w.size,
                OPEN_GAP_FRACTION,
                w.size,
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::Scene;

    const PRESSED_BLOCKS: &str = include_str!("../../../scenes/pressed-blocks.toml");
    const SLAVE: &str = "slave = { body = \"block\", side = \"bottom\" }";

    /// The number after `label` in `e`.
    fn number_after(e: &str, label: &str) -> f64 {
        let rest = &e[e.find(label).unwrap_or_else(|| panic!("{e}")) + label.len()..];
        rest.split([' ', ',']).next().unwrap().parse().unwrap()
    }

    fn build(text: &str) -> Result<crate::model::Model, String> {
        Scene::from_toml_str(text, "blocks.toml")
            .and_then(|s| s.build_model())
            .map_err(|e| e.to_string())
    }

    /// `text` with `keys` added to its `[[contact]]`.
    fn with_keys(text: &str, keys: &str) -> String {
        text.replace(SLAVE, &format!("{SLAVE}\n{keys}"))
    }

    /// The block's top face as the slave face looks away from the base:
    /// an error naming the pair, the worst node and the key; with the key
    /// the initial penetration of the block's height (0.5, the
    /// slave-normal gap through the block) is the next error; with both
    /// keys the scene builds.
    #[test]
    fn a_slave_face_looking_away_is_an_error() {
        let top_slave = "slave = { body = \"block\", side = \"top\" }";
        let top = PRESSED_BLOCKS.replace(SLAVE, top_slave);
        assert!(top.contains(top_slave));
        let e = build(&top).unwrap_err();
        assert!(
            e.starts_with("blocks.toml: contact[0]: contact pair `interface`"),
            "{e}"
        );
        assert!(e.contains("do not face each other"), "{e}");
        assert!(
            e.contains("at the slave node at (") && e.contains(", 1) the"),
            "{e}"
        );
        assert!(e.contains("0.0 degrees apart"), "{e}");
        assert!(e.contains("allow_not_facing = true"), "{e}");
        let keyed = |keys: &str| top.replace(top_slave, &format!("{top_slave}\n{keys}"));
        let e = build(&keyed("allow_not_facing = true")).unwrap_err();
        assert!(
            e.contains("contact pair `interface`: initial penetration"),
            "{e}"
        );
        assert!(
            (number_after(&e, "initial penetration ") - 0.5).abs() < 1e-12,
            "{e}"
        );
        assert!(
            e.contains("tolerance 0.0025 (0.01 of the slave segment's length 0.25)"),
            "{e}"
        );
        assert!(e.contains("allow_initial_penetration = true"), "{e}");
        build(&keyed(
            "allow_not_facing = true\nallow_initial_penetration = true",
        ))
        .unwrap();
    }

    /// `scenes/pressed-blocks.toml` with the block's bottom at `y` (its
    /// loads moved with its top).
    fn block_at(y: f64) -> String {
        let top = y + 0.5;
        PRESSED_BLOCKS
            .replace("origin = [0.0, 0.5]", &format!("origin = [0.0, {y:?}]"))
            .replace(", 1.0]\nforce", &format!(", {top:?}]\nforce"))
    }

    /// A block that starts 0.1 inside its base is an error at its worst
    /// node; 0.001 inside (below 1 % of the slave segments' 0.25) builds,
    /// and the key accepts the deeper one.
    #[test]
    fn initial_penetration_beyond_the_tolerance_is_an_error() {
        let sunk = block_at(0.4);
        let e = build(&sunk).unwrap_err();
        assert!(
            (number_after(&e, "initial penetration ") - 0.1).abs() < 1e-12,
            "{e}"
        );
        assert!(e.contains(", 0.4), beyond"), "{e}");
        build(&with_keys(&sunk, "allow_initial_penetration = true")).unwrap();
        build(&block_at(0.499)).unwrap();
    }

    /// A persistent pair whose block starts 0.05 above its base (beyond
    /// 1 % of the slave segments' 0.25) is an error naming the gap and
    /// the two ways out; unilateral, or with the key, it builds; 0.001
    /// (within the tolerance) builds as it is.
    #[test]
    fn a_persistent_pair_that_starts_open_is_an_error() {
        let unilateral = block_at(0.55);
        let open = unilateral.replace("mode = \"unilateral\"", "mode = \"persistent\"");
        assert_ne!(unilateral, open, "the scene names its mode");
        let e = build(&open).unwrap_err();
        assert!(
            e.starts_with("blocks.toml: contact[0]: contact pair `interface`: initial gap "),
            "{e}"
        );
        assert!(
            (number_after(&e, "initial gap ") - 0.05).abs() < 1e-12,
            "{e}"
        );
        assert!(
            e.contains("tolerance 0.0025 (0.01 of the slave segment's length 0.25)"),
            "{e}"
        );
        assert!(e.contains("mode = \"unilateral\"") && e.contains("allow_initial_gap = true"));
        build(&with_keys(&open, "allow_initial_gap = true")).unwrap();
        build(&unilateral).unwrap();
        build(&block_at(0.501).replace("mode = \"unilateral\"", "mode = \"persistent\"")).unwrap();
    }

    /// A 3D cube (2 x 2 x 1 hexahedra, 1 x 1 x 0.5) on a base (3 x 3 x 1,
    /// 1 x 1 x 0.5): its bottom at `z`, the pair's slave and master sides
    /// and the extra `[[contact]]` keys given.
    fn cube_on_base(z: f64, slave: &str, master: &str, keys: &str) -> String {
        format!(
            r#"
[material]
young = 1000.0
poisson = 0.3

[[body]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 0.5]
nx = 3
ny = 3
nz = 1

[[body]]
name = "cube"
origin = [0.0, 0.0, {z:?}]
size = [1.0, 1.0, 0.5]
nx = 2
ny = 2
nz = 1

[[fix]]
body = "base"
z = 0.0

[[traction]]
body = "cube"
side = "top"
force_per_area = [0.0, 0.0, -1.0]

[[contact]]
name = "seat"
slave = {{ body = "cube", side = "{slave}" }}
master = {{ body = "base", side = "{master}" }}
{keys}

[loading]
load_factor_end = 1.0
steps = [1]
"#
        )
    }

    fn build3d(text: &str) -> Result<crate::model::Model<3>, String> {
        Scene::from_toml_str(text, "cube.toml")
            .and_then(|s| s.build_model::<3>())
            .map_err(|e| e.to_string())
    }

    /// The 3D pair refuses what the 2D one refuses, through the same
    /// checks: a slave face looking away from its master, a master looking
    /// away, an overlap of 0.2 and, persistent, a gap of 0.05; each key
    /// accepts its case, and the cube resting on the base builds.
    #[test]
    fn a_3d_pair_refuses_what_a_2d_pair_refuses() {
        build3d(&cube_on_base(0.5, "bottom", "top", "")).unwrap();

        let e = build3d(&cube_on_base(0.5, "top", "top", "")).unwrap_err();
        assert!(
            e.starts_with("cube.toml: contact[0]: contact pair `seat`: the slave and master faces do not face each other"),
            "{e}"
        );
        assert!(
            e.contains("0.0 degrees apart") && e.contains("(0, 0, 1)"),
            "{e}"
        );
        // with the key, the top is the cube's height (0.5) behind the
        // base's top along its normal
        let e = build3d(&cube_on_base(0.5, "top", "top", "allow_not_facing = true")).unwrap_err();
        assert!(
            (number_after(&e, "initial penetration ") - 0.5).abs() < 1e-12,
            "{e}"
        );

        let e = build3d(&cube_on_base(0.5, "bottom", "bottom", "")).unwrap_err();
        assert!(e.contains("do not face each other"), "{e}");

        let e = build3d(&cube_on_base(0.3, "bottom", "top", "")).unwrap_err();
        assert!(
            (number_after(&e, "initial penetration ") - 0.2).abs() < 1e-12,
            "{e}"
        );
        assert!(
            e.contains("tolerance 0.005 (0.01 of the slave face's size 0.5)"),
            "{e}"
        );
        build3d(&cube_on_base(
            0.3,
            "bottom",
            "top",
            "allow_initial_penetration = true",
        ))
        .unwrap();

        let e = build3d(&cube_on_base(0.55, "bottom", "top", "")).unwrap_err();
        assert!(
            (number_after(&e, "initial gap ") - 0.05).abs() < 1e-12,
            "{e}"
        );
        assert!(e.contains("allow_initial_gap = true"), "{e}");
        build3d(&cube_on_base(
            0.55,
            "bottom",
            "top",
            "allow_initial_gap = true",
        ))
        .unwrap();
        build3d(&cube_on_base(
            0.55,
            "bottom",
            "top",
            "mode = \"unilateral\"",
        ))
        .unwrap();
    }

    /// Every scene shipped in `scenes/`, 2D and 3D, passes the checks
    /// unchanged.
    #[test]
    fn shipped_scenes_pass() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut checked = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let scene = Scene::from_file(&path).unwrap();
                let built = if scene.dimension().unwrap() == crate::scene::Dimension::Three {
                    scene.build_model::<3>().map(|_| ())
                } else {
                    scene.build_model::<2>().map(|_| ())
                };
                built.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                checked += 1;
            }
        }
        assert!(checked >= 15, "{checked}");
    }
}
