//! ASCII VTK XML unstructured-grid (`.vtu`) output, written by hand.
//!
//! One file per state: the points are the **reference** coordinates (z = 0
//! in 2D) and the point field `displacement` (3 components, z = 0 in 2D)
//! moves them to the deformed configuration (ParaView: *Warp By Vector*).
//! Cells are the mesh's elements, each with its kind's cell type
//! ([`crate::element::ElementKind::vtk_cell_type`]: quadrilaterals 9,
//! triangles 5, hexahedra 12, tetrahedra 10), in element order. Fields:
//!
//! * point data: `displacement`, `multiplier` (the Lagrange multiplier at
//!   slave nodes, summed over pairs, zero elsewhere), `contact_pressure`
//!   (`p = -multiplier`, positive in compression), `contact_gap` (the gap
//!   of the node projected onto the master face,
//!   [`crate::contact::nodal_contact`]), `contact_slave` (1 at a slave node of any
//!   pair, 0 elsewhere) and `contact_paired` (1 where the node projects
//!   into a master segment, 0 elsewhere), `contact_clamped` (1 at a slave
//!   node held by supports on both sides, whose multiplier is a reaction
//!   between supports: [`ContactTable::clamped`]), the friction columns of
//!   `contact.csv` ([`super::contact_table`]): `contact_shear` (3
//!   components, z 0 in 2D; summed over a node's pairs), `contact_state`
//!   (0 open, 1 stick, 2 slip; the largest over a node's pairs) and
//!   `contact_slip` (the accumulated slip length, 0 on a frictionless
//!   pair; the largest over a node's pairs). `contact_gap` is 0 where
//!   `contact_paired` is 0. A node that is a slave node of two pairs
//!   carries the sum of its pressures (as `multiplier`) and the gap of the
//!   pair where `|g|` is smallest (the first such pair on a tie);
//!   `node_number` (the node's tag in the mesh file its body was read
//!   from, the `[mesh] file` of a scene; the internal 0-based index for a
//!   node of a block body, which is the VTK point index) and
//!   `node_number_from_mesh_file` (1 where `node_number` is a mesh file's
//!   tag, 0 where it is the internal index); see [`crate::Mesh::node_number`];
//! * cell data: `cauchy_stress` and `pk2_stress` (components
//!   `[xx, yy, xy]` in 2D, `[xx, yy, zz, yz, xz, xy]` in 3D, averaged over
//!   the element's Gauss points) and `body` (the body index).
//!
//! The contact point data come from the nodal contact table of the
//! dimension ([`ContactTable`]: in 2D the node projected with its slave
//! segment, in 3D the node as a point of its first slave face).
//!
//! A state whose nodal contact table does not exist (a
//! [`ContactTableError`]: e.g. a collapsed slave
//! segment) has no `.vtu` document: [`vtu_string`] returns the error and
//! [`write_vtu_state`] reports it as an `InvalidData` I/O error, writing
//! nothing.

use std::fmt::Write as _;
use std::path::Path;

use crate::mesh::NodeNumbering;
use crate::model::Dim;
use crate::solution::{Solution, State};

use super::atomic::write_atomic;
use super::contact_table::{ContactTable, ContactTableError, FrictionTable};
use crate::contact::friction::FrictionState;

/// Writes the final state of `solution` to `path`.
pub fn write_vtu<const D: usize>(
    path: impl AsRef<Path>,
    solution: &Solution<D>,
) -> std::io::Result<()>
where
    Dim<D>: ContactTable<D>,
{
    write_vtu_state(path, solution, &solution.final_state)
}

/// Writes `state` (e.g. one of [`Solution::snapshots`]) to `path`.
pub fn write_vtu_state<const D: usize>(
    path: impl AsRef<Path>,
    solution: &Solution<D>,
    state: &State<D>,
) -> std::io::Result<()>
where
    Dim<D>: ContactTable<D>,
{
    let text = vtu_string(solution, state)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))?;
    write_atomic(path, text)
}

fn array(
    out: &mut String,
    ty: &str,
    name: &str,
    components: usize,
    values: impl Iterator<Item = String>,
) {
    let _ = write!(out, "        <DataArray type=\"{ty}\" Name=\"{name}\"");
    if components > 1 {
        let _ = write!(out, " NumberOfComponents=\"{components}\"");
    }
    out.push_str(" format=\"ascii\">\n");
    let mut line = 0;
    for v in values {
        if line == 0 {
            out.push_str("          ");
        } else {
            out.push(' ');
        }
        out.push_str(&v);
        line += 1;
        if line == 12 {
            out.push('\n');
            line = 0;
        }
    }
    if line != 0 {
        out.push('\n');
    }
    out.push_str("        </DataArray>\n");
}

/// A point or vector of `D` components as VTK's three (z = 0 in 2D).
fn padded<const D: usize>(v: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|c| v.get(c).copied().unwrap_or(0.0))
}

fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:e}")
    } else {
        "nan".to_owned()
    }
}

/// The `.vtu` document of `state`; an error when its nodal contact table
/// cannot be computed (see the module docs).
pub fn vtu_string<const D: usize>(
    solution: &Solution<D>,
    state: &State<D>,
) -> Result<String, ContactTableError>
where
    Dim<D>: ContactTable<D>,
{
    let mesh = &solution.mesh;
    let n = mesh.node_count();
    let m = mesh.elements.len();
    let mut multiplier = vec![0.0; n];
    for (dof, value) in solution.multiplier_dofs.iter().zip(&state.multipliers) {
        multiplier[dof.node] += value;
    }
    let mut slave = vec![0u8; n];
    let mut clamped = vec![0u8; n];
    let mut gap: Vec<Option<f64>> = vec![None; n];
    let mut shear = vec![[0.0; 3]; n];
    let mut friction_state = vec![0u8; n];
    let mut slip = vec![0.0; n];
    let friction = FrictionTable::new(solution, state);
    // (node, gap, clamped, friction) of every row of the nodal contact table
    let rows: Vec<_> = <Dim<D> as ContactTable<D>>::rows(solution, state)?
        .iter()
        .map(|r| {
            let (node, g) = <Dim<D> as ContactTable<D>>::node_gap(r);
            let c = <Dim<D> as ContactTable<D>>::clamped(solution, r);
            (node, g, c, friction.columns(solution, state, r))
        })
        .collect();
    for (node, g, c, f) in rows {
        slave[node] = 1;
        clamped[node] |= u8::from(c);
        for (k, v) in f.shear.iter().enumerate() {
            shear[node][k] += v;
        }
        friction_state[node] = friction_state[node].max(match f.state {
            FrictionState::Open => 0,
            FrictionState::Stick => 1,
            FrictionState::Slip { .. } => 2,
        });
        slip[node] = f64::max(slip[node], f.slip.unwrap_or(0.0));
        if let Some(g) = g
            && gap[node].is_none_or(|old| g.abs() < old.abs())
        {
            gap[node] = Some(g);
        }
    }
    let stresses = solution.element_mean_stresses(state)?;
    let voigt = if D == 2 { 3 } else { 6 };
    let mut out = String::with_capacity(200 * (n + m) + 1024);
    out.push_str("<?xml version=\"1.0\"?>\n");
    out.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    out.push_str("  <UnstructuredGrid>\n");
    let _ = writeln!(
        out,
        "    <Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{m}\">"
    );
    out.push_str("      <PointData Vectors=\"displacement\" Scalars=\"contact_pressure\">\n");
    array(
        &mut out,
        "Float64",
        "displacement",
        3,
        state.displacements.iter().flat_map(|d| padded(d).map(num)),
    );
    array(
        &mut out,
        "Float64",
        "multiplier",
        1,
        multiplier.iter().map(|&v| num(v)),
    );
    array(
        &mut out,
        "Float64",
        "contact_pressure",
        1,
        multiplier.iter().map(|&v| num(-v)),
    );
    array(
        &mut out,
        "Float64",
        "contact_gap",
        1,
        gap.iter().map(|g| num(g.unwrap_or(0.0))),
    );
    array(
        &mut out,
        "UInt8",
        "contact_slave",
        1,
        slave.iter().map(|s| s.to_string()),
    );
    array(
        &mut out,
        "UInt8",
        "contact_paired",
        1,
        gap.iter().map(|g| u8::from(g.is_some()).to_string()),
    );
    array(
        &mut out,
        "UInt8",
        "contact_clamped",
        1,
        clamped.iter().map(|c| c.to_string()),
    );
    array(
        &mut out,
        "Float64",
        "contact_shear",
        3,
        shear.iter().flat_map(|s| s.map(num)),
    );
    array(
        &mut out,
        "UInt8",
        "contact_state",
        1,
        friction_state.iter().map(|s| s.to_string()),
    );
    array(
        &mut out,
        "Float64",
        "contact_slip",
        1,
        slip.iter().map(|&s| num(s)),
    );
    let numbers: Vec<(u64, NodeNumbering)> = (0..n).map(|k| mesh.node_number(k)).collect();
    array(
        &mut out,
        "UInt64",
        "node_number",
        1,
        numbers.iter().map(|(t, _)| t.to_string()),
    );
    array(
        &mut out,
        "UInt8",
        "node_number_from_mesh_file",
        1,
        numbers
            .iter()
            .map(|(_, k)| u8::from(*k == NodeNumbering::MeshFile).to_string()),
    );
    out.push_str("      </PointData>\n");
    out.push_str("      <CellData Scalars=\"body\">\n");
    array(
        &mut out,
        "Float64",
        "cauchy_stress",
        voigt,
        stresses
            .iter()
            .flat_map(|s| s.cauchy().iter().map(|&v| num(v))),
    );
    array(
        &mut out,
        "Float64",
        "pk2_stress",
        voigt,
        stresses
            .iter()
            .flat_map(|s| s.pk2().iter().map(|&v| num(v))),
    );
    array(
        &mut out,
        "Int32",
        "body",
        1,
        mesh.element_body.iter().map(|b| b.to_string()),
    );
    out.push_str("      </CellData>\n");
    out.push_str("      <Points>\n");
    array(
        &mut out,
        "Float64",
        "reference_coordinates",
        3,
        mesh.nodes_ref.iter().flat_map(|p| padded(p).map(num)),
    );
    out.push_str("      </Points>\n");
    out.push_str("      <Cells>\n");
    array(
        &mut out,
        "Int64",
        "connectivity",
        1,
        mesh.elements
            .iter()
            .flatten()
            .map(|v| v.index().to_string()),
    );
    array(
        &mut out,
        "Int64",
        "offsets",
        1,
        mesh.elements.iter().scan(0, |end, el| {
            *end += el.len();
            Some(end.to_string())
        }),
    );
    array(
        &mut out,
        "UInt8",
        "types",
        1,
        mesh.elements
            .iter()
            .map(|el| el.kind().vtk_cell_type().to_string()),
    );
    out.push_str("      </Cells>\n");
    out.push_str("    </Piece>\n");
    out.push_str("  </UnstructuredGrid>\n");
    out.push_str("</VTKFile>\n");
    Ok(out)
}
