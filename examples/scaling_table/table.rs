//! The Markdown tables of the first solver: the 2D one with its contact
//! columns, the 3D one with the pattern-only sizes, the growth exponents
//! and the extrapolation, and the header's thread count.

use solver::{LinearSolverKind, Scene};

use crate::measure::{FillRow, Row};
use crate::stats::{exponent, fmt_fill, fmt_mib, fmt_ms};
use crate::{BLOCK_3D, EXTRAPOLATE_TO, HUGE, LARGE, REPS, REPS_HUGE, REPS_LARGE, SLOW};

/// The 2D table: the paper scene, with the contact columns.
pub(crate) fn print_2d_table(rows: &[Row], linear: &[LinearSolverKind]) {
    println!(
        "One Newton iteration, complete formulation, paper scene refined \
         (first iteration of load step 2 of {}; median of {REPS} runs, {REPS_LARGE} above {LARGE} equations, \
         {REPS_HUGE} above {HUGE}; {} rayon threads):\n",
        paper_steps(),
        rayon_threads()
    );
    if linear.len() > 1 || linear[0] != LinearSolverKind::Lu {
        println!("Linear solver: {}.\n", linear[0]);
    }
    println!(
        "| refine (x, y) | equations | contact points | assembly ms | contact ms | solve ms | total ms | symbolic ms (once) | factor nonzeros | peak MiB |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.label,
            r.equations,
            r.contact_points,
            fmt_ms(r.solid),
            fmt_ms(r.contact),
            fmt_ms(r.linear),
            fmt_ms(r.total),
            fmt_ms(r.symbolic),
            fmt_fill(r.fill),
            fmt_mib(r.peak_mib)
        );
    }
    println!();
    if rows.len() >= 2 {
        let n: Vec<f64> = rows.iter().map(|r| r.equations as f64).collect();
        let cp: Vec<f64> = rows.iter().map(|r| r.contact_points as f64).collect();
        let fit = |f: fn(&Row) -> f64| exponent(&n, &rows.iter().map(f).collect::<Vec<_>>());
        println!(
            "Growth from {} to {} equations, time ∝ equations^p (least squares on log-log): assembly p = {:.2}, \
             contact p = {:.2} (contact points ∝ equations^{:.2}), solve p = {:.2}, total p = {:.2}.",
            rows[0].equations,
            rows[rows.len() - 1].equations,
            fit(|r| r.solid),
            fit(|r| r.contact),
            exponent(&n, &cp),
            fit(|r| r.linear),
            fit(|r| r.total)
        );
        if rows.iter().all(|r| r.fill.is_some()) {
            let fill: Vec<f64> = rows.iter().map(|r| r.fill.unwrap_or(0) as f64).collect();
            println!("Factor nonzeros ∝ equations^{:.2}.", exponent(&n, &fill));
        }
        println!();
    }
}

/// The paper scene's default step count.
fn paper_steps() -> usize {
    Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )
    .map_or(0, |s| s.default_steps())
}

/// The 3D table: the hexahedral block (no contact columns: a 3D model has
/// no contact pairs yet), the growth exponents over all sizes and between
/// the two largest, and the extrapolation to [`EXTRAPOLATE_TO`] equations
/// with the latter (the peak memory as the extrapolated factor plus the
/// rest of the largest size's peak grown linearly: below 1e5 equations the
/// peak is mostly the model and the assembly, which grow linearly, and the
/// factor grows faster).
pub(crate) fn print_3d_table(rows: &[Row], fills: &[FillRow], linear: &[LinearSolverKind]) {
    let steps = Scene::from_toml_str(BLOCK_3D, "block3d.toml").map_or(0, |s| s.default_steps());
    println!(
        "One Newton iteration, `scenes/block3d.toml` refined (hexahedra, St Venant-Kirchhoff, finite strain, \
         no contact; first iteration of load step 2 of {steps}; median of {REPS} runs, {REPS_LARGE} above {LARGE} equations, \
         {REPS_HUGE} above {HUGE} or when the first took over {} s; {} rayon threads):\n",
        SLOW.as_secs(),
        rayon_threads()
    );
    println!("Linear solver: {}.\n", linear[0]);
    println!(
        "| elements (x, y, z) | equations | assembly ms | solve ms | total ms | symbolic ms (once) | factor nonzeros | nonzeros / equation | peak MiB | LU fallbacks |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let per_equation = |fill: Option<usize>, equations: usize| {
        fill.map_or_else(
            || "n/a".into(),
            |f| format!("{:.0}", f as f64 / equations as f64),
        )
    };
    for r in rows {
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.label,
            r.equations,
            fmt_ms(r.solid),
            fmt_ms(r.linear),
            fmt_ms(r.total),
            fmt_ms(r.symbolic),
            fmt_fill(r.fill),
            per_equation(r.fill, r.equations),
            fmt_mib(r.peak_mib),
            r.fallbacks
        );
    }
    println!();
    if !fills.is_empty() {
        println!(
            "Larger sizes, pattern only (assembled at the reference state, analysed by a fresh {} as a \
             solve's first iteration; no numeric factorisation; peak: the model, its assembly and the analysis):\n",
            linear[0]
        );
        println!(
            "| elements (x, y, z) | equations | symbolic ms | factor nonzeros | nonzeros / equation | peak MiB |"
        );
        println!("|---|---:|---:|---:|---:|---:|");
        for r in fills {
            println!(
                "| {} | {} | {} | {} | {} | {} |",
                r.label,
                r.equations,
                fmt_ms(r.symbolic),
                fmt_fill(r.fill),
                per_equation(r.fill, r.equations),
                fmt_mib(r.peak_mib)
            );
        }
        println!();
    }
    if rows.len() < 2 {
        return;
    }
    // (equations, value) series, and their exponents: least squares over
    // all points and between the last two
    let fit = |pts: &[(f64, f64)]| -> (f64, f64) {
        let x: Vec<f64> = pts.iter().map(|p| p.0).collect();
        let y: Vec<f64> = pts.iter().map(|p| p.1).collect();
        let [.., (x0, y0), (x1, y1)] = pts else {
            unreachable!("at least two points")
        };
        (exponent(&x, &y), (y1 / y0).ln() / (x1 / x0).ln())
    };
    let series = |f: &dyn Fn(&Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter().map(|r| (r.equations as f64, f(r))).collect()
    };
    let fmt_fit = |(all, local): (f64, f64)| format!("{all:.2} ({local:.2})");
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    let before = &rows[rows.len() - 2];
    let time_fit = fit(&series(&|r| r.total));
    println!(
        "Growth from {} to {} equations, time ∝ equations^p (least squares on log-log; in brackets between \
         the two largest sizes, {} and {}): assembly p = {}, solve p = {}, total p = {}, symbolic p = {}; \
         peak memory ∝ equations^{}.",
        first.equations,
        last.equations,
        before.equations,
        last.equations,
        fmt_fit(fit(&series(&|r| r.solid))),
        fmt_fit(fit(&series(&|r| r.linear))),
        fmt_fit(time_fit),
        fmt_fit(fit(&series(&|r| r.symbolic))),
        fmt_fit(fit(&series(&|r| r.peak_mib.unwrap_or(f64::NAN)))),
    );
    // the fill over the timed and the pattern-only sizes
    let fill_pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.equations, r.fill))
        .chain(fills.iter().map(|r| (r.equations, r.fill)))
        .filter_map(|(n, f)| Some((n as f64, f? as f64)))
        .collect();
    let fill_fit = (fill_pts.len() >= 2).then(|| fit(&fill_pts));
    if let (Some(ff), Some(&(n0, _)), Some(&(n1, _))) =
        (fill_fit, fill_pts.first(), fill_pts.last())
    {
        println!(
            "Factor nonzeros ∝ equations^{} from {n0} to {n1} equations{}.",
            fmt_fit(ff),
            if fills.is_empty() {
                ""
            } else {
                " (timed and pattern-only sizes)"
            }
        );
    }
    println!();
    // extrapolation with the exponents between the two largest sizes
    // (the steeper ones: the growth steepens with the size in 3D), to the
    // largest pattern-only size if there is one (its fill measured), else
    // to EXTRAPOLATE_TO
    let (to, measured_fill, measured_symbolic) = match fills.last() {
        Some(r) if r.equations > last.equations => (r.equations, r.fill, Some(r.symbolic)),
        _ => (EXTRAPOLATE_TO, None, None),
    };
    let scale = to as f64 / last.equations as f64;
    let total = last.total * scale.powf(time_fit.1);
    let symbolic_fit = fit(&series(&|r| r.symbolic));
    let symbolic = measured_symbolic.unwrap_or(last.symbolic * scale.powf(symbolic_fit.1));
    let nonzeros = match measured_fill {
        Some(f) => Some(f as f64),
        None => fill_fit
            .zip(fill_pts.last())
            .map(|(ff, &(n1, f1))| f1 * (to as f64 / n1).powf(ff.1)),
    };
    // the dense-column estimate of the factorisation's flops, sum of the
    // squared column counts ~ nnz(L)^2 / n, scaled from the largest timed
    // size's solve
    let by_flops = nonzeros
        .zip(last.fill)
        .map(|(nz, f)| last.linear * (nz / f as f64).powi(2) / scale + last.solid * scale);
    // the peak as the factor's values (8 bytes a nonzero) plus the rest
    // (model, assembled system, solver work), the rest grown linearly
    let factor_mib = |f: f64| f * 8.0 / (1024.0 * 1024.0);
    let mib = last
        .peak_mib
        .zip(last.fill)
        .zip(nonzeros)
        .map(|((p, f), nz)| (p - factor_mib(f as f64)).max(0.0) * scale + factor_mib(nz));
    let gib = |m: f64| format!("{:.1}", m / 1024.0);
    println!(
        "Extrapolated, not measured: at {to} equations one iteration would take about {:.0} s with the total \
         time's exponent between the two largest timed sizes ({}; {} s with the factorisation's flops taken \
         as nonzeros^2 / equations, the dense-column estimate, from the {} fill), its symbolic analysis \
         {:.1} s once{}; the factor {} nonzeros{} ({} GiB of values, 8 bytes each); the iteration's \
         peak, those values plus the rest of the largest timed size's peak grown linearly, about {} GiB.",
        total / 1e3,
        format_args!("{:.2}", time_fit.1),
        by_flops.map_or_else(|| "n/a".into(), |t| format!("{:.0}", t / 1e3)),
        if measured_fill.is_some() {
            "measured"
        } else {
            "extrapolated"
        },
        symbolic / 1e3,
        if measured_symbolic.is_some() {
            " (measured, pattern only)"
        } else {
            " (extrapolated)"
        },
        nonzeros.map_or_else(|| "n/a".into(), |f| format!("{f:.2e}")),
        if measured_fill.is_some() {
            " (measured, pattern only)"
        } else {
            " (extrapolated with the fill's last exponent)"
        },
        nonzeros.map_or_else(|| "n/a".into(), |f| gib(factor_mib(f))),
        mib.map_or_else(|| "n/a".into(), gib),
    );
    println!();
}

/// The size of rayon's global pool (assembly and contact run on it).
fn rayon_threads() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(
            std::env::var("RAYON_NUM_THREADS")
                .ok()
                .and_then(|v| v.parse().ok())
                .filter(|&n: &usize| n > 0)
                .unwrap_or(usize::MAX),
        )
}
