//! The kernel plan: everything the generator emits, described without any
//! target language.
//!
//! [`KernelPlan::build`] turns parsed formulations and their lowered
//! [`Program`]s into one plan; an [`crate::emit::Emitter`] turns the plan
//! into source text. Emitters read only the plan: names, documentation,
//! inputs and outputs by name and length, instruction lists and op counts.
//!
//! ## Invariants
//!
//! * Every [`Output`] names a contiguous run `first..first + len` of its
//!   function's `program.outputs` ([`Layout::PackedSymmetric`]: the
//!   `n (n + 1) / 2` entries of the packed upper triangle, see
//!   [`Signature::packed`]; emitters store the full symmetric matrix).
//! * Every [`Input`] loaded by a program's `Load` instructions is listed:
//!   [`InputKind::Coords`] for `Load(Coord(i))` (`i < n`),
//!   [`InputKind::Param`] for `Load(Param(i))` (a slip function's `xi_m0`
//!   is the parameter after the signature's), [`InputKind::Implicit`] or
//!   [`InputKind::ImplicitInOut`] for `Load(Implicit)`.
//! * A function has at least one [`Delivery::Return`] output; the kernel
//!   functions return the gap.
//! * `ops == program.op_count()` for every function.

use crate::formulation::Arity;
use crate::lower::{OpCount, Program};
use crate::programs::{FormulationPrograms, programs};
use crate::signature::Signature;
use crate::truncation::{EntityOrder, TYPES};
use crate::{Error, Formulation, Source};

/// The whole generated unit: every formulation (compiled in or not), the
/// truncation table and the kernels.
#[derive(Debug, Clone)]
pub struct KernelPlan {
    /// One entry per source, in source order.
    pub formulations: Vec<FormulationPlan>,
    /// The truncation table: `[xi_m, x_ms, n]` orders of types 1..=6.
    pub truncation: Vec<[EntityOrder; 3]>,
    /// Where the formulations were read from, as the generated files'
    /// headers name it ([`SHIPPED_ORIGIN`] unless
    /// [`KernelPlan::with_origin`] says otherwise).
    pub origin: String,
}

/// The origin of the shipped formulations (contact-kernels' build).
pub const SHIPPED_ORIGIN: &str = "contact-kernels/formulations/*.rs";

/// One formulation: its enum variant and, if compiled in, its kernels.
#[derive(Debug, Clone)]
pub struct FormulationPlan {
    /// The formulation name (file stem, e.g. `slave-normal`).
    pub name: String,
    /// The type-name form (`SlaveNormal`).
    pub variant: String,
    /// The formulation file's `//!` documentation (may be empty).
    pub doc: String,
    /// The dimension of its points (2: segments, 3: faces).
    pub dim: usize,
    /// The kernels; `None` when not compiled in.
    pub kernels: Option<KernelSetPlan>,
}

/// The generated functions of one compiled formulation.
#[derive(Debug, Clone)]
pub struct KernelSetPlan {
    /// The identifier form of the name (`slave_normal`); functions are
    /// named `{ident}_residual`, `{ident}_gap`, `{ident}_type{t}`.
    pub ident: String,
    /// Documentation of the set.
    pub doc: String,
    /// The inputs `inputs!` declares and their sizes.
    pub signature: Signature,
    /// The residual is affine in the implicit unknown: every kernel solves
    /// the projection itself and writes it to its in/out implicit input.
    pub closed_form_projection: bool,
    /// `[r, dr/dxi]` of the projection at `xi`.
    pub residual: FunctionPlan,
    /// The gap alone.
    pub gap: FunctionPlan,
    /// Types 1..=6.
    pub kernels: Vec<FunctionPlan>,
    /// The slip's components (1 in 2D, 3 in 3D; 0 without `slip!`).
    pub slip_components: usize,
    /// The slip under types 1..=6 (`{ident}_slip_type{t}`; empty without
    /// `slip!`). Inputs: the kernels' with the last converged projection
    /// `xi_m0` (its components, as many as `xi_m`'s) after the parameters;
    /// outputs `s0 .. s{c-1}` returned, `grad0 ..` and, with a second-order
    /// term, `hess0 ..` stored.
    pub slips: Vec<FunctionPlan>,
    /// The projection kernel's cost: the gap, plus one residual evaluation
    /// per Newton iteration when not in closed form.
    pub projection_ops: OpCount,
}

/// One generated function.
#[derive(Debug, Clone)]
pub struct FunctionPlan {
    /// Its name.
    pub name: String,
    /// Its documentation (one paragraph, ends with its cost).
    pub doc: String,
    /// What it is.
    pub role: Role,
    /// Its inputs, in argument order.
    pub inputs: Vec<Input>,
    /// Its outputs, in argument order for stored ones.
    pub outputs: Vec<Output>,
    /// The instruction list.
    pub program: Program,
    /// `program.op_count()`.
    pub ops: OpCount,
}

/// What a generated function computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The projection residual and its derivative.
    Residual,
    /// The gap alone.
    Gap,
    /// An approximation type's gap with its kept derivatives.
    Kernel {
        /// The type, 1..=6.
        ty: usize,
        /// Whether any second-order term survives (else no Hessian output).
        hessian: bool,
    },
    /// An approximation type's slip (its components) with their kept
    /// derivatives.
    Slip {
        /// The type, 1..=6.
        ty: usize,
        /// Whether any second-order term survives (else no Hessian outputs).
        hessian: bool,
    },
}

/// A function input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Input {
    /// Its name.
    pub name: String,
    /// Number of scalars.
    pub len: usize,
    /// Where the program loads it.
    pub kind: InputKind,
}

/// How an input is passed and loaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputKind {
    /// The relative coordinates (`len = n`), read by `Load(Coord(i))`.
    Coords,
    /// Parameter `i` of the signature (`len` components); `i =
    /// params().len()` is a slip function's last converged projection
    /// `xi_m0`, loaded as the parameter components after the signature's.
    Param(usize),
    /// The implicit unknown's value, by value.
    Implicit,
    /// The implicit unknown by reference: read on entry (its converged
    /// value) unless the function solves it in closed form, in which case
    /// an [`Delivery::Implicit`] output writes it on exit.
    ImplicitInOut,
}

/// A function output: a run of program outputs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Output {
    /// Its name.
    pub name: String,
    /// Number of program outputs it covers.
    pub len: usize,
    /// Index of its first program output.
    pub first: usize,
    /// How its entries are arranged.
    pub layout: Layout,
    /// How it reaches the caller.
    pub delivery: Delivery,
}

/// Arrangement of an output's entries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// One scalar.
    Scalar,
    /// A vector of `len` entries.
    Vector,
    /// The packed upper triangle of a symmetric `n x n` matrix
    /// (`len = n (n + 1) / 2`); stored as the full matrix, row-major.
    PackedSymmetric {
        /// The matrix dimension.
        n: usize,
    },
}

/// How an output reaches the caller.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delivery {
    /// Returned by value (several: as an array, in order).
    Return,
    /// Written into a caller's buffer (argument named like the output).
    Store,
    /// Written to the [`InputKind::ImplicitInOut`] input.
    Implicit,
}

impl KernelPlan {
    /// Parses and lowers every source and describes the result (inputs as
    /// the contact-kernels run-time serves them, [`Arity::SegmentPair`]).
    pub fn build(sources: &[Source]) -> Result<KernelPlan, Error> {
        Self::build_with(sources, Arity::SegmentPair)
    }

    /// [`KernelPlan::build`] for formulations whose `inputs!` satisfy
    /// `arity`.
    pub fn build_with(sources: &[Source], arity: Arity) -> Result<KernelPlan, Error> {
        check_names(sources)?;
        let mut formulations = Vec::new();
        for src in sources {
            let f = Formulation::parse_with(&src.name, &src.text, arity)?;
            let kernels = if src.compiled {
                Some(KernelSetPlan::new(&f, &programs(&f)?))
            } else {
                None
            };
            formulations.push(FormulationPlan {
                name: src.name.clone(),
                variant: variant(&src.name),
                doc: f.doc.clone(),
                dim: f.signature.dim(),
                kernels,
            });
        }
        Ok(KernelPlan {
            formulations,
            truncation: TYPES.to_vec(),
            origin: SHIPPED_ORIGIN.to_owned(),
        })
    }

    /// The plan with the generated files' headers naming `origin` (e.g.
    /// the user's file paths) as their source.
    pub fn with_origin(mut self, origin: impl Into<String>) -> KernelPlan {
        self.origin = origin.into();
        self
    }
}

/// Refuses a source name that is not `letters, digits, '-', '_'` starting
/// with a letter, and two names that give one generated identifier
/// (`a_b` and `a-b`: `a_b_type1`, `AB`, `A_B`).
fn check_names(sources: &[Source]) -> Result<(), Error> {
    let mut seen: Vec<(&str, [String; 3])> = Vec::new();
    for src in sources {
        let name = src.name.as_str();
        let file = format!("{name}.rs");
        let valid = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if !valid {
            return Err(Error::Truncation {
                file,
                message: format!(
                    "`{name}` is not a formulation name: letters, digits, `-` and `_`, \
                     starting with a letter"
                ),
            });
        }
        let ident = name.replace('-', "_");
        let keys = [ident.clone(), variant(name), ident.to_uppercase()];
        if let Some((other, _)) = seen
            .iter()
            .find(|(_, k)| k.iter().zip(&keys).any(|(a, b)| a == b))
        {
            return Err(Error::Truncation {
                file,
                message: format!(
                    "formulations `{other}` and `{name}` would generate the same identifiers \
                     (`{ident}_type1`, `{}`): rename one",
                    variant(name)
                ),
            });
        }
        seen.push((name, keys));
    }
    Ok(())
}

/// The enum variant of a formulation name: [`camel`], with `_` appended
/// to the keyword `Self` (a file named `self.rs`).
fn variant(name: &str) -> String {
    let v = camel(name);
    if v == "Self" { v + "_" } else { v }
}

impl KernelSetPlan {
    fn new(f: &Formulation, p: &FormulationPrograms) -> KernelSetPlan {
        let name = &f.name;
        let ident = f.name.replace('-', "_");
        let sig = f.signature.clone();
        let (n, nh) = (sig.coords(), sig.packed_len());
        let affine = p.affine;
        let coords = Input {
            name: "d".into(),
            len: n,
            kind: InputKind::Coords,
        };
        let params = sig.params().iter().enumerate().map(|(i, s)| Input {
            name: s.clone(),
            len: sig.param_len(i),
            kind: InputKind::Param(i),
        });
        let mut inputs: Vec<Input> = std::iter::once(coords).chain(params).collect();
        let mut residual_inputs = inputs.clone();
        let k = sig.implicit_len();
        residual_inputs.push(Input {
            name: "xi".into(),
            len: k,
            kind: InputKind::Implicit,
        });
        inputs.push(Input {
            name: sig.implicit().to_owned(),
            len: k,
            kind: InputKind::ImplicitInOut,
        });
        let scalar = |name: &str, first: usize, delivery: Delivery| Output {
            name: name.into(),
            len: 1,
            first,
            layout: Layout::Scalar,
            delivery,
        };
        // The closed-form projection is the program's last output (its
        // last `k` outputs for a vector unknown).
        let implicit_out = |prog: &Program| {
            affine.then(|| match k {
                1 => scalar(sig.implicit(), prog.outputs.len() - 1, Delivery::Implicit),
                _ => Output {
                    name: sig.implicit().to_owned(),
                    len: k,
                    first: prog.outputs.len() - k,
                    layout: Layout::Vector,
                    delivery: Delivery::Implicit,
                },
            })
        };

        let ops = p.residual.op_count();
        let (residual_doc, residual_outputs) = if k == 1 {
            (
                "`[r, dr/dxi]`",
                vec![
                    scalar("r", 0, Delivery::Return),
                    scalar("r_xi", 1, Delivery::Return),
                ],
            )
        } else {
            (
                "`[r_0, r_1, A_00, A_01, A_10, A_11]` (`A_ac = dr_a/dxi_c`)",
                ["r0", "r1", "a00", "a01", "a10", "a11"]
                    .iter()
                    .enumerate()
                    .map(|(i, n)| scalar(n, i, Delivery::Return))
                    .collect(),
            )
        };
        let residual = FunctionPlan {
            name: format!("{ident}_residual"),
            doc: format!(
                "{residual_doc} of the `{name}` projection at `xi`.{}",
                ops_doc(&ops)
            ),
            role: Role::Residual,
            inputs: residual_inputs,
            outputs: residual_outputs,
            program: p.residual.clone(),
            ops,
        };

        let projection_doc = if affine {
            " The projection is solved in closed form inside (the residual is affine in `xi`); `xi_m` receives it."
        } else {
            " `xi_m` holds the converged projection."
        };
        let ops = p.gap.op_count();
        let gap = FunctionPlan {
            name: format!("{ident}_gap"),
            doc: format!("The `{name}` gap.{projection_doc}{}", ops_doc(&ops)),
            role: Role::Gap,
            inputs: inputs.clone(),
            outputs: std::iter::once(scalar("g", 0, Delivery::Return))
                .chain(implicit_out(&p.gap))
                .collect(),
            program: p.gap.clone(),
            ops,
        };

        // The outputs of a kernel of `c` components (`None`: the gap, one
        // component named `g`, `grad`, `hess`; `Some(c)`: the slip's,
        // numbered `s0`, `grad0`, `hess0`, ...): the values returned, the
        // gradients and (with a second-order term) the packed Hessians
        // stored, component after component, then the closed-form
        // projection.
        let derivatives = |c: Option<usize>, hessian: bool, prog: &Program| {
            let count = c.unwrap_or(1);
            let label = |s: &str, i: usize| match c {
                None => s.to_owned(),
                Some(_) => format!("{s}{i}"),
            };
            let mut outputs: Vec<Output> = (0..count)
                .map(|i| {
                    scalar(
                        &label(if c.is_some() { "s" } else { "g" }, i),
                        i,
                        Delivery::Return,
                    )
                })
                .collect();
            outputs.extend((0..count).map(|i| Output {
                name: label("grad", i),
                len: n,
                first: count + i * n,
                layout: Layout::Vector,
                delivery: Delivery::Store,
            }));
            if hessian {
                outputs.extend((0..count).map(|i| Output {
                    name: label("hess", i),
                    len: nh,
                    first: count + count * n + i * nh,
                    layout: Layout::PackedSymmetric { n },
                    delivery: Delivery::Store,
                }));
            }
            outputs.extend(implicit_out(prog));
            outputs
        };
        let kernels: Vec<FunctionPlan> = p
            .kernels
            .iter()
            .enumerate()
            .map(|(t, (prog, has_hess))| {
                let ops = prog.op_count();
                let orders = TYPES[t].map(|o| o.name().to_lowercase()).join(", ");
                let doc = format!(
                    "`{name}`, type {} (xi_m, x_ms, n: {orders}): gap, gradient{}.{}",
                    t + 1,
                    second_order(*has_hess),
                    ops_doc(&ops)
                );
                let outputs = derivatives(None, *has_hess, prog);
                FunctionPlan {
                    name: format!("{ident}_type{}", t + 1),
                    doc,
                    role: Role::Kernel {
                        ty: t + 1,
                        hessian: *has_hess,
                    },
                    inputs: inputs.clone(),
                    outputs,
                    program: prog.clone(),
                    ops,
                }
            })
            .collect();

        let c = f.slip_components();
        let previous = Input {
            name: format!("{}0", sig.implicit()),
            len: k,
            kind: InputKind::Param(sig.params().len()),
        };
        // The kernels' inputs with `xi_m0` before the projection.
        let mut slip_inputs = inputs.clone();
        slip_inputs.insert(slip_inputs.len() - 1, previous);
        let slips: Vec<FunctionPlan> = p
            .slips
            .iter()
            .enumerate()
            .map(|(t, (prog, has_hess))| {
                let ops = prog.op_count();
                let orders = TYPES[t].map(|o| o.name().to_lowercase()).join(", ");
                let doc = format!(
                    "`{name}`, type {} (xi_m, x_ms and s_m, n: {orders}): the slip ({c} \
                     component{}), gradient{}. `xi_m0` is the last converged projection.{}",
                    t + 1,
                    if c == 1 { "" } else { "s" },
                    second_order(*has_hess),
                    ops_doc(&ops)
                );
                let outputs = derivatives(Some(c), *has_hess, prog);
                FunctionPlan {
                    name: format!("{ident}_slip_type{}", t + 1),
                    doc,
                    role: Role::Slip {
                        ty: t + 1,
                        hessian: *has_hess,
                    },
                    inputs: slip_inputs.clone(),
                    outputs,
                    program: prog.clone(),
                    ops,
                }
            })
            .collect();

        // The projection kernel: the gap kernel, plus one residual
        // evaluation per Newton iteration when not in closed form.
        let mut projection_ops = gap.ops;
        if !affine {
            projection_ops += residual.ops;
        }
        KernelSetPlan {
            doc: format!("The kernels of `{name}`."),
            ident,
            signature: sig,
            closed_form_projection: affine,
            residual,
            gap,
            kernels,
            slip_components: if slips.is_empty() { 0 } else { c },
            slips,
            projection_ops,
        }
    }
}

impl FunctionPlan {
    /// The output named `name`, if any.
    pub fn output(&self, name: &str) -> Option<&Output> {
        self.outputs.iter().find(|o| o.name == name)
    }

    /// Component `j` of a slip of several components alone: the function
    /// `{name}_s{j}` returning `s{j}`, storing `grad{j}` and `hess{j}` as
    /// `grad` and `hess`, and writing the projection back as this function
    /// does, its program [cut](Program::cut) to those outputs (the same
    /// operations, so the same bits). `None` unless this is a slip with a
    /// component `j` (`s{j}`).
    ///
    /// The lane emitter writes a face slip this way: one function of three
    /// components with a 24 x 24 Hessian each is beyond what rustc
    /// compiles in reasonable time, one per component is not.
    pub fn slip_component(&self, j: usize) -> Option<FunctionPlan> {
        let Role::Slip { ty, hessian } = self.role else {
            return None;
        };
        let s = self.output(&format!("s{j}"))?;
        let mut keep = vec![s.first];
        let mut outputs = vec![Output {
            name: "s".into(),
            first: 0,
            ..s.clone()
        }];
        let mut take = |name: &str, o: &Output, keep: &mut Vec<usize>| {
            outputs.push(Output {
                name: name.into(),
                first: keep.len(),
                ..o.clone()
            });
            keep.extend(o.first..o.first + o.len);
        };
        take("grad", self.output(&format!("grad{j}"))?, &mut keep);
        if hessian {
            take("hess", self.output(&format!("hess{j}"))?, &mut keep);
        }
        for o in self
            .outputs
            .iter()
            .filter(|o| o.delivery == Delivery::Implicit)
        {
            take(&o.name, o, &mut keep);
        }
        let program = self.program.cut(&keep);
        let ops = program.op_count();
        Some(FunctionPlan {
            name: format!("{}_s{j}", self.name),
            doc: format!(
                "Component {j} of `{}` alone (its program cut to that component's outputs).{}",
                self.name,
                ops_doc(&ops)
            ),
            role: Role::Slip { ty, hessian },
            inputs: self.inputs.clone(),
            outputs,
            program,
            ops,
        })
    }
}

/// How a kernel's documentation names its second-order term.
fn second_order(hessian: bool) -> &'static str {
    if hessian {
        " and Hessian"
    } else {
        " (no second-order term)"
    }
}

/// The cost sentence closing a function's documentation.
fn ops_doc(ops: &OpCount) -> String {
    format!(" Cost: {ops}.")
}

/// A type name from a formulation name (`slave-normal` -> `SlaveNormal`).
pub fn camel(name: &str) -> String {
    name.split(['-', '_'])
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
                .unwrap_or_default()
        })
        .collect()
}
