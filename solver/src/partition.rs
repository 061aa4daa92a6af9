//! Which elements and nodes each MPI rank owns in a solve across ranks
//! (`linear::Ranks`: one rank unless PETSc's solver was launched under
//! `mpiexec -n N`).
//!
//! The elements are the vertices of their dual graph, two elements adjacent
//! when they share a facet (at least `D` nodes: a face of hexahedra or
//! tetrahedra in 3D, an edge in 2D); the linear solver cuts it into one part
//! per rank ([`LinearSolver::partition`]: PETSc's graph partitioner), each
//! rank giving the graph's rows of one contiguous block of elements. A node
//! belongs to the lowest rank among its elements'.
//!
//! The parts balance the elements' weights, each the entries of Newton's
//! matrix its rank assembles for it: its solid entries `(n D)^2` (`n`
//! nodes), and a share of the contact's. A rank assembles the points of
//! the slave nodes it owns ([`ContactShare`]), each point about
//! `(2 f D + f)^2` entries (`f = 2^(D-1)` nodes on the slave and on the
//! master facet, and the slave's multipliers); the layout's points are
//! spread evenly over its multipliers' nodes, and a node's share evenly
//! over its elements. Without the contact's weight the partitioner put
//! every slave node of the 3D scaling scene on one rank, which then held
//! the whole contact beside half the volume (docs/petsc.md).
//!
//! On one rank nothing is built: every element is the rank's, in element
//! order, so the assembly is the one-rank assembly bit for bit.
//!
//! Invariant: the ranks' element sets are disjoint and cover the mesh, and
//! every rank computes the same partition (the partitioner's answer is
//! gathered on every rank).

use crate::contact::{ContactShare, MultiplierDof};
use crate::ids::ElementId;
use crate::linear::{LinearError, LinearSolver, Ranks};
use crate::model::Model;
use crate::model::{Dim, SurfaceDim};

/// This rank's elements and every node's rank (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Partition {
    /// The ranks of the solve, this one's among them.
    pub ranks: Ranks,
    /// This rank's elements in element order; `None`: every element.
    elements: Option<Vec<ElementId>>,
    /// Each node's rank (empty on one rank).
    pub node_rank: Vec<usize>,
}

impl Partition {
    /// One rank: every element, no node ranks.
    pub fn one() -> Partition {
        Partition {
            ranks: Ranks::ONE,
            elements: None,
            node_rank: Vec::new(),
        }
    }

    /// The partition of `model`'s elements across `linear`'s ranks, the
    /// contact layout's `multipliers` and `points` weighing on their
    /// elements (module docs; collective across the ranks;
    /// [`Partition::one`] on one rank).
    pub fn of<const D: usize>(
        model: &Model<D>,
        linear: &dyn LinearSolver,
        multipliers: &[MultiplierDof],
        points: usize,
    ) -> Result<Partition, LinearError>
    where
        Dim<D>: SurfaceDim<D>,
    {
        let ranks = linear.ranks();
        if ranks.size <= 1 {
            return Ok(Partition::one());
        }
        let mesh = &model.mesh;
        let n_el = mesh.element_count();
        let n_nodes = mesh.node_count();
        let too_big =
            || LinearError::Petsc(format!("{n_el} elements exceed the 32-bit index range"));
        // each node's elements (compressed)
        let mut start = vec![0usize; n_nodes + 1];
        for el in &mesh.elements {
            for n in el.iter() {
                start[n.index() + 1] += 1;
            }
        }
        for i in 0..n_nodes {
            start[i + 1] += start[i];
        }
        let mut next = start.clone();
        let mut of_node = vec![0u32; start[n_nodes]];
        for (e, el) in mesh.elements.iter().enumerate() {
            for n in el.iter() {
                of_node[next[n.index()]] = u32::try_from(e).map_err(|_| too_big())?;
                next[n.index()] += 1;
            }
        }
        drop(next);
        // the contact's entries at each slave node (module docs)
        let mut at_node = vec![0.0f64; n_nodes];
        if !multipliers.is_empty() {
            let f = 1usize << (D - 1);
            let per_point = ((2 * f * D + f) * (2 * f * D + f)) as f64;
            let each = points as f64 * per_point / multipliers.len() as f64;
            for m in multipliers {
                at_node[m.node.index()] += each;
            }
        }
        // this rank's block of the dual graph's rows
        let first = n_el * ranks.rank / ranks.size;
        let last = n_el * (ranks.rank + 1) / ranks.size;
        let mut row_ptr = vec![0i32];
        let mut cols: Vec<i32> = Vec::new();
        let mut weights: Vec<i32> = Vec::with_capacity(last - first);
        let mut around: Vec<u32> = Vec::new();
        for e in first..last {
            let el = &mesh.elements[e];
            let solid = (el.len() * D * el.len() * D) as f64;
            let contact: f64 = el
                .iter()
                .map(|n| at_node[n.index()] / (start[n.index() + 1] - start[n.index()]) as f64)
                .sum();
            weights.push((solid + contact).round().clamp(1.0, i32::MAX as f64) as i32);
            around.clear();
            for n in el.iter() {
                around.extend_from_slice(&of_node[start[n.index()]..start[n.index() + 1]]);
            }
            around.sort_unstable();
            for run in around.chunk_by(|a, b| a == b) {
                if run[0] as usize != e && run.len() >= D {
                    cols.push(i32::try_from(run[0]).map_err(|_| too_big())?);
                }
            }
            row_ptr.push(i32::try_from(cols.len()).map_err(|_| too_big())?);
        }
        let part = linear.partition(n_el, &row_ptr, &cols, &weights)?;
        if part.len() != n_el || part.iter().any(|&r| r >= ranks.size) {
            return Err(LinearError::Petsc(format!(
                "the partitioner gave {} parts in 0..{} for {n_el} elements",
                part.len(),
                ranks.size
            )));
        }
        let mut node_rank = vec![usize::MAX; n_nodes];
        for (el, &r) in mesh.elements.iter().zip(&part) {
            for n in el.iter() {
                node_rank[n.index()] = node_rank[n.index()].min(r);
            }
        }
        // a node in no element (none in a checked model) goes to rank 0
        for r in node_rank.iter_mut().filter(|r| **r == usize::MAX) {
            *r = 0;
        }
        let elements = (0..n_el)
            .filter(|&e| part[e] == ranks.rank)
            .map(ElementId::new)
            .collect();
        Ok(Partition {
            ranks,
            elements: Some(elements),
            node_rank,
        })
    }

    /// This rank's elements in element order (`None`: every element).
    pub fn elements(&self) -> Option<&[ElementId]> {
        self.elements.as_deref()
    }

    /// Whether this rank assembles the terms that are not split across the
    /// ranks: the node ties, the friction, the external force and the
    /// regularisation (rank 0; they are small against the volume).
    pub fn assembles_root_terms(&self) -> bool {
        self.ranks.is_root()
    }

    /// This rank's share of the contact element, `multipliers` its normal
    /// multiplier dofs: the multipliers whose slave node this rank owns
    /// and their points ([`ContactShare`]); `None` on one rank (the whole
    /// element).
    pub fn contact_share(&self, multipliers: &[MultiplierDof]) -> Option<ContactShare> {
        (self.ranks.size > 1).then(|| ContactShare {
            multipliers: multipliers
                .iter()
                .map(|m| self.node_rank[m.node.index()] == self.ranks.rank)
                .collect(),
            root: self.ranks.is_root(),
        })
    }
}

#[cfg(test)]
mod tests {
    use std::cell::RefCell;
    use std::time::Duration;

    use super::*;
    use crate::assembly::{assemble_solid_lifted, assemble_solid_of};
    use crate::contact::{ContactLayout, ContactSpace};
    use crate::mesh::Geometries;
    use crate::system::{DofMap, System};

    /// A graph as `LinearSolver::partition` receives it: the vertex count,
    /// this rank's row pointers, columns and weights.
    type Graph = (usize, Vec<i32>, Vec<i32>, Vec<i32>);

    /// A solver that only plays rank `rank` of `size`: its partition puts
    /// element `e` on rank `e % size` and keeps the graph it was given.
    struct Playing {
        ranks: Ranks,
        graph: RefCell<Option<Graph>>,
    }

    impl LinearSolver for Playing {
        fn analyse(&mut self, _: usize, _: &[u32], _: &[u32]) -> Result<(), LinearError> {
            unreachable!("the partition solves nothing")
        }
        fn factor(&mut self, _: &[f64]) -> Result<(), LinearError> {
            unreachable!()
        }
        fn solve(&mut self, _: &[f64]) -> Result<Vec<f64>, LinearError> {
            unreachable!()
        }
        fn symbolic_factorisations(&self) -> usize {
            0
        }
        fn symbolic_time(&self) -> Duration {
            Duration::ZERO
        }
        fn ranks(&self) -> Ranks {
            self.ranks
        }
        fn partition(
            &self,
            n_total: usize,
            row_ptr: &[i32],
            cols: &[i32],
            weights: &[i32],
        ) -> Result<Vec<usize>, LinearError> {
            *self.graph.borrow_mut() =
                Some((n_total, row_ptr.to_vec(), cols.to_vec(), weights.to_vec()));
            Ok((0..n_total).map(|e| e % self.ranks.size).collect())
        }
    }

    /// On the paper scene played as two ranks: each rank gives its block of
    /// the dual graph (an element's neighbours share an edge with it, and
    /// its edge neighbours are all there), the ranks' elements are disjoint
    /// and cover the mesh, a node is on the lowest rank of its elements, and
    /// the ranks' solid assemblies add up to the one-rank assembly.
    #[test]
    fn two_ranks_split_the_elements_and_their_sums_are_the_whole() {
        let scene =
            crate::Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "paper").unwrap();
        let model = scene.build_model::<2>().unwrap();
        let mesh = &model.mesh;
        let n_el = mesh.element_count();
        let shared = |a: usize, b: usize| {
            mesh.elements[a]
                .iter()
                .filter(|n| mesh.elements[b].contains(n))
                .count()
        };
        let layout = <ContactLayout as ContactSpace<2>>::build(&model, None).unwrap();
        assert!(layout.point_count() > 0);
        let mut weight = 0.0;
        let parts: Vec<Partition> = (0..2)
            .map(|rank| {
                let solver = Playing {
                    ranks: Ranks { rank, size: 2 },
                    graph: RefCell::new(None),
                };
                let p = Partition::of(&model, &solver, layout.multipliers(), layout.point_count())
                    .unwrap();
                let (total, row_ptr, cols, weights) = solver.graph.into_inner().unwrap();
                assert_eq!(total, n_el);
                // each element weighs its solid entries (4 nodes, 2 dofs
                // each) and its share of the contact's
                assert_eq!(weights.len(), row_ptr.len() - 1);
                assert!(weights.iter().all(|&w| w >= 64), "{weights:?}");
                weight += weights.iter().map(|&w| f64::from(w)).sum::<f64>();
                let first = n_el * rank / 2;
                assert_eq!(row_ptr.len(), n_el * (rank + 1) / 2 - first + 1);
                for (k, w) in row_ptr.windows(2).enumerate() {
                    let e = first + k;
                    let mine: Vec<usize> = cols[w[0] as usize..w[1] as usize]
                        .iter()
                        .map(|&c| c as usize)
                        .collect();
                    let expected: Vec<usize> =
                        (0..n_el).filter(|&f| f != e && shared(e, f) >= 2).collect();
                    assert_eq!(mine, expected, "element {e}");
                }
                p
            })
            .collect();
        // the ranks' weights sum to every element's solid entries and every
        // point's contact entries (2 + 2 nodes of 2 dofs and 2 multipliers),
        // up to the rounding of each element's
        let expected = (64 * n_el + 100 * layout.point_count()) as f64;
        assert!(
            (weight - expected).abs() <= 0.5 * n_el as f64,
            "{weight} against {expected}"
        );
        let mut owner = vec![None; n_el];
        for (rank, p) in parts.iter().enumerate() {
            assert_eq!(p.ranks, Ranks { rank, size: 2 });
            assert_eq!(p.assembles_root_terms(), rank == 0);
            for e in p.elements().unwrap() {
                assert!(
                    owner[e.index()].replace(rank).is_none(),
                    "element {e:?} twice"
                );
            }
        }
        assert!(
            owner.iter().all(Option::is_some),
            "every element has a rank"
        );
        assert_eq!(parts[0].node_rank, parts[1].node_rank);
        for (node, &r) in parts[0].node_rank.iter().enumerate() {
            let lowest = mesh
                .elements
                .iter()
                .enumerate()
                .filter(|(_, el)| el.iter().any(|n| n.index() == node))
                .map(|(e, _)| owner[e].unwrap())
                .min()
                .unwrap();
            assert_eq!(r, lowest, "node {node}");
        }
        // the ranks' assemblies add up to the whole, at a deformed state
        let dofs = DofMap::new(&model, 0);
        let u: Vec<f64> = (0..model.dof_count())
            .map(|i| 1e-3 * ((i * 7) % 11) as f64)
            .collect();
        let mut whole = System::new(dofs.n_eq());
        assemble_solid_lifted(&model, &dofs, &u, None, &mut whole).unwrap();
        let mut sum = System::new(dofs.n_eq());
        let mut triplets = 0;
        for p in &parts {
            let mut part = System::new(dofs.n_eq());
            let geometries = Geometries::of(&model.mesh, p.elements()).unwrap();
            assemble_solid_of(&model, &geometries, &dofs, &u, None, &mut part);
            for (s, v) in sum.residual.iter_mut().zip(&part.residual) {
                *s += v;
            }
            sum.energy += part.energy;
            triplets += part.rows.len();
        }
        assert_eq!(triplets, whole.rows.len());
        let scale = whole.residual.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in sum.residual.iter().zip(&whole.residual) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} against {b}");
        }
        assert!((sum.energy - whole.energy).abs() <= 1e-12 * whole.energy.abs());
        // one rank: every element, the one-rank assembly bit for bit
        let one = Partition::of(
            &model,
            &Playing {
                ranks: Ranks::ONE,
                graph: RefCell::new(None),
            },
            layout.multipliers(),
            layout.point_count(),
        )
        .unwrap();
        assert_eq!(one, Partition::one());
        let mut again = System::new(dofs.n_eq());
        let geometries = Geometries::of(&model.mesh, one.elements()).unwrap();
        assemble_solid_of(&model, &geometries, &dofs, &u, None, &mut again);
        assert_eq!(again.residual, whole.residual);
        assert_eq!(again.vals, whole.vals);
    }
}
