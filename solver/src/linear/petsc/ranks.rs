//! The PETSc solve across MPI ranks (`mpiexec -n N gapsim run SCENE
//! --linear petsc`): the same system, Krylov method and preconditioner as
//! [`super::PetscKrylov`], distributed.
//!
//! # Who owns what
//!
//! Every rank holds the whole model and state ([`super::super::Ranks`]);
//! the elements are partitioned across the ranks by a graph partitioner
//! (`crate::partition`), and a node belongs to the lowest rank among its
//! elements' ([`SystemLayout::node_rank`]). PETSc's numbering puts the
//! ranks' nodes one rank after the other, each node's `D` components
//! together, and the constraint rows (multipliers, ties) after the last
//! rank's nodes, on the last rank:
//!
//! ```text
//! rank 0: D (its nodes)          rows of field "u"
//! rank 1: D (its nodes)             ...
//! ...
//! rank N-1: D (its nodes), then every constraint row (field "lambda")
//! ```
//!
//! so each rank owns one contiguous range, its "u" rows whole nodes (block
//! size `D`) with their coordinates for the rigid-body near-null space.
//!
//! # Assembly
//!
//! Each rank hands this solver its own triplets (its elements' and its slave
//! nodes' contact's, and on rank 0 the regularisation's) in Newton's
//! numbering. They are
//! compressed into rows once per pattern (the one-rank path's `compress`);
//! each row's owner preallocates the sum of the ranks' entry counts in that
//! row (an upper bound: two ranks adding to one entry count it twice, and
//! PETSc releases what is not filled at the first assembly), and each
//! iteration PETSc sums every rank's rows into their owner's. A
//! prescribed dof's decoupled row gets the mean absolute diagonal of the
//! free rows, summed over the ranks, as on one rank.
//!
//! # Every rank decides the same
//!
//! Each call is collective: the pattern is rebuilt when any rank's changed
//! (a maximum over the ranks), the right-hand side is the replicated
//! residual's owned part, the correction is gathered on every rank, and the
//! singularity check takes the largest matrix entry over all ranks
//! ([`LinearSolver::solve_system`]). So the
//! Newton loops of all ranks take the same branch at every step.

use std::time::{Duration, Instant};

use super::fill::Fill;
use super::objects::{Comm, IndexSet, Ksp, Matrix, NearNullSpace, Serial, Vector, serial};
use super::{
    Numbering, Objects, STALL_FACTOR, STALL_WINDOW, options_for, petsc_rows, reset_if_poisoned,
    retry_stage, through_parts,
};
use crate::linear::{
    Block, BlockPattern, KrylovCounts, LinearError, LinearSolver, Ranks, SystemLayout,
};

/// PETSc's numbering across the ranks (module docs), and this rank's part.
struct RankNumbering {
    /// The one-rank numbering's fields: PETSc's row of every Newton
    /// equation, the global size, the displacement rows, this rank's
    /// decoupled rows (prescribed dofs of its nodes), the block size.
    numbering: Numbering,
    /// Every rank's first row, and the global size last (`size + 1`).
    starts: Vec<usize>,
    /// This rank's first row and row count.
    first: usize,
    n_local: usize,
    /// This rank's displacement rows (from `first`).
    n_local_u: usize,
    /// Newton's free displacement equations.
    n_free: usize,
    /// This rank's nodes' reference coordinates, in PETSc's order.
    coordinates: Vec<f64>,
}

impl RankNumbering {
    fn new(n: usize, l: &SystemLayout, ranks: Ranks) -> Result<RankNumbering, LinearError> {
        let dim = l.dim;
        let n_free = l.free_dofs.len();
        let n_u = l.coordinates.len();
        let nodes = n_u / dim.max(1);
        if n < n_free || dim == 0 || !n_u.is_multiple_of(dim) || l.node_rank.len() != nodes {
            return Err(LinearError::Petsc(format!(
                "the layout ({n_free} free dofs, {n_u} coordinates in {dim}D, {} node ranks) \
                 does not fit {n} equations",
                l.node_rank.len()
            )));
        }
        if let Some(&r) = l.node_rank.iter().find(|&&r| r >= ranks.size) {
            return Err(LinearError::Petsc(format!(
                "a node is given to rank {r} of {}",
                ranks.size
            )));
        }
        // the nodes in rank order: the position of each
        let mut start = vec![0usize; ranks.size + 1];
        for &r in &l.node_rank {
            start[r + 1] += 1;
        }
        for r in 0..ranks.size {
            start[r + 1] += start[r];
        }
        let mut next = start.clone();
        let mut position = vec![0usize; nodes];
        for (p, &r) in l.node_rank.iter().enumerate() {
            position[p] = next[r];
            next[r] += 1;
        }
        let petsc_dof = |dof: usize| dim * position[dof / dim] + dof % dim;
        let (rows, free) = petsc_rows(n, l, petsc_dof)?;
        let n_total = n_u + n - n_free;
        let first = dim * start[ranks.rank];
        let n_local_u = dim * (start[ranks.rank + 1] - start[ranks.rank]);
        let last = ranks.rank + 1 == ranks.size;
        let n_local = n_local_u + if last { n - n_free } else { 0 };
        let mine = |p: usize| l.node_rank[p] == ranks.rank;
        let decoupled = (0..n_u)
            .filter(|&d| !free[d] && mine(d / dim))
            .map(petsc_dof)
            .collect();
        let starts = (0..=ranks.size)
            .map(|r| {
                if r == ranks.size {
                    n_total
                } else {
                    dim * start[r]
                }
            })
            .collect();
        let mut coordinates = vec![0.0; n_local_u];
        for p in (0..nodes).filter(|&p| mine(p)) {
            let at = dim * position[p] - first;
            coordinates[at..at + dim].copy_from_slice(&l.coordinates[dim * p..dim * (p + 1)]);
        }
        Ok(RankNumbering {
            numbering: Numbering {
                rows,
                n: n_total,
                n_u,
                decoupled,
                dim,
            },
            starts,
            first,
            n_local,
            n_local_u,
            n_free,
            coordinates,
        })
    }

    /// The preallocation of this rank's rows: for each, at most how many
    /// entries fall in its own columns and in the others' (every rank's
    /// distinct entries of the row, `fill`'s with the block `block`, added
    /// up: exact but where two ranks add to one entry). Collective.
    fn row_counts(
        &self,
        s: &Serial,
        fill: &Fill,
        block: Option<&BlockPattern>,
    ) -> Result<(Vec<i32>, Vec<i32>), LinearError> {
        let n = self.numbering.n;
        // [own columns of every row | others' columns of every row]
        let mut counts = vec![0.0; 2 * n];
        fill.entries(&self.numbering, block, |r, c| {
            let owner = self.starts.partition_point(|&f| f <= r) - 1;
            let own = self.starts[owner]..self.starts[owner + 1];
            counts[if own.contains(&c) { r } else { n + r }] += 1.0;
        });
        s.sum(&mut counts)?;
        let mine = self.first..self.first + self.n_local;
        let cap = |v: f64, most: usize| v.min(most as f64) as i32;
        let d = counts[mine.clone()]
            .iter()
            .map(|&v| cap(v, self.n_local))
            .collect();
        let o = counts[n + mine.start..n + mine.end]
            .iter()
            .map(|&v| cap(v, n - self.n_local))
            .collect();
        Ok((d, o))
    }
}

/// The cached pattern across ranks: the numbering, what fills this rank's
/// part of PETSc's matrix, PETSc's objects.
struct RankPattern {
    numbering: RankNumbering,
    fill: Fill,
    objects: Objects,
}

/// PETSc's Krylov solve of the Newton system across MPI ranks (module docs).
pub struct PetscRanks {
    options: String,
    ranks: Ranks,
    layout: Option<SystemLayout>,
    pattern: Option<RankPattern>,
    factored: bool,
    rtol: f64,
    counts: KrylovCounts,
    symbolic_factorisations: usize,
    symbolic_time: Duration,
}

// SAFETY: as `PetscKrylov`: PETSc's objects are only touched under
// `serial()`'s guard.
unsafe impl Send for PetscRanks {}

impl PetscRanks {
    /// A solver of PETSc options `options` on the ranks `ranks`.
    pub fn new(options: &str, ranks: Ranks) -> PetscRanks {
        PetscRanks {
            options: options.to_owned(),
            ranks,
            layout: None,
            pattern: None,
            factored: false,
            rtol: 1e-8,
            counts: KrylovCounts {
                ranks: ranks.size,
                ..KrylovCounts::default()
            },
            symbolic_factorisations: 0,
            symbolic_time: Duration::ZERO,
        }
    }

    fn pattern_options(&self) -> String {
        let constrained = self
            .pattern
            .as_ref()
            .is_some_and(|p| p.numbering.numbering.n > p.numbering.numbering.n_u);
        options_for(&self.options, constrained, &self.counts)
    }

    fn build(
        &self,
        s: &Serial,
        n: usize,
        block: Option<&BlockPattern>,
        (rows, cols): (&[u32], &[u32]),
    ) -> Result<RankPattern, LinearError> {
        let layout = self.layout.as_ref().ok_or_else(|| {
            LinearError::Petsc("a solve across ranks needs the system's layout".into())
        })?;
        let numbering = RankNumbering::new(n, layout, self.ranks)?;
        let nb = &numbering.numbering;
        let fill = Fill::new(nb, numbering.n_free, block, rows, cols)?;
        let constrained = nb.n > nb.n_u;
        s.replace_options(&options_for(&self.options, constrained, &self.counts))?;
        let (d_nnz, o_nnz) = numbering.row_counts(s, &fill, block)?;
        let a = Matrix::new(s, Comm::World, numbering.n_local, nb.n, (&d_nnz, &o_nnz))?;
        drop((d_nnz, o_nnz));
        let mut ksp = Ksp::new(s, Comm::World, &a)?;
        if retry_stage(&self.options, &self.counts).is_some() {
            ksp.watch_stall(s, STALL_WINDOW, STALL_FACTOR)?;
        }
        let mut splits = vec![];
        let mut near_null = None;
        if constrained && ksp.is_fieldsplit(s)? {
            let mut u =
                IndexSet::range(s, Comm::World, numbering.first, numbering.n_local_u, nb.dim)?;
            if nb.dim > 1 {
                let sp = NearNullSpace::rigid_body(s, Comm::World, &numbering.coordinates, nb.dim)?;
                u.attach_near_null_space(s, &sp)?;
                near_null = Some(sp);
            }
            let lambda = IndexSet::range(
                s,
                Comm::World,
                numbering.first + numbering.n_local_u,
                numbering.n_local - numbering.n_local_u,
                1,
            )?;
            ksp.add_split(s, "u", &u)?;
            ksp.add_split(s, "lambda", &lambda)?;
            splits = vec![u, lambda];
        }
        let b = Vector::new(s, Comm::World, numbering.n_local, 1)?;
        let x = Vector::new(s, Comm::World, numbering.n_local, 1)?;
        Ok(RankPattern {
            numbering,
            fill,
            objects: Objects {
                ksp,
                splits,
                _near_null: near_null,
                a,
                b,
                x,
                comm: Comm::World,
            },
        })
    }

    /// Drops the cached pattern's PETSc objects under the guard.
    fn pattern_reset(&mut self) {
        if self.pattern.is_some()
            && let Ok(_s) = serial()
        {
            self.pattern = None;
        }
    }
}

impl Drop for PetscRanks {
    fn drop(&mut self) {
        self.pattern_reset();
    }
}

impl PetscRanks {
    /// [`LinearSolver::analyse_with_block`] with the block optional.
    fn analyse_parts(
        &mut self,
        n: usize,
        block: Option<&BlockPattern>,
        rows: &[u32],
        cols: &[u32],
    ) -> Result<(), LinearError> {
        let s = serial()?;
        let here = self.pattern.as_ref().is_some_and(|p| {
            p.numbering.numbering.rows.len() == n && p.fill.holds(block, rows, cols)
        });
        // rebuilt (collectively) when any rank's pattern changed
        let mut changed = [if here { 0.0 } else { 1.0 }];
        s.max(&mut changed)?;
        if changed[0] == 0.0 {
            return Ok(());
        }
        let t = Instant::now();
        self.pattern = None;
        self.factored = false;
        self.pattern = Some(self.build(&s, n, block, (rows, cols))?);
        self.symbolic_factorisations += 1;
        self.symbolic_time += t.elapsed();
        Ok(())
    }

    /// [`LinearSolver::solve`] with the cached objects.
    fn solve_cached(&mut self, rhs: &[f64]) -> Result<Vec<f64>, LinearError> {
        if !std::mem::take(&mut self.factored) {
            return Err(LinearError::Singular("no factorisation".into()));
        }
        let s = serial()?;
        let rtol = self.rtol;
        let p = self
            .pattern
            .as_mut()
            .ok_or_else(|| LinearError::Singular("no pattern".into()))?;
        let nb = &p.numbering;
        if rhs.len() != nb.numbering.rows.len() {
            return Err(LinearError::Singular(format!(
                "right-hand side of {} for {} equations",
                rhs.len(),
                nb.numbering.rows.len()
            )));
        }
        let mut b = vec![0.0; nb.n_local];
        let owned = nb.first..nb.first + nb.n_local;
        for (i, &v) in rhs.iter().enumerate() {
            let r = nb.numbering.rows[i];
            if owned.contains(&r) {
                b[r - nb.first] = v;
            }
        }
        let constrained = nb.numbering.n > nb.numbering.n_u;
        let o = &mut p.objects;
        o.solve(&s, &b, rtol, (&self.options, constrained), &mut self.counts)?;
        let x = o.x.gather_all(&s, nb.numbering.n)?;
        Ok(nb.numbering.rows.iter().map(|&r| x[r]).collect())
    }

    /// [`LinearSolver::factor_with_block`] with the block optional.
    fn factor_parts(&mut self, block: Option<&Block>, vals: &[f64]) -> Result<(), LinearError> {
        self.factored = false;
        let s = serial()?;
        let options = self.pattern_options();
        let Some(p) = self.pattern.as_mut() else {
            return Err(LinearError::Singular("no pattern".into()));
        };
        let RankPattern {
            numbering,
            fill,
            objects,
        } = p;
        let n_free = numbering.n_free;
        // the decoupled rows' diagonal: the mean absolute diagonal of the
        // free displacement rows, every rank's contributions summed
        let mean = |entries: &mut dyn Iterator<Item = (usize, f64)>| {
            let mut diagonal = vec![0.0; n_free];
            for (r, v) in entries {
                diagonal[r] = v;
            }
            s.sum(&mut diagonal)?;
            let sum: f64 = diagonal.iter().map(|d| d.abs()).sum();
            Ok(if sum > 0.0 { sum / n_free as f64 } else { 1.0 })
        };
        let nb = &numbering.numbering;
        fill.fill_matrix(&s, &mut objects.a, nb, (block, vals), mean)?;
        s.replace_options(&options)?;
        objects.ksp.set_up(&s)?;
        self.factored = true;
        Ok(())
    }
}

impl LinearSolver for PetscRanks {
    through_parts!();

    fn symbolic_factorisations(&self) -> usize {
        self.symbolic_factorisations
    }

    fn symbolic_time(&self) -> Duration {
        self.symbolic_time
    }

    fn set_layout(&mut self, layout: &SystemLayout) {
        self.layout = Some(layout.clone());
        self.pattern_reset();
    }

    fn set_forcing(&mut self, rtol: f64) {
        self.rtol = rtol;
    }

    fn krylov(&self) -> Option<KrylovCounts> {
        Some(self.counts.clone())
    }

    fn ranks(&self) -> Ranks {
        self.ranks
    }

    fn sum_over_ranks(&self, values: &mut [f64]) -> Result<(), LinearError> {
        Ok(serial()?.sum(values)?)
    }

    fn max_over_ranks(&self, values: &mut [f64]) -> Result<(), LinearError> {
        Ok(serial()?.max(values)?)
    }

    fn partition(
        &self,
        n_total: usize,
        row_ptr: &[i32],
        cols: &[i32],
        weights: &[i32],
    ) -> Result<Vec<usize>, LinearError> {
        let s = serial()?;
        // the partitioner reads the options too (`-mat_partitioning_type`)
        s.replace_options(&options_for(&self.options, true, &KrylovCounts::default()))?;
        Ok(s.partition(n_total, row_ptr, cols, weights)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three nodes in 2D, node 1 on rank 0 and nodes 0 and 2 on rank 1,
    /// node 0 held in x, one constraint row: each rank's contiguous range
    /// (its nodes whole, the constraint on the last rank), PETSc's row of
    /// every Newton equation, the decoupled row on its node's rank, the
    /// rank's coordinates in its order.
    #[test]
    fn each_rank_owns_its_nodes_and_the_last_the_constraints() {
        let layout = SystemLayout {
            dim: 2,
            // dof 0 (node 0, x) prescribed
            free_dofs: vec![1, 2, 3, 4, 5],
            coordinates: vec![0.0, 0.0, 1.0, 0.0, 2.0, 0.0],
            node_rank: vec![1, 0, 1],
        };
        let n = 6;
        let r0 = RankNumbering::new(n, &layout, Ranks { rank: 0, size: 2 }).unwrap();
        let r1 = RankNumbering::new(n, &layout, Ranks { rank: 1, size: 2 }).unwrap();
        // PETSc's order: node 1 (rank 0), then nodes 0 and 2 (rank 1), then
        // the constraint
        let rows = vec![3, 0, 1, 4, 5, 6];
        assert_eq!(r0.numbering.rows, rows);
        assert_eq!(r1.numbering.rows, rows);
        assert_eq!((r0.first, r0.n_local, r0.n_local_u), (0, 2, 2));
        assert_eq!((r1.first, r1.n_local, r1.n_local_u), (2, 5, 4));
        assert_eq!(r0.numbering.n, 7);
        assert!(r0.numbering.decoupled.is_empty());
        assert_eq!(r1.numbering.decoupled, vec![2]);
        assert_eq!(r0.coordinates, vec![1.0, 0.0]);
        assert_eq!(r1.coordinates, vec![0.0, 0.0, 2.0, 0.0]);
        // a node given to a rank that does not exist is refused
        let mut bad = layout.clone();
        bad.node_rank[2] = 2;
        assert!(RankNumbering::new(n, &bad, Ranks { rank: 0, size: 2 }).is_err());
        // node ranks missing: refused, not guessed
        bad.node_rank.clear();
        assert!(RankNumbering::new(n, &bad, Ranks { rank: 0, size: 2 }).is_err());
    }
}
