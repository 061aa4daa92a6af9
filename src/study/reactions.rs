//! The reaction-force error of a type against the complete formulation.
//!
//! Where a scene prescribes displacements (its `[[fix]]` and
//! `[[prescribe]]` items, [`solver::Solution::support_groups`]), every
//! converged step records the reaction `R_g` (`[x, y]`, `[x, y, z]`) of each support
//! group `g` ([`solver::StepRecord::reactions`]). A type's reaction error
//! at `N` load steps compares it with the complete formulation's at the same
//! `N`, over the end of every scheduled step `k = 1..N` (the last converged
//! sub-step of step `k`: both runs reach the same load factors there) and
//! every group:
//!
//! ```text
//! e_R % = 100 max_{k,g} |R_type(k,g) - R_complete(k,g)| / max_{k,g} |R_complete(k,g)|
//! ```
//!
//! with `|.|` the Euclidean norm of the `D`-vector. The denominator is the
//! largest reaction of the whole complete history, so a group that carries
//! almost nothing does not blow the error up; the numerator is the largest
//! deviation at any step, so a type that is right only at the end still
//! shows its error on the way.
//!
//! The error is undefined (`None`) when the scene has no support groups,
//! when the complete reactions are all zero, or when the two histories do
//! not have the same shape (a failed run has no history).
//!
//! Reading: under load control the supports' total reaction equals the
//! applied load by equilibrium (see `solver/src/newton/reactions.rs`), so with
//! a single support group the error only measures the Newton tolerance;
//! it is informative where displacements are prescribed (a drag, a press)
//! or where several groups share the load.

use solver::{Dim, Solution};

/// The reactions at the end of each scheduled step: `[k][g]` for
/// `k = 0..solution.steps` and `g` over [`Solution::support_groups`]. A
/// scheduled step without a converged record (cannot happen in a returned
/// solution) is left out.
pub fn scheduled_reactions<const D: usize>(solution: &Solution<D>) -> Vec<Vec<[f64; D]>>
where
    Dim<D>: solver::SurfaceDim<D>,
{
    (1..=solution.steps)
        .filter_map(|k| {
            solution
                .step_records
                .iter()
                .rev()
                .find(|r| r.step == k)
                .map(|r| r.reactions.clone())
        })
        .collect()
}

/// `|v|`, `hypot` axis after axis (in 2D `v[0].hypot(v[1])` to the bit).
fn norm<const D: usize>(v: [f64; D]) -> f64 {
    v[1..].iter().fold(v[0].abs(), |n, x| n.hypot(*x))
}

/// The largest reaction `max_{k,g} |R(k,g)|` of a history (`None` when it
/// has no reaction).
pub fn max_reaction<const D: usize>(history: &[Vec<[f64; D]>]) -> Option<f64> {
    history.iter().flatten().map(|r| norm(*r)).reduce(f64::max)
}

/// The reaction error `e_R` in percent of `history` against `reference`
/// (module docs); `None` when undefined.
pub fn reaction_error_percent<const D: usize>(
    history: &[Vec<[f64; D]>],
    reference: &[Vec<[f64; D]>],
) -> Option<f64> {
    if history.len() != reference.len()
        || history
            .iter()
            .zip(reference)
            .any(|(a, b)| a.len() != b.len())
    {
        return None;
    }
    let scale = max_reaction(reference)?;
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let deviation = history
        .iter()
        .flatten()
        .zip(reference.iter().flatten())
        .map(|(a, b)| norm::<D>(std::array::from_fn(|c| a[c] - b[c])))
        .reduce(f64::max)?;
    deviation.is_finite().then(|| 100.0 * deviation / scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_is_the_largest_deviation_over_the_largest_reference() {
        let reference = vec![vec![[3.0, 4.0], [0.0, 1.0]], vec![[6.0, 8.0], [0.0, 2.0]]];
        let history = vec![vec![[3.0, 4.0], [0.0, 1.5]], vec![[6.0, 7.0], [0.0, 2.0]]];
        // largest deviation 1.0 (step 2, group 0), largest reference 10.0
        let e = reaction_error_percent(&history, &reference).unwrap();
        assert!((e - 10.0).abs() < 1e-12, "{e}");
        assert_eq!(reaction_error_percent(&reference, &reference), Some(0.0));
    }

    #[test]
    fn undefined_without_groups_zero_reference_or_mismatch() {
        assert_eq!(
            reaction_error_percent::<2>(&[vec![], vec![]], &[vec![], vec![]]),
            None
        );
        let zero = vec![vec![[0.0, 0.0]]];
        assert_eq!(reaction_error_percent(&zero, &zero), None);
        let one = vec![vec![[1.0, 0.0]]];
        assert_eq!(reaction_error_percent(&[], &one), None);
        assert_eq!(
            reaction_error_percent(&[vec![[1.0, 0.0], [1.0, 0.0]]], &one),
            None
        );
    }
}
