//! The nodal contact table of a solved state in either dimension, and how
//! `contact.csv` writes its rows: the trait [`ContactTable`], implemented
//! for `Dim<2>` (segments: [`crate::contact::nodal_contact`]) and `Dim<3>` (faces:
//! [`crate::contact::FaceLayout::nodal_table`]). The `.vtu` contact fields
//! ([`super::vtu`]) and `contact.csv` ([`super::contact_csv`]) read the
//! table through it, without knowing the dimension.
//!
//! The columns of `contact.csv` come from the dimension:
//!
//! ```text
//! 2D: pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering
//! 3D: pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering
//! ```
//!
//! (every column is described in [`super::contact_csv`]).

use crate::contact::{
    FaceLayout, FaceLayoutError, FaceNodalError, FaceNodalRow, NodalContactError, NodalContactRow,
    NodalState, nodal_contact,
};
use crate::dim::SpaceDim;
use crate::ids::NodeId;
use crate::model::{Dim, SurfaceDim};
use crate::solution::{Solution, State};

use super::csv::{field, num};

/// Why a state has no nodal contact table.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactTableError {
    /// A slave node of a 2D pair the kernels cannot project
    /// ([`crate::contact::nodal_contact`]).
    #[error(transparent)]
    Segments(#[from] NodalContactError),
    /// The solution's 3D pairs cannot be laid out again (cannot happen
    /// for a solution of these pairs).
    #[error(transparent)]
    Layout(#[from] FaceLayoutError),
    /// A slave-side kernel failure at a node of a 3D pair.
    #[error(transparent)]
    Faces(#[from] FaceNodalError),
}

/// The nodal contact table of dimension `D` (module docs).
pub trait ContactTable<const D: usize>: SpaceDim<D> {
    /// One slave node of one pair.
    type Row;
    /// The header line of `contact.csv` (without the line break).
    const HEADER: &'static str;

    /// The table of `state` (one of `solution`'s states): one row per
    /// slave node and pair, pair by pair; an error for the first node the
    /// kernels cannot project.
    fn rows(solution: &Solution<D>, state: &State<D>) -> Result<Vec<Self::Row>, ContactTableError>
    where
        Dim<D>: SurfaceDim<D>;

    /// A row's slave node and its gap (`None`: it projects nowhere).
    fn node_gap(row: &Self::Row) -> (usize, Option<f64>);

    /// A row's line of `contact.csv` (without the line break).
    fn csv_line(solution: &Solution<D>, row: &Self::Row) -> String
    where
        Dim<D>: SurfaceDim<D>;
}

impl ContactTable<2> for Dim<2> {
    type Row = NodalContactRow;
    const HEADER: &'static str = "pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering";

    fn rows(solution: &Solution, state: &State) -> Result<Vec<NodalContactRow>, ContactTableError> {
        Ok(nodal_contact(&NodalState {
            mesh: &solution.mesh,
            pairs: &solution.contact_pairs,
            formulations: &solution.formulations,
            multiplier_dofs: &solution.multiplier_dofs,
            displacements: &state.displacements,
            multipliers: &state.multipliers,
        })?)
    }

    fn node_gap(row: &NodalContactRow) -> (usize, Option<f64>) {
        (row.node, row.projection.map(|p| p.gap))
    }

    fn csv_line(solution: &Solution, row: &NodalContactRow) -> String {
        let number = |n: usize| solution.mesh.node_number(n);
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
        format!(
            "{name},{node},{},{},{projection},{},{},{master_numbering}",
            num(row.position[0]),
            num(row.position[1]),
            num(row.tributary_length),
            numbering.as_str(),
        )
    }
}

impl ContactTable<3> for Dim<3> {
    type Row = FaceNodalRow;
    const HEADER: &'static str = "pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering";

    fn rows(
        solution: &Solution<3>,
        state: &State<3>,
    ) -> Result<Vec<FaceNodalRow>, ContactTableError> {
        let mesh = &solution.mesh;
        let layout = FaceLayout::new(mesh, &solution.contact_pairs, None)?;
        let u: Vec<f64> = state.displacements.iter().flatten().copied().collect();
        Ok(layout.nodal_table(mesh, &u, &state.multipliers)?.0)
    }

    fn node_gap(row: &FaceNodalRow) -> (usize, Option<f64>) {
        (row.node.index(), row.gap)
    }

    fn csv_line(solution: &Solution<3>, row: &FaceNodalRow) -> String {
        let number = |n: usize| solution.mesh.node_number(n).0.to_string();
        let numbering = |n: NodeId| solution.mesh.node_number(n.index()).1.as_str();
        let name = field(&solution.contact_pairs[row.pair.index()].name);
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
        let master_numbering = row
            .master
            .map_or("", |(_, face)| numbering(face.nodes()[0]));
        format!(
            "{name},{},{x},{y},{z},{},{},{},{master_numbering}",
            number(row.node.index()),
            fields.join(","),
            num(row.tributary_area),
            numbering(row.node),
        )
    }
}
