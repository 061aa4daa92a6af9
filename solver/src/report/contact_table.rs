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
//! 2D: pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped
//! 3D: pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering,clamped
//! ```
//!
//! (every column is described in [`super::contact_csv`]).
//!
//! **Clamped rows.** A slave node that supports hold (every dof
//! prescribed, [`Solution::held_nodes`]) and whose projection lies on a
//! master point the supports hold too (every master node of its facet with
//! a shape-function weight above [`HELD_WEIGHT`] at `xi_m` held) has its
//! motion fixed on both sides: its multiplier is a reaction between two
//! supports, not a contact pressure (docs/conventions.md, "A slave node
//! fixed on a fixed master point"). [`ContactTable::clamped`] marks it;
//! `contact.csv`'s last column is `1` there, `0` elsewhere.

use crate::contact::{
    FaceLayout, FaceLayoutError, FaceNodalError, FaceNodalRow, NodalContactError, NodalContactRow,
    NodalState, nodal_contact,
};
use crate::dim::SpaceDim;
use crate::element::FaceKind;
use crate::ids::NodeId;
use crate::mesh::face_shape::FaceShape;
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

/// A master node whose shape-function weight at the projection is at most
/// this does not move the master point (module docs, clamped rows).
pub const HELD_WEIGHT: f64 = 1e-9;

/// Whether slave node `slave` and the master point of `master` (the
/// facet's nodes and kind, the projection's parametric coordinates) are
/// both held by supports (module docs, clamped rows): the one decision of
/// both dimensions.
fn held_on_both_sides(
    held: &[bool],
    slave: usize,
    master: Option<(&[usize], FaceKind, [f64; 2])>,
) -> bool {
    let Some((nodes, kind, xi)) = master else {
        return false;
    };
    let shape = FaceShape::at(kind, xi);
    held[slave]
        && nodes
            .iter()
            .zip(shape.n)
            .all(|(&n, w)| w.abs() <= HELD_WEIGHT || held[n])
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

    /// Whether the row's slave node is held by supports on both sides
    /// (module docs, clamped rows): its pressure is a reaction between
    /// supports.
    fn clamped(solution: &Solution<D>, row: &Self::Row) -> bool
    where
        Dim<D>: SurfaceDim<D>;
}

impl ContactTable<2> for Dim<2> {
    type Row = NodalContactRow;
    const HEADER: &'static str = "pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped";

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
            "{name},{node},{},{},{projection},{},{},{master_numbering},{}",
            num(row.position[0]),
            num(row.position[1]),
            num(row.tributary_length),
            numbering.as_str(),
            u8::from(Self::clamped(solution, row)),
        )
    }

    fn clamped(solution: &Solution, row: &NodalContactRow) -> bool {
        let master = row
            .projection
            .as_ref()
            .map(|p| (&p.master_nodes[..], FaceKind::Segment, [p.xi_m, 0.0]));
        held_on_both_sides(&solution.held_nodes, row.node, master)
    }
}

impl ContactTable<3> for Dim<3> {
    type Row = FaceNodalRow;
    const HEADER: &'static str = "pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering,clamped";

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
            "{name},{},{x},{y},{z},{},{},{},{master_numbering},{}",
            number(row.node.index()),
            fields.join(","),
            num(row.tributary_area),
            numbering(row.node),
            u8::from(Self::clamped(solution, row)),
        )
    }

    fn clamped(solution: &Solution<3>, row: &FaceNodalRow) -> bool {
        let nodes: Option<Vec<usize>> = row
            .master
            .map(|(_, face)| face.nodes().iter().map(|n| n.index()).collect());
        let master = match (&nodes, row.master, row.xi_m) {
            (Some(nodes), Some((_, face)), Some(xi)) => Some((&nodes[..], face.kind(), xi)),
            _ => None,
        };
        held_on_both_sides(&solution.held_nodes, row.node.index(), master)
    }
}
