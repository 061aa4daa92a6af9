//! The generated kernels of a formulation file, run by codegen's
//! instruction-list interpreter ([`codegen::Program::run`]) instead of being
//! compiled: exactly the instructions every emitter writes out, one per
//! statement, in order.
//!
//! [`InterpretedKernels::flip_sign`] is the verifier's mutation hook: it
//! turns one `+` of a kernel into `-` (or one `-` into `+`), the kind of
//! slip a hand-edited or mis-generated kernel has, so that tests and
//! docs/kernels.md can show the verifier catching a broken kernel.

use codegen::lower::Instr;
use codegen::{Formulation, FormulationPrograms, Program};

use super::{KernelOutput, VerifyError};

/// Newton iterations of the projection when the kernels do not solve it in
/// closed form (as contact-kernels' projection).
const ITERATIONS: usize = 20;
/// A Newton correction below this (relative to `1 + |xi|`) ends the solve.
const TOLERANCE: f64 = 1e-12;

/// One formulation's programs, ready to run.
#[derive(Debug, Clone)]
pub struct InterpretedKernels {
    programs: FormulationPrograms,
    n: usize,
    dim: usize,
    /// Components of the implicit unknown (1, or 2 for faces).
    k: usize,
    /// The slip's components (0 without `slip!`).
    slip_components: usize,
}

/// What [`InterpretedKernels::flip_sign`] changed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Flip {
    /// The type (1..=6).
    pub ty: usize,
    /// The instruction index in that type's program.
    pub instr: usize,
    /// The instruction before, e.g. `Add(r3, r7)`.
    pub before: String,
    /// The instruction after.
    pub after: String,
}

impl InterpretedKernels {
    /// Derives and lowers every program of `f` (codegen's pipeline).
    pub fn new(f: &Formulation) -> Result<InterpretedKernels, codegen::Error> {
        Ok(InterpretedKernels {
            programs: codegen::programs(f)?,
            n: f.signature.coords(),
            dim: f.signature.dim(),
            k: f.implicit.dim(),
            slip_components: f.slip_components(),
        })
    }

    /// The program of type `ty` (1..=6).
    pub fn program(&self, ty: usize) -> &Program {
        &self.programs.kernels[ty - 1].0
    }

    /// Flips the sign of instruction `instr` of type `ty`'s program: an
    /// addition becomes a subtraction and a subtraction an addition.
    pub fn flip_sign(&mut self, ty: usize, instr: usize) -> Result<Flip, VerifyError> {
        if !(1..=6).contains(&ty) {
            return Err(VerifyError::Mutation(format!("no type {ty} (1 to 6)")));
        }
        let prog = &mut self.programs.kernels[ty - 1].0;
        let len = prog.instrs.len();
        let Some(i) = prog.instrs.get_mut(instr) else {
            return Err(VerifyError::Mutation(format!(
                "type {ty} has {len} instructions, no instruction {instr}"
            )));
        };
        let before = format!("{i:?}");
        *i = match *i {
            Instr::Add(a, b) => Instr::Sub(a, b),
            Instr::Sub(a, b) => Instr::Add(a, b),
            _ => {
                let adds: Vec<usize> = prog
                    .instrs
                    .iter()
                    .enumerate()
                    .filter(|(_, x)| matches!(x, Instr::Add(..) | Instr::Sub(..)))
                    .map(|(k, _)| k)
                    .take(8)
                    .collect();
                return Err(VerifyError::Mutation(format!(
                    "type {ty} instruction {instr} is {before}, not an addition or subtraction \
                     (some that are: {adds:?})"
                )));
            }
        };
        Ok(Flip {
            ty,
            instr,
            before,
            after: format!("{i:?}"),
        })
    }

    /// The coordinates relative to the first point, as the kernels receive
    /// them (`d[i] = q[i] - q[i mod dim]`).
    pub fn relative(&self, q: &[f64]) -> Vec<f64> {
        q.iter()
            .enumerate()
            .map(|(i, v)| v - q[i % self.dim])
            .collect()
    }

    /// Runs type `ty` (1..=6) at relative coordinates `d`. `None` when the
    /// projection (Newton on the residual program) fails.
    pub fn eval(&self, ty: usize, d: &[f64], params: &[f64]) -> Option<KernelOutput> {
        let (prog, has_hessian) = &self.programs.kernels[ty - 1];
        self.run(prog, *has_hessian, 1, d, params)?.pop()
    }

    /// Whether the formulation defines a slip (`slip!`).
    pub fn has_slip(&self) -> bool {
        !self.programs.slips.is_empty()
    }

    /// Runs type `ty`'s slip program at relative coordinates `d`; `params`
    /// ends with the last converged projection `xi_m0`. One output per slip
    /// component (its value in [`KernelOutput::gap`]); `None` when the
    /// projection fails or the formulation has no slip.
    pub fn eval_slip(&self, ty: usize, d: &[f64], params: &[f64]) -> Option<Vec<KernelOutput>> {
        let (prog, has_hessian) = self.programs.slips.get(ty.checked_sub(1)?)?;
        self.run(prog, *has_hessian, self.slip_components, d, params)
    }

    /// Runs a kernel program of `c` components (the gap's: 1; the layout
    /// `[values, gradients, packed Hessians]` of
    /// [`FormulationPrograms::kernels`] and `slips`, the closed-form
    /// projection last), the projection solved first unless the program
    /// solves it. `None` when the projection fails.
    fn run(
        &self,
        prog: &Program,
        has_hessian: bool,
        c: usize,
        d: &[f64],
        params: &[f64],
    ) -> Option<Vec<KernelOutput>> {
        let (n, k) = (self.n, self.k);
        let xi = if self.programs.affine {
            vec![0.0; k]
        } else {
            self.project(d, params)?
        };
        let out = prog.run_vector(d, params, &xi);
        let xi_m = if self.programs.affine {
            // The closed-form projection is the last `k` outputs.
            out[out.len() - k..].to_vec()
        } else {
            xi
        };
        let packed = n * (n + 1) / 2;
        Some(
            (0..c)
                .map(|i| {
                    let grad = out[c + i * n..c + (i + 1) * n].to_vec();
                    let hess = has_hessian.then(|| {
                        let mut h = vec![0.0; n * n];
                        let first = c + c * n + i * packed;
                        unpack_hessian(&out[first..first + packed], n, &mut h);
                        h
                    });
                    KernelOutput {
                        gap: out[i],
                        xi_m: xi_m[0],
                        xi_rest: xi_m[1..].to_vec(),
                        grad,
                        hess,
                    }
                })
                .collect(),
        )
    }

    /// Newton's method on the residual program from `xi = 0` (a 2-vector
    /// unknown: the residual program's `[r_0, r_1, A_00, A_01, A_10, A_11]`,
    /// the step by Cramer's rule, until `max|dxi| <= tol (1 + max|xi|)`).
    fn project(&self, d: &[f64], params: &[f64]) -> Option<Vec<f64>> {
        let mut xi = vec![0.0_f64; self.k];
        let reach = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for _ in 0..ITERATIONS {
            let r = self.programs.residual.run_vector(d, params, &xi);
            let step = match self.k {
                1 => vec![r[0] / r[1]],
                _ => {
                    let [r0, r1, a00, a01, a10, a11] = [r[0], r[1], r[2], r[3], r[4], r[5]];
                    let det = a00 * a11 - a01 * a10;
                    vec![(a11 * r0 - a01 * r1) / det, (a00 * r1 - a10 * r0) / det]
                }
            };
            if !step.iter().all(|s| s.is_finite()) {
                return None;
            }
            xi.iter_mut().zip(&step).for_each(|(x, s)| *x -= s);
            if reach(&step) <= TOLERANCE * (1.0 + reach(&xi)) {
                return Some(xi);
            }
        }
        None
    }
}

/// The interpreted kernels behind contact-kernels' run-time seam, so that
/// a formulation file is evaluated with the compiled kernels' validation,
/// projection and output checks (`gapsim kernel --formulation FILE.rs`).
impl contact_kernels::RuntimeKernels for InterpretedKernels {
    fn coords(&self) -> usize {
        self.n
    }

    fn closed_form_projection(&self) -> bool {
        self.programs.affine
    }

    fn residual(&self, d: &[f64], xi_s: f64, xi: f64) -> [f64; 2] {
        let r = self.programs.residual.run(d, &[xi_s], xi);
        [r[0], r[1]]
    }

    fn has_hessian(&self, ty: contact_kernels::ApproxType) -> bool {
        self.programs.kernels[ty.index() - 1].1
    }

    fn eval(
        &self,
        ty: contact_kernels::ApproxType,
        d: &[f64],
        xi_s: f64,
        xi_m: &mut f64,
        grad: &mut [f64],
        hess: &mut [f64],
    ) -> f64 {
        let n = self.n;
        let (prog, has_hessian) = &self.programs.kernels[ty.index() - 1];
        let out = prog.run(d, &[xi_s], *xi_m);
        if self.programs.affine {
            *xi_m = *out
                .last()
                .expect("the closed-form projection is the last output");
        }
        grad.copy_from_slice(&out[1..1 + n]);
        if *has_hessian {
            unpack_hessian(&out[1 + n..], n, hess);
        }
        out[0]
    }
}

/// The `n x n` Hessian `hess` (row-major) from its packed upper triangle
/// `packed` (row by row, `j <= k`), as a kernel program outputs it.
fn unpack_hessian(packed: &[f64], n: usize, hess: &mut [f64]) {
    let mut at = 0;
    for j in 0..n {
        for k in j..n {
            hess[j * n + k] = packed[at];
            hess[k * n + j] = packed[at];
            at += 1;
        }
    }
}
