//! `contact.csv`: the nodal contact table of a solved state
//! ([`super::nodal`]) as comma-separated values, written by `gapsim run
//! --out DIR`.
//!
//! One row per slave node and contact pair, pair by pair and in slave-face
//! order, with the header
//!
//! ```text
//! pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering
//! ```
//!
//! `pair` is the pair's name (quoted when it holds a comma, quote or line
//! break, [`super::csv::field`]), `node` the slave node, `x`, `y` its current coordinates,
//! `pressure` the contact pressure `p = -lambda` (positive in compression),
//! `gap`, `xi_m`, `master_segment` (index within the pair's master face)
//! and its two global nodes where the node projects into the master face
//! (all five empty where it does not), `tributary_length` the reference
//! length the node's pressure acts on (`sum pressure x tributary_length`
//! over a pair is the pressure's integral over its slave face). Node
//! numbers (`node`, `master_node_1`, `master_node_2`) are those of the
//! node's body ([`crate::Mesh::node_number`]): the mesh file's node tag for
//! a body read from the scene's `[mesh] file`, the internal 0-based index
//! for a block body; `node_numbering` says which `node` is (`msh` or
//! `internal`), `master_numbering` which the two master nodes are (empty
//! with them; the master face is one body). The gap is
//! that of the node itself projected onto the master face; with
//! `slave-normal`, along the normal of the slave segment that starts at
//! the node (the last node of an open face: the segment ending there); a
//! node of two pairs has a row in each. Numbers are
//! written in Rust's shortest round-trip form (with an exponent below
//! 1e-4 and from 1e15 on). A state with a slave node the kernels cannot
//! project for a slave-side reason (a collapsed or folded slave segment,
//! see [`super::nodal`]) has no table: the error is returned,
//! never a row without a gap.

use crate::solution::{Solution, State};

use super::csv::field;
use super::nodal::{NodalContactError, nodal_contact};

/// The header line of `contact.csv` (without the line break).
pub const HEADER: &str = "pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering";

/// `v` in Rust's shortest round-trip form: positional, or with an
/// exponent where that is shorter (below 1e-4 and from 1e15 on).
pub(super) fn num(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e15).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The `contact.csv` text of `state` (one of `solution`'s states), or why
/// its nodal contact table does not exist.
pub fn contact_csv(solution: &Solution, state: &State) -> Result<String, NodalContactError> {
    let mut out = format!("{HEADER}\n");
    let number = |n: usize| solution.mesh.node_number(n);
    for row in nodal_contact(solution, state)? {
        let name = field(&solution.contact_pairs[row.pair].name);
        let (projection, master_numbering) = match row.projection {
            Some(p) => {
                let (m1, numbering) = number(p.master_nodes[0]);
                (
                    format!(
                        "{},{},{},{},{},{}",
                        num(p.gap),
                        num(row.pressure),
                        num(p.xi_m),
                        p.master_segment,
                        m1,
                        number(p.master_nodes[1]).0
                    ),
                    numbering.as_str(),
                )
            }
            None => (format!(",{},,,,", num(row.pressure)), ""),
        };
        let (node, numbering) = number(row.node);
        out.push_str(&format!(
            "{name},{node},{},{},{projection},{},{},{master_numbering}\n",
            num(row.position[0]),
            num(row.position[1]),
            num(row.tributary_length),
            numbering.as_str(),
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.0,
            -0.0,
            1.0,
            0.49492293187714653,
            -5.551115123125783e-17,
            1e-4,
            3e15,
            -1.5e300,
        ] {
            assert_eq!(num(v).parse::<f64>().unwrap().to_bits(), v.to_bits(), "{v}");
        }
        assert_eq!(num(-5.551115123125783e-17), "-5.551115123125783e-17");
        assert_eq!(num(0.25), "0.25");
    }

    /// A Gmsh scene's rows number the nodes by the mesh file's tags: each
    /// row's `node` is the tag of the file node at that slave node's
    /// reference position (`msh`), and so are the master nodes; a block
    /// scene keeps the internal indices (`internal`).
    #[test]
    fn gmsh_nodes_are_numbered_by_their_file_tags() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
        let scene = crate::Scene::from_file(format!("{dir}/hertz-coarse.toml")).unwrap();
        let sol = crate::solve(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let msh = crate::mesh::gmsh::MshMesh::read(format!("{dir}/hertz-coarse.msh")).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        let table = nodal_contact(&sol, &sol.final_state).unwrap();
        let at_tag = |field: &str| msh.nodes()[msh.node_index(field.parse().unwrap()).unwrap()];
        let mut differs = 0;
        assert_eq!(text.lines().count(), table.len() + 1);
        for (line, row) in text.lines().skip(1).zip(&table) {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), 13, "{line}");
            assert_eq!(f[11], "msh", "{line}");
            assert_eq!(at_tag(f[1]), sol.mesh.nodes_ref[row.node], "{line}");
            differs += usize::from(f[1] != row.node.to_string());
            if let Some(p) = row.projection {
                assert_eq!(f[12], "msh", "{line}");
                for (k, n) in p.master_nodes.iter().enumerate() {
                    assert_eq!(at_tag(f[8 + k]), sol.mesh.nodes_ref[*n], "{line}");
                }
            }
        }
        // the internal numbers are not the tags (the test can fail)
        assert!(differs > 0, "{text}");
        // the `.vtu`'s node_number is the tag of every node
        let vtu = crate::report::vtu_string(&sol, &sol.final_state).unwrap();
        let values = |name: &str| -> Vec<u64> {
            let at = vtu.find(&format!("Name=\"{name}\"")).unwrap();
            let body = &vtu[at..];
            let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
            body.split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect()
        };
        let numbers = values("node_number");
        assert_eq!(numbers.len(), sol.mesh.node_count());
        for (n, tag) in numbers.iter().enumerate() {
            assert_eq!(at_tag(&tag.to_string()), sol.mesh.nodes_ref[n]);
        }
        assert!(values("node_number_from_mesh_file").iter().all(|&v| v == 1));
        let scene = crate::Scene::from_file(format!("{dir}/pressed-blocks.toml")).unwrap();
        let sol = crate::solve(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        let table = nodal_contact(&sol, &sol.final_state).unwrap();
        for (line, row) in text.lines().skip(1).zip(&table) {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(
                (f[1], f[11], f[12]),
                (row.node.to_string().as_str(), "internal", "internal")
            );
        }
        // the `.vtu` carries the same numbers
        let vtu = crate::report::vtu_string(&sol, &sol.final_state).unwrap();
        assert!(vtu.contains("Name=\"node_number\""), "{vtu}");
        assert!(vtu.contains("Name=\"node_number_from_mesh_file\""), "{vtu}");
    }

    /// A solved state with a collapsed slave segment has no table: the
    /// error names the pair and the slave segment's failure.
    #[test]
    fn a_collapsed_slave_segment_is_reported() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/pressed-blocks.toml");
        let scene = crate::Scene::from_file(path).unwrap();
        let mut sol = crate::solve(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        assert_eq!(text.lines().count(), 6, "{text}");
        let [a, b] = sol.contact_pairs[0].slave[0];
        let x = &sol.mesh.nodes_ref;
        let d = &mut sol.final_state.displacements;
        d[a] = [x[b][0] + d[b][0] - x[a][0], x[b][1] + d[b][1] - x[a][1]];
        let msg = contact_csv(&sol, &sol.final_state).unwrap_err().to_string();
        assert!(
            msg.contains("contact pair `interface`")
                && msg.contains(&format!("slave node {a} "))
                && msg.contains("degenerate slave segment"),
            "{msg}"
        );
    }
}
