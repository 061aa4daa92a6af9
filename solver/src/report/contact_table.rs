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
//! 2D: pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped,shear_x,shear_y,state,slip
//! 3D: pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering,clamped,shear_x,shear_y,shear_z,state,slip
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
//! `contact.csv`'s `clamped` column is `1` there, `0` elsewhere.
//!
//! **Friction columns** ([`FrictionTable`], docs/conventions.md, "Coulomb
//! friction"): `shear_x`, `shear_y` (, `shear_z`) `= -t_a tau`, the
//! tangential traction the master exerts on the slave node (`t_a` its
//! tangential multiplier, `tau` the slip's unit tangent at the row's
//! projection: 2D `slave-normal` the direction of the slave segment the
//! row is evaluated on, `closest-point` the reverse of its master
//! segment's); `state` the node's `open`, `stick` or `slip` at the state;
//! `slip` its accumulated slip length. A pair without friction has no
//! shear, `state` `open` where the multiplier is exactly zero (an inactive
//! node) and `slip` elsewhere (frictionless contact slides freely), and an
//! empty `slip`.

use std::collections::HashMap;

use crate::contact::friction::FrictionState;
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
    /// An element's geometry for its stresses (cannot happen for a mesh
    /// whose nodes were not moved, [`crate::mesh::Mesh::geometry`]).
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
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

    /// A row's pair and slave node.
    fn pair_node(row: &Self::Row) -> (usize, usize);

    /// The unit tangent `tau` of the slip at a row's node in `state`
    /// (module docs, friction columns); zero where the dimension solves no
    /// friction.
    fn tangent(solution: &Solution<D>, state: &State<D>, row: &Self::Row) -> [f64; D]
    where
        Dim<D>: SurfaceDim<D>;

    /// A row's line of `contact.csv` (without the line break), its
    /// friction columns `friction`.
    fn csv_line(solution: &Solution<D>, row: &Self::Row, friction: &RowFriction<D>) -> String
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
    const HEADER: &'static str = "pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped,shear_x,shear_y,state,slip";

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

    fn pair_node(row: &NodalContactRow) -> (usize, usize) {
        (row.pair, row.node)
    }

    /// `slave-normal`: the direction of the slave segment the row is
    /// evaluated on; `closest-point`: the reverse of its master segment's
    /// (the slave's direction where none is paired).
    fn tangent(solution: &Solution, state: &State, row: &NodalContactRow) -> [f64; 2] {
        let x = |n: NodeId| {
            let (r, d) = (solution.mesh.node_ref(n), state.displacements[n.index()]);
            [r[0] + d[0], r[1] + d[1]]
        };
        let [a, b] = solution.contact_pairs[row.pair].slave[row.slave_segment].map(x);
        let [a, b] = match (solution.formulations[row.pair], row.projection) {
            (contact_kernels::Formulation::ClosestPoint, Some(p)) => {
                let [m1, m2] = p.master_nodes.map(|n| x(NodeId::new(n)));
                [m2, m1]
            }
            _ => [a, b],
        };
        let d = [b[0] - a[0], b[1] - a[1]];
        let l = d[0].hypot(d[1]);
        if l > 0.0 {
            [d[0] / l, d[1] / l]
        } else {
            [0.0; 2]
        }
    }

    fn csv_line(solution: &Solution, row: &NodalContactRow, friction: &RowFriction<2>) -> String {
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
            "{name},{node},{},{},{projection},{},{},{master_numbering},{},{}",
            num(row.position[0]),
            num(row.position[1]),
            num(row.tributary_length),
            numbering.as_str(),
            u8::from(Self::clamped(solution, row)),
            friction.csv_fields(),
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
    const HEADER: &'static str = "pair,node,x,y,z,gap,pressure,xi_m_u,xi_m_v,master_face,master_node_1,master_node_2,master_node_3,master_node_4,tributary_area,node_numbering,master_numbering,clamped,shear_x,shear_y,shear_z,state,slip";

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

    fn pair_node(row: &FaceNodalRow) -> (usize, usize) {
        (row.pair.index(), row.node.index())
    }

    /// Unused: a 3D node's shear is along its frame
    /// ([`crate::contact::friction::NodalFriction::frame`]); zero where it
    /// has none (no point of the node has a slip, its multipliers 0).
    fn tangent(_: &Solution<3>, _: &State<3>, _: &FaceNodalRow) -> [f64; 3] {
        [0.0; 3]
    }

    fn csv_line(solution: &Solution<3>, row: &FaceNodalRow, friction: &RowFriction<3>) -> String {
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
            "{name},{},{x},{y},{z},{},{},{},{master_numbering},{},{}",
            number(row.node.index()),
            fields.join(","),
            num(row.tributary_area),
            numbering(row.node),
            u8::from(Self::clamped(solution, row)),
            friction.csv_fields(),
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

/// A row's friction columns (module docs): the shear traction on the slave
/// node in global components, its state, and its accumulated slip length
/// (`None`: a frictionless pair, whose slip is not tracked).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowFriction<const D: usize> {
    /// `-t_a tau`: the tangential traction the master exerts on the slave
    /// node (0 on a frictionless pair).
    pub shear: [f64; D],
    /// `open`, `stick` or `slip`.
    pub state: FrictionState,
    /// The accumulated slip length, `None` on a frictionless pair.
    pub slip: Option<f64>,
}

impl<const D: usize> RowFriction<D> {
    /// `shear_x,shear_y(,shear_z),state,slip` (slip empty when `None`).
    fn csv_fields(&self) -> String {
        let shear: Vec<String> = self.shear.iter().map(|&v| num(v)).collect();
        format!(
            "{},{},{}",
            shear.join(","),
            self.state.name(),
            self.slip.map_or(String::new(), num)
        )
    }
}

/// The friction of a state's nodes by `(pair, node)`: the normal multiplier
/// and, with friction, the index into [`State::friction`].
pub struct FrictionTable {
    normal: HashMap<(usize, usize), usize>,
    tangential: HashMap<usize, usize>,
}

impl FrictionTable {
    /// The lookup of `state` (one of `solution`'s states).
    pub fn new<const D: usize>(solution: &Solution<D>, state: &State<D>) -> FrictionTable
    where
        Dim<D>: SurfaceDim<D>,
    {
        FrictionTable {
            normal: solution
                .multiplier_dofs
                .iter()
                .enumerate()
                .map(|(m, d)| ((d.pair, d.node), m))
                .collect(),
            tangential: state
                .friction
                .iter()
                .enumerate()
                .map(|(k, f)| (f.multiplier.index(), k))
                .collect(),
        }
    }

    /// The friction columns of `row` (module docs): on a pair with friction
    /// `-t_a tau`, the node's state and accumulated slip; on a frictionless
    /// one no shear, `open` where the multiplier is exactly zero (an
    /// inactive node) and `slip` elsewhere (frictionless contact slides
    /// freely), no slip.
    pub fn columns<const D: usize>(
        &self,
        solution: &Solution<D>,
        state: &State<D>,
        row: &<Dim<D> as ContactTable<D>>::Row,
    ) -> RowFriction<D>
    where
        Dim<D>: ContactTable<D> + SurfaceDim<D>,
    {
        let (pair, node) = <Dim<D> as ContactTable<D>>::pair_node(row);
        let Some(&m) = self.normal.get(&(pair, node)) else {
            return RowFriction {
                shear: [0.0; D],
                state: FrictionState::Open,
                slip: None,
            };
        };
        match self.tangential.get(&m) {
            Some(&k) => {
                let f = &state.friction[k];
                let t = |d: usize| state.multipliers[f.tangential.index() + d];
                let shear = match f.frame {
                    // 3D: -(t_a1 d_a1 + t_a2 d_a2)
                    Some([d1, d2]) => std::array::from_fn(|c| -(t(0) * d1[c] + t(1) * d2[c])),
                    None => <Dim<D> as ContactTable<D>>::tangent(solution, state, row)
                        .map(|c| -t(0) * c),
                };
                RowFriction {
                    shear,
                    state: f.state,
                    slip: Some(f.slip),
                }
            }
            None => RowFriction {
                shear: [0.0; D],
                state: if state.multipliers[m] == 0.0 {
                    FrictionState::Open
                } else {
                    FrictionState::Slip {
                        direction: [1.0, 0.0],
                        ratio: 0.0,
                    }
                },
                slip: None,
            },
        }
    }
}
