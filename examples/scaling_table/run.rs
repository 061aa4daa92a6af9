//! The sizes of a run: the refine factors of the paper scene (2D) or of
//! the hexahedral block (3D) from the command line or the defaults, each
//! measured, and the rows collected per solver.

use solver::{LinearSolverKind, Scene};

use crate::measure::{FillRow, Row, measure, measure_3d, measure_fill_3d};
use crate::{BLOCK_3D, EXTRA_SIZES, EXTRA_SIZES_3D, SIZES, SIZES_3D};

fn parse_size(s: &str) -> Option<(usize, usize)> {
    let (x, y) = s.split_once(['x', ','])?;
    let (x, y) = (x.trim().parse().ok()?, y.trim().parse().ok()?);
    (x > 0 && y > 0).then_some((x, y))
}

/// The rows of the first solver and those of the others, per size.
type Rows = (Vec<Row>, Vec<Vec<Option<Row>>>);

/// Splits each size's rows into the first solver's and the others'.
fn collect(
    results: impl Iterator<Item = Result<Vec<Option<Row>>, Box<dyn std::error::Error>>>,
) -> Result<Rows, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    let mut others = Vec::new();
    for r in results {
        let mut r = r?;
        match r.remove(0) {
            Some(first) => {
                rows.push(first);
                others.push(r);
            }
            None => unreachable!("the first solver always runs"),
        }
    }
    Ok((rows, others))
}

/// The paper scene at the refinements `raw` (default [`SIZES`], plus
/// [`EXTRA_SIZES`] up to `max_equations`).
pub(crate) fn run_2d(
    raw: &[String],
    max_equations: Option<usize>,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<Rows, Box<dyn std::error::Error>> {
    let mut sizes = raw
        .iter()
        .map(|a| {
            parse_size(a).ok_or_else(|| format!("expected refine factors like `26x13`, got `{a}`"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if sizes.is_empty() {
        sizes = SIZES.to_vec();
    }
    if let Some(max) = max_equations {
        sizes.extend(
            EXTRA_SIZES
                .iter()
                .filter(|&&(_, n)| n <= max)
                .map(|&(size, _)| size),
        );
    }
    let base = Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )?;
    collect(sizes.iter().map(|&size| {
        measure(&base, size, linear, lu_max)
            .map_err(|e| format!("refine {}x{}: {e}", size.0, size.1).into())
    }))
}

/// The 3D block at the refine factors `raw` (default [`SIZES_3D`], plus
/// [`EXTRA_SIZES_3D`] up to `max_equations`), and the pattern alone of
/// the [`EXTRA_SIZES_3D`] above those up to `fill_max` (checked against
/// the largest timed size's fill).
pub(crate) fn run_3d(
    raw: &[String],
    max_equations: Option<usize>,
    fill_max: Option<usize>,
    linear: &[LinearSolverKind],
    lu_max: usize,
) -> Result<(Rows, Vec<FillRow>), Box<dyn std::error::Error>> {
    let mut sizes = raw
        .iter()
        .map(|a| {
            a.parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| format!("--3d: expected a refine factor like `13`, got `{a}`"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if sizes.is_empty() {
        sizes = SIZES_3D.to_vec();
    }
    let timed_max = max_equations.unwrap_or(0);
    sizes.extend(
        EXTRA_SIZES_3D
            .iter()
            .filter(|&&(_, n)| n <= timed_max)
            .map(|&(size, _)| size),
    );
    let base = Scene::from_toml_str(BLOCK_3D, "block3d.toml")?;
    let rows = collect(sizes.iter().map(|&n| {
        measure_3d(&base, n, linear, lu_max).map_err(|e| format!("refine {n}: {e}").into())
    }))?;
    let pattern_only: Vec<usize> = EXTRA_SIZES_3D
        .iter()
        .filter(|&&(_, n)| n > timed_max && n <= fill_max.unwrap_or(0))
        .map(|&(size, _)| size)
        .collect();
    let mut fills = Vec::new();
    if let (Some(&last), false) = (sizes.last(), pattern_only.is_empty()) {
        // the pattern-only path gives the timed fill
        let check = measure_fill_3d(&base, last, linear[0])?;
        let timed = rows.0.last().and_then(|r| r.fill);
        if check.fill != timed {
            return Err(format!(
                "refine {last}: pattern-only fill {:?}, the probe's {timed:?}",
                check.fill
            )
            .into());
        }
        for n in pattern_only {
            fills.push(
                measure_fill_3d(&base, n, linear[0]).map_err(|e| format!("refine {n}: {e}"))?,
            );
        }
    }
    Ok((rows, fills))
}
