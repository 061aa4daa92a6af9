//! `contact.csv` of a 3D solution: the nodal contact table of a state on
//! the face pairs ([`crate::contact::FaceLayout::nodal_table`]), written by
//! `gapsim run --out DIR` for a 3D scene with `[[contact]]` pairs.
//!
//! One row per slave node and pair, pair by pair in multiplier order (the
//! order the nodes first appear on the slave faces), with the header
//!
//! ```text
//! pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area
//! ```
//!
//! `pair` is the pair's name (quoted as in 2D, [`super::csv::field`]),
//! `node` the slave node's number ([`crate::Mesh::node_number`]: the mesh
//! file's tag, or the internal index of a block body), `x, y, z` its
//! current coordinates, `pressure` `p = -lambda` (positive in
//! compression). `gap`, `xi_m_u`, `xi_m_v`, `master_face` (the index
//! within the pair's master surface) and the master face's nodes are those
//! of the node taken as a point of its first adjacent slave face (the
//! face's corner), projected onto the master surface with the pair's
//! reading; all empty where it projects into no master face;
//! `master_node_4` is empty on a tri3 master face. `tributary_area` is
//! `sum w J0 N_a` over the node's integration points: `sum pressure x
//! tributary_area` over a pair is the pressure's resultant. Numbers in
//! Rust's shortest round-trip form, as the 2D file.

use thiserror::Error;

use crate::contact::{FaceLayout, FaceLayoutError, FaceNodalError, FaceNodalRow};
use crate::solution::{Solution, State};

use super::contact_csv::num;
use super::csv::field;

/// The header line of the 3D `contact.csv` (without the line break).
pub const HEADER_3D: &str = "pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area";

/// Why a 3D state has no nodal contact table.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FaceContactError {
    /// The solution's face pairs cannot be laid out again (cannot happen
    /// for a solution of these pairs).
    #[error(transparent)]
    Layout(#[from] FaceLayoutError),
    /// A slave-side kernel failure at a node.
    #[error(transparent)]
    Node(#[from] FaceNodalError),
}

/// The nodal contact table of `state` (one of `solution`'s states) on
/// the solution's face pairs: the rows of the 3D `contact.csv` and the
/// `.vtu` contact fields.
pub fn face_nodal_rows(
    solution: &Solution<3>,
    state: &State<3>,
) -> Result<Vec<FaceNodalRow>, FaceContactError> {
    let mesh = &solution.mesh;
    let layout = FaceLayout::new(mesh, &solution.face_pairs, None)?;
    let u: Vec<f64> = state.displacements.iter().flatten().copied().collect();
    Ok(layout.nodal_table(mesh, &u, &state.multipliers)?.0)
}

/// The 3D `contact.csv` text of `state` (one of `solution`'s states).
pub fn contact_csv_3d(
    solution: &Solution<3>,
    state: &State<3>,
) -> Result<String, FaceContactError> {
    let mesh = &solution.mesh;
    let rows = face_nodal_rows(solution, state)?;
    let number = |n: usize| mesh.node_number(n).0.to_string();
    let mut out = format!("{HEADER_3D}\n");
    for row in rows {
        let name = field(&solution.face_pairs[row.pair.index()].name);
        let [x, y, z] = row.x.map(num);
        // gap, pressure, xi_m_u, xi_m_v, master_face, 4 master nodes
        let mut fields = vec![String::new(); 9];
        fields[1] = num(row.pressure);
        if let (Some(g), Some([xu, xv]), Some((face, nodes))) = (row.gap, row.xi_m, row.master) {
            fields[0] = num(g);
            fields[2] = num(xu);
            fields[3] = num(xv);
            fields[4] = face.index().to_string();
            for (k, n) in nodes.nodes().iter().enumerate() {
                fields[5 + k] = number(n.index());
            }
        }
        out.push_str(&format!(
            "{name},{},{x},{y},{z},{},{}\n",
            number(row.node.index()),
            fields.join(","),
            num(row.tributary_area)
        ));
    }
    Ok(out)
}
