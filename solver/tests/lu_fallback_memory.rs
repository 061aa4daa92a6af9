//! The LDLᵀ's LU fallback allocates within the memory the system has
//! available (`solver::linear::fallback`, "The LU's memory"): under an
//! address-space limit, an allocation past it fails instead of the system
//! killing the process, and the solve is `LinearError::OutOfMemory` naming
//! the check the LDLᵀ failed. The limit holds for the whole process, so this
//! file is its own test process with one test.

use solver::linear::{FallbackReason, LinearError, LinearSolver, LuOutcome, SparseLdlt};
use solver::meminfo::AddressSpaceLimit;

/// The 7-point Laplacian of an `m^3` grid, as triplets, with two more
/// equations coupled only to each other by `[0 1; 1 0]`: nonsingular, and
/// a zero pivot for the unpivoted LDLᵀ in any order (so it falls back).
fn laplacian_with_a_zero_pivot(m: usize) -> (usize, Vec<u32>, Vec<u32>, Vec<f64>) {
    let id = |i: usize, j: usize, k: usize| ((i * m + j) * m + k) as u32;
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..m {
        for j in 0..m {
            for k in 0..m {
                let a = id(i, j, k);
                rows.push(a);
                cols.push(a);
                vals.push(6.0);
                let mut couple = |b: u32| {
                    rows.extend([a, b]);
                    cols.extend([b, a]);
                    vals.extend([-1.0, -1.0]);
                };
                if i + 1 < m {
                    couple(id(i + 1, j, k));
                }
                if j + 1 < m {
                    couple(id(i, j + 1, k));
                }
                if k + 1 < m {
                    couple(id(i, j, k + 1));
                }
            }
        }
    }
    let n = m * m * m;
    rows.extend([n as u32, n as u32 + 1]);
    cols.extend([n as u32 + 1, n as u32]);
    vals.extend([1.0, 1.0]);
    (n + 2, rows, cols, vals)
}

/// Whether `bytes` can be reserved (not touched: no memory is used).
fn can_reserve(bytes: usize) -> bool {
    Vec::<u8>::new().try_reserve_exact(bytes).is_ok()
}

#[test]
fn the_lu_fallback_allocates_within_the_available_memory() {
    // the limit: an allocation past it fails, and is possible again after
    {
        let limit = AddressSpaceLimit::new(0);
        assert!(limit.is_set(), "no address-space limit on this system");
        assert!(!can_reserve(1 << 30));
    }
    assert!(can_reserve(1 << 30));

    // a matrix whose LU needs far more than nothing
    let (n, rows, cols, vals) = laplacian_with_a_zero_pivot(24);
    let b = vec![1.0; n];
    let mut ldlt = SparseLdlt::with_available_memory(|| Some(0));
    let err = ldlt.solve_system(n, &rows, &cols, &vals, &b).unwrap_err();
    assert!(
        matches!(&err, LinearError::OutOfMemory(m) if m.contains("zero or non-finite pivot")),
        "{err}"
    );
    let log = ldlt.fallback_log();
    assert_eq!(log.len(), 1);
    assert_eq!(log[0].reason, FallbackReason::Pivot);
    assert!(matches!(
        log[0].lu,
        LuOutcome::OutOfMemory {
            available: Some(0),
            ..
        }
    ));
    // the limit is gone: a large allocation succeeds again
    assert!(can_reserve(1 << 30));
}
