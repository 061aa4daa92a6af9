//! The sympy-cse peers of the kernel benchmark (`benches/peer/`) compute
//! what gapsim's Type 6 kernels compute (gap, xi_m, gradient, full
//! Hessian): the 2D one the slave-normal kernel's, the 3D one the
//! tri3-slave-normal kernel's, so `benches/kernels.rs` compares like with
//! like.

#[path = "../benches/peer/sympy_kernel.rs"]
mod sympy_kernel;

#[path = "../benches/peer/sympy_kernel_3d.rs"]
mod sympy_kernel_3d;

use gapsim::contact_kernels::{ApproxType, Formulation, GapOut, Kernel};

#[test]
fn the_peer_computes_the_type6_slave_normal_kernel() {
    let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6).unwrap();
    let mut out = GapOut::new(&kernel);
    let base = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    for k in 0..64 {
        let q: [f64; 8] =
            std::array::from_fn(|i| base[i] + 0.1 * ((k * 7 + i * 3) % 11) as f64 / 11.0);
        let xi_s = -0.9 + 1.8 * (k as f64) / 63.0;
        kernel.eval(&q, xi_s, &mut out).unwrap();
        let (mut g, mut xi_m) = (0.0, 0.0);
        let mut grad = [0.0; 8];
        let mut hess = [[0.0; 8]; 8];
        sympy_kernel::gap_hess_sympy(&q, xi_s, &mut g, &mut xi_m, &mut grad, &mut hess);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * (1.0 + b.abs());
        assert!(close(g, out.gap()), "gap {g} vs {}", out.gap());
        assert!(close(xi_m, out.xi_m()));
        let kernel_hess = out.hess().unwrap();
        for (j, row) in hess.iter().enumerate() {
            assert!(close(grad[j], out.grad()[j]), "grad {j}");
            for (l, &h) in row.iter().enumerate() {
                assert!(close(h, kernel_hess[8 * j + l]), "hess {j} {l}");
            }
        }
    }
    assert_eq!(sympy_kernel::SYMPY_OPS, 1331);
}

/// The 3D peer against `tri3-slave-normal` Type 6 on the worked example of
/// docs/conventions.md ("3D faces") and 63 configurations around it.
#[test]
fn the_3d_peer_computes_the_type6_tri3_slave_normal_kernel() {
    let kernel = Kernel::new(Formulation::Tri3SlaveNormal, ApproxType::Type6).unwrap();
    let mut out = GapOut::new(&kernel);
    let base = [
        0.0, 0.0, 1.0, 0.1, 1.0, 1.05, 1.0, 0.1, 0.95, -0.3, -0.2, 0.8, 1.4, 0.1, 0.85, 0.2, 1.5,
        0.75,
    ];
    for k in 0..64 {
        let q: [f64; 18] =
            std::array::from_fn(|i| base[i] + 0.1 * ((k * 7 + i * 3) % 11) as f64 / 11.0);
        let (u, v) = (
            0.3 * ((k % 5) as f64) / 4.0,
            0.2 + 0.4 * ((k % 7) as f64) / 6.0,
        );
        kernel.eval(&q, [u, v], &mut out).unwrap();
        let (mut g, mut xi_m) = (0.0, [0.0; 2]);
        let mut grad = [0.0; 18];
        let mut hess = [[0.0; 18]; 18];
        sympy_kernel_3d::gap_hess_sympy_3d(&q, u, v, &mut g, &mut xi_m, &mut grad, &mut hess);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * (1.0 + b.abs());
        assert!(close(g, out.gap()), "gap {g} vs {}", out.gap());
        assert!(close(xi_m[0], out.xi_m_all()[0]) && close(xi_m[1], out.xi_m_all()[1]));
        let kernel_hess = out.hess().unwrap();
        for (j, row) in hess.iter().enumerate() {
            assert!(close(grad[j], out.grad()[j]), "grad {j}");
            for (l, &h) in row.iter().enumerate() {
                assert!(close(h, kernel_hess[18 * j + l]), "hess {j} {l}");
            }
        }
    }
    assert_eq!(sympy_kernel_3d::SYMPY_OPS_3D, 17153);
}
