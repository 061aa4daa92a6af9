//! The solid elements' and the external loads' part of the Newton system
//! ([`crate::system`]: its numbering and sink; the contact element's part
//! is `crate::contact`'s `assemble_contact`). The residual is
//!
//! ```text
//! r_u  = f_int(u) + sum_gp w J0 lambda g' - lambda_L f_ref      (free dofs)
//! r_la = sum_gp w J0 N_a g        (active multiplier)  or  l_a  (inactive)
//! ```
//!
//! and the tangent its exact derivative (see [`crate::element::solid`] and
//! [`crate::contact`]). Element matrices are computed in parallel
//! (`crate::par`), a chunk of elements at a time, collected in element
//! order and scattered sequentially into coordinate triplets (or the
//! system's solid block, [`crate::system::Block`]), so the result is
//! deterministic. The triplet index order depends
//! only on the mesh, the prescribed set, the pairing and the presence of
//! Hessians, which lets [`crate::linear`] reuse the symbolic factorisation.

use crate::element::ElementResponse;
use crate::ids::{DofId, ElementId, NodeId};
use crate::linear::{BlockPattern, LinearError};
use crate::mesh::{Geometries, MeshError};
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};
use crate::par;
use crate::system::{DofMap, System};

/// Elements per rayon task.
pub(crate) const PAR_MIN_LEN: usize = 64;

/// Elements whose matrices are computed together before they are scattered
/// (in element order: the result does not depend on it).
const ASSEMBLY_CHUNK: usize = 4096;

/// Adds the solid elements' internal forces, tangents and energies at
/// displacements `u`, element after element, each through the element seam
/// ([`crate::element::ElementGeometry::response`]): for an element of `n`
/// nodes in `D` dimensions, its `D n` rows in dof order, each row's `D n`
/// columns in order. Computes every element's geometry first (a solve
/// keeps them, [`assemble_solid_of`]); fails only when a node was moved
/// since its body was added ([`crate::mesh::Mesh::geometry`]).
pub fn assemble_solid<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    u: &[f64],
    sys: &mut System,
) -> Result<(), MeshError>
where
    Dim<D>: SurfaceDim<D>,
{
    assemble_solid_lifted(model, dofs, u, None, sys)
}

/// [`assemble_solid`], and with `lift` (a displacement increment on the
/// prescribed dofs, every dof's entry, zero on the free ones) also the
/// linearised effect of that increment on the free rows, `K_fp du_p`, added
/// to each free row after its internal force: the residual of the Newton
/// step's linearised Dirichlet predictor (see [`crate::newton`],
/// "Prescribed increments"). Without a lift this is [`assemble_solid`] bit
/// for bit.
pub fn assemble_solid_lifted<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    u: &[f64],
    lift: Option<&[f64]>,
    sys: &mut System,
) -> Result<(), MeshError>
where
    Dim<D>: SurfaceDim<D>,
{
    let geometries = Geometries::of(&model.mesh, None)?;
    assemble_solid_of(model, &geometries, dofs, u, lift, sys);
    Ok(())
}

/// [`assemble_solid_lifted`] over the elements of `geometries` only (in
/// their order, with their geometry; every element's: bit for bit
/// [`assemble_solid_lifted`]): one MPI rank's part of the solid elements
/// (`crate::partition`).
pub fn assemble_solid_of<const D: usize>(
    model: &Model<D>,
    geometries: &Geometries,
    dofs: &DofMap,
    u: &[f64],
    lift: Option<&[f64]>,
    sys: &mut System,
) where
    Dim<D>: SurfaceDim<D>,
{
    let mesh = &model.mesh;
    let count = geometries.len();
    let element = |k: usize| geometries.at(k).0;
    // exactly the triplets this assembly adds, so that a first assembly
    // never holds an old and a doubled buffer at once (none into a block,
    // which holds these elements' entries)
    let triplets: usize = (0..count)
        .filter(|_| sys.block.is_none())
        .map(|k| {
            let eqs = dofs.element_eqs::<D>(&mesh.elements[element(k).index()]);
            let n = eqs.iter().flatten().count();
            n * n
        })
        .sum();
    sys.rows.reserve_exact(triplets);
    sys.cols.reserve_exact(triplets);
    sys.vals.reserve_exact(triplets);
    // the element matrices of one chunk at a time (a hexahedron's is 4.6
    // kB: all of a 10^6-equation mesh's at once would be 1.7 GB)
    for start in (0..count).step_by(ASSEMBLY_CHUNK) {
        let len = ASSEMBLY_CHUNK.min(count - start);
        let responses: Vec<ElementResponse> = par::map(len, PAR_MIN_LEN, |k| {
            let (e, geometry) = geometries.at(start + k);
            let material = &mesh.bodies[mesh.element_body[e.index()]].material;
            geometry.response(&mesh.element_displacements(e, u), material)
        });
        for (k, resp) in responses.iter().enumerate() {
            let el = &mesh.elements[element(start + k).index()];
            let eqs = dofs.element_eqs::<D>(el);
            let f_int = resp.f_int();
            let n = f_int.len();
            for p in 0..n {
                let Some(ep) = eqs[p] else { continue };
                sys.residual[ep.index()] += f_int[p];
                let k = resp.k_row(p);
                match &mut sys.block {
                    // what the block does not hold, as triplets in order
                    // (`System::push`'s split, a node's columns together)
                    Some(block) => {
                        let (rows, cols, vals) = (&mut sys.rows, &mut sys.cols, &mut sys.vals);
                        block.add_row(ep, &eqs[..n], k, D, |eq, v| {
                            rows.push(ep.index() as u32);
                            cols.push(eq.index() as u32);
                            vals.push(v);
                        });
                    }
                    None => {
                        for q in 0..n {
                            if let Some(eq) = eqs[q] {
                                sys.push(ep, eq, k[q]);
                            }
                        }
                    }
                }
                if let Some(du) = lift {
                    for q in (0..n).filter(|&q| eqs[q].is_none()) {
                        sys.residual[ep.index()] +=
                            k[q] * du[DofId::in_dim::<D>(el[q / D], q % D).index()];
                    }
                }
            }
            sys.energy += resp.energy();
        }
    }
}

/// The solid block's pattern ([`crate::linear::BlockPattern`]): the
/// entries the solid elements `elements` of `model` (`None`: all)
/// couple among the free dofs of `dofs`: row `r` (a free dof of node
/// `a`) holds the free dofs of every node sharing an element with `a`,
/// in equation order.
pub fn solid_pattern<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    elements: Option<&[ElementId]>,
) -> Result<BlockPattern, LinearError>
where
    Dim<D>: SurfaceDim<D>,
{
    let mesh = &model.mesh;
    let nodes = mesh.node_count();
    let count = elements.map_or(mesh.element_count(), <[_]>::len);
    let element = |k: usize| -> &[NodeId] {
        let e = elements.map_or(k, |list| list[k].index());
        &mesh.elements[e]
    };
    // the elements of each node
    let mut start = vec![0usize; nodes + 1];
    for k in 0..count {
        for n in element(k) {
            start[n.index() + 1] += 1;
        }
    }
    for a in 0..nodes {
        start[a + 1] += start[a];
    }
    let mut next = start.clone();
    let mut of_node = vec![0u32; start[nodes]];
    for k in 0..count {
        for n in element(k) {
            of_node[next[n.index()]] = k as u32;
            next[n.index()] += 1;
        }
    }
    drop(next);
    let eqs = |a: usize| (0..D).filter_map(move |c| dofs.eq(DofId::in_dim::<D>(NodeId::new(a), c)));
    let mut row_ptr = Vec::with_capacity(dofs.n_free + 1);
    row_ptr.push(0);
    let mut cols: Vec<u32> = Vec::new();
    let mut seen = vec![usize::MAX; nodes];
    let mut neighbours: Vec<usize> = Vec::new();
    let mut columns: Vec<u32> = Vec::new();
    for a in 0..nodes {
        if eqs(a).next().is_none() {
            continue;
        }
        neighbours.clear();
        for &k in &of_node[start[a]..start[a + 1]] {
            for n in element(k as usize) {
                if seen[n.index()] != a {
                    seen[n.index()] = a;
                    neighbours.push(n.index());
                }
            }
        }
        // free equations follow the dof order: sorted nodes give
        // sorted columns
        neighbours.sort_unstable();
        columns.clear();
        columns.extend(
            neighbours
                .iter()
                .flat_map(|&b| eqs(b))
                .map(|e| e.index() as u32),
        );
        for _ in eqs(a) {
            cols.extend_from_slice(&columns);
            row_ptr.push(cols.len());
        }
    }
    cols.shrink_to_fit();
    BlockPattern::new(row_ptr, cols)
}

/// Subtracts the external force at `load_factor` (`load_factor f_ref`, each
/// load with a curve scaled by it instead, [`Model::factor`]); returns its
/// norm.
pub fn add_external<const D: usize>(
    model: &Model<D>,
    dofs: &DofMap,
    load_factor: f64,
    sys: &mut System,
) -> f64
where
    Dim<D>: SurfaceDim<D>,
{
    let f = external_force(model, load_factor);
    for (dof, v) in f.iter().enumerate() {
        if let Some(e) = dofs.eq(DofId::new(dof)) {
            sys.residual[e.index()] -= v;
        }
    }
    norm(&f)
}

/// The norm of the external force at `load_factor` (what [`add_external`]
/// returns, without adding it).
pub fn external_force_norm<const D: usize>(model: &Model<D>, load_factor: f64) -> f64
where
    Dim<D>: SurfaceDim<D>,
{
    norm(&external_force(model, load_factor))
}

/// The external force at `load_factor` at every dof.
fn external_force<const D: usize>(model: &Model<D>, load_factor: f64) -> Vec<f64>
where
    Dim<D>: SurfaceDim<D>,
{
    let mut f = vec![0.0; model.dof_count()];
    for l in &model.loads {
        f[l.dof.index()] += model.factor(l.amplitude, load_factor) * l.value;
    }
    f
}

fn norm(f: &[f64]) -> f64 {
    f.iter().map(|v| v * v).sum::<f64>().sqrt()
}
