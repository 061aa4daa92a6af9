//! The study's error and cost table on any scene: `study-errors.csv`.
//!
//! The paper's `study.csv` keeps its contract columns (docs/conventions.md)
//! unchanged; this companion file holds what the study measures on every
//! scene, one row per (formulation, method, step count), complete first:
//!
//! * `energy_error_percent`: `100 (U_type - U_complete) / U_complete`, final
//!   strain energies at the same step count (empty for the complete
//!   formulation and for a failed run);
//! * `reaction_error_percent`: the support reactions' error against the
//!   complete formulation over every scheduled step ([`super::reactions`];
//!   empty when undefined: no support groups, a failed run);
//! * `max_reaction`: the run's largest support reaction (the error's scale
//!   for the complete row);
//! * the cost against complete at the same step count: `newton_iterations`
//!   and `newton_ratio` (Newton iterations spent: with the attempts a step
//!   repeat discarded, [`super::Run::iterations_spent`]; `study.csv` keeps
//!   the converged attempts' count) and `kernel_ratio` (kernel evaluations
//!   with derivatives), deterministic; the times are the `*_seconds` columns
//!   (medians over repeats; their ratios are left to the reader so that
//!   every other column compares value for value between runs, as
//!   `scripts/compare-study.sh` does);
//! * `failure`: the solver's message when the run failed.

use std::fmt::Write as _;

use contact_kernels::ApproxType;
use solver::Method;

use super::FormulationStudy;

/// The header of `study-errors.csv`.
pub const ERRORS_HEADER: &str = "formulation,type,steps,strain_energy,energy_error_percent,\
reaction_error_percent,max_reaction,newton_iterations,newton_ratio,kernel_evaluations,\
kernel_ratio,wall_seconds,contact_seconds,failure";

/// Shortest round-trip float, empty for `None` or a non-finite value.
pub(crate) fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite())
        .map(|x| format!("{x:e}"))
        .unwrap_or_default()
}

/// A ratio `a / b`, `None` when `b` is zero or either is missing.
pub(crate) fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b != 0.0 && a.is_finite() && b.is_finite() => Some(a / b),
        _ => None,
    }
}

/// A free-text CSV cell: commas, quotes and line breaks become `;` (as in
/// `study.csv`), so that every line splits on commas alone (the comparison
/// scripts split with `awk -F,`).
pub(crate) fn cell(text: &str) -> String {
    text.replace([',', '\n', '\r', '"'], ";")
}

/// `study-errors.csv` for the given formulation studies (module docs).
pub fn csv<'a>(studies: impl IntoIterator<Item = &'a FormulationStudy>) -> String {
    let mut out = String::from(ERRORS_HEADER);
    out.push('\n');
    for s in studies {
        for r in &s.runs {
            let complete = s
                .run(Method::Complete, r.steps)
                .filter(|c| c.failure.is_none());
            let ok = r.failure.is_none();
            let newton = ok.then_some(r.iterations_spent() as f64);
            let kernels = ok.then_some(r.kernel_evaluations as f64);
            let c_newton = complete.map(|c| c.iterations_spent() as f64);
            let c_kernels = complete.map(|c| c.kernel_evaluations as f64);
            let row = [
                r.formulation.to_string(),
                r.method.to_string(),
                r.steps.to_string(),
                opt(r.strain_energy),
                opt(r.error_percent),
                opt(r.reaction_error_percent),
                opt(r.max_reaction),
                newton.map(|n| n.to_string()).unwrap_or_default(),
                opt(ratio(newton, c_newton)),
                kernels.map(|n| n.to_string()).unwrap_or_default(),
                opt(ratio(kernels, c_kernels)),
                opt(Some(r.wall_seconds)),
                opt(Some(r.contact_seconds)),
                cell(r.failure.as_deref().unwrap_or("")),
            ];
            out.push_str(&row.join(","));
            out.push('\n');
        }
    }
    out
}

/// A terminal table of the reaction errors of one formulation's study
/// (type x step count, percent); a one-line note when the scene has no
/// support group.
pub fn reaction_summary(study: &FormulationStudy) -> String {
    let steps = study.steps();
    let defined = study.runs.iter().any(|r| r.max_reaction.is_some());
    if !defined {
        return "\nreaction error: the scene prescribes no displacement (no support group)\n"
            .to_owned();
    }
    let mut out = format!(
        "\nreaction error e_R % ({}, max over steps and support groups):\n| type |",
        study.formulation
    );
    for n in &steps {
        let _ = write!(out, " {n} |");
    }
    out.push('\n');
    for ty in ApproxType::ALL {
        let _ = write!(out, "| {ty} |");
        for n in &steps {
            let r = study.run(Method::Approx(ty), *n);
            let text = match r {
                Some(r) if r.failure.is_some() => r.failure_word().to_owned(),
                Some(r) => r
                    .reaction_error_percent
                    .map(|e| format!("{e:.3e}"))
                    .unwrap_or_else(|| "-".into()),
                None => "-".into(),
            };
            let _ = write!(out, " {text} |");
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_never_hold_a_separator() {
        assert_eq!(cell("plain"), "plain");
        assert_eq!(cell("a, b\nc \"d\""), "a; b;c ;d;");
    }

    #[test]
    fn ratio_needs_both_and_a_non_zero_denominator() {
        assert_eq!(ratio(Some(1.0), Some(4.0)), Some(0.25));
        assert_eq!(ratio(Some(1.0), Some(0.0)), None);
        assert_eq!(ratio(None, Some(1.0)), None);
        assert_eq!(ratio(Some(f64::NAN), Some(1.0)), None);
    }
}
