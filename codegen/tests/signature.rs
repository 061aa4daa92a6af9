//! The sizes come from `inputs!`: a formulation with three points (a slave
//! segment against a master point, six coordinates) and one without
//! parameters lower, plan and emit with their own counts.

use codegen::emit::RustEmitter;
use codegen::formulation::Arity;
use codegen::lower::{Instr, Source as Load};
use codegen::plan::{InputKind, Layout};
use codegen::{Formulation, KernelPlan, Source};

/// A slave segment against a master point: `xi_m` is pinned to `xi_s`.
const POINT: &str = "//! Segment against a point.
inputs!(xs1, xs2, xm; xi_s);
let x_s = lerp(xs1, xs2, xi_s);
let t_s = xs2 - xs1;
let xi_m = implicit!(xi => xi - xi_s);
let x_ms = entity!(xm - x_s);
let n = entity!(perp(t_s) / norm(t_s));
gap!(dot(n, x_ms));
";

fn slave_normal() -> String {
    std::fs::read_to_string(format!(
        "{}/../contact-kernels/formulations/slave-normal.rs",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// The largest coordinate index and parameter count a program loads.
fn loads(p: &codegen::Program) -> (usize, usize) {
    let (mut coord, mut params) = (0, 0);
    for i in &p.instrs {
        match i {
            Instr::Load(Load::Coord(k)) => coord = coord.max(*k),
            Instr::Load(Load::Param(k)) => params = params.max(k + 1),
            _ => {}
        }
    }
    (coord, params)
}

#[test]
fn three_points_lower_with_six_coordinates() {
    let f = Formulation::parse_with("point", POINT, Arity::Any).unwrap();
    let sig = &f.signature;
    assert_eq!(sig.points(), ["xs1", "xs2", "xm"]);
    assert_eq!(sig.params(), ["xi_s"]);
    assert_eq!(sig.implicit(), "xi_m");
    assert_eq!((sig.coords(), sig.packed_len()), (6, 21));
    let p = codegen::programs(&f).unwrap();
    assert!(p.affine);
    for (prog, has_hess) in &p.kernels {
        // [g, grad(6), packed hess(21), xi_m]
        assert_eq!(prog.outputs.len(), 1 + 6 + 21 + 1);
        assert!(loads(prog).0 < 6);
        let _ = has_hess;
    }
    // The interpreter agrees with the geometry: slave along x at y = 1,
    // master point at (0.5, 0.25): gap = -(0.25 - 1) . (0, -1) ... = 0.75
    // along the outward normal (0, -1) of a segment running in +x.
    let d = [0.0, 0.0, 2.0, 0.0, 0.5, -0.75];
    let out = p.kernels[5].0.run(&d, &[0.3], 0.0);
    assert!((out[0] - 0.75).abs() < 1e-15, "{}", out[0]);
    assert_eq!(out[1 + 6 + 21], 0.3);

    // The strict parse (the run-time's segment pair) still refuses it.
    let e = Formulation::parse("point", POINT).unwrap_err().to_string();
    assert!(e.contains("four points"), "{e}");
}

#[test]
fn the_plan_and_the_rust_emitter_take_the_signature_sizes() {
    let src = Source {
        name: "point".into(),
        text: POINT.into(),
        compiled: true,
    };
    let plan = KernelPlan::build_with(&[src], Arity::Any).unwrap();
    let set = plan.formulations[0].kernels.as_ref().unwrap();
    let t6 = &set.kernels[5];
    assert_eq!(t6.inputs[0].kind, InputKind::Coords);
    assert_eq!(t6.inputs[0].len, 6);
    let hess = t6.output("hess").unwrap();
    assert_eq!(
        (hess.len, hess.layout),
        (21, Layout::PackedSymmetric { n: 6 })
    );
    assert_eq!(t6.output("grad").unwrap().len, 6);
    assert_eq!(t6.ops, t6.program.op_count());
    let code = RustEmitter.source(&plan);
    assert!(code.contains("let d = &d[..6];"), "{code}");
    assert!(code.contains("let hess = &mut hess[..36];"));
    assert!(code.contains("coords: 6,"));
}

#[test]
fn a_parameterless_formulation_loads_no_parameter() {
    let text = slave_normal()
        .replace("xm2; xi_s)", "xm2;)")
        .replace("lerp(xs1, xs2, xi_s)", "lerp(xs1, xs2, 0.25)");
    let f = Formulation::parse_with("fixed", &text, Arity::Any).unwrap();
    assert!(f.signature.params().is_empty());
    assert_eq!(f.signature.coords(), 8);
    let p = codegen::programs(&f).unwrap();
    for (prog, _) in &p.kernels {
        assert_eq!(loads(prog).1, 0);
    }
    // The same kernels as slave-normal at xi_s = 0.25.
    let sn = codegen::programs(&Formulation::parse("sn", &slave_normal()).unwrap()).unwrap();
    let d = [0.0, 0.0, 2.0, 0.1, 2.1, -0.1, -0.1, 0.0];
    let a = p.kernels[5].0.run(&d, &[], 0.0);
    let b = sn.kernels[5].0.run(&d, &[0.25], 0.0);
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-14 * (1.0 + y.abs()), "{x} vs {y}");
    }
}
