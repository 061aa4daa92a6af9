//! Lowering: from output expressions to a straight-line instruction list.
//!
//! The instruction list is the only input of the emitter. It is produced by
//!
//! 1. **relative coordinates**: the coordinates of the first point (slave
//!    node 1, [`Signature::origin_coords`]) are substituted by zero (the caller passes coordinates relative to that
//!    node; formulations are translation invariant), and the expressions are
//!    rebuilt and re-simplified;
//! 2. **dead-code removal**: only nodes reachable from the outputs are kept;
//! 3. **common-subexpression elimination**: already done by hash-consing —
//!    each live node becomes exactly one instruction;
//! 4. **ordering**: arena order, which is topological (children precede
//!    parents).
//!
//! ## Instructions
//!
//! Every [`Instr`] defines a fresh register (`v0, v1, ...`) from operands
//! that are earlier registers or constants:
//!
//! | instruction | meaning | counted as |
//! |---|---|---|
//! | `Load(Coord(i))` | `d[i]` | — |
//! | `Load(Param(i))` | parameter component `i` (`xi_s`; after the parameters, `xi_m0`'s components in a slip program) | — |
//! | `Load(Implicit)` | `xi_m` (or `xi` in the residual) | — |
//! | `Load(ImplicitComponent(k))` | component `k` of a 2-vector `xi_m` | — |
//! | `Add(a, b)`, `Sub(a, b)` | `a + b`, `a - b` | add |
//! | `Mul(a, b)` | `a * b` | mul |
//! | `Square(a)` | `a * a` | mul |
//! | `Powi(a, n)` | `a.powi(n)`, `n >= 3` | `n - 1` mul (upper bound) |
//! | `Recip(a)` | `1 / a` | div |
//! | `Neg(a)` | `-a` | neg |
//! | `Sqrt(a)` | `a.sqrt()` | sqrt |

use std::collections::HashMap;

use crate::expr::{Dag, Id, Node, Sym};
use crate::signature::Signature;

/// Where a loaded value comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// Relative coordinate `d[i]`.
    Coord(usize),
    /// Parameter component `i` of the signature (`xi_s`); the components
    /// after the signature's parameters are the last converged projection
    /// `xi_m0`'s ([`Signature::previous_syms`], slip programs only).
    Param(usize),
    /// The implicit variable's value.
    Implicit,
    /// Component `k` of a vector implicit variable (`implicit!(xi: 2 =>
    /// ..)`; a scalar one is [`Source::Implicit`]).
    ImplicitComponent(usize),
}

/// An instruction operand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Operand {
    /// A register defined by an earlier instruction.
    Reg(u32),
    /// A finite constant.
    Const(f64),
}

/// One instruction; defines register number = its index in the list.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Instr {
    /// Load an input.
    Load(Source),
    /// `a + b`.
    Add(Operand, Operand),
    /// `a - b`.
    Sub(Operand, Operand),
    /// `a * b`.
    Mul(Operand, Operand),
    /// `a * a`.
    Square(Operand),
    /// `a^n`, `|n| >= 3`.
    Powi(Operand, i32),
    /// `1 / a`.
    Recip(Operand),
    /// `-a`.
    Neg(Operand),
    /// `sqrt(a)`.
    Sqrt(Operand),
}

impl Instr {
    /// Its operands (`None` past the last).
    pub fn operands(&self) -> [Option<Operand>; 2] {
        match *self {
            Instr::Load(_) => [None, None],
            Instr::Add(a, b) | Instr::Sub(a, b) | Instr::Mul(a, b) => [Some(a), Some(b)],
            Instr::Square(a)
            | Instr::Powi(a, _)
            | Instr::Recip(a)
            | Instr::Neg(a)
            | Instr::Sqrt(a) => [Some(a), None],
        }
    }
}

/// Floating-point operation counts of a program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: u32,
    /// Multiplications.
    pub mul: u32,
    /// Divisions (reciprocals).
    pub div: u32,
    /// Square roots.
    pub sqrt: u32,
    /// Negations.
    pub neg: u32,
}

impl OpCount {
    /// All operations.
    pub fn total(&self) -> u32 {
        self.add + self.mul + self.div + self.sqrt + self.neg
    }
}

impl std::ops::Add for OpCount {
    type Output = OpCount;
    fn add(self, o: OpCount) -> OpCount {
        OpCount {
            add: self.add + o.add,
            mul: self.mul + o.mul,
            div: self.div + o.div,
            sqrt: self.sqrt + o.sqrt,
            neg: self.neg + o.neg,
        }
    }
}

impl std::ops::AddAssign for OpCount {
    fn add_assign(&mut self, o: OpCount) {
        *self = *self + o;
    }
}

impl std::iter::Sum for OpCount {
    fn sum<I: Iterator<Item = OpCount>>(iter: I) -> OpCount {
        iter.fold(OpCount::default(), |a, b| a + b)
    }
}

impl std::fmt::Display for OpCount {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ops ({} add, {} mul, {} div, {} sqrt, {} neg)",
            self.total(),
            self.add,
            self.mul,
            self.div,
            self.sqrt,
            self.neg
        )
    }
}

/// A lowered kernel: instructions and where each output comes from.
#[derive(Debug, Clone)]
pub struct Program {
    /// The instructions in execution order.
    pub instrs: Vec<Instr>,
    /// One operand per requested output; `None` = structural zero.
    pub outputs: Vec<Option<Operand>>,
}

impl Program {
    /// Lowers `outputs` (expressions of `dag` over the inputs of `sig`)
    /// with the origin's coordinates ([`Signature::origin_coords`]) replaced
    /// by zero; coordinate `i` is loaded from `d[i]`.
    pub fn lower(dag: &Dag, outputs: &[Option<Id>], sig: &Signature) -> Program {
        let coords = sig.coord_syms();
        // The parameters' components, then the last converged projection's
        // (`xi_m0`, loaded by the slip's programs after the parameters).
        let params: Vec<Sym> = (0..sig.param_count())
            .map(|i| sig.param_sym(i))
            .chain(sig.previous_syms())
            .collect();
        let implicit = sig.implicit_sym();
        let vector = sig.implicit_syms();
        let vector = if vector.len() > 1 { vector } else { Vec::new() };
        let zeros: HashMap<Sym, f64> = sig
            .origin_coords()
            .into_iter()
            .map(|i| (coords[i], 0.0))
            .collect();
        let (mut dag, mut roots) = dag.substitute(outputs, &zeros);
        for r in roots.iter_mut().flatten() {
            *r = dag.absorb_negation(*r);
        }
        dag.check_invariants_debug();
        let live = dag.reachable(roots.iter().flatten().copied());
        let mut reg: Vec<Option<Operand>> = vec![None; dag.len()];
        let mut instrs = Vec::new();
        for (i, live) in live.iter().enumerate() {
            if !*live {
                continue;
            }
            let node = dag.node(Id(i as u32));
            if let Node::Const(bits) = node {
                reg[i] = Some(Operand::Const(f64::from_bits(bits)));
                continue;
            }
            let o = |id: Id| reg[id.index()].expect("children precede parents");
            let instr = match node {
                Node::Const(_) => unreachable!("handled above"),
                Node::Input(s) if vector.contains(&s) => Instr::Load(Source::ImplicitComponent(
                    vector.iter().position(|v| *v == s).expect("contained"),
                )),
                Node::Input(s) if s == implicit => Instr::Load(Source::Implicit),
                Node::Input(s) if params.contains(&s) => Instr::Load(Source::Param(
                    params.iter().position(|p| *p == s).expect("contained"),
                )),
                Node::Input(s) => {
                    Instr::Load(Source::Coord(coords.iter().position(|c| *c == s).expect(
                        "every input symbol is a coordinate, the parameter or the implicit",
                    )))
                }
                Node::Add(a, b) => Instr::Add(o(a), o(b)),
                Node::Sub(a, b) => Instr::Sub(o(a), o(b)),
                Node::Mul(a, b) => Instr::Mul(o(a), o(b)),
                Node::Powi(a, 2) => Instr::Square(o(a)),
                Node::Powi(a, n) => Instr::Powi(o(a), n),
                Node::Recip(a) => Instr::Recip(o(a)),
                Node::Neg(a) => Instr::Neg(o(a)),
                Node::Sqrt(a) => Instr::Sqrt(o(a)),
            };
            reg[i] = Some(Operand::Reg(instrs.len() as u32));
            instrs.push(instr);
        }
        let outputs = roots
            .iter()
            .map(|r| r.map(|id| reg[id.index()].expect("root is live")))
            .collect();
        Program { instrs, outputs }
    }

    /// The program cut to the outputs `keep` (in that order): the
    /// instructions those outputs reach, in their original order and
    /// renumbered, so each kept output is computed by the same operations
    /// on the same operands as in `self` (the same bits). The slip of a
    /// face is emitted over lanes one component at a time this way
    /// ([`crate::plan::FunctionPlan::slip_component`]).
    pub fn cut(&self, keep: &[usize]) -> Program {
        let mut live = vec![false; self.instrs.len()];
        for o in keep.iter().filter_map(|&k| self.outputs[k]) {
            if let Operand::Reg(r) = o {
                live[r as usize] = true;
            }
        }
        // Operands precede their instruction: one backward sweep marks
        // everything a live instruction reads.
        for i in (0..self.instrs.len()).rev() {
            if live[i] {
                for o in self.instrs[i].operands().into_iter().flatten() {
                    if let Operand::Reg(r) = o {
                        live[r as usize] = true;
                    }
                }
            }
        }
        let mut renumber = vec![u32::MAX; self.instrs.len()];
        let map = |renumber: &[u32], o: Operand| match o {
            Operand::Reg(r) => Operand::Reg(renumber[r as usize]),
            c => c,
        };
        let mut instrs = Vec::new();
        for (i, instr) in self.instrs.iter().enumerate() {
            if !live[i] {
                continue;
            }
            let m = |o| map(&renumber, o);
            let cut = match *instr {
                Instr::Load(s) => Instr::Load(s),
                Instr::Add(a, b) => Instr::Add(m(a), m(b)),
                Instr::Sub(a, b) => Instr::Sub(m(a), m(b)),
                Instr::Mul(a, b) => Instr::Mul(m(a), m(b)),
                Instr::Square(a) => Instr::Square(m(a)),
                Instr::Powi(a, n) => Instr::Powi(m(a), n),
                Instr::Recip(a) => Instr::Recip(m(a)),
                Instr::Neg(a) => Instr::Neg(m(a)),
                Instr::Sqrt(a) => Instr::Sqrt(m(a)),
            };
            renumber[i] = instrs.len() as u32;
            instrs.push(cut);
        }
        let outputs = keep
            .iter()
            .map(|&k| self.outputs[k].map(|o| map(&renumber, o)))
            .collect();
        Program { instrs, outputs }
    }

    /// The operation count.
    pub fn op_count(&self) -> OpCount {
        let mut c = OpCount::default();
        for i in &self.instrs {
            match *i {
                Instr::Load(_) => {}
                Instr::Add(..) | Instr::Sub(..) => c.add += 1,
                Instr::Mul(..) | Instr::Square(_) => c.mul += 1,
                Instr::Powi(_, n) => c.mul += n.unsigned_abs() - 1,
                Instr::Recip(_) => c.div += 1,
                Instr::Neg(_) => c.neg += 1,
                Instr::Sqrt(_) => c.sqrt += 1,
            }
        }
        c
    }

    /// Interprets the program (reference semantics for tests): `d` the
    /// relative coordinates, `params` the parameters, `implicit` the
    /// implicit unknown.
    pub fn run(&self, d: &[f64], params: &[f64], implicit: f64) -> Vec<f64> {
        self.run_vector(d, params, &[implicit])
    }

    /// [`Program::run`] with every component of the implicit unknown
    /// (`implicit[0]` for [`Source::Implicit`]).
    pub fn run_vector(&self, d: &[f64], params: &[f64], implicit: &[f64]) -> Vec<f64> {
        let mut regs: Vec<f64> = Vec::with_capacity(self.instrs.len());
        let val = |regs: &Vec<f64>, o: Operand| match o {
            Operand::Reg(r) => regs[r as usize],
            Operand::Const(c) => c,
        };
        for i in &self.instrs {
            let v = match *i {
                Instr::Load(Source::Coord(k)) => d[k],
                Instr::Load(Source::Param(i)) => params[i],
                Instr::Load(Source::Implicit) => implicit[0],
                Instr::Load(Source::ImplicitComponent(k)) => implicit[k],
                Instr::Add(a, b) => val(&regs, a) + val(&regs, b),
                Instr::Sub(a, b) => val(&regs, a) - val(&regs, b),
                Instr::Mul(a, b) => val(&regs, a) * val(&regs, b),
                Instr::Square(a) => val(&regs, a) * val(&regs, a),
                Instr::Powi(a, n) => val(&regs, a).powi(n),
                Instr::Recip(a) => 1.0 / val(&regs, a),
                Instr::Neg(a) => -val(&regs, a),
                Instr::Sqrt(a) => val(&regs, a).sqrt(),
            };
            regs.push(v);
        }
        self.outputs
            .iter()
            .map(|o| o.map_or(0.0, |o| val(&regs, o)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `a = d0 * d1`, `b = a + 2`, `c = sqrt(d2)`, `e = b * c`; outputs
    /// `[b, c, e, zero]`.
    fn program() -> Program {
        use Instr::*;
        use Operand::*;
        Program {
            instrs: vec![
                Load(Source::Coord(0)),
                Load(Source::Coord(1)),
                Load(Source::Coord(2)),
                Mul(Reg(0), Reg(1)),
                Add(Reg(3), Const(2.0)),
                Sqrt(Reg(2)),
                Mul(Reg(4), Reg(5)),
            ],
            outputs: vec![Some(Reg(4)), Some(Reg(5)), Some(Reg(6)), None],
        }
    }

    #[test]
    fn a_cut_program_computes_the_kept_outputs_bit_for_bit_with_fewer_instructions() {
        let p = program();
        let d = [1.3, -0.7, 2.9];
        let all = p.run(&d, &[], 0.0);
        for keep in [
            vec![0],
            vec![1],
            vec![2],
            vec![3],
            vec![2, 0],
            vec![0, 1, 2, 3],
        ] {
            let c = p.cut(&keep);
            let got = c.run(&d, &[], 0.0);
            let want: Vec<f64> = keep.iter().map(|&k| all[k]).collect();
            assert_eq!(
                got.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                want.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                "{keep:?}"
            );
            // every operand refers to an earlier instruction
            for (i, instr) in c.instrs.iter().enumerate() {
                for o in instr.operands().into_iter().flatten() {
                    if let Operand::Reg(r) = o {
                        assert!((r as usize) < i, "{keep:?}: {instr:?}");
                    }
                }
            }
        }
        // only what an output reaches survives
        assert_eq!(p.cut(&[0]).instrs.len(), 4); // two loads, mul, add
        assert_eq!(p.cut(&[1]).instrs.len(), 2); // load, sqrt
        assert_eq!(p.cut(&[3]).instrs.len(), 0); // a structural zero
        assert_eq!(p.cut(&[0, 1, 2, 3]).instrs, p.instrs);
    }
}
