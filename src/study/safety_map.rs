//! The safety map: which approximation type is safe on which scene, and
//! what it costs against the complete formulation.
//!
//! For each scene (its first contact pair's formulation) and each of its
//! step counts `N`, the complete formulation and Types 1–6 are solved
//! (`study_formulation` in the parent module; a failed solve, the complete one
//! included, is recorded, never fatal). Per step count and type:
//!
//! * `e_U = 100 (U_type - U_complete) / U_complete`, the final strain
//!   energy's error in percent;
//! * `e_R`, the support reactions' error in percent over every scheduled
//!   step ([`super::reactions`]; undefined without support groups).
//!
//! A type is *acceptable* at `N` when both solves converged,
//! `|e_U| < energy_tolerance_percent` (default
//! [`ENERGY_TOLERANCE_PERCENT`] = 0.05 %) and, where defined,
//! `e_R < reaction_tolerance_percent` (default
//! [`REACTION_TOLERANCE_PERCENT`] = 1 %). Its verdict on the scene
//! ([`Safety`]), read at the scene's largest step count `N_max`:
//!
//! * `safe`: acceptable at every step count studied;
//! * `safe from N steps`: acceptable at `N` and every larger count studied,
//!   not below;
//! * `unsafe`: converged at `N_max` but not acceptable there (the errors
//!   are too large at any step count the user would pick from this
//!   schedule);
//! * `fails`: the type's solve diverged at `N_max`;
//! * `refused`: the solver refuses the type on the scene
//!   ([`solver::SolverError::NotApplicable`]: Type 1 on a frictional pair,
//!   whose slip is zero within a step);
//! * `no reference`: the complete formulation failed at `N_max`.
//!
//! The cost columns are ratios type / complete at `N_max`: Newton
//! iterations spent (with the attempts a step repeat discarded) and kernel
//! evaluations (deterministic), wall time and contact
//! time (medians over the repeats; machine dependent).
//!
//! Outputs: `safety-map.csv` (one row per scene and type),
//! `safety-map-runs.csv` (every run, as `study-errors.csv` with the scene
//! first) and `safety-map.md` (the scene x type table with its legend, for
//! docs/benchmarks.md).

use std::fmt::{self, Write as _};

use contact_kernels::{ApproxType, Formulation};
use solver::{Method, Scene};

use super::errors::{cell, opt, ratio};
use super::{FormulationStudy, OnReferenceFailure, Progress, Run, StudyError};

/// Default energy tolerance of a safe type, percent.
pub const ENERGY_TOLERANCE_PERCENT: f64 = 0.05;
/// Default reaction tolerance of a safe type, percent.
pub const REACTION_TOLERANCE_PERCENT: f64 = 1.0;

/// The header of `safety-map.csv`.
pub const MAP_HEADER: &str = "scene,formulation,type,step_counts,steps,energy_error_percent,\
reaction_error_percent,max_abs_energy_error_percent,max_reaction_error_percent,verdict,\
safe_from_steps,newton_ratio,kernel_ratio,wall_time_ratio,contact_time_ratio,\
complete_strain_energy,complete_wall_seconds,failure";

/// One scene of the map.
#[derive(Debug, Clone)]
pub struct MapScene {
    /// The scene.
    pub scene: Scene,
    /// Its label in the tables (e.g. the file stem).
    pub label: String,
    /// Step counts to study, ascending (e.g. the scene's `loading.steps`).
    pub steps: Vec<usize>,
}

/// Settings of the map.
#[derive(Debug, Clone)]
pub struct MapOptions {
    /// Solves per configuration; times are medians.
    pub repeats: usize,
    /// A safe type's energy error bound, percent.
    pub energy_tolerance_percent: f64,
    /// A safe type's reaction error bound, percent.
    pub reaction_tolerance_percent: f64,
}

impl Default for MapOptions {
    fn default() -> Self {
        MapOptions {
            repeats: 1,
            energy_tolerance_percent: ENERGY_TOLERANCE_PERCENT,
            reaction_tolerance_percent: REACTION_TOLERANCE_PERCENT,
        }
    }
}

/// A type's verdict on a scene (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Safety {
    /// Acceptable at every step count studied.
    Safe,
    /// Acceptable from this step count on (every larger count studied).
    SafeFrom(usize),
    /// Converged but not acceptable at the largest step count.
    Unsafe,
    /// The type's solve failed at the largest step count.
    Fails,
    /// The solver refuses the type on the scene (it cannot mean what the
    /// scene asks).
    Refused,
    /// The complete formulation failed at the largest step count.
    NoReference,
}

impl Safety {
    /// Safe at the largest step count (from some step count on).
    pub fn is_safe(self) -> bool {
        matches!(self, Safety::Safe | Safety::SafeFrom(_))
    }

    /// The CSV key: `safe`, `safe-from`, `unsafe`, `fails`, `refused`,
    /// `no-reference`.
    pub fn key(self) -> &'static str {
        match self {
            Safety::Safe => "safe",
            Safety::SafeFrom(_) => "safe-from",
            Safety::Unsafe => "unsafe",
            Safety::Fails => "fails",
            Safety::Refused => "refused",
            Safety::NoReference => "no-reference",
        }
    }
}

impl fmt::Display for Safety {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Safety::SafeFrom(n) => write!(f, "safe from {n} steps"),
            Safety::NoReference => f.write_str("no reference"),
            s => f.write_str(s.key()),
        }
    }
}

/// One row of the map: one type on one scene.
#[derive(Debug, Clone)]
pub struct MapRow {
    /// The scene's label.
    pub scene: String,
    /// The formulation studied (the scene's first contact pair's).
    pub formulation: Formulation,
    /// The type.
    pub ty: ApproxType,
    /// The step counts studied, ascending.
    pub step_counts: Vec<usize>,
    /// The largest of them, where the verdict and the cost are read.
    pub steps: usize,
    /// `e_U` at `steps`.
    pub energy_error_percent: Option<f64>,
    /// `e_R` at `steps`.
    pub reaction_error_percent: Option<f64>,
    /// The largest `|e_U|` over the step counts where it is defined.
    pub max_abs_energy_error_percent: Option<f64>,
    /// The largest `e_R` over the step counts where it is defined.
    pub max_reaction_error_percent: Option<f64>,
    /// The verdict.
    pub safety: Safety,
    /// Newton iterations spent (repeated steps' discarded attempts
    /// included), type / complete, at `steps`.
    pub newton_ratio: Option<f64>,
    /// Kernel evaluations with derivatives, type / complete, at `steps`.
    pub kernel_ratio: Option<f64>,
    /// Wall time, type / complete, at `steps`.
    pub wall_time_ratio: Option<f64>,
    /// Contact evaluation time, type / complete, at `steps`.
    pub contact_time_ratio: Option<f64>,
    /// The complete formulation's strain energy at `steps`.
    pub complete_strain_energy: Option<f64>,
    /// The complete formulation's wall time at `steps`.
    pub complete_wall_seconds: Option<f64>,
    /// The first failure among the type's runs (with its step count), or
    /// the complete formulation's at `steps`.
    pub failure: Option<String>,
}

/// The map: every scene's study and one row per scene and type.
#[derive(Debug, Clone)]
pub struct SafetyMap {
    /// The options it was made with.
    pub options: MapOptions,
    /// Each scene's label and its study, in the order given.
    pub studies: Vec<(String, FormulationStudy)>,
    /// One row per scene and type, scenes in order, Types 1–6.
    pub rows: Vec<MapRow>,
}

fn ok(r: &Run) -> Option<&Run> {
    (r.failure.is_none()).then_some(r)
}

/// The row of `ty` on a scene's study (module docs).
pub fn classify(
    label: &str,
    study: &FormulationStudy,
    ty: ApproxType,
    options: &MapOptions,
) -> MapRow {
    let method = Method::Approx(ty);
    let step_counts = study.steps();
    let steps = step_counts.last().copied().unwrap_or(0);
    let acceptable = |n: usize| -> bool {
        let (Some(c), Some(t)) = (study.run(Method::Complete, n), study.run(method, n)) else {
            return false;
        };
        if c.failure.is_some() || t.failure.is_some() {
            return false;
        }
        let energy = t
            .error_percent
            .is_some_and(|e| e.abs() < options.energy_tolerance_percent);
        let reaction = t
            .reaction_error_percent
            .is_none_or(|e| e < options.reaction_tolerance_percent);
        energy && reaction
    };
    let complete = study.run(Method::Complete, steps);
    let run = study.run(method, steps);
    let safety = if complete.and_then(ok).is_none() {
        Safety::NoReference
    } else if run.is_some_and(|r| r.refused) {
        Safety::Refused
    } else if run.and_then(ok).is_none() {
        Safety::Fails
    } else if !acceptable(steps) {
        Safety::Unsafe
    } else {
        let from = step_counts
            .iter()
            .rev()
            .take_while(|n| acceptable(**n))
            .last()
            .copied()
            .unwrap_or(steps);
        if from == step_counts[0] {
            Safety::Safe
        } else {
            Safety::SafeFrom(from)
        }
    };
    let type_runs = || step_counts.iter().filter_map(|n| study.run(method, *n));
    let failure = type_runs()
        .find_map(|r| {
            r.failure
                .as_ref()
                .map(|f| format!("{} steps: {f}", r.steps))
        })
        .or_else(|| {
            complete
                .and_then(|c| c.failure.as_ref())
                .map(|f| format!("complete, {steps} steps: {f}"))
        });
    let c_ok = complete.and_then(ok);
    let t_ok = run.and_then(ok);
    let pair = |f: fn(&Run) -> f64| ratio(t_ok.map(f), c_ok.map(f));
    MapRow {
        scene: label.to_owned(),
        formulation: study.formulation,
        ty,
        steps,
        energy_error_percent: run.and_then(|r| r.error_percent),
        reaction_error_percent: run.and_then(|r| r.reaction_error_percent),
        max_abs_energy_error_percent: type_runs()
            .filter_map(|r| r.error_percent.map(f64::abs))
            .reduce(f64::max),
        max_reaction_error_percent: type_runs()
            .filter_map(|r| r.reaction_error_percent)
            .reduce(f64::max),
        safety,
        newton_ratio: pair(|r| r.iterations_spent() as f64),
        kernel_ratio: pair(|r| r.kernel_evaluations as f64),
        wall_time_ratio: pair(|r| r.wall_seconds),
        contact_time_ratio: pair(|r| r.contact_seconds),
        complete_strain_energy: c_ok.and_then(|c| c.strain_energy),
        complete_wall_seconds: c_ok.map(|c| c.wall_seconds),
        failure,
        step_counts,
    }
}

/// Runs every scene's study and classifies every type.
///
/// Errors: a scene without contact ([`StudyError::NoContact`]) or without
/// step counts ([`StudyError::NoSteps`]), checked for every scene before
/// anything is solved. Solver failures are recorded in the rows.
pub fn run_map(
    scenes: &[MapScene],
    options: &MapOptions,
    progress: &dyn Progress,
) -> Result<SafetyMap, StudyError> {
    let mut plan = Vec::new();
    for s in scenes {
        let formulation = s
            .scene
            .contacts
            .first()
            .ok_or_else(|| StudyError::NoContact(s.label.clone()))?
            .formulation;
        if s.steps.is_empty() || s.steps.contains(&0) {
            return Err(StudyError::NoSteps);
        }
        let mut steps = s.steps.clone();
        steps.sort_unstable();
        steps.dedup();
        plan.push((s, formulation, steps));
    }
    let total: usize = plan
        .iter()
        .map(|(_, _, n)| n.len() * Method::ALL.len())
        .sum();
    progress.start(total as u64);
    let mut studies = Vec::new();
    let mut rows = Vec::new();
    for (s, formulation, steps) in plan {
        let study = super::study_formulation::<2>(
            &s.scene,
            formulation,
            &steps,
            options.repeats,
            progress,
            OnReferenceFailure::Record,
        )?;
        for ty in ApproxType::ALL {
            rows.push(classify(&s.label, &study, ty, options));
        }
        studies.push((s.label.clone(), study));
    }
    Ok(SafetyMap {
        options: options.clone(),
        studies,
        rows,
    })
}

/// `safety-map.csv`: the header [`MAP_HEADER`], one row per scene and type.
pub fn csv(map: &SafetyMap) -> String {
    let mut out = String::from(MAP_HEADER);
    out.push('\n');
    for r in &map.rows {
        let counts: Vec<String> = r.step_counts.iter().map(|n| n.to_string()).collect();
        let from = match r.safety {
            Safety::Safe => r.step_counts.first().map(|n| n.to_string()),
            Safety::SafeFrom(n) => Some(n.to_string()),
            _ => None,
        };
        let row = [
            cell(&r.scene),
            r.formulation.to_string(),
            r.ty.to_string(),
            counts.join(";"),
            r.steps.to_string(),
            opt(r.energy_error_percent),
            opt(r.reaction_error_percent),
            opt(r.max_abs_energy_error_percent),
            opt(r.max_reaction_error_percent),
            r.safety.key().to_owned(),
            from.unwrap_or_default(),
            opt(r.newton_ratio),
            opt(r.kernel_ratio),
            opt(r.wall_time_ratio),
            opt(r.contact_time_ratio),
            opt(r.complete_strain_energy),
            opt(r.complete_wall_seconds),
            cell(r.failure.as_deref().unwrap_or("")),
        ];
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// `safety-map-runs.csv`: every run of every scene, the columns of
/// `study-errors.csv` ([`super::errors`]) after a `scene` column.
pub fn runs_csv(map: &SafetyMap) -> String {
    let mut out = format!("scene,{}\n", super::errors::ERRORS_HEADER);
    for (label, study) in &map.studies {
        for line in super::errors::csv([study]).lines().skip(1) {
            let _ = writeln!(out, "{},{line}", cell(label));
        }
    }
    out
}

fn percent(v: Option<f64>) -> String {
    match v {
        Some(e) if e.is_finite() => {
            if e == 0.0 {
                "0 %".into()
            } else if e.abs() >= 0.01 && e.abs() < 1000.0 {
                format!("{e:+.3} %")
            } else {
                format!("{e:+.1e} %")
            }
        }
        _ => "–".into(),
    }
}

fn times(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite())
        .map(|x| format!("×{x:.2}"))
        .unwrap_or_else(|| "–".into())
}

fn step_range(counts: &[usize]) -> String {
    match counts {
        [] => String::new(),
        [n] => n.to_string(),
        [a, .., b] => format!("{a}–{b}"),
    }
}

/// `safety-map.md`: the scene x type table, its legend, the scenes and a
/// reading generated from the verdicts. `command` is the command that made
/// it.
pub fn markdown(map: &SafetyMap, command: &str) -> String {
    let o = &map.options;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Safety map of the approximation types: each cell is a type's verdict on a scene, \
         its strain-energy error e_U and reaction error e_R against the complete formulation \
         and its wall time against complete, at the scene's largest step count \
         (regenerate: `{command}`).\n"
    );
    out.push_str("| scene (steps) |");
    for ty in ApproxType::ALL {
        let _ = write!(out, " Type {ty} |");
    }
    out.push_str("\n|---|");
    for _ in ApproxType::ALL {
        out.push_str("---|");
    }
    out.push('\n');
    for (label, study) in &map.studies {
        let _ = write!(out, "| {label} ({}) |", step_range(&study.steps()));
        for r in map.rows.iter().filter(|r| &r.scene == label) {
            let verdict = if r.safety.is_safe() {
                format!("**{}**", r.safety)
            } else {
                r.safety.to_string()
            };
            let reaction = r
                .reaction_error_percent
                .map(|e| format!(" · R {}", percent(Some(e)).trim_start_matches('+')))
                .unwrap_or_default();
            let _ = write!(
                out,
                " {verdict}<br>U {}{reaction} · t {} |",
                percent(r.energy_error_percent),
                times(r.wall_time_ratio)
            );
        }
        out.push('\n');
    }
    let _ = write!(
        out,
        "\nLegend. e_U = 100 (U_type − U_complete) / U_complete (final strain energy, same step \
         count); e_R = 100 max over steps and support groups of |R_type − R_complete| / max \
         |R_complete| (reaction forces where displacements are prescribed; left out when the \
         scene has no support group). A type is acceptable at a step count when both solves \
         converge, |e_U| < {} % and e_R < {} %. **safe**: acceptable at every step count \
         studied; **safe from N steps**: acceptable from N steps on; unsafe: converges but \
         not acceptable at the largest step count; fails: its solve diverges there; no \
         reference: the complete formulation fails there. t: wall time type / complete \
         (median of {} solve(s), machine dependent); Newton and kernel-call ratios are in \
         `safety-map.csv`.",
        o.energy_tolerance_percent, o.reaction_tolerance_percent, o.repeats
    );
    if map.rows.iter().any(|r| r.safety == Safety::Refused) {
        out.push_str(
            " refused: the solver refuses the type on the scene (Type 1 on a frictional pair: \
             it keeps xi_m constant, so its slip is zero within a step).",
        );
    }
    out.push_str("\n\n");
    out.push_str(
        "| scene | formulation | step counts | U complete | complete wall time | failures |\n",
    );
    out.push_str("|---|---|---|---:|---:|---|\n");
    for (label, study) in &map.studies {
        let steps = study.steps();
        let hi = steps.last().copied().unwrap_or(0);
        let c = study.run(Method::Complete, hi).and_then(ok);
        let failed = study
            .runs
            .iter()
            .filter(|r| r.failure.is_some() && !r.refused)
            .count();
        let refused = match study.runs.iter().filter(|r| r.refused).count() {
            0 => String::new(),
            k => format!(", {k} refused"),
        };
        let _ = writeln!(
            out,
            "| {label} | {} | {} | {} | {} | {failed} of {} runs{refused} |",
            study.formulation,
            steps
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            c.and_then(|c| c.strain_energy)
                .map(|u| format!("{u:.6e}"))
                .unwrap_or_else(|| "failed".into()),
            c.map(|c| format!("{:.1} ms", 1e3 * c.wall_seconds))
                .unwrap_or_else(|| "–".into()),
            study.runs.len(),
        );
    }
    out.push_str("\nReading:\n\n");
    out.push_str(&reading(map));
    out.push_str(&by_step_count(map));
    out
}

/// Per scene, `e_U` and `e_R` of every type at every step count (a
/// collapsed `<details>` block: the map reads only the largest).
fn by_step_count(map: &SafetyMap) -> String {
    let mut out =
        String::from("\n<details><summary>Errors at every step count (e_U %, e_R %)</summary>\n\n");
    for (label, study) in &map.studies {
        let steps = study.steps();
        let _ = write!(out, "{label}:\n\n| type |");
        for n in &steps {
            let _ = write!(out, " {n} steps |");
        }
        out.push_str("\n|---|");
        for _ in &steps {
            out.push_str("---:|");
        }
        out.push('\n');
        for method in Method::ALL {
            let _ = write!(out, "| {method} |");
            for n in &steps {
                let text = match study.run(method, *n) {
                    None => "–".to_owned(),
                    Some(r) if r.failure.is_some() => r.failure_word().to_owned(),
                    Some(_) if method == Method::Complete => "reference".to_owned(),
                    Some(r) => match r.reaction_error_percent {
                        Some(e) => format!(
                            "{} · {}",
                            percent(r.error_percent),
                            percent(Some(e)).trim_start_matches('+')
                        ),
                        None => percent(r.error_percent),
                    },
                };
                let _ = write!(out, " {text} |");
            }
            out.push('\n');
        }
        out.push('\n');
    }
    out.push_str("</details>\n");
    out
}

/// One line per type: the scenes where it is safe, and the others.
pub fn reading(map: &SafetyMap) -> String {
    let mut out = String::new();
    for ty in ApproxType::ALL {
        let rows: Vec<&MapRow> = map.rows.iter().filter(|r| r.ty == ty).collect();
        let safe: Vec<String> = rows
            .iter()
            .filter(|r| r.safety.is_safe())
            .map(|r| match r.safety {
                Safety::SafeFrom(n) => format!("{} (from {n} steps)", r.scene),
                _ => r.scene.clone(),
            })
            .collect();
        let not: Vec<String> = rows
            .iter()
            .filter(|r| !r.safety.is_safe())
            .map(|r| format!("{} ({})", r.scene, r.safety))
            .collect();
        let line = if not.is_empty() {
            format!("safe on every scene ({})", safe.join(", "))
        } else if safe.is_empty() {
            format!("never safe: {}", not.join(", "))
        } else {
            format!("safe on {}; not on {}", safe.join(", "), not.join(", "))
        };
        let _ = writeln!(out, "- Type {ty}: {line}.");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run with the given energy error (`None`: failed) and reaction
    /// error.
    fn run(method: Method, steps: usize, energy: Option<f64>, reaction: Option<f64>) -> Run {
        let failed = energy.is_none();
        Run {
            formulation: Formulation::SlaveNormal,
            method,
            steps,
            strain_energy: (!failed).then_some(1.0),
            error_percent: energy.filter(|_| method != Method::Complete),
            newton_iterations: if failed { 0 } else { 10 },
            repeated_iterations: 0,
            cutbacks: 0,
            wall_seconds: if failed { f64::NAN } else { 2.0 },
            contact_seconds: if failed { f64::NAN } else { 1.0 },
            solid_seconds: 0.0,
            solve_seconds: 0.0,
            kernel_evaluations: if failed { 0 } else { 100 },
            projections: 0,
            max_abs_gap: None,
            kernel_ops: None,
            failure: failed.then(|| "no convergence".to_owned()),
            refused: false,
            reaction_error_percent: reaction,
            max_reaction: Some(1.0),
        }
    }

    /// Steps 10, 20, 40; the complete formulation converges everywhere
    /// except where `complete_fails`; each type's energy errors per step
    /// count (`None`: its solve failed), reaction error 0.1 %.
    fn study(complete_fails: &[usize], types: [[Option<f64>; 3]; 6]) -> FormulationStudy {
        let mut runs = Vec::new();
        for (i, n) in [10, 20, 40].into_iter().enumerate() {
            let c = (!complete_fails.contains(&n)).then_some(0.0);
            runs.push(run(Method::Complete, n, c, None));
            for (ty, errors) in ApproxType::ALL.into_iter().zip(&types) {
                runs.push(run(Method::Approx(ty), n, errors[i], Some(0.1)));
            }
        }
        FormulationStudy {
            formulation: Formulation::SlaveNormal,
            runs,
        }
    }

    #[test]
    fn verdicts_follow_the_definition() {
        let s = study(
            &[],
            [
                [Some(0.01), Some(-0.01), Some(0.001)], // safe
                [Some(3.0), Some(0.04), Some(0.01)],    // safe from 20
                [Some(0.01), Some(0.01), Some(0.2)],    // unsafe at the largest
                [Some(0.01), Some(0.01), None],         // fails at the largest
                [None, Some(0.06), Some(0.0)],          // safe from 40
                [Some(0.0), Some(0.07), Some(0.0)],     // safe from 40: not at 20
            ],
        );
        let o = MapOptions::default();
        let verdicts: Vec<Safety> = ApproxType::ALL
            .into_iter()
            .map(|ty| classify("s", &s, ty, &o).safety)
            .collect();
        assert_eq!(
            verdicts,
            [
                Safety::Safe,
                Safety::SafeFrom(20),
                Safety::Unsafe,
                Safety::Fails,
                Safety::SafeFrom(40),
                Safety::SafeFrom(40),
            ]
        );
        let failed = classify("s", &s, ApproxType::Type4, &o);
        assert_eq!(failed.failure.as_deref(), Some("40 steps: no convergence"));
        assert_eq!(failed.wall_time_ratio, None);
        let row = classify("s", &s, ApproxType::Type1, &o);
        assert_eq!(row.steps, 40);
        assert_eq!(row.step_counts, [10, 20, 40]);
        assert_eq!(row.energy_error_percent, Some(0.001));
        assert_eq!(row.max_abs_energy_error_percent, Some(0.01));
        assert_eq!(row.wall_time_ratio, Some(1.0));
        // a reaction error above the bound makes the same type unsafe
        let strict = MapOptions {
            reaction_tolerance_percent: 0.05,
            ..MapOptions::default()
        };
        assert_eq!(
            classify("s", &s, ApproxType::Type1, &strict).safety,
            Safety::Unsafe
        );
    }

    #[test]
    fn a_failed_reference_is_recorded_not_judged() {
        let s = study(&[40], [[Some(0.0); 3]; 6]);
        let row = classify("s", &s, ApproxType::Type6, &MapOptions::default());
        assert_eq!(row.safety, Safety::NoReference);
        assert_eq!(
            row.failure.as_deref(),
            Some("complete, 40 steps: no convergence")
        );
        assert!(!row.safety.is_safe());
        assert_eq!(row.safety.to_string(), "no reference");
    }

    #[test]
    fn a_refused_type_is_marked_refused_not_failed() {
        let mut s = study(&[], [[Some(0.0); 3]; 6]);
        for r in s
            .runs
            .iter_mut()
            .filter(|r| r.method == Method::Approx(ApproxType::Type1))
        {
            r.failure = Some("refused: Type 1 cannot carry friction".into());
            r.refused = true;
        }
        let o = MapOptions::default();
        let rows: Vec<MapRow> = ApproxType::ALL
            .into_iter()
            .map(|ty| classify("f", &s, ty, &o))
            .collect();
        assert_eq!(rows[0].safety, Safety::Refused);
        assert_eq!(rows[0].safety.key(), "refused");
        assert!(rows[1..].iter().all(|r| r.safety == Safety::Safe));
        let map = SafetyMap {
            options: o,
            rows,
            studies: vec![("f".into(), s)],
        };
        let md = markdown(&map, "test");
        assert!(md.contains("| f (10–40) | refused<br>"), "{md}");
        assert!(md.contains("0 of 21 runs, 3 refused"), "{md}");
        assert!(md.contains("| 1 | refused | refused | refused |"), "{md}");
        assert!(md.contains(" refused: the solver refuses the type"), "{md}");
        assert!(reading(&map).contains("- Type 1: never safe: f (refused)."));
    }

    #[test]
    fn csv_rows_have_the_header_s_columns() {
        let s = study(&[20], [[Some(0.0), None, Some(1.0)]; 6]);
        let o = MapOptions::default();
        let map = SafetyMap {
            options: o.clone(),
            rows: ApproxType::ALL
                .into_iter()
                .map(|ty| classify("a, b", &s, ty, &o))
                .collect(),
            studies: vec![("a, b".into(), s)],
        };
        let text = csv(&map);
        let width = MAP_HEADER.split(',').count();
        assert_eq!(text.lines().count(), 7);
        assert!(
            text.lines().all(|l| l.split(',').count() == width),
            "{text}"
        );
        let runs = runs_csv(&map);
        let width = runs.lines().next().unwrap().split(',').count();
        assert_eq!(runs.lines().count(), 1 + 3 * 7);
        assert!(
            runs.lines().all(|l| l.split(',').count() == width),
            "{runs}"
        );
        let md = markdown(&map, "test");
        assert!(md.contains("| a, b (10–40) |") && md.contains("Legend"));
        assert!(
            md.contains("| 1 | 0 % · 0.100 % | failed | +1.000 % · 0.100 % |"),
            "{md}"
        );
        assert!(
            md.contains("| complete | reference | failed | reference |"),
            "{md}"
        );
    }
}
