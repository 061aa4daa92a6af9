//! The front-page example: evaluate the exact and the cheapest kernel, and
//! re-project.
//!
//! ```text
//! cargo run -p contact-kernels --example quickstart
//! ```
use contact_kernels::{ApproxType, Formulation, KernelError, evaluate, project};

fn main() -> Result<(), KernelError> {
    // q = [xs1, ys1, xs2, ys2, xm1, ym1, xm2, ym2], current coordinates.
    let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    let exact = evaluate(Formulation::SlaveNormal, ApproxType::Type6, &q, 0.3)?;
    let cheap = evaluate(Formulation::SlaveNormal, ApproxType::Type1, &q, 0.3)?; // no Hessian
    let p = project(Formulation::SlaveNormal, &q, 0.3)?; // gap and xi_m only
    assert_eq!(exact.gap, cheap.gap);
    assert!(cheap.hess.is_none() && (p.xi_m - exact.xi_m).abs() < 1e-15);
    println!("gap {:.12}, xi_m {:.12}", exact.gap, exact.xi_m);
    println!("dg/dq (exact) {:.6}", exact.grad.transpose());
    println!("dg/dq (type 1) {:.6}", cheap.grad.transpose());
    Ok(())
}
