//! How Newton's matrix fills PETSc's: the solid block's rows
//! ([`crate::linear::Block`]) handed over as they are, each column mapped
//! into PETSc's numbering, and the remaining triplets compressed into rows
//! once per pattern ([`super::compress`]) with the decoupled rows'
//! diagonals.
//!
//! # Sums
//!
//! PETSc's matrix is zeroed, then every row added: the block's entries
//! (each the sum, in Newton's order, of its contributions) and the
//! compressed triplets' (each the sum of its triplets in their order). A
//! block entry and a triplet never share an entry (a contribution goes to
//! the block when its pattern holds the entry), so each entry is zero plus
//! one sum: the matrix of summing every contribution in Newton's order, bit
//! for bit. Across ranks PETSc then sums the ranks' rows on their owners.
//!
//! # Memory
//!
//! Per pattern this keeps only the triplets' indices (to recognise the
//! pattern next time) and their compressed rows: with the block, a few
//! entries per contact point. The block's rows go to PETSc from Newton's
//! buffer with one row of mapped columns as work space.

use super::objects::{Matrix, PetscError, RowAdder, Serial};
use super::{Compressed, Numbering, compress};
use crate::linear::{Block, BlockPattern, LinearError};

/// Where a free row's diagonal entry is.
#[derive(Debug, Clone, Copy)]
enum Diagonal {
    /// The block's entry.
    Block(usize),
    /// The compressed triplets' entry.
    Triplet(usize),
}

/// What fills PETSc's matrix for one pattern (module docs).
pub(super) struct Fill {
    /// The block's pattern ([`BlockPattern::id`]), `None` without one.
    block: Option<u64>,
    /// Newton's triplet rows and columns this pattern was built from.
    rows: Vec<u32>,
    cols: Vec<u32>,
    /// The triplets and the decoupled diagonals compressed in PETSc's
    /// numbering (every row of the numbering; sorted unique columns), each
    /// one's entry, and the entries' values.
    row_ptr: Vec<i32>,
    pcols: Vec<i32>,
    slot: Vec<u32>,
    values: Vec<f64>,
    /// Each free Newton row's diagonal entry where this rank has one, in
    /// row order.
    diagonal: Vec<(u32, Diagonal)>,
}

impl Fill {
    /// The fill of the block `block` (if any) and the triplets `(rows,
    /// cols)` in the numbering `nb`.
    pub(super) fn new(
        nb: &Numbering,
        n_free: usize,
        block: Option<&BlockPattern>,
        rows: &[u32],
        cols: &[u32],
    ) -> Result<Fill, LinearError> {
        if let Some(b) = block
            && (b.rows() > nb.rows.len() || b.cols().iter().any(|&c| c as usize >= nb.rows.len()))
        {
            return Err(LinearError::Petsc(format!(
                "a block of {} rows for {} equations",
                b.rows(),
                nb.rows.len()
            )));
        }
        if i32::try_from(nb.n).is_err() {
            return Err(LinearError::Petsc(format!(
                "{} equations exceed PETSc's 32-bit index range",
                nb.n
            )));
        }
        let Compressed {
            row_ptr,
            cols: pcols,
            slot,
        } = compress(nb, rows, cols)?;
        let mut diagonal = Vec::new();
        for r in 0..n_free {
            let at = block.and_then(|b| {
                let e = crate::ids::EquationIndex::new(r);
                b.find(e, e)
            });
            let d = match at {
                Some(k) => Some(Diagonal::Block(k)),
                None => {
                    let pr = nb.rows[r];
                    let (a, b) = (row_ptr[pr] as usize, row_ptr[pr + 1] as usize);
                    pcols[a..b]
                        .binary_search(&(pr as i32))
                        .ok()
                        .map(|k| Diagonal::Triplet(a + k))
                }
            };
            if let Some(d) = d {
                diagonal.push((r as u32, d));
            }
        }
        Ok(Fill {
            block: block.map(BlockPattern::id),
            rows: rows.to_vec(),
            cols: cols.to_vec(),
            values: vec![0.0; pcols.len()],
            row_ptr,
            pcols,
            slot,
            diagonal,
        })
    }

    /// Whether Newton's block and triplets are those this fill was built
    /// from (then only the values change).
    pub(super) fn holds(&self, block: Option<&BlockPattern>, rows: &[u32], cols: &[u32]) -> bool {
        self.has_block(block) && self.rows == rows && self.cols == cols
    }

    /// Whether `block` is the block this fill was built with (both none
    /// included).
    pub(super) fn has_block(&self, block: Option<&BlockPattern>) -> bool {
        self.block == block.map(BlockPattern::id)
    }

    /// Calls `entry(row, col)` for every entry this rank adds, in PETSc's
    /// numbering (the block's, then the compressed triplets').
    pub(super) fn entries(
        &self,
        nb: &Numbering,
        block: Option<&BlockPattern>,
        mut entry: impl FnMut(usize, usize),
    ) {
        if let Some(b) = block {
            for (r, w) in b.row_ptr().windows(2).enumerate() {
                let pr = nb.rows[r];
                for &c in &b.cols()[w[0]..w[1]] {
                    entry(pr, nb.rows[c as usize]);
                }
            }
        }
        for (r, w) in self.row_ptr.windows(2).enumerate() {
            for &c in &self.pcols[w[0] as usize..w[1] as usize] {
                entry(r, c as usize);
            }
        }
    }

    /// Fills PETSc's matrix `a` (this rank's part) from the block `block`
    /// (over this fill's pattern) and the triplets' values `vals`: the
    /// triplets summed into their entries, the decoupled rows' diagonal set
    /// to `decoupled` of this rank's free diagonal entries (`(row, value)`
    /// in row order), every row added.
    pub(super) fn fill_matrix(
        &mut self,
        s: &Serial,
        a: &mut Matrix,
        nb: &Numbering,
        (block, vals): (Option<&Block>, &[f64]),
        decoupled: impl FnOnce(&mut dyn Iterator<Item = (usize, f64)>) -> Result<f64, LinearError>,
    ) -> Result<(), LinearError> {
        if !self.has_block(block.map(|b| &*b.pattern)) {
            return Err(LinearError::Singular(
                "the block is not over the analysed pattern".into(),
            ));
        }
        self.sum_triplets(vals)?;
        let values = block.map_or(&[][..], |b| &b.values[..]);
        let d = decoupled(&mut self.diagonal(values))?;
        self.set_decoupled(d);
        a.fill(s, |add| {
            self.add_to(add, nb, block.map(|b| (&*b.pattern, values)))
        })?;
        Ok(())
    }

    /// Sums the triplets' values `vals` into their entries.
    fn sum_triplets(&mut self, vals: &[f64]) -> Result<(), LinearError> {
        if vals.len() != self.rows.len() {
            return Err(LinearError::Singular(format!(
                "{} values for {} triplets",
                vals.len(),
                self.rows.len()
            )));
        }
        self.values.fill(0.0);
        for (&k, &v) in self.slot.iter().zip(vals) {
            self.values[k as usize] += v;
        }
        Ok(())
    }

    /// The free rows' diagonal entries this rank holds, with the block's
    /// values `block` (after [`Fill::sum_triplets`]): `(row, value)` in
    /// row order.
    fn diagonal<'a>(&'a self, block: &'a [f64]) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.diagonal.iter().map(|&(r, d)| {
            let v = match d {
                Diagonal::Block(k) => block[k],
                Diagonal::Triplet(k) => self.values[k],
            };
            (r as usize, v)
        })
    }

    /// Sets the decoupled rows' diagonal to `d`.
    fn set_decoupled(&mut self, d: f64) {
        for &k in &self.slot[self.rows.len()..] {
            self.values[k as usize] = d;
        }
    }

    /// Adds this rank's rows to PETSc's matrix being filled: the block's
    /// (`block`: its pattern and values) with their columns mapped, then the
    /// compressed triplets'.
    fn add_to(
        &self,
        add: &mut RowAdder<'_>,
        nb: &Numbering,
        block: Option<(&BlockPattern, &[f64])>,
    ) -> Result<(), PetscError> {
        let mut mapped: Vec<i32> = Vec::new();
        if let Some((b, values)) = block {
            for (r, w) in b.row_ptr().windows(2).enumerate() {
                if w[0] == w[1] {
                    continue;
                }
                mapped.clear();
                // PETSc's rows fit its 32-bit index (checked in `new`)
                mapped.extend(
                    b.cols()[w[0]..w[1]]
                        .iter()
                        .map(|&c| nb.rows[c as usize] as i32),
                );
                add.add(nb.rows[r], &mapped, &values[w[0]..w[1]])?;
            }
        }
        for (r, w) in self.row_ptr.windows(2).enumerate() {
            let (a, b) = (w[0] as usize, w[1] as usize);
            if a < b {
                add.add(r, &self.pcols[a..b], &self.values[a..b])?;
            }
        }
        Ok(())
    }
}
