//! The crate's one parallel map: a function of an index over `0..n`, run on
//! rayon's pool in chunks of at least `min_len` indices.
//!
//! Invariant: results come back in index order whatever the scheduling, and
//! nothing is reduced in parallel (callers sum sequentially, in index
//! order), so every result is independent of the number of threads.

use std::ops::AddAssign;

use rayon::prelude::*;

/// `[f(0), f(1), ..., f(n - 1)]`, computed in parallel (chunks of at least
/// `min_len` indices).
pub fn map<T, F>(n: usize, min_len: usize, f: F) -> Vec<T>
where
    T: Send,
    F: Fn(usize) -> T + Sync + Send,
{
    (0..n)
        .into_par_iter()
        .with_min_len(min_len)
        .map(f)
        .collect()
}

/// [`map`] of a fallible `f` that also counts (e.g. kernel calls) into a
/// fresh `C` per index: the values in index order and the counts summed in
/// index order, or the error of the first failing index.
pub fn try_map_counted<T, E, C, F>(n: usize, min_len: usize, f: F) -> Result<(Vec<T>, C), E>
where
    T: Send,
    E: Send,
    C: Default + AddAssign + Send,
    F: Fn(usize, &mut C) -> Result<T, E> + Sync + Send,
{
    let results: Vec<(Result<T, E>, C)> = map(n, min_len, |i| {
        let mut c = C::default();
        (f(i, &mut c), c)
    });
    let mut counts = C::default();
    let mut out = Vec::with_capacity(results.len());
    for (r, c) in results {
        counts += c;
        out.push(r?);
    }
    Ok((out, counts))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_in_index_order_and_first_error() {
        let squares = map(1000, 7, |i| i * i);
        assert!(squares.iter().enumerate().all(|(i, &s)| s == i * i));
        let counted = try_map_counted(1000, 7, |i, c: &mut usize| {
            *c += 1;
            Ok::<_, usize>(i)
        });
        assert_eq!(counted.map(|(v, c)| (v.len(), c)), Ok((1000, 1000)));
        let failed = try_map_counted(
            1000,
            7,
            |i, _: &mut usize| {
                if i % 300 == 299 { Err(i) } else { Ok(i) }
            },
        );
        assert_eq!(failed, Err(299));
    }
}
