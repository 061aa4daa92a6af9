//! The reference geometry of a contact pair, checked before a solve: faces
//! that do not face each other and initial penetration are errors unless
//! the `[[contact]]` acknowledges them (`allow_not_facing`,
//! `allow_initial_penetration`; see [`super::ContactSpec`]).
//!
//! Every slave node is projected onto the master face in the reference
//! configuration as `contact.csv` does it ([`crate::contact::nodal_contact`]): the
//! pair's formulation on the slave segment that starts at the node (the
//! last node of an open face: the one ending there), every master segment
//! tried, the smallest `|g|` among those the node projects into
//! (`|xi_m| <= 1 +` [`crate::contact::XI_INSIDE_TOL`]). A node that
//! projects into none is not checked (it does not pair). Where a node
//! pairs:
//!
//! * **facing**: the outward normals of its slave segment and of the
//!   master segment (each face runs counter-clockwise around its body, so
//!   the outward normal of a segment `a -> b` is `(b - a)` turned
//!   clockwise) must be opposed, `n_s . n_m <= FACING_TOL`; a slave face
//!   looking away from its master (the far side of the slave body) has
//!   `n_s . n_m` near 1;
//! * **penetration**: `g >= -PENETRATION_FRACTION h`, `h` the length of
//!   that slave segment (the element size at the node).
//!
//! The error names the pair and its worst node (largest `n_s . n_m`; most
//! negative `g / h`) by its reference coordinates, and the key that
//! acknowledges it.

use contact_kernels::{Formulation, PAIR_COORDS};

use crate::contact::XI_INSIDE_TOL;
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::model::ContactPair;

/// The largest `n_s . n_m` of faces that face each other (the normals at
/// most 90 degrees from opposed; the slack is round-off).
pub const FACING_TOL: f64 = 1e-9;

/// The largest initial penetration accepted, as a fraction of the slave
/// segment's length.
pub const PENETRATION_FRACTION: f64 = 1e-2;

/// A slave node paired with a master segment in the reference
/// configuration.
struct Paired {
    node: NodeId,
    gap: f64,
    slave_length: f64,
    cos: f64,
    normals: [[f64; 2]; 2],
}

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

/// Every slave node of `pair` that pairs in the reference configuration,
/// with `formulation` (module docs).
fn paired_nodes(mesh: &Mesh, pair: &ContactPair, formulation: Formulation) -> Vec<Paired> {
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
        out.push(Paired {
            node,
            gap,
            slave_length,
            cos: n_s[0] * n_m[0] + n_s[1] * n_m[1],
            normals: [n_s, n_m],
        });
    }
    out
}

/// `[x, y]` written for a message.
fn point(x: [f64; 2]) -> String {
    format!("({}, {})", x[0], x[1])
}

/// Checks `pair`'s reference geometry (module docs); `allow_not_facing`
/// and `allow_initial_penetration` skip the two checks. The message names
/// the pair and its worst node.
pub(super) fn check_initial_contact(
    mesh: &Mesh,
    pair: &ContactPair,
    allow_not_facing: bool,
    allow_initial_penetration: bool,
) -> Result<(), String> {
    if allow_not_facing && allow_initial_penetration {
        return Ok(());
    }
    let paired = paired_nodes(mesh, pair, pair.formulation);
    if !allow_not_facing {
        let worst = paired
            .iter()
            .filter(|p| p.cos > FACING_TOL)
            .max_by(|a, b| a.cos.total_cmp(&b.cos));
        if let Some(w) = worst {
            let angle = w.cos.clamp(-1.0, 1.0).acos().to_degrees();
            return Err(format!(
                "contact pair `{}`: the slave and master faces do not face each other: at the \
                 slave node at {} the outward normals of the slave face {} and of the master \
                 face {} are {angle:.1} degrees apart (facing faces have opposed normals, 180 \
                 degrees; the slave face may be the far side of its body); set \
                 `allow_not_facing = true` in this [[contact]] if that is intended",
                pair.name,
                point(mesh.node_ref(w.node)),
                point(w.normals[0]),
                point(w.normals[1]),
            ));
        }
    }
    if !allow_initial_penetration {
        let worst = paired
            .iter()
            .filter(|p| p.gap < -PENETRATION_FRACTION * p.slave_length)
            .min_by(|a, b| (a.gap / a.slave_length).total_cmp(&(b.gap / b.slave_length)));
        if let Some(w) = worst {
            return Err(format!(
                "contact pair `{}`: initial penetration {} at the slave node at {}, beyond the \
                 tolerance {} ({} of the slave segment's length {}); set \
                 `allow_initial_penetration = true` in this [[contact]] if that is intended",
                pair.name,
                -w.gap,
                point(mesh.node_ref(w.node)),
                PENETRATION_FRACTION * w.slave_length,
                PENETRATION_FRACTION,
                w.slave_length,
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

    /// Every 2D scene shipped in `scenes/` passes both checks unchanged
    /// (3D scenes have no reference check of their pairs: `solid.rs`).
    #[test]
    fn shipped_scenes_pass() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut checked = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let scene = Scene::from_file(&path).unwrap();
                if scene.dimension().unwrap() == crate::scene::Dimension::Three {
                    continue;
                }
                scene
                    .build_model::<2>()
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                checked += 1;
            }
        }
        assert!(checked >= 9, "{checked}");
    }
}
