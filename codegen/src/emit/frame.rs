//! The frame of one generated Rust function, shared by the scalar
//! ([`super::rust`]) and the lane ([`super::lanes`]) emitter: its
//! parameters by kind, the prologue (buffers resliced to their lengths, the
//! components of a vector input of `P` values read into `x_0`, `x_1`), the
//! names the instructions read, the read of the converged projection, the
//! stores, the implicit write-back and the returned values. The emitters
//! differ only in the value type and in how they write an output
//! ([`Frame::new`]'s `output` and `store`).

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::lower::{Operand, Program};
use crate::plan::{Delivery, FunctionPlan, InputKind, Layout, Output};

/// How a parameter is passed: a value by value or by reference, or a
/// buffer of values (`&[T]`, `&mut [T]`).
#[derive(Clone, Copy)]
pub(super) enum Param {
    Slice,
    SliceMut,
    Value,
    ValueMut,
}

/// One function's frame (module docs).
pub(super) struct Frame {
    /// The parameters in order: the plan's inputs, then its stored outputs.
    pub(super) params: Vec<(Ident, Param)>,
    pub(super) prologue: Vec<TokenStream>,
    /// The relative coordinates' name.
    pub(super) coords: Ident,
    /// The scalar parameters' names (a vector parameter's components).
    pub(super) scalar_params: Vec<Ident>,
    /// The implicit unknown's name in the body (its components `_0`, `_1`
    /// for a vector unknown).
    pub(super) implicit: Ident,
    /// The read of the converged projection (unless this function solves
    /// it).
    pub(super) read: TokenStream,
    pub(super) stores: Vec<TokenStream>,
    pub(super) returns: Vec<TokenStream>,
    pub(super) write_back: Option<TokenStream>,
}

impl Frame {
    /// The frame of `f`: `implicit` names the unknown when no input does,
    /// `output` writes an output value, `store` the assignments of a stored
    /// output into its buffer.
    pub(super) fn new(
        f: &FunctionPlan,
        implicit: &str,
        output: fn(Option<Operand>) -> TokenStream,
        store: fn(&Program, &Output, &Ident) -> TokenStream,
    ) -> Frame {
        let ident = |s: &str| format_ident!("{}", s);
        let mut params = Vec::new();
        let mut prologue = Vec::new();
        let mut coords = ident("d");
        let mut scalar_params = Vec::new();
        let mut implicit = ident(implicit);
        let mut implicit_ref = None;
        // A vector input `x` of `len` components: a buffer, its components
        // bound to `x_0`, `x_1` (`component`).
        let component = |x: &Ident, k: usize| format_ident!("{}_{}", x, k);
        let mut implicit_len = 1;
        for input in &f.inputs {
            let x = ident(&input.name);
            match input.kind {
                InputKind::Coords => {
                    let len = idx(input.len);
                    params.push((x.clone(), Param::Slice));
                    prologue.push(quote!(let #x = &#x[..#len];));
                    coords = x;
                }
                InputKind::Param(_) if input.len > 1 => {
                    params.push((x.clone(), Param::Slice));
                    for k in 0..input.len {
                        let (c, kk) = (component(&x, k), idx(k));
                        prologue.push(quote!(let #c = #x[#kk];));
                        scalar_params.push(c);
                    }
                }
                InputKind::Param(_) => {
                    params.push((x.clone(), Param::Value));
                    scalar_params.push(x);
                }
                InputKind::Implicit if input.len > 1 => {
                    params.push((x.clone(), Param::Slice));
                    for k in 0..input.len {
                        let (c, kk) = (component(&x, k), idx(k));
                        prologue.push(quote!(let #c = #x[#kk];));
                    }
                    implicit = x;
                }
                InputKind::Implicit => {
                    params.push((x.clone(), Param::Value));
                    implicit = x;
                }
                InputKind::ImplicitInOut if input.len > 1 => {
                    params.push((x.clone(), Param::SliceMut));
                    implicit = ident("xi_in");
                    implicit_ref = Some(x);
                    implicit_len = input.len;
                }
                InputKind::ImplicitInOut => {
                    params.push((x.clone(), Param::ValueMut));
                    implicit = ident("xi_in");
                    implicit_ref = Some(x);
                }
            }
        }
        let mut stores = Vec::new();
        let mut returns = Vec::new();
        let mut write_back = None;
        for out in &f.outputs {
            match out.delivery {
                Delivery::Return => returns.push(output(f.program.outputs[out.first])),
                Delivery::Implicit if out.len > 1 => {
                    let target = implicit_ref.as_ref().expect("an in/out implicit input");
                    let stmts = (0..out.len).map(|k| {
                        let v = output(f.program.outputs[out.first + k]);
                        let k = idx(k);
                        quote!(#target[#k] = #v;)
                    });
                    write_back = Some(quote!(#(#stmts)*));
                }
                Delivery::Implicit => {
                    let target = implicit_ref.as_ref().expect("an in/out implicit input");
                    let v = output(f.program.outputs[out.first]);
                    write_back = Some(quote!(*#target = #v;));
                }
                Delivery::Store => {
                    let x = ident(&out.name);
                    let len = idx(match out.layout {
                        Layout::PackedSymmetric { n } => n * n,
                        _ => out.len,
                    });
                    params.push((x.clone(), Param::SliceMut));
                    prologue.push(quote!(let #x = &mut #x[..#len];));
                    stores.push(store(&f.program, out, &x));
                }
            }
        }
        // The converged projection is read unless this function solves it.
        let read = match (&implicit_ref, &write_back) {
            (Some(r), None) if implicit_len > 1 => {
                let stmts = (0..implicit_len).map(|k| {
                    let (c, kk) = (component(&implicit, k), idx(k));
                    quote!(let #c = #r[#kk];)
                });
                quote!(#(#stmts)*)
            }
            (Some(r), None) => quote!(let #implicit = *#r;),
            _ => quote!(),
        };
        Frame {
            params,
            prologue,
            coords,
            scalar_params,
            implicit,
            read,
            stores,
            returns,
            write_back,
        }
    }

    /// The parameters declared with the value type `ty`.
    pub(super) fn declare(&self, ty: &TokenStream) -> Vec<TokenStream> {
        self.params
            .iter()
            .map(|(x, k)| match k {
                Param::Slice => quote!(#x: &[#ty]),
                Param::SliceMut => quote!(#x: &mut [#ty]),
                Param::Value => quote!(#x: #ty),
                Param::ValueMut => quote!(#x: &mut #ty),
            })
            .collect()
    }
}

/// An index as an unsuffixed literal.
fn idx(i: usize) -> proc_macro2::Literal {
    proc_macro2::Literal::usize_unsuffixed(i)
}
