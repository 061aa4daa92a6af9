//! The kernel verifier: every type of a formulation's generated kernels
//! against num-dual hyper-dual numbers of the same formulation, on seeded
//! random configurations and the hard families ([`families`]).
//!
//! * The kernels under test are any function from a type and a
//!   configuration to a [`KernelOutput`]: the compiled contact-kernels
//!   (tests/kernels_ad.rs) or the generated instruction lists run by
//!   codegen's interpreter ([`interpreted`], `gapsim verify FILE.rs`).
//! * The reference ([`reference`]) evaluates the formulation's expression
//!   DAG over num-dual numbers, independently of the generator's
//!   derivative pipeline: Type 6 against the exact Hessian, Types 1–5
//!   against the truncated formula built from num-dual partial derivatives.
//!   It runs on absolute coordinates, each configuration moved by an offset
//!   of its own size ([`offset`]): the kernels take coordinates relative to
//!   the first point, so a formulation that is not translation invariant
//!   fails here. Only far-away configurations (coordinates more than
//!   [`FAR`] times their size from the origin) are compared in the
//!   kernels' relative coordinates, so that they are not blurred by the
//!   reference's own cancellation.
//!
//! ## Tolerance
//!
//! Each block's error is divided by a bound at the block's natural scale,
//! with `L` the size of the configuration (largest relative coordinate):
//!
//! | block | scaled error |
//! |---|---|
//! | `g`    | `|g - g_ref| / max(|g_ref|, L)` |
//! | `xi_m` | `|xi - xi_ref| / (1 + |xi_ref|)` |
//! | `g'`   | `‖g' - g'_ref‖ / max(‖g'_ref‖, 1)` (Euclidean) |
//! | `g''`  | `‖g'' - g''_ref‖_F / max(‖g''_ref‖_F, 1 / L)` (Frobenius) |
//!
//! `g` scales like `L`, `g'` like 1 and `g''` like `1 / L`: the bounds are
//! scale-free. A type passes when every scaled error is at most [`TOL`] =
//! 1e-10: both sides are accurate to ~1e-14 on well-conditioned input, which
//! leaves four orders of magnitude for the projection's conditioning (up to
//! `1 / cos(89°)^2 ≈ 3300` on the steep family), while a wrong sign, term or
//! truncation rule gives errors of order 1e-3 to 1.
//!
//! A configuration whose projection the reference cannot solve (no root,
//! or `|xi_m| > 5`) is skipped and counted; a configuration the kernels
//! refuse while the reference solves it is a failure.

pub mod families;
pub mod interpreted;
pub mod reference;

use std::fmt;

pub use families::Config;
pub use interpreted::{Flip, InterpretedKernels};
pub use reference::{AdFormulation, Quantity};

/// The default tolerance on every scaled error (see the module
/// documentation).
pub const TOL: f64 = 1e-10;

/// A configuration whose coordinates lie more than this times its size
/// from the origin is far: the reference takes it relative to its first
/// point.
pub const FAR: f64 = 4.0;

/// The configuration `q` (dimension `dim`) moved by `(0.625 L, -0.375 L,
/// ...)`, `L` its size: the absolute coordinates the verifier feeds both
/// sides (module documentation).
pub fn offset(q: &[f64], dim: usize) -> Vec<f64> {
    let d: Vec<f64> = q.iter().enumerate().map(|(i, v)| v - q[i % dim]).collect();
    let l = size(&d);
    q.iter()
        .enumerate()
        .map(|(i, v)| v + l * if i % dim == 0 { 0.625 } else { -0.375 })
        .collect()
}

/// `|xi_m|` beyond which the verifier skips a configuration.
pub const XI_M_SKIP: f64 = 5.0;

/// Errors of the verifier (not verification failures: those are a
/// [`Report`] that does not pass).
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// The formulation file is malformed or does not fit the generator.
    #[error(transparent)]
    Formulation(#[from] codegen::Error),
    /// An entity has no column in the truncation table.
    #[error("{file}: entity `{name}` has no column in the truncation table (known: xi_m, x_ms, n)")]
    Entity {
        /// The file.
        file: String,
        /// The entity.
        name: String,
    },
    /// The families need a segment pair.
    #[error(
        "{file}: the verifier's configurations are segment pairs (4 points for two-node \
         segments or 6 for 3-node segments, 1 parameter); the formulation declares \
         {points} points and {params} parameters"
    )]
    Arity {
        /// The file.
        file: String,
        /// Declared points.
        points: usize,
        /// Declared parameters.
        params: usize,
    },
    /// A mutation request that does not fit the kernels.
    #[error("cannot mutate the kernel: {0}")]
    Mutation(String),
}

/// What a kernel returns for one configuration: the gap, `xi_m`, the
/// gradient (`n`) and the Hessian (row-major `n x n`; `None` for a type
/// without second-order term).
#[derive(Debug, Clone, PartialEq)]
pub struct KernelOutput {
    /// The gap.
    pub gap: f64,
    /// The projection coordinate (a face's: its first component `u`).
    pub xi_m: f64,
    /// The projection's further components (`[v]` for a face, empty for
    /// a segment).
    pub xi_rest: Vec<f64>,
    /// `dg/dq`.
    pub grad: Vec<f64>,
    /// `d2g/dq2`, row-major.
    pub hess: Option<Vec<f64>>,
}

/// A reference value of the gap and its kept derivatives.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// The gap.
    pub gap: f64,
    /// The projection coordinate (a face's: its first component `u`).
    pub xi_m: f64,
    /// The projection's further components (`[v]` for a face).
    pub xi_rest: Vec<f64>,
    /// The kept gradient.
    pub grad: Vec<f64>,
    /// The kept Hessian, row-major `n x n`.
    pub hess: Vec<f64>,
}

impl Reference {
    /// All zeros for `n` coordinates.
    pub fn zeros(n: usize) -> Reference {
        Reference {
            gap: 0.0,
            xi_m: 0.0,
            xi_rest: Vec::new(),
            grad: vec![0.0; n],
            hess: vec![0.0; n * n],
        }
    }

    /// Sets the projection from all its components.
    pub fn set_xi(&mut self, xi: &[f64]) {
        self.xi_m = xi[0];
        self.xi_rest = xi[1..].to_vec();
    }
}

/// The scaled errors of one comparison (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Scaled {
    /// `g`.
    pub gap: f64,
    /// `xi_m`.
    pub xi_m: f64,
    /// `g'`.
    pub grad: f64,
    /// `g''`.
    pub hess: f64,
}

impl Scaled {
    /// The largest of the four (NaN counts as infinite).
    pub fn max(&self) -> f64 {
        [self.gap, self.xi_m, self.grad, self.hess]
            .into_iter()
            .map(|v| if v.is_nan() { f64::INFINITY } else { v })
            .fold(0.0, f64::max)
    }
}

fn norm(v: impl IntoIterator<Item = f64>) -> f64 {
    v.into_iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The size `L` of relative coordinates `d`.
pub fn size(d: &[f64]) -> f64 {
    d.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// The scaled errors of `out` against `r` for a configuration of size `l`.
/// A missing Hessian counts as zero.
pub fn scaled_errors(out: &KernelOutput, r: &Reference, l: f64) -> Scaled {
    let zeros = vec![0.0; r.hess.len()];
    let h = out.hess.as_ref().unwrap_or(&zeros);
    let nan_inf = |v: f64| if v.is_nan() { f64::INFINITY } else { v };
    Scaled {
        gap: nan_inf((out.gap - r.gap).abs() / r.gap.abs().max(l)),
        xi_m: nan_inf(
            std::iter::once((out.xi_m, r.xi_m))
                .chain(out.xi_rest.iter().copied().zip(r.xi_rest.iter().copied()))
                .map(|(a, b)| (a - b).abs() / (1.0 + b.abs()))
                .fold(0.0, f64::max)
                + if out.xi_rest.len() == r.xi_rest.len() {
                    0.0
                } else {
                    f64::INFINITY
                },
        ),
        grad: nan_inf(
            norm(out.grad.iter().zip(&r.grad).map(|(a, b)| a - b))
                / norm(r.grad.iter().copied()).max(1.0),
        ),
        hess: nan_inf(
            norm(h.iter().zip(&r.hess).map(|(a, b)| a - b))
                / norm(r.hess.iter().copied()).max(1.0 / l),
        ),
    }
}

/// The worst scaled error of one output over the configurations, and where.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Worst {
    /// The scaled error.
    pub error: f64,
    /// The configuration's label.
    pub at: String,
}

impl Worst {
    fn update(&mut self, e: f64, at: &str) {
        if e > self.error || self.at.is_empty() {
            self.error = e;
            self.at = at.to_owned();
        }
    }
}

/// One type's row of the report.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Row {
    /// The type (1..=6).
    pub ty: usize,
    /// `g`.
    pub gap: Worst,
    /// `xi_m`.
    pub xi_m: Worst,
    /// `g'`.
    pub grad: Worst,
    /// `g''`.
    pub hess: Worst,
    /// Configurations the kernel refused although the reference solved them.
    pub refused: Vec<String>,
}

impl Row {
    /// The largest scaled error of the row.
    pub fn max(&self) -> f64 {
        [&self.gap, &self.xi_m, &self.grad, &self.hess]
            .iter()
            .map(|w| w.error)
            .fold(0.0, f64::max)
    }

    /// Whether the row is within `tol` and nothing was refused.
    pub fn passes(&self, tol: f64) -> bool {
        self.max() <= tol && self.refused.is_empty()
    }
}

/// The outcome of a verification.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The formulation's name.
    pub name: String,
    /// One row per type, 1 to 6.
    pub rows: Vec<Row>,
    /// Configurations compared.
    pub checked: usize,
    /// Configurations skipped (no projection, or `|xi_m| > 5`).
    pub skipped: usize,
    /// The tolerance.
    pub tol: f64,
}

impl Report {
    /// Whether every type passed (and at least one configuration was
    /// compared).
    pub fn passed(&self) -> bool {
        self.checked > 0 && self.rows.iter().all(|r| r.passes(self.tol))
    }

    /// The rows that fail.
    pub fn failures(&self) -> Vec<&Row> {
        self.rows.iter().filter(|r| !r.passes(self.tol)).collect()
    }
}

impl fmt::Display for Report {
    /// The Markdown table of the worst scaled errors.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{}: {} configurations checked, {} skipped; tolerance {:e} (scaled errors, \
             see `gapsim verify --help`)",
            self.name, self.checked, self.skipped, self.tol
        )?;
        writeln!(f)?;
        writeln!(f, "| type | g | xi_m | g' | g'' | worst at | status |")?;
        writeln!(f, "|---|---:|---:|---:|---:|---|---|")?;
        for r in &self.rows {
            let worst = [&r.gap, &r.xi_m, &r.grad, &r.hess]
                .into_iter()
                .max_by(|a, b| a.error.total_cmp(&b.error))
                .expect("four outputs");
            let status = if r.passes(self.tol) {
                "ok".to_owned()
            } else if !r.refused.is_empty() {
                format!(
                    "FAIL ({} refused, first: {})",
                    r.refused.len(),
                    r.refused[0]
                )
            } else {
                "FAIL".to_owned()
            };
            writeln!(
                f,
                "| {} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {} | {} |",
                r.ty, r.gap.error, r.xi_m.error, r.grad.error, r.hess.error, worst.at, status
            )?;
        }
        Ok(())
    }
}

/// The kernels under test: type (1..=6), absolute coordinates `q` and the
/// parameters in, the output out (`None` when the kernel refuses the
/// configuration).
pub type KernelFn<'a> = dyn Fn(usize, &[f64], &[f64]) -> Option<KernelOutput> + 'a;

/// The slip kernels under test: type (1..=6), absolute coordinates `q`
/// and the parameters followed by the last converged projection `xi_m0`
/// in, one output per slip component out (its value in
/// [`KernelOutput::gap`]; `None` when the kernel refuses the
/// configuration).
pub type SlipKernelFn<'a> = dyn Fn(usize, &[f64], &[f64]) -> Option<Vec<KernelOutput>> + 'a;

/// The last converged projection the slip is verified at: the
/// configuration's projection moved by `(0.15, -0.1)` (per component), so
/// that the master point has moved and every term of the slip is alive.
pub fn previous_projection(xi_m: &[f64]) -> Vec<f64> {
    xi_m.iter().zip([0.15, -0.1]).map(|(x, d)| x + d).collect()
}

/// Verifies `kernel` against the AD reference of the same formulation on
/// `configs`.
pub fn verify(
    reference: &AdFormulation,
    kernel: &KernelFn<'_>,
    configs: &[Config],
    tol: f64,
) -> Result<Report, VerifyError> {
    let run = |ty: usize, q: &[f64], p: &[f64]| kernel(ty, q, p).map(|o| vec![o]);
    compare(reference, &run, configs, tol, Quantity::Gap)
}

/// Verifies the slip `kernel` against the AD reference of the same
/// formulation's slip on `configs`, at the last converged projection
/// [`previous_projection`] of each (the worst component of each block per
/// type; the report's `g` column is the slip).
pub fn verify_slip(
    reference: &AdFormulation,
    kernel: &SlipKernelFn<'_>,
    configs: &[Config],
    tol: f64,
) -> Result<Report, VerifyError> {
    compare(reference, kernel, configs, tol, Quantity::Slip)
}

/// [`verify`] and [`verify_slip`]: every component of `quantity`.
fn compare(
    reference: &AdFormulation,
    kernel: &SlipKernelFn<'_>,
    configs: &[Config],
    tol: f64,
    quantity: Quantity,
) -> Result<Report, VerifyError> {
    let f = reference.formulation();
    let dim = f.signature.dim();
    let mut rows: Vec<Row> = (1..=6)
        .map(|ty| Row {
            ty,
            ..Row::default()
        })
        .collect();
    let (mut checked, mut skipped) = (0, 0);
    for c in configs {
        let d: Vec<f64> =
            c.q.iter()
                .enumerate()
                .map(|(i, v)| v - c.q[i % dim])
                .collect();
        let l = size(&d);
        // Absolute coordinates, moved by an offset; far ones as they are,
        // and the reference relative to their first point.
        let far = size(&c.q) > FAR * l;
        let q = if far { c.q.clone() } else { offset(&c.q, dim) };
        let at = if far { &d } else { &q };
        let Some(xi0) = reference.project(at, &c.params, XI_M_SKIP) else {
            skipped += 1;
            continue;
        };
        checked += 1;
        let mut params = c.params.clone();
        if quantity == Quantity::Slip {
            params.extend(previous_projection(&xi0));
        }
        let refs = reference.references_of(at, &params, &xi0, quantity)?;
        for (row, r) in rows.iter_mut().zip(&refs) {
            match kernel(row.ty, &q, &params) {
                Some(outs) if outs.len() == r.len() => {
                    for (out, r) in outs.iter().zip(r) {
                        let e = scaled_errors(out, r, l);
                        row.gap.update(e.gap, &c.label);
                        row.xi_m.update(e.xi_m, &c.label);
                        row.grad.update(e.grad, &c.label);
                        row.hess.update(e.hess, &c.label);
                    }
                }
                Some(_) | None => row.refused.push(c.label.clone()),
            }
        }
    }
    let name = match quantity {
        Quantity::Gap => f.name.clone(),
        Quantity::Slip => format!("{} (slip)", f.name),
    };
    Ok(Report {
        name,
        rows,
        checked,
        skipped,
        tol,
    })
}

/// The configurations for `reference`'s formulation: for two-node segment
/// pairs (4 points) [`families::all`] constructed along the slave normal,
/// for 3-node segment pairs (6 points) [`families::quadratic`]; one
/// parameter (`xi_s`) either way.
pub fn configurations(reference: &AdFormulation) -> Result<Vec<Config>, VerifyError> {
    let sig = &reference.formulation().signature;
    if sig.dim() == 3 && sig.param_count() == 2 {
        let slave = families::faces::FaceKind::of_nodes(sig.slave_points());
        let master = families::faces::FaceKind::of_nodes(sig.points().len() - sig.slave_points());
        if let (Some(s), Some(m)) = (slave, master) {
            return Ok(families::faces::faces(s, m));
        }
    }
    match (sig.points().len(), sig.params().len()) {
        (4, 1) => Ok(families::all(families::Normal::Slave)),
        (6, 1) => Ok(families::quadratic()),
        (points, params) => Err(VerifyError::Arity {
            file: format!("{}.rs", reference.formulation().name),
            points,
            params,
        }),
    }
}

/// What [`verify_source`] found: the gap kernels' report, the slip
/// kernels' (when the file has a `slip!`) and the mutation applied.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceReport {
    /// The gap kernels.
    pub gap: Report,
    /// The slip kernels, if the formulation defines a slip.
    pub slip: Option<Report>,
    /// The instruction `flip` changed, if any.
    pub flip: Option<Flip>,
}

impl SourceReport {
    /// Whether every report passed.
    pub fn passed(&self) -> bool {
        self.gap.passed() && self.slip.as_ref().is_none_or(Report::passed)
    }
}

/// Verifies the generated kernels of one formulation file (its name and
/// text), run by codegen's interpreter, on every family, and its slip
/// kernels when it defines a slip; `flip` mutates one instruction of a gap
/// kernel first ([`InterpretedKernels::flip_sign`]: type, instruction).
pub fn verify_source(
    name: &str,
    text: &str,
    flip: Option<(usize, usize)>,
) -> Result<SourceReport, VerifyError> {
    let reference = AdFormulation::parse(name, text)?;
    let configs = configurations(&reference)?;
    let mut kernels = InterpretedKernels::new(reference.formulation())?;
    let flipped = flip.map(|(ty, i)| kernels.flip_sign(ty, i)).transpose()?;
    let run = |ty: usize, q: &[f64], params: &[f64]| {
        let d = kernels.relative(q);
        kernels.eval(ty, &d, params)
    };
    let gap = verify(&reference, &run, &configs, TOL)?;
    let slip = if kernels.has_slip() {
        let run = |ty: usize, q: &[f64], params: &[f64]| {
            let d = kernels.relative(q);
            kernels.eval_slip(ty, &d, params)
        };
        Some(verify_slip(&reference, &run, &configs, TOL)?)
    } else {
        None
    };
    Ok(SourceReport {
        gap,
        slip,
        flip: flipped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SLAVE_NORMAL: &str = include_str!("../../contact-kernels/formulations/slave-normal.rs");

    fn out(r: &Reference) -> KernelOutput {
        KernelOutput {
            gap: r.gap,
            xi_m: r.xi_m,
            xi_rest: r.xi_rest.clone(),
            grad: r.grad.clone(),
            hess: Some(r.hess.clone()),
        }
    }

    /// The interpreted `kernels` against `reference` on `configs`.
    fn verify_interpreted(
        reference: &AdFormulation,
        kernels: &InterpretedKernels,
        configs: &[Config],
    ) -> Report {
        verify(
            reference,
            &|ty, q, p| kernels.eval(ty, &kernels.relative(q), p),
            configs,
            TOL,
        )
        .unwrap()
    }

    /// The indices of the `Add` instructions of Type `ty`'s program.
    fn adds(kernels: &InterpretedKernels, ty: usize) -> Vec<usize> {
        (kernels.program(ty).instrs.iter().enumerate())
            .filter(|(_, i)| matches!(i, codegen::lower::Instr::Add(..)))
            .map(|(k, _)| k)
            .collect()
    }

    /// The types that fail in `report`.
    fn failing(report: &Report) -> Vec<usize> {
        report.failures().iter().map(|r| r.ty).collect()
    }

    #[test]
    fn scaled_errors_measure_each_block_against_its_bound() {
        let mut r = Reference::zeros(2);
        r.gap = 0.5;
        r.grad = vec![3.0, 4.0];
        r.hess = vec![1.0, 0.0, 0.0, 1.0];
        assert_eq!(scaled_errors(&out(&r), &r, 2.0), Scaled::default());
        let mut o = out(&r);
        o.gap = 0.5 + 1e-3; // bound max(|g|, L) = 2
        o.grad[0] += 5e-3; // bound ‖g'‖ = 5
        o.hess = None; // missing Hessian counts as zero: ‖g''‖ / ‖g''‖ = 1
        let e = scaled_errors(&o, &r, 2.0);
        assert!((e.gap - 5e-4).abs() < 1e-15, "{e:?}");
        assert!((e.grad - 1e-3).abs() < 1e-15, "{e:?}");
        assert_eq!(e.hess, 1.0);
        o.gap = f64::NAN;
        assert_eq!(scaled_errors(&o, &r, 2.0).max(), f64::INFINITY);
    }

    #[test]
    fn a_kernel_that_refuses_fails_and_names_the_configuration() {
        let reference = AdFormulation::parse("slave-normal", SLAVE_NORMAL).unwrap();
        let configs = configurations(&reference).unwrap();
        let refuse = |_: usize, _: &[f64], _: &[f64]| None;
        let report = verify(&reference, &refuse, &configs[..3], TOL).unwrap();
        assert!(!report.passed());
        assert_eq!(report.failures().len(), 6);
        assert_eq!(report.rows[0].refused[0], "worked");
        assert!(
            report
                .to_string()
                .contains("FAIL (3 refused, first: worked)")
        );
    }

    #[test]
    fn the_interpreted_kernels_pass_and_a_flipped_sign_fails() {
        let reference = AdFormulation::parse("slave-normal", SLAVE_NORMAL).unwrap();
        let configs = configurations(&reference).unwrap();
        let mut kernels = InterpretedKernels::new(reference.formulation()).unwrap();
        let report = verify_interpreted(&reference, &kernels, &configs[..50]);
        assert!(report.passed(), "{report}");
        let flip = kernels
            .flip_sign(6, *adds(&kernels, 6).last().unwrap())
            .unwrap();
        assert!(flip.before.starts_with("Add(") && flip.after.starts_with("Sub("));
        let report = verify_interpreted(&reference, &kernels, &configs[..50]);
        assert_eq!(failing(&report), [6], "{report}");
    }

    /// The 3-node formulation: its families are 3-node configurations, the
    /// interpreted kernels pass on them, and a flipped sign fails.
    #[test]
    fn the_quadratic_formulation_verifies_and_a_flipped_sign_fails() {
        const QUADRATIC: &str =
            include_str!("../../contact-kernels/formulations/quadratic-slave-normal.rs");
        let source = verify_source("quadratic-slave-normal", QUADRATIC, None).unwrap();
        assert!(source.flip.is_none());
        let report = source.gap;
        assert!(report.passed(), "{report}");
        let slip = source.slip.expect("the shipped file defines a slip");
        assert!(slip.passed(), "{slip}");
        let configs = families::quadratic();
        assert!(
            configs
                .iter()
                .all(|c| c.q.len() == 12 && c.params.len() == 1)
        );
        assert!(
            report.checked * 10 >= configs.len() * 9,
            "only {} of {} configurations compared",
            report.checked,
            configs.len()
        );
        let reference = AdFormulation::parse("quadratic-slave-normal", QUADRATIC).unwrap();
        let mut kernels = InterpretedKernels::new(reference.formulation()).unwrap();
        let adds = adds(&kernels, 3);
        kernels.flip_sign(3, adds[adds.len() / 2]).unwrap();
        let report = verify_interpreted(&reference, &kernels, &configs[..60]);
        assert_eq!(failing(&report), [3], "{report}");
    }

    /// Kernels that take coordinates relative to the first point (the
    /// lowering's shortcut) of a formulation that is not translation
    /// invariant fail: the verifier compares on absolute coordinates with
    /// an offset. The same kernels of the invariant formulation pass.
    #[test]
    fn relative_kernels_of_a_translation_dependent_formulation_fail() {
        let relative_kernels = |reference: &AdFormulation| {
            let reference = reference.clone();
            move |ty: usize, q: &[f64], p: &[f64]| {
                let d: Vec<f64> = q.iter().enumerate().map(|(i, v)| v - q[i % 2]).collect();
                let xi = reference.project(&d, p, XI_M_SKIP)?;
                let r = reference.references(&d, p, &xi).ok()?;
                Some(out(&r[ty - 1]))
            }
        };
        let bad = SLAVE_NORMAL.replace("let t_s = xs2 - xs1;", "let t_s = xs2 - xs1 + xs1;");
        assert_ne!(bad, SLAVE_NORMAL);
        for (text, passes) in [(SLAVE_NORMAL, true), (bad.as_str(), false)] {
            let reference = AdFormulation::parse("f", text).unwrap();
            let configs = configurations(&reference).unwrap();
            let kernel = relative_kernels(&reference);
            let report = verify(&reference, &kernel, &configs[..40], TOL).unwrap();
            assert_eq!(report.passed(), passes, "{report}");
        }
    }

    #[test]
    fn bad_mutations_and_shapes_are_errors() {
        let reference = AdFormulation::parse("slave-normal", SLAVE_NORMAL).unwrap();
        let mut kernels = InterpretedKernels::new(reference.formulation()).unwrap();
        for (ty, i) in [(7, 0), (3, 0), (3, 1_000_000)] {
            assert!(
                matches!(kernels.flip_sign(ty, i), Err(VerifyError::Mutation(_))),
                "{ty}:{i}"
            );
        }
        let three_points = SLAVE_NORMAL
            .replace(
                "inputs!(xs1, xs2, xm1, xm2; xi_s);",
                "inputs!(xs1, xs2, xm1; xi_s);",
            )
            .replace("lerp(xm1, xm2, xi)", "lerp(xm1, xs1, xi)")
            .replace("lerp(xm1, xm2, xi_m)", "lerp(xm1, xs1, xi_m)")
            .replace("lerp(xm1, xm2, xi_m0)", "lerp(xm1, xs1, xi_m0)");
        let r = AdFormulation::parse("three", &three_points).unwrap();
        let e = configurations(&r).unwrap_err();
        assert!(
            matches!(
                e,
                VerifyError::Arity {
                    points: 3,
                    params: 1,
                    ..
                }
            ),
            "{e}"
        );
    }
}
