//! Every type of every 3D face formulation (compiled in contact-kernels)
//! against num-dual hyper-dual numbers, through the one verifier
//! (`gapsim::verify`): Type 6 against the exact gradient and Hessian of
//! the gap, Types 1–5 against the truncated formula with `xi = (u, v)`
//! (`E' = E_q + sum_b E_xi_b xi_b'`, ...) assembled by the verifier from
//! num-dual partial derivatives, on the face families of `gapsim-families`
//! (random, rotated, warped quad4, edges and corners, offsets to 1e6,
//! scales 1e-6 and 1e6, masters steep to 85 degrees, penetration).
//!
//! The interpreted programs (`gapsim verify`'s path) of the same files are
//! checked too, and a sign flipped on purpose in a Type 6 kernel fails.

use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, compiled_formulations};
use gapsim::verify::{self, AdFormulation, InterpretedKernels, KernelOutput, TOL};

/// The compiled face formulations and their files.
fn face_formulations() -> Vec<(Formulation, AdFormulation)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/contact-kernels/formulations");
    compiled_formulations()
        .into_iter()
        .filter(|f| f.param_dim() == Some(2))
        .map(|f| {
            let text = std::fs::read_to_string(format!("{dir}/{}.rs", f.name())).unwrap();
            (f, AdFormulation::parse(f.name(), &text).unwrap())
        })
        .collect()
}

#[test]
fn every_face_formulation_is_compiled_in() {
    let names: Vec<&str> = face_formulations().iter().map(|(f, _)| f.name()).collect();
    for kind in ["tri3", "quad4", "tri3-quad4", "quad4-tri3"] {
        for reading in ["slave-normal", "closest-point"] {
            let name = format!("{kind}-{reading}");
            assert!(names.contains(&name.as_str()), "{name} missing: {names:?}");
        }
    }
}

#[test]
fn every_type_of_every_face_kernel_matches_num_dual() {
    for (f, reference) in face_formulations() {
        let handles: Vec<Kernel> = ApproxType::ALL
            .iter()
            .map(|&ty| Kernel::new(f, ty).unwrap())
            .collect();
        let kernel = |ty: usize, q: &[f64], params: &[f64]| {
            let k = &handles[ty - 1];
            let mut out = GapOut::new(k);
            k.eval(q, params, &mut out).ok().map(|()| KernelOutput {
                gap: out.gap(),
                xi_m: out.xi_m_all()[0],
                xi_rest: out.xi_m_all()[1..].to_vec(),
                grad: out.grad().to_vec(),
                hess: out.hess().map(<[f64]>::to_vec),
            })
        };
        let configs = verify::configurations(&reference).unwrap();
        let report = verify::verify(&reference, &kernel, &configs, TOL).unwrap();
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

#[test]
fn the_interpreted_face_programs_verify_and_a_flipped_sign_fails() {
    let (f, reference) = face_formulations()
        .into_iter()
        .find(|(f, _)| f.name() == "quad4-slave-normal")
        .unwrap();
    let configs = verify::configurations(&reference).unwrap();
    let mut kernels = InterpretedKernels::new(reference.formulation()).unwrap();
    let run = |k: &InterpretedKernels| {
        verify::verify(
            &reference,
            &|ty, q, p| k.eval(ty, &k.relative(q), p),
            &configs[..40],
            TOL,
        )
        .unwrap()
    };
    let report = run(&kernels);
    assert!(report.passed(), "{f}:\n{report}");
    let adds: Vec<usize> = (kernels.program(6).instrs.iter().enumerate())
        .filter(|(_, i)| matches!(i, codegen::lower::Instr::Add(..)))
        .map(|(k, _)| k)
        .collect();
    kernels.flip_sign(6, adds[adds.len() / 2]).unwrap();
    let report = run(&kernels);
    let failing: Vec<usize> = report.failures().iter().map(|r| r.ty).collect();
    assert_eq!(failing, [6], "{report}");
}
