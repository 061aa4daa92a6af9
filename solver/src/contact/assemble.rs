//! The contact element's part of the Newton system ([`crate::system`]):
//! the terms of every evaluated integration point and its multipliers, in
//! both dimensions (the node ties are `ties.rs`), whole or one MPI rank's
//! share of them ([`ContactShare`]).

use crate::ids::{EquationIndex, MultiplierIndex};
use crate::system::{DofMap, System};

use super::term::MultiplierShape;
use super::{GapTerm, WeightedPoint};

/// The part of the contact element one MPI rank assembles
/// (`crate::partition`): the normal multipliers whose slave node the rank
/// owns, their rows' diagonals and inactive residuals, and the points whose
/// first multiplier is one of them (a point's terms all go to one rank). A
/// point without multipliers (its terms are zeros) and the terms that are
/// summed over nodes before they are assembled (friction with its
/// tangential multipliers' rows, node ties) go to the `root` rank.
///
/// Invariant: over the ranks' shares every multiplier and every point is
/// assembled exactly once, so the ranks' systems sum to the whole one.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactShare {
    /// Whether this rank assembles each normal multiplier (in multiplier
    /// order; the tangential ones after them are `root`'s).
    pub multipliers: Vec<bool>,
    /// Whether this rank is the one that assembles the rest (rank 0).
    pub root: bool,
}

impl ContactShare {
    /// Whether this rank assembles the point of multiplier shape `shape`.
    fn point(&self, shape: &MultiplierShape) -> bool {
        shape
            .iter()
            .next()
            .map_or(self.root, |(m, _)| self.multiplier(m.index()))
    }

    /// Whether this rank assembles multiplier `m`.
    pub fn multiplier(&self, m: usize) -> bool {
        self.multipliers.get(m).copied().unwrap_or(self.root)
    }
}

/// Whether `share` (`None`: the whole element, one rank) assembles the
/// terms that go to the root rank ([`ContactShare`]).
pub fn assembles_root_terms(share: Option<&ContactShare>) -> bool {
    share.is_none_or(|s| s.root)
}

/// Adds the contact contributions of the evaluated integration points
/// (`evals[i]`, `None` = inactive) with multipliers `lambda` and the
/// multiplier rows (constraint for `active` multipliers, `l_a = 0` with a
/// unit diagonal for inactive ones).
///
/// A point contributes entries on its slave and paired master nodes only,
/// so the pattern changes when a point is re-paired (then the symbolic
/// factorisation is redone). Reserving the neighbouring master segments in
/// the pattern was tried and measured: on a refined paper scene (26 000
/// equations, complete formulation, 27 iterations) it cut the symbolic
/// analyses from 17 to 6 but made each numeric factorisation about 10 %
/// slower; the two roughly cancel (2 % net), not worth the complexity.
///
/// The points and evaluations are of any dimension (see
/// [`crate::contact::term`]): 2D segments (`N = 8`) or 3D faces (`N = 24`,
/// padding coordinates skipped). Per point, in this order: the
/// displacement residual `w J0 lambda g'`, the Hessian term
/// `w J0 lambda g''`, then per multiplier `a` of the slave face the
/// constraint residual `w J0 N_a g` (active) and the coupling
/// `w J0 N_a g'` both ways (zero in the inactive row); then the
/// multiplier rows' diagonals.
pub fn assemble_contact<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
    points: &[P],
    evals: &[Option<E>],
    lambda: &[f64],
    active: &[bool],
    dofs: &DofMap,
    sys: &mut System,
) {
    assemble_contact_of(points, evals, lambda, active, dofs, None, sys);
}

/// [`assemble_contact`], only the points and multipliers of `share` (one
/// MPI rank's, [`ContactShare`], in their order; `None`: every one, bit for
/// bit [`assemble_contact`]).
pub fn assemble_contact_of<P: WeightedPoint, E: GapTerm<N>, const N: usize>(
    points: &[P],
    evals: &[Option<E>],
    lambda: &[f64],
    active: &[bool],
    dofs: &DofMap,
    share: Option<&ContactShare>,
    sys: &mut System,
) {
    for (pt, ev) in points.iter().zip(evals) {
        let Some(ev) = ev else { continue };
        let shape = pt.multiplier_shape();
        if share.is_some_and(|s| !s.point(&shape)) {
            continue;
        }
        let w = pt.weight_ref();
        let lam = shape.lambda(lambda);
        let eqs: [Option<EquationIndex>; N] =
            std::array::from_fn(|k| ev.dof(k).and_then(|d| dofs.eq(d)));
        let grad = ev.grad();
        for p in 0..N {
            if let Some(ep) = eqs[p] {
                sys.residual[ep.index()] += w * lam * grad[p];
            }
        }
        if let Some(h) = ev.hess() {
            for p in 0..N {
                let Some(ep) = eqs[p] else { continue };
                for q in 0..N {
                    if let Some(eq) = eqs[q] {
                        sys.push(ep, eq, w * lam * h[(p, q)]);
                    }
                }
            }
        }
        for (m, n_a) in shape.iter() {
            let row = dofs.mult_eq(m);
            let on = active[m.index()];
            if on {
                sys.residual[row.index()] += w * n_a * ev.gap();
            }
            for p in 0..N {
                if let Some(ep) = eqs[p] {
                    let v = w * n_a * grad[p];
                    sys.push(ep, row, v);
                    sys.push(row, ep, if on { v } else { 0.0 });
                }
            }
        }
    }
    for (m, &on) in active.iter().enumerate() {
        if share.is_some_and(|s| !s.multiplier(m)) {
            continue;
        }
        let row = dofs.mult_eq(MultiplierIndex::new(m));
        if on {
            sys.push(row, row, 0.0);
        } else {
            sys.residual[row.index()] = lambda[m];
            sys.push(row, row, 1.0);
        }
    }
}
