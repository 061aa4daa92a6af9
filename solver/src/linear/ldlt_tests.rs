//! Tests of `ldlt.rs` (its child module, private items included): the
//! LDL^T against LU on quasi-definite systems without a fallback, the
//! refinement of an inactive multiplier to the assembled system, the LU
//! fallback of an indefinite stiffness (its reason logged), the inertia check of a mode held
//! only by a constraint, the factor's nonzeros, and a singular matrix or
//! mismatched sizes (errors, never a panic).

use super::*;
use faer::sparse::linalg::SupernodalThreshold;

/// The triplets `(row, col, value)` as the index and value lists.
fn triplets(t: &[(usize, usize, f64)]) -> (Vec<u32>, Vec<u32>, Vec<f64>) {
    (
        t.iter().map(|e| e.0 as u32).collect(),
        t.iter().map(|e| e.1 as u32).collect(),
        t.iter().map(|e| e.2).collect(),
    )
}

/// Solves with the LDL^T `ldlt` (as it is set up) and a fresh LU; returns
/// both solutions.
fn solve_both(
    ldlt: &mut SparseLdlt,
    n: usize,
    t: &[(usize, usize, f64)],
    b: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let (rows, cols, vals) = triplets(t);
    let x = ldlt.solve_system(n, &rows, &cols, &vals, b).unwrap();
    let y = SparseLu::new()
        .solve_system(n, &rows, &cols, &vals, b)
        .unwrap();
    (x, y)
}

/// Solves with a fresh LDL^T and a fresh LU; returns both solutions and
/// the LDL^T solver.
fn both(n: usize, t: &[(usize, usize, f64)], b: &[f64]) -> (Vec<f64>, Vec<f64>, SparseLdlt) {
    let mut ldlt = SparseLdlt::new();
    let (x, y) = solve_both(&mut ldlt, n, t, b);
    (x, y, ldlt)
}

fn assert_close(x: &[f64], y: &[f64]) {
    for (a, b) in x.iter().zip(y) {
        assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{x:?} vs {y:?}");
    }
}

/// A quasi-definite saddle-point system (`K` positive definite, an
/// active regularised multiplier): LDL^T, no fallback, LU's solution.
#[test]
fn quasi_definite_without_fallback() {
    let t = [
        (0, 0, 4.0),
        (1, 1, 3.0),
        (0, 1, 1.0),
        (1, 0, 1.0),
        (0, 2, 1.0),
        (2, 0, 1.0),
        (1, 2, 2.0),
        (2, 1, 2.0),
        (2, 2, -1e-3),
    ];
    let (x, y, s) = both(3, &t, &[1.0, -2.0, 0.5]);
    assert_close(&x, &y);
    assert_eq!(s.fallbacks(), 0);
    assert_eq!(s.symbolic_factorisations(), 1);
}

/// An inactive multiplier as the assembly writes it (`G^T` in its
/// column, zeros in its row, a unit diagonal): the lower triangle is
/// decoupled, and one refinement step recovers the unsymmetric system's
/// solution exactly, without fallback.
#[test]
fn inactive_multiplier_is_refined_to_the_assembled_system() {
    let t = [
        (0, 0, 4.0),
        (1, 1, 3.0),
        (0, 1, 1.0),
        (1, 0, 1.0),
        (0, 2, 1.0),
        (2, 0, 0.0),
        (1, 2, 2.0),
        (2, 1, 0.0),
        (2, 2, 1.0),
        (2, 2, 0.0),
    ];
    let (x, y, s) = both(3, &t, &[1.0, -2.0, 0.5]);
    assert_close(&x, &y);
    assert_eq!(x[2], 0.5);
    assert_eq!(s.fallbacks(), 0);
    assert!(s.refinements() >= 1);
}

/// An indefinite `K` (pivots 1 and -3 where both rows count positive) is
/// kept: the refined solve is LU's, and the solve is recorded with its
/// inertia rather than handed to the LU.
#[test]
fn indefinite_stiffness_is_kept_and_recorded() {
    let t = [(0, 0, 1.0), (1, 1, 1.0), (0, 1, 2.0), (1, 0, 2.0)];
    let (x, y, s) = both(2, &t, &[1.0, 0.0]);
    assert_close(&x, &y);
    assert_eq!(s.fallbacks(), 0);
    assert_eq!(
        s.indefinite_log(),
        [IndefiniteSolve {
            solve: 1,
            inertia: Inertia {
                positive: 1,
                expected: 2
            },
        }]
    );
}

/// A zero pivot falls back to LU, which solves: `[0 1; 1 0]` has one in
/// any order.
#[test]
fn a_zero_pivot_falls_back_to_lu() {
    let t = [(0, 1, 1.0), (1, 0, 1.0)];
    let (x, y, s) = both(2, &t, &[1.0, 0.0]);
    assert_close(&x, &y);
    assert_close(&x, &[0.0, 1.0]);
    assert_eq!(
        s.fallback_log(),
        [Fallback {
            solve: 1,
            reason: FallbackReason::Pivot,
            lu: LuOutcome::Solved,
        }]
    );
    // the multiplier eliminated before its dofs: a zero pivot too
    let t = [(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 0.0)];
    let (x, y, _) = both(2, &t, &[1.0, 1.0]);
    assert_close(&x, &y);
}

/// With the available memory unknown, the LU fallback runs without a
/// limit (a limit's refusal is `tests/lu_fallback_memory.rs`, its own
/// process: the limit holds for every thread).
#[test]
fn an_lu_fallback_without_a_known_memory_runs() {
    let (rows, cols, vals) = triplets(&[(0, 1, 1.0), (1, 0, 1.0)]);
    let mut s = SparseLdlt::with_available_memory(|| None);
    let x = s.solve_system(2, &rows, &cols, &vals, &[1.0, 0.0]).unwrap();
    assert_eq!(s.fallbacks(), 1);
    assert_eq!(s.fallback_log()[0].lu, LuOutcome::Solved);
    assert_close(&x, &[0.0, 1.0]);
}

/// `K` slightly indefinite along a mode that only the constraint holds
/// (a body held only by contact): `K = [1 -1; -1 1 - d]`, the multiplier
/// on dof 1 ordered after it. The pivots are `1, -d, 1/d + eps`: two
/// with the wrong sign for their rows but the right inertia (two
/// positive, one negative), so the LDL^T is kept and gives LU's
/// solution without fallback. A per-row sign check fell back here.
#[test]
fn mode_held_only_by_the_constraint_keeps_the_ldlt() {
    let d = 0.02;
    let t = [
        (0, 0, 1.0),
        (0, 1, -1.0),
        (1, 0, -1.0),
        (1, 1, 1.0 - d),
        (1, 2, 1.0),
        (2, 1, 1.0),
        (2, 2, -1e-8),
    ];
    let mut s = SparseLdlt::new();
    s.set_constraints_from(2);
    let (x, y) = solve_both(&mut s, 3, &t, &[1.0, 0.5, -0.25]);
    assert_close(&x, &y);
    assert_eq!(s.fallbacks(), 0);
    // the multiplier after both displacement dofs: the wrong-signed pair
    let p = s.pattern.as_ref().unwrap();
    let fwd = p.cholesky.perm().unwrap().arrays().0;
    assert_eq!(fwd[2], 2);
    // K indefinite on the constraint's null space (buckling: the
    // constraint on dof 2, the indefinite block on dofs 0 and 1, every
    // diagonal positive): two positive pivots for three expected, kept
    // and recorded
    let t = [
        (0, 0, 1.0),
        (0, 1, 2.0),
        (1, 0, 2.0),
        (1, 1, 1.0),
        (2, 2, 1.0),
        (2, 3, 1.0),
        (3, 2, 1.0),
        (3, 3, -1e-8),
    ];
    s.set_constraints_from(3);
    let (x, y) = solve_both(&mut s, 4, &t, &[1.0, 0.5, -0.25, 0.125]);
    assert_close(&x, &y);
    assert_eq!(s.fallbacks(), 0);
    assert_eq!(
        s.indefinite_log(),
        [IndefiniteSolve {
            solve: 2,
            inertia: Inertia {
                positive: 2,
                expected: 3
            },
        }]
    );
}

/// A displacement row whose assembled diagonal is negative (the
/// geometric stiffness of a large multiplier) inside its own constraint's
/// row: `K = [-0.41 0.1; 0.1 1]`, the multiplier on dof 0. `K` is
/// positive definite on the constraint's null space (dof 1), so the
/// matrix has two positive eigenvalues and one negative: the rows counted
/// by kind (both displacement rows positive) find the expected inertia.
/// Counted by diagonal, without the layout hint, the same matrix looks
/// indefinite. With the constraint on dof 1 instead, `K` is negative on
/// the null space (dof 0): one positive pivot for two displacement rows.
/// Every one of them is solved by the LDL^T, as the LU solves it.
#[test]
fn a_negative_diagonal_held_by_its_constraint_has_the_expected_inertia() {
    let solve = |constrained: usize, hint: bool| {
        let t = [
            (0, 0, -0.41),
            (0, 1, 0.1),
            (1, 0, 0.1),
            (1, 1, 1.0),
            (constrained, 2, 1.0),
            (2, constrained, 1.0),
            (2, 2, -1e-8),
        ];
        let mut s = SparseLdlt::new();
        if hint {
            s.set_constraints_from(2);
        }
        let (x, y) = solve_both(&mut s, 3, &t, &[1.0, 0.5, -0.25]);
        assert_close(&x, &y);
        assert_eq!(s.fallbacks(), 0);
        s.indefinite_log()
            .iter()
            .map(|i| (i.inertia.positive, i.inertia.expected))
            .collect::<Vec<_>>()
    };
    assert_eq!(solve(0, true), []);
    assert_eq!(solve(0, false), [(2, 1)]);
    assert_eq!(solve(1, true), [(1, 2)]);
}

/// The fill: a tridiagonal matrix factorises without fill (`2n - 1`
/// entries of `L`), a dense one fills its whole lower triangle, and a
/// 2D grid Laplacian's count is the exact elimination fill of its AMD
/// ordering (counted here by eliminating the graph), which is what a
/// simplicial factor stores and less than a supernodal one stores.
#[test]
fn factor_nonzeros_counts_the_lower_triangle_of_l() {
    let analysed = |n: usize, t: &[(usize, usize)]| {
        let rows: Vec<u32> = t.iter().map(|e| e.0 as u32).collect();
        let cols: Vec<u32> = t.iter().map(|e| e.1 as u32).collect();
        let mut s = SparseLdlt::new();
        assert_eq!(s.factor_nonzeros(), None);
        s.analyse(n, &rows, &cols).unwrap();
        s
    };
    let n = 50;
    let tri: Vec<(usize, usize)> = (0..n)
        .flat_map(|i: usize| [(i, i), (i, i.saturating_sub(1)), (i.saturating_sub(1), i)])
        .collect();
    assert_eq!(analysed(n, &tri).factor_nonzeros(), Some(2 * n - 1));
    let dense: Vec<(usize, usize)> = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).collect();
    assert_eq!(analysed(n, &dense).factor_nonzeros(), Some(n * (n + 1) / 2));
    // 5-point Laplacian on a 40 x 40 grid, analysed both ways
    let m = 40;
    let id = |i: usize, j: usize| i * m + j;
    let mut grid = Vec::new();
    for i in 0..m {
        for j in 0..m {
            grid.push(Pair {
                row: id(i, j),
                col: id(i, j),
            });
            if i + 1 < m {
                grid.push(Pair {
                    row: id(i + 1, j),
                    col: id(i, j),
                });
            }
            if j + 1 < m {
                grid.push(Pair {
                    row: id(i, j + 1),
                    col: id(i, j),
                });
            }
        }
    }
    let (lower, _) = SymbolicSparseColMat::try_new_from_indices(m * m, m * m, &grid).unwrap();
    for threshold in [
        SupernodalThreshold::FORCE_SIMPLICIAL,
        SupernodalThreshold::FORCE_SUPERNODAL,
    ] {
        let cholesky = factorize_symbolic_cholesky(
            lower.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: threshold,
                ..Default::default()
            },
        )
        .unwrap();
        let inv = cholesky.perm().unwrap().arrays().1.to_vec();
        // exact fill: eliminate the graph in the factorisation's order
        let mut adj = vec![std::collections::BTreeSet::<usize>::new(); m * m];
        for e in grid.iter().filter(|e| e.row != e.col) {
            adj[inv[e.row]].insert(inv[e.col]);
            adj[inv[e.col]].insert(inv[e.row]);
        }
        let mut exact = 0;
        for k in 0..m * m {
            let later: Vec<usize> = adj[k].range(k + 1..).copied().collect();
            exact += 1 + later.len();
            for &a in &later {
                adj[a].extend(later.iter().filter(|&&b| b != a));
            }
        }
        assert_eq!(exact_factor_nonzeros(lower.as_ref(), Some(&inv)), exact);
        match cholesky.raw() {
            // a simplicial factor stores exactly these entries
            SymbolicCholeskyRaw::Simplicial(_) => assert_eq!(cholesky.len_val(), exact),
            // a supernodal one more (relaxation, dense diagonal blocks)
            SymbolicCholeskyRaw::Supernodal(_) => assert!(cholesky.len_val() > exact),
        }
    }
}

/// A singular matrix is an error (after the fallback), never a panic;
/// so are mismatched sizes.
#[test]
fn singular_is_an_error() {
    let (rows, cols) = ([0, 0, 1, 1], [0, 1, 0, 1]);
    let vals = [1.0, 1.0, 1.0, 1.0];
    let mut s = SparseLdlt::new();
    let r = s
        .solve(&[1.0, 1.0])
        .and_then(|x| check_solution(&vals, &[1.0, 1.0], x));
    assert!(r.is_err());
    assert!(s.solve_system(2, &rows, &cols, &vals, &[1.0, 2.0]).is_err());
    assert_eq!(s.fallbacks(), 1);
    assert!(s.analyse(2, &[0, 2], &[0, 0]).is_err());
    s.analyse(2, &rows, &cols).unwrap();
    assert!(s.factor(&[1.0]).is_err());
    s.factor(&[2.0, 0.0, 0.0, 2.0]).unwrap();
    assert!(s.solve(&[1.0]).is_err());
}
