//! A block of the matrix in compressed rows over a fixed pattern, beside
//! the coordinate triplets: Newton's solid block, the entries of the free
//! displacement rows that the solid elements couple, held once per entry
//! instead of one triplet per element entry.
//!
//! A hexahedron adds 24 x 24 entries to the tangent; as triplets (16 bytes
//! each) they are the largest buffer of a 3D run, 2.3 times the distinct
//! entries they sum into. The block keeps one value (8 bytes) per distinct
//! entry beside a pattern (4 bytes per entry) built once from the mesh and
//! the prescribed set (`crate::assembly::solid_pattern`). A linear solver that
//! takes it ([`crate::linear::LinearSolver::takes_block`]) gets the tangent
//! as the block plus the remaining triplets.
//!
//! # Sums
//!
//! Every contribution whose entry is in the pattern is added to the block
//! in the order it arrives, whatever its source (the contact element and
//! the ties too), the rest become triplets. So an entry in the pattern is
//! the sum of the same terms, in the same order, as the triplets it
//! replaces, starting from zero: a solver that adds the block's value to
//! zero and the remaining triplets in their order forms the same matrix,
//! bit for bit, as one summing all triplets in order. The largest absolute
//! contribution added ([`Block::max_abs`]) stands in for the replaced
//! triplets' in the checks that use it (the regularisation's `max|K_uu|`,
//! the singularity test).
//!
//! Invariant ([`BlockPattern::check_invariants`]): `row_ptr` has one more
//! entry than there are rows and does not decrease, and each row's columns
//! are strictly increasing.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::ids::EquationIndex;

use super::LinearError;

/// Tells patterns apart without comparing their entries.
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// Compressed rows over Newton's first `rows()` equations (module docs).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BlockPattern {
    /// Distinguishes this pattern from every other built in the process
    /// (a solver's cached analysis is keyed on it).
    id: u64,
    /// Where each row's entries start (`rows() + 1`).
    row_ptr: Vec<usize>,
    /// Each entry's column (strictly increasing in a row).
    cols: Vec<u32>,
}

impl BlockPattern {
    /// The pattern of compressed rows `row_ptr`, `cols`, checked against
    /// the invariant (module docs).
    pub fn new(row_ptr: Vec<usize>, cols: Vec<u32>) -> Result<BlockPattern, LinearError> {
        let p = BlockPattern {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            row_ptr,
            cols,
        };
        p.check_invariants().map_err(LinearError::Singular)?;
        Ok(p)
    }

    /// A pattern of `rows` rows, each listed with its strictly increasing
    /// columns.
    pub fn from_rows(rows: &[Vec<u32>]) -> Result<BlockPattern, LinearError> {
        let mut row_ptr = vec![0];
        let mut cols = Vec::new();
        for r in rows {
            cols.extend_from_slice(r);
            row_ptr.push(cols.len());
        }
        BlockPattern::new(row_ptr, cols)
    }

    /// Identifies this pattern among those of the process (equal ids: the
    /// same pattern).
    pub fn id(&self) -> u64 {
        self.id
    }

    /// How many rows (Newton's equations `0..rows()`).
    pub fn rows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// How many entries.
    pub fn len(&self) -> usize {
        self.cols.len()
    }

    /// Whether the pattern has no entry.
    pub fn is_empty(&self) -> bool {
        self.cols.is_empty()
    }

    /// Where each row's entries start (`rows() + 1`).
    pub fn row_ptr(&self) -> &[usize] {
        &self.row_ptr
    }

    /// Each entry's column.
    pub fn cols(&self) -> &[u32] {
        &self.cols
    }

    /// The row of every entry, in entry order.
    pub fn entry_rows(&self) -> impl Iterator<Item = u32> + '_ {
        self.row_ptr
            .windows(2)
            .enumerate()
            .flat_map(|(r, w)| std::iter::repeat_n(r as u32, w[1] - w[0]))
    }

    /// The entry of `(r, c)`, `None` when the pattern does not hold it.
    pub fn find(&self, r: EquationIndex, c: EquationIndex) -> Option<usize> {
        let (r, c) = (r.index(), c.index());
        if r >= self.rows() {
            return None;
        }
        let (a, b) = (self.row_ptr[r], self.row_ptr[r + 1]);
        let c = u32::try_from(c).ok()?;
        self.cols[a..b].binary_search(&c).ok().map(|k| a + k)
    }

    /// The pattern's invariant (module docs): `Err` names the first row
    /// that breaks it.
    pub fn check_invariants(&self) -> Result<(), String> {
        if self.row_ptr.first() != Some(&0) || self.row_ptr.last() != Some(&self.cols.len()) {
            return Err("row pointers do not span the entries".into());
        }
        for (r, w) in self.row_ptr.windows(2).enumerate() {
            if w[1] < w[0] {
                return Err(format!("row {r} ends before it starts"));
            }
            if self.cols[w[0]..w[1]].windows(2).any(|p| p[0] >= p[1]) {
                return Err(format!("row {r}'s columns are not strictly increasing"));
            }
        }
        Ok(())
    }
}

/// The solid block's values over a pattern ([`BlockPattern`], module docs).
#[derive(Debug, Clone)]
pub struct Block {
    /// The pattern (shared with the solve that built it).
    pub pattern: std::sync::Arc<BlockPattern>,
    /// One value per entry of the pattern.
    pub values: Vec<f64>,
    /// The largest absolute contribution added so far (0 when none).
    pub max_abs: f64,
}

impl Block {
    /// Zero values over `pattern`.
    pub fn new(pattern: std::sync::Arc<BlockPattern>) -> Block {
        Block {
            values: vec![0.0; pattern.len()],
            pattern,
            max_abs: 0.0,
        }
    }

    /// Zeroes the values and the largest contribution.
    pub fn clear(&mut self) {
        self.values.fill(0.0);
        self.max_abs = 0.0;
    }

    /// Adds row `r`'s contributions `vals` at the columns `cols` (`None`:
    /// nothing added) in order, each as [`Block::add`] would, handing each
    /// one the pattern does not hold to `rest` (in order). The columns come
    /// in groups of `group` (a node's dofs): within a group the entry after
    /// a found one is tried first (a node's free dofs are consecutive
    /// equations), so a row of an element of `n` nodes costs `n` searches
    /// instead of one per column.
    pub fn add_row(
        &mut self,
        r: EquationIndex,
        cols: &[Option<EquationIndex>],
        vals: &[f64],
        group: usize,
        mut rest: impl FnMut(EquationIndex, f64),
    ) {
        let (row_start, row_end) = match self.pattern.row_ptr.get(r.index()..r.index() + 2) {
            Some(w) => (w[0], w[1]),
            None => (0, 0),
        };
        let group = group.max(1);
        // the entry of the last column added, a guess for the next
        let mut last: Option<usize> = None;
        for (q, (&c, &v)) in cols.iter().zip(vals).enumerate() {
            let Some(c) = c else { continue };
            let guess = last.filter(|&k| {
                q % group != 0 && k + 1 < row_end && self.pattern.cols[k + 1] as usize == c.index()
            });
            let at = match guess {
                Some(k) => Some(k + 1),
                None => u32::try_from(c.index()).ok().and_then(|c| {
                    self.pattern.cols[row_start..row_end]
                        .binary_search(&c)
                        .ok()
                        .map(|k| row_start + k)
                }),
            };
            last = at;
            match at {
                Some(k) => {
                    self.values[k] += v;
                    self.max_abs = self.max_abs.max(v.abs());
                }
                None => rest(c, v),
            }
        }
    }

    /// Adds `v` to entry `(r, c)` when the pattern holds it (`false`
    /// otherwise: nothing added).
    pub fn add(&mut self, r: EquationIndex, c: EquationIndex, v: f64) -> bool {
        match self.pattern.find(r, c) {
            Some(k) => {
                self.values[k] += v;
                self.max_abs = self.max_abs.max(v.abs());
                true
            }
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eq(i: usize) -> EquationIndex {
        EquationIndex::new(i)
    }

    /// Entries are found where the rows list them and nowhere else; a
    /// block adds only into its pattern; malformed rows are refused.
    #[test]
    fn entries_are_found_and_malformed_rows_refused() {
        let p = BlockPattern::from_rows(&[vec![0, 2], vec![], vec![1, 2, 5]]).unwrap();
        assert_eq!((p.rows(), p.len()), (3, 5));
        assert_eq!(p.entry_rows().collect::<Vec<_>>(), vec![0, 0, 2, 2, 2]);
        assert_eq!(p.find(eq(0), eq(2)), Some(1));
        assert_eq!(p.find(eq(2), eq(5)), Some(4));
        assert_eq!(p.find(eq(1), eq(1)), None);
        assert_eq!(p.find(eq(0), eq(1)), None);
        assert_eq!(p.find(eq(3), eq(0)), None, "a row past the block");
        let q = BlockPattern::from_rows(&[vec![0, 2], vec![], vec![1, 2, 5]]).unwrap();
        assert_ne!(p.id(), q.id(), "each pattern its own id");
        let mut b = Block::new(std::sync::Arc::new(p));
        assert!(b.add(eq(2), eq(1), -3.0));
        assert!(b.add(eq(2), eq(1), 1.0));
        assert!(!b.add(eq(1), eq(0), 7.0));
        assert_eq!(b.values, vec![0.0, 0.0, -2.0, 0.0, 0.0]);
        assert_eq!(b.max_abs, 3.0);
        b.clear();
        assert_eq!((b.values.iter().sum::<f64>(), b.max_abs), (0.0, 0.0));
        // a row at once equals its entries one by one, whatever the guesses
        // meet: a column missing (`None`), consecutive columns the pattern
        // does not hold, a group's columns out of order
        let cols = [
            Some(eq(2)),
            Some(eq(5)),
            None,
            Some(eq(1)),
            Some(eq(3)),
            Some(eq(2)),
            Some(eq(1)),
        ];
        let vals = [1.0, 2.0, 3.0, -4.0, 5.0, 6.0, -7.5];
        let mut rest = vec![];
        b.add_row(eq(2), &cols, &vals, 2, |c, v| rest.push((c.index(), v)));
        let mut one = Block::new(b.pattern.clone());
        let mut one_rest = vec![];
        for (c, v) in cols.iter().zip(vals) {
            if let Some(c) = c
                && !one.add(eq(2), *c, v)
            {
                one_rest.push((c.index(), v));
            }
        }
        assert_eq!(
            (&b.values, b.max_abs, &rest),
            (&one.values, one.max_abs, &one_rest)
        );
        assert_eq!(rest, vec![(3, 5.0)]);
        // a row past the block: everything to `rest`
        let mut past = vec![];
        b.add_row(eq(7), &cols[..2], &vals[..2], 1, |c, v| {
            past.push((c.index(), v))
        });
        assert_eq!(past, vec![(2, 1.0), (5, 2.0)]);
        assert!(
            BlockPattern::from_rows(&[vec![1, 1]]).is_err(),
            "a repeated column"
        );
        assert!(
            BlockPattern::from_rows(&[vec![2, 1]]).is_err(),
            "columns out of order"
        );
        assert!(
            BlockPattern::new(vec![0, 2, 1], vec![0, 1]).is_err(),
            "a row ending early"
        );
        assert!(
            BlockPattern::new(vec![1], vec![]).is_err(),
            "pointers not from zero"
        );
    }
}
