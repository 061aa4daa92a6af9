//! Study outputs in text: the CSV files, the convergence estimate, the
//! Markdown results section and the terminal summary.

use std::fmt::Write as _;

use contact_kernels::{ApproxType, Formulation};
use solver::Method;

use super::{FormulationStudy, Run, StudyResults};

/// The CSV header: the six contract columns, then extras.
pub const CSV_HEADER: &str = "type,steps,strain_energy,error_percent,newton_iterations,wall_seconds,\
contact_seconds,solid_seconds,solve_seconds,kernel_evaluations,projections,max_abs_gap,kernel_ops,cutbacks,formulation,failure";

fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite())
        .map(|x| format!("{x:e}"))
        .unwrap_or_default()
}

fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:e}")
    } else {
        String::new()
    }
}

/// The CSV text of one formulation's study (one row per run).
pub fn csv(study: &FormulationStudy) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for r in &study.runs {
        let failure = r
            .failure
            .as_deref()
            .unwrap_or("")
            .replace([',', '\n', '"'], ";");
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.method,
            r.steps,
            opt(r.strain_energy),
            opt(r.error_percent),
            r.newton_iterations,
            num(r.wall_seconds),
            num(r.contact_seconds),
            num(r.solid_seconds),
            num(r.solve_seconds),
            r.kernel_evaluations,
            r.projections,
            opt(r.max_abs_gap),
            r.kernel_ops.map(|o| o.to_string()).unwrap_or_default(),
            r.cutbacks,
            r.formulation,
            failure
        );
    }
    out
}

/// Errors below this (in percent) are at the solver's tolerance: the
/// Newton residual `1e-10` leaves the energy uncertain to about `1e-9`
/// relative.
pub const ERROR_FLOOR_PERCENT: f64 = 1e-6;

/// How a type's error behaves as the number of steps grows.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// Every error is below [`ERROR_FLOOR_PERCENT`].
    AtTolerance,
    /// The error falls like `N^-order`.
    Converges {
        /// Fitted order `p` of `e(N) = a + C N^-p` over the finer half of
        /// the step counts.
        order: f64,
        /// The local orders between the first two and the last two step
        /// counts of that range.
        local: (f64, f64),
    },
    /// The error tends to a non-zero limit as `N` grows.
    DoesNotVanish {
        /// The extrapolated limit (percent).
        limit: f64,
    },
    /// The error changes sign among the finer step counts: not yet in its
    /// asymptotic range, no order can be read off.
    PreAsymptotic,
    /// The error falls, but no order fits yet (the best fit lies at the edge
    /// of the searched range).
    NotAsymptotic {
        /// The local orders between the first two and the last two step
        /// counts of the finer half.
        local: (f64, f64),
    },
    /// Some solves failed.
    Failed,
    /// The solver refused the type on the scene
    /// ([`solver::SolverError::NotApplicable`]); the reason.
    Refused(String),
    /// The study has one step count: no trend to estimate.
    OneStepCount,
}

/// The convergence estimate of one type.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// The type.
    pub ty: ApproxType,
    /// The verdict.
    pub verdict: Verdict,
    /// The limit `a` of `e(N) = a + C N^-p` fitted to the finer half of the
    /// step counts (percent).
    pub limit: f64,
    /// Whether the error changes sign over the step counts.
    pub sign_changes: bool,
}

/// Least squares `e(N) = a + C N^-p` over a grid of orders `p`: returns
/// `(a, p)` of the best fit.
fn power_fit(points: &[(f64, f64)]) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for k in 0..=(P_MAX * 100.0) as usize - (P_MIN * 100.0) as usize {
        let p = P_MIN + k as f64 * 0.01;
        // Linear least squares in (a, C) with basis [1, N^-p].
        let (mut s11, mut s1x, mut sxx, mut s1y, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (n, e) in points {
            let x = n.powf(-p);
            s11 += 1.0;
            s1x += x;
            sxx += x * x;
            s1y += e;
            sxy += x * e;
        }
        let det = s11 * sxx - s1x * s1x;
        if det.abs() < 1e-300 {
            continue;
        }
        let a = (sxx * s1y - s1x * sxy) / det;
        let c = (s11 * sxy - s1x * s1y) / det;
        let res: f64 = points
            .iter()
            .map(|(n, e)| (a + c * n.powf(-p) - e).powi(2))
            .sum();
        if res < best.0 {
            best = (res, a, p);
        }
    }
    (best.1, best.2)
}

/// The range of orders the fit considers.
const P_MIN: f64 = 0.25;
/// See [`P_MIN`].
const P_MAX: f64 = 4.0;

/// Estimates how `ty`'s error falls with the number of steps.
///
/// The finer half of the step counts (at least three) is the *tail*. A sign
/// change in the tail means the error is not yet asymptotic. Otherwise the
/// tail is fitted with `e(N) = a + C N^-p`: a limit `a` of the finest
/// error's sign and above 30 % of it means the error does not vanish; a
/// best order at the edge of the searched range `[0.25, 4]` means no
/// asymptotic order can be read off yet; otherwise the error converges to
/// zero with order `p`.
pub fn convergence(study: &FormulationStudy, ty: ApproxType) -> Convergence {
    let runs: Vec<&Run> = study
        .runs
        .iter()
        .filter(|r| r.method == Method::Approx(ty))
        .collect();
    let errors: Vec<(f64, f64)> = runs
        .iter()
        .filter_map(|r| r.error_percent.map(|e| (r.steps as f64, e)))
        .collect();
    let sign_changes = errors.windows(2).any(|w| w[0].1 * w[1].1 < 0.0);
    let mk = |verdict, limit| Convergence {
        ty,
        verdict,
        limit,
        sign_changes,
    };
    if let Some(r) = runs.iter().find(|r| r.refused) {
        let why = r.failure.clone().unwrap_or_default();
        return mk(Verdict::Refused(why), f64::NAN);
    }
    if errors.len() < runs.len() {
        return mk(Verdict::Failed, f64::NAN);
    }
    if runs.len() == 1 {
        return mk(Verdict::OneStepCount, f64::NAN);
    }
    if errors.len() < 2 {
        return mk(Verdict::Failed, f64::NAN);
    }
    let mut sorted = errors.clone();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    if sorted.iter().all(|(_, e)| e.abs() <= ERROR_FLOOR_PERCENT) {
        return mk(Verdict::AtTolerance, 0.0);
    }
    let start = (sorted.len() / 2).min(sorted.len().saturating_sub(3));
    let tail = &sorted[start..];
    if tail.iter().all(|(_, e)| e.abs() <= ERROR_FLOOR_PERCENT) {
        return mk(
            Verdict::Converges {
                order: f64::INFINITY,
                local: (f64::INFINITY, f64::INFINITY),
            },
            0.0,
        );
    }
    if tail.windows(2).any(|w| w[0].1 * w[1].1 < 0.0) {
        return mk(Verdict::PreAsymptotic, f64::NAN);
    }
    let last = tail.last().expect("non-empty").1;
    let local_order = |w: &[(f64, f64)]| (w[0].1 / w[1].1).abs().ln() / (w[1].0 / w[0].0).ln();
    let local = (
        local_order(&tail[..2]),
        local_order(&tail[tail.len() - 2..]),
    );
    let (limit, order) = power_fit(tail);
    if order <= P_MIN + 1e-9 || order >= P_MAX - 1e-9 {
        return mk(Verdict::NotAsymptotic { local }, limit);
    }
    if limit * last > 0.0 && limit.abs() > 0.3 * last.abs() {
        return mk(Verdict::DoesNotVanish { limit }, limit);
    }
    mk(Verdict::Converges { order, local }, limit)
}

impl std::fmt::Display for Convergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.verdict {
            Verdict::AtTolerance => write!(f, "at solver tolerance for every step count"),
            Verdict::Converges { order, .. } if order.is_infinite() => {
                write!(f, "below tolerance on the finer step counts")
            }
            Verdict::Converges {
                order,
                local: (a, b),
            } if (b - a).abs() > 0.25 * a.abs().max(b.abs()) => write!(
                f,
                "falls over the finer step counts, but not yet asymptotically: local order {a:.2} -> {b:.2} \
                 (fitted {order:.2}); extrapolated limit {:+.1e} %",
                self.limit
            ),
            Verdict::Converges {
                order,
                local: (a, b),
            } => {
                write!(
                    f,
                    "converges to zero, order {order:.2} (local order {a:.2} -> {b:.2})"
                )
            }
            Verdict::DoesNotVanish { limit } => {
                write!(
                    f,
                    "does not vanish: tends to about {limit:+.2e} % (extrapolated)"
                )
            }
            Verdict::PreAsymptotic => write!(
                f,
                "changes sign among the finer step counts: not yet asymptotic"
            ),
            Verdict::NotAsymptotic { local: (a, b) } => {
                write!(
                    f,
                    "falls, but no asymptotic order yet (local order {a:.2} -> {b:.2})"
                )
            }
            Verdict::Failed => write!(f, "some solves failed"),
            Verdict::Refused(why) => write!(f, "{why}"),
            Verdict::OneStepCount => write!(f, "one step count: no convergence estimate"),
        }?;
        if self.sign_changes && !matches!(self.verdict, Verdict::PreAsymptotic) {
            write!(f, " (the sign changes at coarse step counts)")?;
        }
        Ok(())
    }
}

fn short_order(c: &Convergence) -> String {
    match &c.verdict {
        Verdict::AtTolerance => "exact".into(),
        Verdict::Converges { order, .. } if order.is_infinite() => "fast".into(),
        Verdict::Converges {
            order,
            local: (a, b),
        } if (b - a).abs() > 0.25 * a.abs().max(b.abs()) => {
            format!("{order:.2} (pre-asymptotic)")
        }
        Verdict::Converges { order, .. } => format!("{order:.2}"),
        Verdict::DoesNotVanish { limit } => format!("→ {limit:+.1e}"),
        Verdict::PreAsymptotic | Verdict::NotAsymptotic { .. } => "pre-asymptotic".into(),
        Verdict::Failed => "failed".into(),
        Verdict::Refused(_) => "refused".into(),
        Verdict::OneStepCount => "–".into(),
    }
}

fn fmt_err(r: Option<&Run>) -> String {
    match r {
        Some(Run {
            error_percent: Some(e),
            ..
        }) => format!("{e:+.3e}"),
        Some(
            r @ Run {
                failure: Some(_), ..
            },
        ) => r.failure_word().into(),
        _ => "–".into(),
    }
}

fn orders_text(ty: ApproxType) -> String {
    ty.orders()
        .map(|o| format!("{o:?}").to_lowercase())
        .join(", ")
}

/// The machine the study ran on (CPU model and core count).
pub fn machine_description() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    format!(
        "{cpu}, {cores} cores available, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

/// The plot files of a study, relative to its output directory.
pub fn plot_files(results: &StudyResults) -> Vec<(String, String)> {
    let mut v = Vec::new();
    for s in &results.formulations {
        let f = s.formulation;
        v.push((
            format!("Error against load steps ({f})"),
            format!("error-vs-steps-{f}.png"),
        ));
        v.push((
            format!("Speed against error ({f})"),
            format!("error-vs-time-{f}.png"),
        ));
    }
    if results.heavy.is_some() {
        v.push((
            "Speed against error, contact-heavy variant".into(),
            "error-vs-time-contact-heavy.png".into(),
        ));
    }
    if results.deformed.is_some() {
        v.push((
            "Deformed configuration at the final load factor".into(),
            "deformed.png".into(),
        ));
    }
    v
}

fn ratio(a: f64, b: f64) -> String {
    if a.is_finite() && b.is_finite() && b > 0.0 {
        format!("{:.2}", a / b)
    } else {
        "–".into()
    }
}

/// The cost table of a study: per type and step count (`steps`, or all),
/// time ratios to the complete formulation at the same step count.
fn cost_table(out: &mut String, s: &FormulationStudy, steps: Option<&[usize]>) {
    let _ = writeln!(
        out,
        "| type | steps | error % | kernel ops | Newton its | contact time / complete | total time / complete |"
    );
    let _ = writeln!(out, "|---|---:|---:|---:|---:|---:|---:|");
    for n in steps.map_or_else(|| s.steps(), <[usize]>::to_vec) {
        let Some(c) = s.run(Method::Complete, n) else {
            continue;
        };
        let _ = writeln!(
            out,
            "| complete | {n} | – | {} | {} | 1.00 ({:.2} ms) | 1.00 ({:.2} ms) |",
            c.kernel_ops.map(|o| o.to_string()).unwrap_or_default(),
            c.newton_iterations,
            1e3 * c.contact_seconds,
            1e3 * c.wall_seconds
        );
        for ty in ApproxType::ALL {
            let Some(r) = s.run(Method::Approx(ty), n) else {
                continue;
            };
            let _ = writeln!(
                out,
                "| {ty} | {n} | {} | {} | {} | {} | {} |",
                fmt_err(Some(r)),
                r.kernel_ops.map(|o| o.to_string()).unwrap_or_default(),
                r.newton_iterations,
                ratio(r.contact_seconds, c.contact_seconds),
                ratio(r.wall_seconds, c.wall_seconds)
            );
        }
    }
}

/// The Markdown results section. `link_prefix` is prepended to plot file
/// names (the output directory as seen from where the Markdown lives).
pub fn markdown(results: &StudyResults, link_prefix: &str, command: &str) -> String {
    let mut out = String::new();
    let forms: Vec<Formulation> = results.formulations.iter().map(|s| s.formulation).collect();
    let _ = writeln!(
        out,
        "Generated by `{command}` on {}.",
        machine_description()
    );
    let _ = writeln!(
        out,
        "Scene: {}. Times are medians of {} repeated solves (release build, linear solver: {}); \
         errors are `100 (U_type - U_complete) / U_complete` at the scene's last load factor \
         with the same number of steps.\n",
        results.scene_name, results.repeats, results.linear
    );

    // Error table at the coarsest and finest step counts.
    let steps = results.formulations[0].steps();
    let (lo, hi) = (steps[0], *steps.last().expect("non-empty"));
    let _ = writeln!(
        out,
        "#### Strain-energy error (%) at {lo} and {hi} load steps\n"
    );
    let mut header = String::from("| type | xi_m, x_ms, n | kernel ops |");
    let mut rule = String::from("|---|---|---:|");
    for f in &forms {
        let _ = write!(header, " {f}, {lo} steps | {f}, {hi} steps | {f}, order |");
        rule.push_str("---:|---:|---:|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    for ty in ApproxType::ALL {
        let ops: Vec<String> = forms
            .iter()
            .map(|f| {
                super::kernel_ops(*f, Method::Approx(ty)).map_or("–".into(), |o| o.to_string())
            })
            .collect();
        let _ = write!(out, "| {ty} | {} | {} |", orders_text(ty), ops.join(" / "));
        for s in &results.formulations {
            let c = convergence(s, ty);
            let _ = write!(
                out,
                " {} | {} | {} |",
                fmt_err(s.run(Method::Approx(ty), lo)),
                fmt_err(s.run(Method::Approx(ty), hi)),
                short_order(&c)
            );
        }
        out.push('\n');
    }
    let _ = writeln!(
        out,
        "\nKernel ops are the generated kernel's floating-point operations per integration point \
         ({}); the complete formulation evaluates the Type-6 kernel and re-projects at every iteration.\n",
        forms
            .iter()
            .map(|f| f.to_string())
            .collect::<Vec<_>>()
            .join(" / ")
    );

    // Convergence in words.
    let _ = writeln!(out, "#### How the error falls with the number of steps\n");
    for s in &results.formulations {
        let _ = writeln!(out, "*{}*:\n", s.formulation);
        for ty in ApproxType::ALL {
            let _ = writeln!(out, "- Type {ty}: {}", convergence(s, ty));
        }
        out.push('\n');
    }

    // Cost where contact dominates.
    if let Some(h) = &results.heavy {
        let _ = writeln!(out, "#### Cost where contact dominates\n");
        let _ = writeln!(
            out,
            "{}: {} solid elements, {} slave integration points. Ratios are to the complete formulation \
             measured in the same run.\n",
            h.study.formulation, h.solid_elements, h.contact_points
        );
        cost_table(&mut out, &h.study, None);
        out.push('\n');
    }
    let _ = writeln!(
        out,
        "#### Cost on the scene ({}, {lo} and {hi} steps; every step count in the CSV)\n",
        results.formulations[0].formulation
    );
    cost_table(&mut out, &results.formulations[0], Some(&[lo, hi]));
    out.push('\n');

    // Plots.
    let _ = writeln!(out, "#### Plots\n");
    for (title, file) in plot_files(results) {
        let _ = writeln!(out, "![{title}]({link_prefix}{file})\n");
    }

    let _ = writeln!(out, "#### Reading\n");
    out.push_str(&reading(results));
    out
}

/// A short reading of the results, derived from the numbers.
pub fn reading(results: &StudyResults) -> String {
    let mut out = String::new();
    for s in &results.formulations {
        let steps = s.steps();
        let hi = *steps.last().expect("non-empty");
        let mut by_error: Vec<(ApproxType, f64)> = ApproxType::ALL
            .into_iter()
            .filter_map(|t| {
                s.run(Method::Approx(t), hi)
                    .and_then(|r| r.error_percent)
                    .map(|e| (t, e.abs()))
            })
            .collect();
        by_error.sort_by(|a, b| a.1.total_cmp(&b.1));
        if let (Some(best), Some(worst)) = (by_error.first(), by_error.last()) {
            let _ = writeln!(
                out,
                "- {}: at {hi} steps the smallest error is Type {}'s ({:.2e} %), the largest Type {}'s ({:.2e} %).",
                s.formulation, best.0, best.1, worst.0, worst.1
            );
        }
        // Types whose energies coincide at every step count.
        let mut groups: Vec<Vec<ApproxType>> = Vec::new();
        for t in ApproxType::ALL {
            let energies: Vec<Option<f64>> = steps
                .iter()
                .map(|n| s.run(Method::Approx(t), *n).and_then(|r| r.strain_energy))
                .collect();
            let same = groups.iter_mut().find(|g| {
                let e0: Vec<Option<f64>> = steps.iter().map(|n| s.run(Method::Approx(g[0]), *n).and_then(|r| r.strain_energy)).collect();
                e0.iter().zip(&energies).all(|(a, b)| matches!((a, b), (Some(a), Some(b)) if (a - b).abs() <= 1e-9 * a.abs()))
            });
            match same {
                Some(g) => g.push(t),
                None => groups.push(vec![t]),
            }
        }
        let coinciding: Vec<String> = groups
            .iter()
            .filter(|g| g.len() > 1)
            .map(|g| {
                g.iter()
                    .map(|t| t.to_string())
                    .collect::<Vec<_>>()
                    .join(" = ")
            })
            .collect();
        if coinciding.is_empty() {
            let _ = writeln!(
                out,
                "- {}: all six types give different energies.",
                s.formulation
            );
        } else {
            let _ = writeln!(
                out,
                "- {}: Types {} give the same energy (to 1e-9) at every step count.",
                s.formulation,
                coinciding.join(", ")
            );
        }
        let vanishing: Vec<String> = ApproxType::ALL
            .into_iter()
            .filter(|t| matches!(convergence(s, *t).verdict, Verdict::DoesNotVanish { .. }))
            .map(|t| t.to_string())
            .collect();
        if vanishing.is_empty() {
            let _ = writeln!(
                out,
                "- {}: every type's error falls as the steps get smaller.",
                s.formulation
            );
        } else {
            let _ = writeln!(
                out,
                "- {}: the error of Type(s) {} does not vanish with more steps.",
                s.formulation,
                vanishing.join(", ")
            );
        }
    }
    if let Some(h) = &results.heavy {
        let s = &h.study;
        let hi = *s.steps().last().expect("non-empty");
        if let Some(c) = s.run(Method::Complete, hi) {
            let cheapest = ApproxType::ALL
                .into_iter()
                .filter_map(|t| {
                    s.run(Method::Approx(t), hi)
                        .filter(|r| r.wall_seconds.is_finite())
                        .map(|r| (t, r))
                })
                .min_by(|a, b| a.1.wall_seconds.total_cmp(&b.1.wall_seconds));
            if let Some((t, r)) = cheapest {
                let _ = writeln!(
                    out,
                    "- Contact-heavy variant, {hi} steps: the fastest type is Type {t}, {} of the complete formulation's total time \
                     and {} of its contact time, at {} % error.",
                    ratio(r.wall_seconds, c.wall_seconds),
                    ratio(r.contact_seconds, c.contact_seconds),
                    fmt_err(Some(r))
                );
            }
        }
    }
    out
}

/// The terminal summary: error and time per type at every step count.
pub fn terminal_summary(results: &StudyResults) -> String {
    let mut out = String::new();
    for s in &results.formulations {
        let _ = writeln!(out, "\n{} — error % (wall ms)", s.formulation);
        let steps = s.steps();
        let _ = write!(out, "{:>9}", "type");
        for n in &steps {
            let _ = write!(out, "{:>22}", format!("{n} steps"));
        }
        out.push('\n');
        for m in Method::ALL {
            let _ = write!(out, "{:>9}", m.to_string());
            for n in &steps {
                let cell = match s.run(m, *n) {
                    Some(r) if r.failure.is_some() => r.failure_word().to_owned(),
                    Some(r) => match r.error_percent {
                        Some(e) => format!("{e:+.2e} ({:.1})", 1e3 * r.wall_seconds),
                        None => format!(
                            "U={:.6} ({:.1})",
                            r.strain_energy.unwrap_or(f64::NAN),
                            1e3 * r.wall_seconds
                        ),
                    },
                    None => "–".into(),
                };
                let _ = write!(out, "{cell:>22}");
            }
            out.push('\n');
        }
        for ty in ApproxType::ALL {
            let _ = writeln!(out, "  Type {ty}: {}", convergence(s, ty));
        }
    }
    if let Some(h) = &results.heavy {
        let _ = writeln!(
            out,
            "\ncontact-heavy variant ({} solid elements, {} contact points):",
            h.solid_elements, h.contact_points
        );
        let mut t = String::new();
        cost_table(&mut t, &h.study, None);
        out.push_str(&t);
    }
    out
}

/// Markers around the generated section of a Markdown page (e.g. `docs/study.md`).
pub const README_BEGIN: &str = "<!-- study:begin -->";
/// See [`README_BEGIN`].
pub const README_END: &str = "<!-- study:end -->";

/// Replaces the text between the study markers of `readme` by `section`.
/// `None` if the markers are missing or out of order.
pub fn splice_readme(readme: &str, section: &str) -> Option<String> {
    let b = readme.find(README_BEGIN)? + README_BEGIN.len();
    let e = readme[b..].find(README_END)? + b;
    Some(format!(
        "{}\n{}\n{}",
        &readme[..b],
        section.trim_end(),
        &readme[e..]
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::{FormulationStudy, Run};

    fn study(errors: impl Fn(f64) -> f64) -> FormulationStudy {
        let runs = (2..=10)
            .map(|k| {
                let n = 2 * k;
                Run {
                    formulation: Formulation::SlaveNormal,
                    method: Method::Approx(ApproxType::Type3),
                    steps: n,
                    strain_energy: Some(1.0),
                    error_percent: Some(errors(n as f64)),
                    newton_iterations: 1,
                    repeated_iterations: 0,
                    cutbacks: 0,
                    wall_seconds: 1.0,
                    contact_seconds: 1.0,
                    solid_seconds: 0.0,
                    solve_seconds: 0.0,
                    kernel_evaluations: 0,
                    projections: 0,
                    max_abs_gap: None,
                    kernel_ops: None,
                    failure: None,
                    refused: false,
                    reaction_error_percent: None,
                    max_reaction: None,
                }
            })
            .collect();
        FormulationStudy {
            formulation: Formulation::SlaveNormal,
            runs,
        }
    }

    #[test]
    fn second_order_error_is_recognised() {
        let c = convergence(&study(|n| 3.0 / (n * n)), ApproxType::Type3);
        match c.verdict {
            // Exact power law: the fitted order is 2 to rounding.
            Verdict::Converges { order, .. } => assert!((order - 2.0).abs() < 1e-9, "{order}"),
            v => panic!("{v:?}"),
        }
        assert!(c.limit.abs() < 1e-12, "{}", c.limit);
    }

    #[test]
    fn a_plateau_is_not_called_convergence() {
        let c = convergence(&study(|n| 0.34 + 5.5 / n), ApproxType::Type3);
        match c.verdict {
            // a + b/N is inside the fitted family: the limit is exact.
            Verdict::DoesNotVanish { limit } => assert!((limit - 0.34).abs() < 1e-9, "{limit}"),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn sign_changes_on_the_fine_steps_are_pre_asymptotic() {
        let c = convergence(&study(|n| (n * 0.9).cos() / n), ApproxType::Type3);
        assert_eq!(c.verdict, Verdict::PreAsymptotic);
    }

    #[test]
    fn a_refused_type_reads_as_refused_with_its_reason() {
        let mut s = study(|n| 1.0 / n);
        for r in &mut s.runs {
            r.error_percent = None;
            r.failure = Some("refused: no slip".into());
            r.refused = true;
        }
        let c = convergence(&s, ApproxType::Type3);
        assert_eq!(c.verdict, Verdict::Refused("refused: no slip".into()));
        assert_eq!(c.to_string(), "refused: no slip");
        assert_eq!(fmt_err(s.runs.first()), "refused");
    }

    #[test]
    fn readme_section_is_replaced_between_markers() {
        let text = format!("intro\n{README_BEGIN}\nold\n{README_END}\ntail\n");
        let new = splice_readme(&text, "new results").unwrap();
        assert_eq!(
            new,
            format!("intro\n{README_BEGIN}\nnew results\n{README_END}\ntail\n")
        );
        assert!(splice_readme("no markers", "x").is_none());
    }
}
