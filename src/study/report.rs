//! Study outputs in text: the CSV files, the convergence estimate, the
//! Markdown results section and the terminal summary.

use std::fmt::Write as _;

use contact_kernels::{ApproxType, Formulation};
use solver::Method;

use super::{FormulationStudy, HeavyStudy, Run, StudyResults};

/// The CSV header: the six contract columns, then extras.
pub const CSV_HEADER: &str = "type,steps,strain_energy,error_percent,newton_iterations,wall_seconds,\
contact_seconds,solid_seconds,solve_seconds,kernel_evaluations,projections,max_abs_gap,kernel_ops,cutbacks,formulation,failure";

fn opt(v: Option<f64>) -> String {
    v.filter(|x| x.is_finite()).map(|x| format!("{x:e}")).unwrap_or_default()
}

fn num(x: f64) -> String {
    if x.is_finite() { format!("{x:e}") } else { String::new() }
}

/// The CSV text of one formulation's study (one row per run).
pub fn csv(study: &FormulationStudy) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for r in &study.runs {
        let failure = r.failure.as_deref().unwrap_or("").replace([',', '\n', '"'], ";");
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
        /// Fitted order (minus the slope of log|e| against log N).
        order: f64,
    },
    /// The error does not fall to zero: it stays near `plateau` percent.
    DoesNotVanish {
        /// The error at the largest step count.
        plateau: f64,
        /// Fitted slope of log|e| against log N.
        slope: f64,
    },
    /// Some solves failed.
    Failed,
}

/// The convergence estimate of one type.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// The type.
    pub ty: ApproxType,
    /// The verdict.
    pub verdict: Verdict,
    /// Whether the error changes sign over the step counts.
    pub sign_changes: bool,
}

/// Least-squares slope of `log|e|` against `log N`.
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x.ln(), b + y.abs().ln()));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        let dx = x.ln() - mx;
        (a + dx * (y.abs().ln() - my), b + dx * dx)
    });
    num / den
}

/// Estimates how `ty`'s error falls with the number of steps.
pub fn convergence(study: &FormulationStudy, ty: ApproxType) -> Convergence {
    let runs: Vec<&Run> = study.runs.iter().filter(|r| r.method == Method::Approx(ty)).collect();
    let errors: Vec<(f64, f64)> = runs.iter().filter_map(|r| r.error_percent.map(|e| (r.steps as f64, e))).collect();
    let sign_changes = errors.windows(2).any(|w| w[0].1.signum() != w[1].1.signum() && w[0].1 != 0.0 && w[1].1 != 0.0);
    if errors.len() < runs.len() || errors.len() < 2 {
        return Convergence { ty, verdict: Verdict::Failed, sign_changes };
    }
    let above: Vec<(f64, f64)> = errors.iter().copied().filter(|(_, e)| e.abs() > ERROR_FLOOR_PERCENT).collect();
    if above.is_empty() {
        return Convergence { ty, verdict: Verdict::AtTolerance, sign_changes };
    }
    if above.len() < 2 {
        // Only the coarsest step count is above tolerance: it vanishes fast.
        return Convergence { ty, verdict: Verdict::Converges { order: f64::INFINITY }, sign_changes };
    }
    let s = slope(&above);
    let first = errors.first().map(|p| p.1.abs()).unwrap_or(0.0);
    let last = errors.last().map(|p| p.1).unwrap_or(0.0);
    // A factor 5 in N: an error that falls by less than a factor 2 (slope
    // above -0.43) is not going to zero at any useful rate.
    let verdict = if s > -0.43 && last.abs() > 0.5 * first {
        Verdict::DoesNotVanish { plateau: last, slope: s }
    } else {
        Verdict::Converges { order: -s }
    };
    Convergence { ty, verdict, sign_changes }
}

impl std::fmt::Display for Convergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.verdict {
            Verdict::AtTolerance => write!(f, "at solver tolerance for every step count"),
            Verdict::Converges { order } if order.is_infinite() => write!(f, "below tolerance beyond the coarsest step count"),
            Verdict::Converges { order } => write!(f, "converges to zero, order {order:.2}"),
            Verdict::DoesNotVanish { plateau, slope } => {
                write!(f, "does not vanish: {plateau:+.3e} % at the finest step count (slope {slope:.2})")
            }
            Verdict::Failed => write!(f, "some solves failed"),
        }?;
        if self.sign_changes {
            write!(f, "; the sign changes")?;
        }
        Ok(())
    }
}

fn short_order(c: &Convergence) -> String {
    match &c.verdict {
        Verdict::AtTolerance => "exact".into(),
        Verdict::Converges { order } if order.is_infinite() => "fast".into(),
        Verdict::Converges { order } => format!("{order:.2}"),
        Verdict::DoesNotVanish { .. } => "does not vanish".into(),
        Verdict::Failed => "failed".into(),
    }
}

fn fmt_err(r: Option<&Run>) -> String {
    match r {
        Some(Run { error_percent: Some(e), .. }) => format!("{e:+.3e}"),
        Some(Run { failure: Some(_), .. }) => "failed".into(),
        _ => "–".into(),
    }
}

fn orders_text(ty: ApproxType) -> String {
    ty.orders().map(|o| format!("{o:?}").to_lowercase()).join(", ")
}

/// The machine the study ran on (CPU model and core count).
pub fn machine_description() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("model name")).and_then(|l| l.split(':').nth(1)).map(|s| s.trim().to_owned()))
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    format!("{cpu}, {cores} cores available, {} {}", std::env::consts::OS, std::env::consts::ARCH)
}

/// The plot files of a study, relative to its output directory.
pub fn plot_files(results: &StudyResults) -> Vec<(String, String)> {
    let mut v = Vec::new();
    for s in &results.formulations {
        let f = s.formulation;
        v.push((format!("Error against load steps ({f})"), format!("error-vs-steps-{f}.png")));
        v.push((format!("Speed against error ({f})"), format!("error-vs-time-{f}.png")));
    }
    if results.heavy.is_some() {
        v.push(("Speed against error, contact-heavy variant".into(), "error-vs-time-contact-heavy.png".into()));
    }
    v.push(("Deformed configuration at the final load factor".into(), "deformed.png".into()));
    v
}

fn ratio(a: f64, b: f64) -> String {
    if a.is_finite() && b.is_finite() && b > 0.0 { format!("{:.2}", a / b) } else { "–".into() }
}

/// The cost table of a study: per type and step count, time ratios to the
/// complete formulation at the same step count.
fn cost_table(out: &mut String, s: &FormulationStudy) {
    let _ = writeln!(out, "| type | steps | error % | kernel ops | Newton its | contact time / complete | total time / complete |");
    let _ = writeln!(out, "|---|---:|---:|---:|---:|---:|---:|");
    for n in s.steps() {
        let Some(c) = s.run(Method::Complete, n) else { continue };
        let _ = writeln!(
            out,
            "| complete | {n} | – | {} | {} | 1.00 ({:.2} ms) | 1.00 ({:.2} ms) |",
            c.kernel_ops.map(|o| o.to_string()).unwrap_or_default(),
            c.newton_iterations,
            1e3 * c.contact_seconds,
            1e3 * c.wall_seconds
        );
        for ty in ApproxType::ALL {
            let Some(r) = s.run(Method::Approx(ty), n) else { continue };
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
    let _ = writeln!(out, "Generated by `{command}` on {}.", machine_description());
    let _ = writeln!(
        out,
        "Scene: {}. Times are medians of {} repeated solves (release build); errors are \
         `100 (U_type - U_complete) / U_complete` at load factor 10 with the same number of steps.\n",
        results.scene_name, results.repeats
    );

    // Error table at the coarsest and finest step counts.
    let steps = results.formulations[0].steps();
    let (lo, hi) = (steps[0], *steps.last().expect("non-empty"));
    let _ = writeln!(out, "#### Strain-energy error (%) at {lo} and {hi} load steps\n");
    let mut header = String::from("| type | xi_m, x_ms, n | kernel ops |");
    let mut rule = String::from("|---|---|---:|");
    for f in &forms {
        let _ = write!(header, " {f}, {lo} steps | {f}, {hi} steps | {f}, order |");
        rule.push_str("---:|---:|---:|");
    }
    let _ = writeln!(out, "{header}\n{rule}");
    for ty in ApproxType::ALL {
        let ops: Vec<String> = forms.iter().map(|f| super::kernel_ops(*f, Method::Approx(ty)).map_or("–".into(), |o| o.to_string())).collect();
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
        forms.iter().map(|f| f.to_string()).collect::<Vec<_>>().join(" / ")
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
        cost_table(&mut out, &h.study);
        out.push('\n');
    }
    let _ = writeln!(out, "#### Cost on the paper scene ({})\n", results.formulations[0].formulation);
    cost_table(&mut out, &results.formulations[0]);
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
            .filter_map(|t| s.run(Method::Approx(t), hi).and_then(|r| r.error_percent).map(|e| (t, e.abs())))
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
            let energies: Vec<Option<f64>> = steps.iter().map(|n| s.run(Method::Approx(t), *n).and_then(|r| r.strain_energy)).collect();
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
            .map(|g| g.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(" = "))
            .collect();
        if coinciding.is_empty() {
            let _ = writeln!(out, "- {}: all six types give different energies.", s.formulation);
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
            let _ = writeln!(out, "- {}: every type's error falls as the steps get smaller.", s.formulation);
        } else {
            let _ = writeln!(out, "- {}: the error of Type(s) {} does not vanish with more steps.", s.formulation, vanishing.join(", "));
        }
    }
    if let Some(h) = &results.heavy {
        let s = &h.study;
        let hi = *s.steps().last().expect("non-empty");
        if let Some(c) = s.run(Method::Complete, hi) {
            let cheapest = ApproxType::ALL
                .into_iter()
                .filter_map(|t| s.run(Method::Approx(t), hi).filter(|r| r.wall_seconds.is_finite()).map(|r| (t, r)))
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
                    Some(r) if r.failure.is_some() => "failed".to_owned(),
                    Some(r) => match r.error_percent {
                        Some(e) => format!("{e:+.2e} ({:.1})", 1e3 * r.wall_seconds),
                        None => format!("U={:.6} ({:.1})", r.strain_energy.unwrap_or(f64::NAN), 1e3 * r.wall_seconds),
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
        let _ = writeln!(out, "\ncontact-heavy variant ({} solid elements, {} contact points):", h.solid_elements, h.contact_points);
        let mut t = String::new();
        cost_table(&mut t, &h.study);
        out.push_str(&t);
    }
    out
}

/// Markers around the generated section of a README.
pub const README_BEGIN: &str = "<!-- study:begin -->";
/// See [`README_BEGIN`].
pub const README_END: &str = "<!-- study:end -->";

/// Replaces the text between the study markers of `readme` by `section`.
/// `None` if the markers are missing or out of order.
pub fn splice_readme(readme: &str, section: &str) -> Option<String> {
    let b = readme.find(README_BEGIN)? + README_BEGIN.len();
    let e = readme[b..].find(README_END)? + b;
    Some(format!("{}\n{}\n{}", &readme[..b], section.trim_end(), &readme[e..]))
}

/// Cost ratios of one heavy-study type at `steps`: `(contact, total)`.
pub fn heavy_ratios(h: &HeavyStudy, ty: ApproxType, steps: usize) -> Option<(f64, f64)> {
    let c = h.study.run(Method::Complete, steps)?;
    let r = h.study.run(Method::Approx(ty), steps)?;
    Some((r.contact_seconds / c.contact_seconds, r.wall_seconds / c.wall_seconds))
}
