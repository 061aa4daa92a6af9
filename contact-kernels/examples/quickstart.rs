//! The front-page example: evaluate the exact and the cheapest kernel,
//! re-project, and evaluate in a loop into buffers the caller owns.
//!
//! ```text
//! cargo run -p contact-kernels --example quickstart
//! ```
use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, KernelError, evaluate, project};

fn main() -> Result<(), KernelError> {
    // q = [xs1, ys1, xs2, ys2, xm1, ym1, xm2, ym2], current coordinates.
    let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    let exact = evaluate(Formulation::SlaveNormal, ApproxType::Type6, &q, 0.3)?;
    let cheap = evaluate(Formulation::SlaveNormal, ApproxType::Type1, &q, 0.3)?; // no Hessian
    let p = project(Formulation::SlaveNormal, &q, 0.3)?; // gap and xi_m only
    assert_eq!(exact.gap, cheap.gap);
    assert!(cheap.hess.is_none() && (p.xi_m - exact.xi_m).abs() < 1e-15);

    // In a solver's loop: one handle per (formulation, type), the output
    // buffers allocated once and reused; same bits as `evaluate`.
    let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6)?;
    let mut out = GapOut::new(&kernel); // gradient: 8 values, Hessian: 8 x 8 row-major
    for xi_s in [-0.577, 0.3, 0.577] {
        kernel.eval(&q, xi_s, &mut out)?;
        println!(
            "xi_s {xi_s:+.3}: gap {:.12}, xi_m {:+.12}",
            out.gap(),
            out.xi_m()
        );
    }
    kernel.eval(&q, 0.3, &mut out)?;
    assert_eq!((out.gap(), out.grad()), (exact.gap, exact.grad.as_slice()));

    println!("dg/dq (exact) {:.6}", exact.grad.transpose());
    println!("dg/dq (type 1) {:.6}", cheap.grad.transpose());
    Ok(())
}
