//! `contact.csv`: the nodal contact table of a solved state
//! ([`super::contact_table`]) as comma-separated values, written by
//! `gapsim run --out DIR`; its columns come from the dimension.
//!
//! # 2D
//!
//! One row per slave node and contact pair, pair by pair and in slave-face
//! order, with the header
//!
//! ```text
//! pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped,shear_x,shear_y,state,slip
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
//! with them; the master face is one body). `clamped` is `1` where the
//! slave node and the master point it projects onto are both held by
//! supports (every dof prescribed; [`super::ContactTable::clamped`]): its
//! `pressure` is then a reaction between supports, not a contact pressure
//! (docs/conventions.md); `0` elsewhere. `shear_x`, `shear_y`, `state`
//! and `slip` are the friction columns (docs/conventions.md, "Coulomb
//! friction", [`super::contact_table::FrictionTable`]): the tangential
//! traction on the slave node exerted by the master, in global components
//! and the units of `pressure`; `open`, `stick` or `slip`; the accumulated
//! slip length (empty on a pair without friction). The gap is
//! that of the node itself projected onto the master face; with
//! `slave-normal`, along the normal of the slave segment that starts at
//! the node (the last node of an open face: the segment ending there); a
//! node of two pairs has a row in each. Numbers are
//! written in Rust's shortest round-trip form (with an exponent below
//! 1e-4 and from 1e15 on). A state with a slave node the kernels cannot
//! project for a slave-side reason (a collapsed or folded slave segment,
//! see [`crate::contact::nodal_contact`]) has no table: the error is returned,
//! never a row without a gap.
//!
//! # 3D
//!
//! One row per slave node and pair, pair by pair in multiplier order (the
//! order the nodes first appear on the slave faces), with the header
//!
//! ```text
//! pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering,clamped,shear_x,shear_y,shear_z,state,slip
//! ```
//!
//! `pair` is the pair's name (quoted as in 2D), `node` the slave node's
//! number ([`crate::Mesh::node_number`]: the mesh file's tag, or the
//! internal index of a block body), `x, y, z` its current coordinates,
//! `pressure` `p = -lambda` (positive in compression). `gap`, `xi_m_u`,
//! `xi_m_v`, `master_face` (the index within the pair's master surface)
//! and the master face's nodes are those of the node taken as a point of
//! its first adjacent slave face (the face's corner), projected onto the
//! master surface with the pair's reading
//! ([`crate::contact::FaceLayout::nodal_table`]); all empty where it
//! projects into no master face; `master_node_4` is empty on a tri3
//! master face. `tributary_area` is `sum w J0 N_a` over the node's
//! integration points: `sum pressure x tributary_area` over a pair is the
//! pressure's resultant. `node_numbering` says how `node` is numbered
//! (`msh` or `internal`, as in 2D) and `master_numbering` how the master
//! face's nodes are (empty with them): in a scene of a block body and a
//! mesh-file body, one side's numbers are mesh tags and the other's
//! internal indices. `clamped` as in 2D; the friction columns as in 2D
//! with `shear_z` (3D pairs have no friction yet: no shear, `open` or
//! `slip`, no slip). Numbers in Rust's shortest
//! round-trip form, as the 2D file.

use crate::model::Dim;
use crate::solution::{Solution, State};

use super::contact_table::{ContactTable, ContactTableError, FrictionTable};

/// The `contact.csv` text of `state` (one of `solution`'s states), or why
/// its nodal contact table does not exist.
pub fn contact_csv<const D: usize>(
    solution: &Solution<D>,
    state: &State<D>,
) -> Result<String, ContactTableError>
where
    Dim<D>: ContactTable<D>,
{
    let mut out = format!("{}\n", <Dim<D> as ContactTable<D>>::HEADER);
    let friction = FrictionTable::new(solution, state);
    for row in <Dim<D> as ContactTable<D>>::rows(solution, state)? {
        let columns = friction.columns(solution, state, &row);
        out.push_str(&<Dim<D> as ContactTable<D>>::csv_line(
            solution, &row, &columns,
        ));
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Dim;
    use crate::report::ContactTable;

    /// A Gmsh scene's rows number the nodes by the mesh file's tags: each
    /// row's `node` is the tag of the file node at that slave node's
    /// reference position (`msh`), and so are the master nodes; a block
    /// scene keeps the internal indices (`internal`).
    #[test]
    fn gmsh_nodes_are_numbered_by_their_file_tags() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
        let scene = crate::Scene::from_file(format!("{dir}/hertz-coarse.toml")).unwrap();
        let sol = crate::solve::<2>(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let msh = crate::mesh::gmsh::MshMesh::read(format!("{dir}/hertz-coarse.msh")).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        let table = Dim::<2>::rows(&sol, &sol.final_state).unwrap();
        let at_tag = |field: &str| msh.nodes()[msh.node_index(field.parse().unwrap()).unwrap()];
        let mut differs = 0;
        assert_eq!(text.lines().count(), table.len() + 1);
        for (line, row) in text.lines().skip(1).zip(&table) {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), 18, "{line}");
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
        let sol = crate::solve::<2>(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        let table = Dim::<2>::rows(&sol, &sol.final_state).unwrap();
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
        let mut sol = crate::solve::<2>(&scene, &crate::SolveOptions::from_scene(&scene)).unwrap();
        let text = contact_csv(&sol, &sol.final_state).unwrap();
        assert_eq!(text.lines().count(), 6, "{text}");
        let [a, b] = sol.contact_pairs[0].slave[0].map(crate::ids::NodeId::index);
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
