//! The lowered programs compute what their expressions say.
//!
//! For each shipped formulation and type, the instruction list (run by the
//! reference interpreter [`codegen::Program::run`], in coordinates relative
//! to slave node 1) must agree with the DAG evaluated directly in absolute
//! coordinates. This checks the relative-coordinate substitution, the
//! simplifier, dead-code removal and the output sign absorption together.

use std::collections::HashMap;

use codegen::expr::Sym;
use codegen::truncation::{Quantity, derive};
use codegen::{Formulation, TYPES};

fn load(name: &str) -> Formulation {
    let path = format!(
        "{}/../contact-kernels/formulations/{name}.rs",
        env!("CARGO_MANIFEST_DIR")
    );
    Formulation::parse(name, &std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A tiny deterministic generator (xorshift), enough for sampling.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

#[test]
fn programs_agree_with_direct_evaluation() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    for name in ["slave-normal", "closest-point"] {
        let f = load(name);
        let programs = codegen::programs(&f).unwrap();
        let sig = &f.signature;
        for (t, row) in TYPES.iter().enumerate() {
            let mut dag = f.dag.clone();
            let k = derive(&f, &mut dag, *row, Quantity::Gap).unwrap().remove(0);
            dag.check_invariants();
            let prog = &programs.kernels[t].0;
            for _ in 0..20 {
                // Slave roughly along x at y = 1, master roughly along -x at y = 0.9.
                let origin = [3.0 * rng.next(), 3.0 * rng.next()];
                let rel = [
                    0.0,
                    0.0,
                    2.0 + 0.3 * rng.next(),
                    0.2 * rng.next(),
                    2.0 + 0.3 * rng.next(),
                    -0.1 + 0.1 * rng.next(),
                    0.1 * rng.next(),
                    -0.1 + 0.2 * rng.next(),
                ];
                let (xi_s, xi_in) = (rng.next(), rng.next());
                let mut got = prog.run(&rel, &[xi_s], xi_in);
                // Affine projections are solved inside the program, which
                // returns xi_m last; otherwise xi_m is the input.
                let xi_m = if programs.affine {
                    got.pop().unwrap()
                } else {
                    xi_in
                };
                let mut vals: HashMap<Sym, f64> = (0..sig.coords())
                    .map(|i| (sig.coord_sym(i), rel[i] + origin[i % 2]))
                    .collect();
                vals.insert(sig.param_sym(0), xi_s);
                vals.insert(sig.implicit_sym(), xi_m);
                if programs.affine {
                    // The returned xi_m solves r = 0 (r is O(1) here).
                    let r = programs.residual.run(&rel, &[xi_s], xi_m)[0];
                    assert!(
                        r.abs() < 1e-12,
                        "{name}: residual {r} at the program's xi_m"
                    );
                }
                let want: Vec<f64> = std::iter::once(Some(k.gap))
                    .chain(k.grad.iter().copied())
                    .chain(k.hess.iter().copied())
                    .map(|e| e.map_or(0.0, |id| dag.eval(id, &vals)))
                    .collect();
                assert_eq!(got.len(), want.len());
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    // Both are O(1) quantities here; rounding differs by the
                    // translation (|origin| <= 3), so 1e-12 absolute.
                    assert!(
                        (g - w).abs() <= 1e-12 * (1.0 + w.abs()),
                        "{name} type {}: output {i}: {g} vs {w}",
                        t + 1
                    );
                }
            }
        }
    }
}

#[test]
fn type_one_has_no_hessian_and_type_six_keeps_every_entry() {
    for name in ["slave-normal", "closest-point"] {
        let p = codegen::programs(&load(name)).unwrap();
        assert!(
            !p.kernels[0].1,
            "{name}: type 1 must have no second-order term"
        );
        for (t, (_, has)) in p.kernels.iter().enumerate().skip(1) {
            assert!(*has, "{name}: type {} must have a Hessian", t + 1);
        }
        // Fewer kept terms never cost more than the full type.
        let ops: Vec<u32> = p
            .kernels
            .iter()
            .map(|(prog, _)| prog.op_count().total())
            .collect();
        assert!(ops.iter().all(|&o| o <= ops[5]), "{name}: {ops:?}");
    }
}

#[test]
fn malformed_formulations_are_reported_with_position() {
    let text = std::fs::read_to_string(format!(
        "{}/../contact-kernels/formulations/slave-normal.rs",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let cases = [
        (
            text.replace("let n = entity!", "let nn = entity!")
                .replace("dot(n, x_ms)", "dot(nn, x_ms)"),
            "entity `n`",
        ),
        (
            text.replace("gap!(dot(n, x_ms));", "gap!(dot(n, x_s));"),
            "the gap may only use entities",
        ),
        (
            text.replace(
                "inputs!(xs1, xs2, xm1, xm2; xi_s);",
                "inputs!(xs1, xs2, xm1; xi_s);",
            ),
            "four points",
        ),
        (
            text.replace("norm(t_s)", "norm(t_s, t_s)"),
            "takes 1 argument",
        ),
    ];
    for (src, expect) in cases {
        let err = codegen::generate(&[codegen::Source {
            name: "bad".into(),
            text: src,
            compiled: true,
        }])
        .unwrap_err();
        assert!(
            err.to_string().contains(expect),
            "expected `{expect}` in: {err}"
        );
    }
}
