//! 3-node quadratic segments (the faces of Q8/Q9 elements): the
//! `quadratic-slave-normal` kernels through the handles, 12 coordinates.
//!
//! ```text
//! cargo run -p contact-kernels --features quadratic-slave-normal --example quadratic
//! ```
use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, KernelError, Projector};

fn main() -> Result<(), KernelError> {
    // Each segment's nodes in Gmsh line3 order: end, end, mid.
    // q = [xs1, ys1, xs2, ys2, xs3, ys3, xm1, ym1, xm2, ym2, xm3, ym3].
    // A straight slave along +x and a master below it, its mid node raised
    // towards the slave: x_m(xi) = (1 - xi, -0.8 - 0.2 xi^2).
    let q = [
        0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 1.0, -0.8,
    ];
    let kernel = Kernel::new(Formulation::QuadraticSlaveNormal, ApproxType::Type6)?;
    let mut out = GapOut::new(&kernel); // gradient: 12 values, Hessian: 12 x 12 row-major
    kernel.eval(&q, 0.5, &mut out)?;
    // The slave point (1.5, 0) projects along (0, -1) onto xi_m = -0.5,
    // (1.5, -0.85): g = 0.85.
    println!("gap {:.15}, xi_m {:+.15}", out.gap(), out.xi_m());
    println!(
        "dg/dym1, dg/dym2, dg/dym3 = {:?}",
        [7, 9, 11].map(|k| out.grad()[k])
    );

    // Re-projection only (Newton on the quadratic residual from xi = 0).
    let p = Projector::new(Formulation::QuadraticSlaveNormal)?;
    let mut scratch = [0.0; 12];
    for xi_s in [-0.774597, 0.0, 0.774597] {
        let pr = p.project(&q, xi_s, &mut scratch)?;
        println!("xi_s {xi_s:+.6}: gap {:.12}, xi_m {:+.12}", pr.gap, pr.xi_m);
    }

    // A mid node at the quarter point folds the segment: a typed error.
    let mut folded = q;
    folded[4] = 1.5;
    println!(
        "folded slave: {}",
        kernel.eval(&folded, 0.5, &mut out).unwrap_err()
    );
    Ok(())
}
