//! The slip kernels (`slip!`) of every compiled formulation, segments and
//! faces, against num-dual hyper-dual numbers through the one verifier
//! (`gapsim::verify::verify_slip`): Type 6 against the exact gradient and
//! Hessian of every slip component, Types 1–5 against the truncated
//! formula (the slip's entity `s_m` in `x_ms`'s column) assembled by the
//! verifier from num-dual partial derivatives, on the verifier's families,
//! at the last converged projection `verify::previous_projection` of each
//! configuration. Also: the references tell the types apart (Type 6's
//! kernels fail as Types 1–5), the slip vanishes where the master point has
//! not moved, and Type 1 keeps no slip within a step.

use contact_kernels::{ApproxType, Formulation, Kernel, Slip, SlipOut, compiled_formulations};
use gapsim::verify::{self, AdFormulation, KernelOutput, TOL};

/// Every compiled formulation and its file's AD reference.
fn formulations() -> Vec<(Formulation, AdFormulation)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/contact-kernels/formulations");
    compiled_formulations()
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(format!("{dir}/{}.rs", f.name())).unwrap();
            (f, AdFormulation::parse(f.name(), &text).unwrap())
        })
        .collect()
}

/// The slip handles of `f`, types 1 to 6.
fn slips(f: Formulation) -> Vec<Slip> {
    ApproxType::ALL
        .iter()
        .map(|&ty| {
            Kernel::new(f, ty)
                .unwrap()
                .slip()
                .unwrap_or_else(|| panic!("{f} defines no slip"))
        })
        .collect()
}

/// `slip`'s outputs at `q` with `params = [xi_s.., xi_m0..]`.
fn run(slip: &Slip, q: &[f64], params: &[f64]) -> Option<Vec<KernelOutput>> {
    let k = slip.kernel().param_dim();
    let mut out = SlipOut::new(slip);
    slip.eval(q, &params[..k], &params[k..], &mut out).ok()?;
    Some(
        (0..slip.components())
            .map(|c| KernelOutput {
                gap: out.slip()[c],
                xi_m: out.xi_m_all()[0],
                xi_rest: out.xi_m_all()[1..].to_vec(),
                grad: out.grad(c).to_vec(),
                hess: out.hess(c).map(<[f64]>::to_vec),
            })
            .collect(),
    )
}

#[test]
fn every_shipped_formulation_has_a_slip_of_its_dimension() {
    let all = formulations();
    assert!(all.len() >= 10, "{} compiled formulations", all.len());
    for (f, _) in all {
        for slip in slips(f) {
            let expected = if slip.kernel().param_dim() == 1 { 1 } else { 3 };
            assert_eq!(slip.components(), expected, "{f}");
            assert!(slip.op_count().total() > 0);
        }
    }
}

#[test]
fn every_type_of_every_slip_kernel_matches_num_dual() {
    for (f, reference) in formulations() {
        let handles = slips(f);
        let kernel = |ty: usize, q: &[f64], params: &[f64]| run(&handles[ty - 1], q, params);
        let configs = verify::configurations(&reference).unwrap();
        let report = verify::verify_slip(&reference, &kernel, &configs, TOL).unwrap();
        eprintln!("{report}");
        assert!(report.passed(), "{f}:\n{report}");
        assert!(
            report.checked * 10 >= configs.len() * 8,
            "{f}: only {} of {} configurations compared",
            report.checked,
            configs.len()
        );
    }
}

/// Type 6's slip kernel in place of every type fails Types 1–5: the
/// truncated references differ from the exact one (the test above cannot
/// pass by comparing equal things), and Type 6 passes.
#[test]
fn the_slip_references_tell_the_types_apart() {
    for name in ["slave-normal", "tri3-quad4-closest-point"] {
        let (f, reference) = formulations()
            .into_iter()
            .find(|(f, _)| f.name() == name)
            .unwrap();
        let handles = slips(f);
        let exact = |_: usize, q: &[f64], params: &[f64]| run(&handles[5], q, params);
        let configs = verify::configurations(&reference).unwrap();
        let report = verify::verify_slip(&reference, &exact, &configs[..40], TOL).unwrap();
        let failing: Vec<usize> = report.failures().iter().map(|r| r.ty).collect();
        assert_eq!(failing, [1, 2, 3, 4, 5], "{name}:\n{report}");
    }
}

/// Where the slave point still faces the master point it faced
/// (`xi_m0 = xi_m`) the slip is zero under every type; Type 1 (`xi_m`
/// constant, `s_m` linear at fixed `xi_m`: `N(xi_m) - N(xi_m0)` on the
/// master nodes) then has a zero gradient too: it keeps no slip within a
/// load step. Type 6's gradient is not zero there (the slip's first
/// variation).
#[test]
fn the_slip_vanishes_where_the_master_point_has_not_moved() {
    for (f, reference) in formulations() {
        let configs = verify::configurations(&reference).unwrap();
        let handles = slips(f);
        let k = handles[0].kernel().param_dim();
        let mut tried = 0;
        for c in configs.iter().take(30) {
            let dim = if k == 1 { 2 } else { 3 };
            let d: Vec<f64> =
                c.q.iter()
                    .enumerate()
                    .map(|(i, v)| v - c.q[i % dim])
                    .collect();
            let Some(xi_m) = reference.project(&d, &c.params, 5.0) else {
                continue;
            };
            // The kernels' own projection, so that xi_m0 equals it bit for bit.
            let mut out = SlipOut::new(&handles[5]);
            let params: Vec<f64> = c.params.iter().copied().chain(xi_m).collect();
            if handles[5]
                .eval(&c.q, &params[..k], &params[k..], &mut out)
                .is_err()
            {
                continue;
            }
            let xi_m0 = out.xi_m_all().to_vec();
            tried += 1;
            for (t, slip) in handles.iter().enumerate() {
                let mut out = SlipOut::new(slip);
                slip.eval(&c.q, &c.params[..], &xi_m0[..], &mut out)
                    .unwrap();
                let l = verify::size(&d);
                for (i, s) in out.slip().iter().enumerate() {
                    assert!(s.abs() <= 1e-12 * l, "{f} type {}: s{i} = {s}", t + 1);
                    let g: f64 = out.grad(i).iter().map(|x| x.abs()).fold(0.0, f64::max);
                    if t == 0 {
                        assert!(g <= 1e-12, "{f} type 1: |s{i}'| = {g}");
                    }
                }
                if t == 5 {
                    let g: f64 = (0..slip.components())
                        .flat_map(|i| out.grad(i).to_vec())
                        .map(f64::abs)
                        .fold(0.0, f64::max);
                    assert!(g > 1e-3, "{f}: Type 6's slip gradient vanishes ({g})");
                }
            }
        }
        assert!(tried >= 10, "{f}: only {tried} configurations");
    }
}

/// Bad `xi_m0`: a wrong count and a non-finite value are errors naming
/// them, never a panic or a NaN.
#[test]
fn a_bad_previous_projection_is_refused() {
    let slip = Kernel::new(Formulation::SlaveNormal, ApproxType::Type6)
        .unwrap()
        .slip()
        .unwrap();
    let mut out = SlipOut::new(&slip);
    let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    let e = slip.eval(&q, 0.3, [0.1, 0.2], &mut out).unwrap_err();
    assert!(
        matches!(
            e,
            contact_kernels::KernelError::ParamCount {
                expected: 1,
                found: 2
            }
        ),
        "{e}"
    );
    let e = slip.eval(&q, 0.3, f64::NAN, &mut out).unwrap_err();
    assert!(
        matches!(e, contact_kernels::KernelError::NonFinite { index: 9, .. }),
        "{e}"
    );
    slip.eval(&q, 0.3, -0.2, &mut out).unwrap();
    assert!(out.slip()[0].is_finite() && out.slip()[0] != 0.0);
}
