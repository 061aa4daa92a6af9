//! `reactions.csv`: the reaction of every support group at every converged
//! (sub)step ([`crate::StepRecord::reactions`]), written by `gapsim run
//! --out DIR` for a scene with `[[fix]]` or `[[prescribe]]` items.
//!
//! The header is `step,load_factor,<group>_x,<group>_y,...` (in 3D
//! `<group>_x,<group>_y,<group>_z` per group) in
//! [`Solution::support_groups`] order (names quoted where CSV needs it,
//! [`super::csv::field`]), then one row per converged (sub)step: the
//! scheduled step it belongs to, its load factor and the reactions, values
//! in Rust's shortest round-trip form (`{:?}`).

use crate::dim::SpaceDim;
use crate::model::Dim;
use crate::solution::Solution;

use super::csv::field;

/// The `reactions.csv` text of `solution` (see the module docs).
pub fn reactions_csv<const D: usize>(solution: &Solution<D>) -> String
where
    Dim<D>: SpaceDim<D>,
{
    let mut out = String::from("step,load_factor");
    for g in &solution.support_groups {
        for c in Dim::<D>::AXES {
            out.push(',');
            out.push_str(&field(&format!("{g}_{c}")));
        }
    }
    out.push('\n');
    for r in &solution.step_records {
        out.push_str(&format!("{},{:?}", r.step, r.load_factor));
        for v in r.reactions.iter().flatten() {
            out.push_str(&format!(",{v:?}"));
        }
        out.push('\n');
    }
    out
}
