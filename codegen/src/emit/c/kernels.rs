//! The generated functions as `static` C functions: the arguments from the
//! plan's inputs and outputs, one `const double vN = ...;` per instruction
//! in the program's order with the Rust emitter's operations and operand
//! order, constants as round-trip literals, stored outputs (a packed
//! Hessian mirrored into the full matrix) and the `gapsim_powi` helper.

use std::fmt::Write as _;

use super::comment;
use crate::lower::{Instr, Operand, Program, Source};
use crate::plan::{Delivery, FunctionPlan, InputKind, Layout};

/// `a^n` by binary powering, in the order of LLVM's `powi` expansion and
/// compiler-rt's `__powidf2` (what Rust's `f64::powi` computes).
pub(super) const POWI: &str =
    "/* a^n by binary powering, in the order of Rust's f64::powi (LLVM). */
static double gapsim_powi(double a, int n)
{
    int recip = n < 0;
    double r = 1.0;
    for (;;) {
        if (n & 1) {
            r *= a;
        }
        n /= 2;
        if (n == 0) {
            break;
        }
        a *= a;
    }
    return recip ? 1.0 / r : r;
}

";

/// One generated function as a `static` C function: the plan's inputs
/// (coordinates as `const double *`, scalar parameters and the implicit
/// value by value, vector ones as `const double *` read by component, the
/// in/out implicit as `double *`), its stored outputs as
/// `double *`, the first returned output as the return value and further
/// returned outputs through `double *` arguments named like them.
pub(super) fn function(f: &FunctionPlan) -> String {
    let mut args = Vec::new();
    let mut coords = "d".to_owned();
    let mut params = Vec::new();
    // Per parameter: its name and the indices of its components in
    // `params` (a vector parameter is passed as `const double *`).
    let mut param_inputs: Vec<(String, Vec<usize>)> = Vec::new();
    let mut implicit = "xi".to_owned();
    let mut implicit_ref = None;
    // A 2-vector unknown (faces) is read and written through its pointer.
    let mut implicit_vector = false;
    for input in &f.inputs {
        match input.kind {
            InputKind::Coords => {
                args.push(format!("const double *{}", input.name));
                coords = input.name.clone();
            }
            InputKind::Param(_) if input.len > 1 => {
                args.push(format!("const double *{}", input.name));
                let first = params.len();
                for k in 0..input.len {
                    params.push(format!("{}[{k}]", input.name));
                }
                param_inputs.push((input.name.clone(), (first..params.len()).collect()));
            }
            InputKind::Param(_) => {
                args.push(format!("double {}", input.name));
                param_inputs.push((input.name.clone(), vec![params.len()]));
                params.push(input.name.clone());
            }
            InputKind::Implicit if input.len > 1 => {
                args.push(format!("const double *{}", input.name));
                implicit = input.name.clone();
                implicit_vector = true;
            }
            InputKind::Implicit => {
                args.push(format!("double {}", input.name));
                implicit = input.name.clone();
            }
            InputKind::ImplicitInOut if input.len > 1 => {
                args.push(format!("double *{}", input.name));
                implicit = input.name.clone();
                implicit_ref = Some(input.name.clone());
                implicit_vector = true;
            }
            InputKind::ImplicitInOut => {
                args.push(format!("double *{}", input.name));
                implicit = "xi_in".into();
                implicit_ref = Some(input.name.clone());
            }
        }
    }
    let mut stores = String::new();
    let mut returned = None;
    let mut write_back = String::new();
    for out in &f.outputs {
        match out.delivery {
            Delivery::Return => {
                let v = output(f.program.outputs[out.first]);
                if returned.is_none() {
                    returned = Some(v);
                } else {
                    args.push(format!("double *{}", out.name));
                    let _ = writeln!(stores, "    *{} = {v};", out.name);
                }
            }
            Delivery::Implicit if out.len > 1 => {
                let target = implicit_ref.as_ref().expect("an in/out implicit input");
                for k in 0..out.len {
                    let v = output(f.program.outputs[out.first + k]);
                    let _ = writeln!(write_back, "    {target}[{k}] = {v};");
                }
            }
            Delivery::Implicit => {
                let target = implicit_ref.as_ref().expect("an in/out implicit input");
                let v = output(f.program.outputs[out.first]);
                write_back = format!("    *{target} = {v};\n");
            }
            Delivery::Store => {
                args.push(format!("double *{}", out.name));
                store(&mut stores, &f.program, out);
            }
        }
    }
    let mut text = comment(&f.doc, "");
    let _ = writeln!(text, "static double {}({})\n{{", f.name, args.join(", "));
    let loaded = |s: Source| f.program.instrs.contains(&Instr::Load(s));
    let implicit_loaded = if implicit_vector {
        f.program
            .instrs
            .iter()
            .any(|i| matches!(i, Instr::Load(Source::ImplicitComponent(_))))
    } else {
        loaded(Source::Implicit)
    };
    // The converged projection is read unless this function solves it.
    if let (Some(r), true) = (&implicit_ref, write_back.is_empty()) {
        if implicit_vector {
            if !implicit_loaded {
                let _ = writeln!(text, "    (void){r};");
            }
        } else if implicit_loaded {
            let _ = writeln!(text, "    const double {implicit} = *{r};");
        } else {
            let _ = writeln!(text, "    (void){r};");
        }
    }
    for (p, components) in &param_inputs {
        if !components.iter().any(|&i| loaded(Source::Param(i))) {
            let _ = writeln!(text, "    (void){p};");
        }
    }
    if implicit_ref.is_none() && !implicit_loaded {
        let _ = writeln!(text, "    (void){implicit};");
    }
    text.push_str(&body(&f.program, &coords, &params, &implicit));
    text.push_str(&stores);
    text.push_str(&write_back);
    let _ = writeln!(
        text,
        "    return {};\n}}",
        returned.expect("a function returns at least one output")
    );
    text
}

/// Assignments of a stored output: a vector entry by entry, a packed
/// symmetric matrix into the full row-major `n x n` buffer, mirrored.
fn store(text: &mut String, p: &Program, out: &crate::plan::Output) {
    let x = &out.name;
    match out.layout {
        Layout::Scalar => {
            let _ = writeln!(text, "    {x}[0] = {};", output(p.outputs[out.first]));
        }
        Layout::Vector => {
            for j in 0..out.len {
                let _ = writeln!(text, "    {x}[{j}] = {};", output(p.outputs[out.first + j]));
            }
        }
        Layout::PackedSymmetric { n } => {
            let mut at = out.first;
            for j in 0..n {
                for k in j..n {
                    let v = output(p.outputs[at]);
                    at += 1;
                    let _ = writeln!(text, "    {x}[{}] = {v};", j * n + k);
                    if j != k {
                        let _ = writeln!(text, "    {x}[{}] = {v};", k * n + j);
                    }
                }
            }
        }
    }
}

/// The declarations of a program's instructions. `coords` names the
/// coordinate array, `params[i]` parameter `i`, `implicit` the implicit
/// unknown's value.
pub fn body(p: &Program, coords: &str, params: &[String], implicit: &str) -> String {
    let mut text = String::new();
    for (i, instr) in p.instrs.iter().enumerate() {
        let rhs = match *instr {
            Instr::Load(Source::Coord(k)) => format!("{coords}[{k}]"),
            Instr::Load(Source::Param(i)) => params[i].clone(),
            Instr::Load(Source::Implicit) => implicit.to_owned(),
            Instr::Load(Source::ImplicitComponent(k)) => format!("{implicit}[{k}]"),
            Instr::Add(a, b) => format!("{} + {}", operand(a), operand(b)),
            Instr::Sub(a, b) => format!("{} - {}", operand(a), operand(b)),
            Instr::Mul(a, b) => format!("{} * {}", operand(a), operand(b)),
            Instr::Square(a) => {
                let a = operand(a);
                format!("{a} * {a}")
            }
            Instr::Powi(a, n) => format!("gapsim_powi({}, {n})", operand(a)),
            Instr::Recip(a) => format!("1.0 / {}", operand(a)),
            Instr::Neg(a) => format!("-{}", operand(a)),
            Instr::Sqrt(a) => format!("sqrt({})", operand(a)),
        };
        let _ = writeln!(text, "    const double v{i} = {rhs};");
    }
    text
}

fn operand(o: Operand) -> String {
    match o {
        Operand::Reg(r) => format!("v{r}"),
        Operand::Const(c) => float_literal(c),
    }
}

/// An output expression: the operand, or `0.0` for a structural zero.
fn output(o: Option<Operand>) -> String {
    o.map_or_else(|| "0.0".into(), operand)
}

/// A C `double` literal that round-trips: Rust's shortest exact
/// representation (`{:?}`, always with a `.` or an exponent, so never an
/// integer literal); negative values are parenthesised.
///
/// # Panics
/// If `c` is not finite (constants in a [`Program`] are finite by the DAG's
/// invariant).
pub fn float_literal(c: f64) -> String {
    assert!(c.is_finite(), "non-finite constant {c}");
    let text = format!("{:?}", c.abs());
    debug_assert!(text.contains(['.', 'e']), "{text} is not a double literal");
    debug_assert_eq!(text.parse::<f64>().map(f64::to_bits), Ok(c.abs().to_bits()));
    if c.is_sign_negative() && c != 0.0 {
        format!("(-{text})")
    } else {
        text
    }
}
