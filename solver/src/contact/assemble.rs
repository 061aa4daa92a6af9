//! The contact element's part of the Newton system ([`crate::system`]):
//! the terms of every evaluated integration point and its multipliers, in
//! both dimensions (the node ties are `ties.rs`).

use crate::ids::{EquationIndex, MultiplierIndex};
use crate::system::{DofMap, System};

use super::{GapTerm, WeightedPoint};

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
    for (pt, ev) in points.iter().zip(evals) {
        let Some(ev) = ev else { continue };
        let shape = pt.multiplier_shape();
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
        let row = dofs.mult_eq(MultiplierIndex::new(m));
        if on {
            sys.push(row, row, 0.0);
        } else {
            sys.residual[row.index()] = lambda[m];
            sys.push(row, row, 1.0);
        }
    }
}
