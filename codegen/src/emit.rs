//! Emission: instruction lists to Rust source with `quote!`, formatted with
//! `prettyplease`.
//!
//! Only [`Program`]s are emitted; the emitter knows nothing of expressions.
//! Registers become `let vN = ...;` bindings, constants become literals
//! written so that they round-trip exactly.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::lower::{Instr, OpCount, Operand, Program, Source};
use crate::truncation::{N, packed};

fn idx(i: usize) -> proc_macro2::Literal {
    proc_macro2::Literal::usize_unsuffixed(i)
}

fn reg(r: u32) -> Ident {
    format_ident!("v{}", r)
}

/// A float literal that round-trips (`{:?}` prints the shortest exact
/// representation); negative values are parenthesised.
///
/// # Panics
/// If `c` is not finite (constants in a [`Program`] are finite by the DAG's
/// invariant).
pub fn float_literal(c: f64) -> TokenStream {
    assert!(c.is_finite(), "non-finite constant {c}");
    let text = format!("{:?}", c.abs());
    let lit: TokenStream = text
        .parse()
        .expect("a finite float prints as a valid literal");
    if c.is_sign_negative() && c != 0.0 {
        quote!((-#lit))
    } else {
        lit
    }
}

fn operand(o: Operand) -> TokenStream {
    match o {
        Operand::Reg(r) => {
            let r = reg(r);
            quote!(#r)
        }
        Operand::Const(c) => float_literal(c),
    }
}

/// The `let` bindings of a program's instructions. `coords` names the
/// coordinate array, `param`/`implicit` the scalar inputs.
pub fn body(p: &Program, coords: &Ident, param: &Ident, implicit: &Ident) -> TokenStream {
    let stmts = p.instrs.iter().enumerate().map(|(i, instr)| {
        let dst = reg(i as u32);
        let rhs = match *instr {
            Instr::Load(Source::Coord(k)) => {
                let k = idx(k);
                quote!(#coords[#k])
            }
            Instr::Load(Source::Param) => quote!(#param),
            Instr::Load(Source::Implicit) => quote!(#implicit),
            Instr::Add(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a + #b)
            }
            Instr::Sub(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a - #b)
            }
            Instr::Mul(a, b) => {
                let (a, b) = (operand(a), operand(b));
                quote!(#a * #b)
            }
            Instr::Square(a) => {
                let a = operand(a);
                quote!(#a * #a)
            }
            Instr::Powi(a, n) => {
                let a = operand(a);
                quote!(#a.powi(#n))
            }
            Instr::Recip(a) => {
                let a = operand(a);
                quote!(1.0 / #a)
            }
            Instr::Neg(a) => {
                let a = operand(a);
                quote!(-#a)
            }
            Instr::Sqrt(a) => {
                let a = operand(a);
                quote!(#a.sqrt())
            }
        };
        quote!(let #dst = #rhs;)
    });
    quote!(#(#stmts)*)
}

/// An output expression: the operand, or `0.0` for a structural zero.
pub fn output(o: Option<Operand>) -> TokenStream {
    o.map_or_else(|| quote!(0.0), operand)
}

/// Assignments of a gradient (outputs `first..first+N`) and a packed upper
/// Hessian (outputs `first+N..`) to `grad` / `hess`, mirroring the Hessian.
pub fn store_derivatives(p: &Program, first: usize, with_hessian: bool) -> TokenStream {
    let grad = (0..N).map(|j| {
        let v = output(p.outputs[first + j]);
        let j = idx(j);
        quote!(grad[#j] = #v;)
    });
    let hess = with_hessian.then(|| {
        let mut stmts = Vec::new();
        for j in 0..N {
            for k in j..N {
                let v = output(p.outputs[first + N + packed(j, k)]);
                let (same, j, k) = (j == k, idx(j), idx(k));
                if same {
                    stmts.push(quote!(hess[#j][#k] = #v;));
                } else {
                    stmts.push(quote!(hess[#j][#k] = #v; hess[#k][#j] = #v;));
                }
            }
        }
        quote!(#(#stmts)*)
    });
    quote!(#(#grad)* #hess)
}

/// A doc line describing an operation count.
pub fn ops_doc(ops: &OpCount) -> String {
    format!(" Cost: {ops}.")
}

/// An `OpCount { .. }` literal of the run-time crate.
pub fn ops_literal(ops: &OpCount) -> TokenStream {
    let OpCount {
        add,
        mul,
        div,
        sqrt,
        neg,
    } = *ops;
    quote!(OpCount { add: #add, mul: #mul, div: #div, sqrt: #sqrt, neg: #neg })
}

/// Formats a token stream as a Rust file.
///
/// # Panics
/// If the tokens are not a valid file (a generator bug).
pub fn format_file(tokens: TokenStream) -> String {
    let file: syn::File = syn::parse2(tokens).expect("generated tokens form a valid Rust file");
    prettyplease::unparse(&file)
}

/// An identifier from a formulation name (`slave-normal` -> `slave_normal`).
pub fn snake(name: &str) -> Ident {
    Ident::new(&name.replace('-', "_"), Span::call_site())
}

/// A type name from a formulation name (`slave-normal` -> `SlaveNormal`).
pub fn camel(name: &str) -> Ident {
    let s: String = name
        .split(['-', '_'])
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
                .unwrap_or_default()
        })
        .collect();
    Ident::new(&s, Span::call_site())
}
