//! `gapsim kernel`: evaluate one generated contact kernel and print the
//! result as JSON.
//!
//! ```text
//! gapsim kernel --formulation F --type T --xi-s XI --nodes q1,q2,...,qn
//! ```
//!
//! prints one line, a JSON object
//! `{"gap":..,"xi_m":..,"grad":[n numbers],"hess":[n rows of n]}` whose
//! numbers round-trip to the kernel's exact `f64` values; `hess` is all zeros
//! for Type 1, which has no second-order term.
//!
//! The coordinate count `n` is the formulation's ([`Formulation::coords`]):
//! 8 for the two-node formulations (`slave-normal`, `closest-point`: slave
//! node 1, slave node 2, master node 1, master node 2), 12 for
//! `quadratic-slave-normal` (two 3-node segments, six points: each segment's
//! end nodes, then its mid node, as Gmsh's line3), 18 to 24 for the 3D face
//! formulations (`tri3-slave-normal`, `quad4-closest-point`,
//! `tri3-quad4-slave-normal`, ...: the slave face's nodes, then the master
//! face's, each `x, y, z`). `--nodes` is read once the formulation is known,
//! so a wrong count is reported with the count and the coordinate names that
//! formulation expects.
//!
//! `--xi-s` is one number for segments and two, comma-separated, for faces
//! (`--xi-s 0.2,-0.1`: `(u, v)`); a face's `xi_m` is printed as `[u, v]`:
//! `{"gap":..,"xi_m":[u,v],"grad":[..],"hess":[[..]..]}`.
//!
//! `--formulation FILE.rs` evaluates a formulation file of the user's: its
//! kernels are generated and run by codegen's interpreter
//! ([`gapsim::verify::InterpretedKernels`]) through contact-kernels' own
//! validation, projection and output checks
//! ([`contact_kernels::eval_runtime`]), so the output (and every error) is
//! what the compiled kernels of the same file give (segment formulations).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, KernelError};
use gapsim::verify::InterpretedKernels;
use serde::Serialize;

use super::CommandResult;
use super::generate::{GenerateError, locate, read_source};

/// What `--formulation` names: a formulation compiled into gapsim, or a
/// formulation file (`NAME.rs`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FormulationArg {
    /// A compiled-in formulation (`slave-normal`, ...).
    Compiled(Formulation),
    /// A formulation file.
    File(PathBuf),
}

impl std::fmt::Display for FormulationArg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FormulationArg::Compiled(c) => write!(f, "{c}"),
            FormulationArg::File(p) => write!(f, "{}", p.display()),
        }
    }
}

/// Parses `--formulation`: a path ending in `.rs` is a file, anything else
/// a compiled-in formulation's name.
fn parse_formulation(s: &str) -> Result<FormulationArg, String> {
    if s.ends_with(".rs") {
        return Ok(FormulationArg::File(PathBuf::from(s)));
    }
    s.parse::<Formulation>()
        .map(FormulationArg::Compiled)
        .map_err(|e| format!("{e}; or a formulation file NAME.rs"))
}

/// Names of the `n` coordinates of a segment-pair kernel, in kernel order:
/// the slave segment's points `xs1, ys1, xs2, ys2, ...`, then the master
/// segment's `xm1, ym1, ...` (`n / 4` points per segment).
pub fn coordinate_names(n: usize) -> Vec<String> {
    let per_segment = n / 4;
    ["s", "m"]
        .into_iter()
        .flat_map(|side| {
            (1..=per_segment).flat_map(move |k| [format!("x{side}{k}"), format!("y{side}{k}")])
        })
        .collect()
}

/// Names of the coordinates of a face-pair kernel: the slave face's
/// `slave` nodes `xs1, ys1, zs1, ...`, then the master face's `master`
/// nodes `xm1, ym1, zm1, ...`.
pub fn face_coordinate_names(slave: usize, master: usize) -> Vec<String> {
    [("s", slave), ("m", master)]
        .into_iter()
        .flat_map(|(side, nodes)| {
            (1..=nodes).flat_map(move |k| {
                [
                    format!("x{side}{k}"),
                    format!("y{side}{k}"),
                    format!("z{side}{k}"),
                ]
            })
        })
        .collect()
}

/// Arguments of `gapsim kernel`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Examples:\n  gapsim kernel --type 6 --xi-s 0.3 --nodes 0,1,2,1.1,2.1,0.9,-0.1,1.0\n  \
gapsim kernel --formulation quadratic-slave-normal --type 6 --xi-s 0.5 \\\n      \
--nodes 0,0,2,0,1,0,2,-1,0,-1,1,-0.8\n  \
gapsim kernel --formulation my-normal.rs --type 6 --xi-s 0.3 --nodes 0,1,2,1.1,2.1,0.9,-0.1,1.0\n  \
gapsim kernel --formulation quad4-slave-normal --type 6 --xi-s 0.2,-0.1 \\\n      \
--nodes 0,0,1,0,1,1.1,1,1,1,1,0,0.9,-0.2,-0.1,0.8,1.2,0,0.85,1.1,1.3,0.75,-0.1,1.2,0.8\n\n\
Output: one JSON object {\"gap\":..,\"xi_m\":..,\"grad\":[n],\"hess\":[[n]xn]} \
(derivatives with respect to the n coordinates: 8 for slave-normal and closest-point, \
12 for quadratic-slave-normal, 3 per node of both faces for the face formulations, whose \
xi_m is [u,v]; hess is all zeros for Type 1)."
)]
pub struct KernelArgs {
    /// Contact formulation: `slave-normal` (projection along the slave
    /// normal, the paper's), `closest-point` (orthogonal projection onto
    /// the master segment), or `quadratic-slave-normal` (slave-normal
    /// projection between 3-node quadratic segments; 12 coordinates).
    /// Or a formulation file of your own, `NAME.rs` (docs/formulations.md):
    /// its kernels are generated and interpreted, with the same checks.
    #[arg(long, value_name = "F", default_value = "slave-normal", value_parser = parse_formulation)]
    pub formulation: FormulationArg,

    /// Approximation type, 1 to 6 (6: exact gradient and Hessian; 1: no
    /// Hessian).
    #[arg(long = "type", value_name = "T")]
    pub ty: ApproxType,

    /// Parametric coordinate of the slave integration point on the slave
    /// segment, in [-1, 1] (-1: slave node 1, 1: slave node 2); for a face,
    /// `u,v` (tri3: u, v >= 0, u + v <= 1; quad4: [-1, 1]^2).
    #[arg(long = "xi-s", value_name = "XI", allow_hyphen_values = true, value_parser = parse_xi)]
    pub xi_s: Xi,

    /// Current coordinates of the slave segment's nodes, then the master
    /// segment's, comma-separated, as many as the formulation takes.
    /// Two-node formulations (slave-normal, closest-point), 8:
    /// xs1,ys1,xs2,ys2,xm1,ym1,xm2,ym2. quadratic-slave-normal (3-node
    /// segments, 6 points), 12: xs1,ys1,xs2,ys2,xs3,ys3,xm1,ym1,xm2,ym2,xm3,ym3
    /// (each segment's end nodes 1 and 2, then its mid node 3).
    #[arg(long, value_name = "Q1,Q2,...", allow_hyphen_values = true)]
    pub nodes: String,
}

/// `--xi-s`: one finite number (a segment's) or several, comma-separated
/// (a face's `u,v`).
#[derive(Debug, Clone, PartialEq)]
pub struct Xi(pub Vec<f64>);

/// The projection as printed: a number for a segment, `[u, v]` for a face.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum XiM {
    /// A segment's `xi_m`.
    One(f64),
    /// A face's `(u, v)`.
    Many(Vec<f64>),
}

/// The JSON printed by `gapsim kernel` (field order as in the contract).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KernelOutput {
    /// The gap `g` (negative when penetrating).
    pub gap: f64,
    /// The master parametric coordinate(s) of the projection.
    pub xi_m: XiM,
    /// `dg/dq` (`n` entries).
    pub grad: Vec<f64>,
    /// `d2g/dq2`, row by row (`n` rows of `n`; all zeros for Type 1).
    pub hess: Vec<Vec<f64>>,
}

impl From<&GapOut> for KernelOutput {
    fn from(out: &GapOut) -> Self {
        let n = out.coords();
        KernelOutput {
            gap: out.gap(),
            xi_m: match out.xi_m_all() {
                [x] => XiM::One(*x),
                all => XiM::Many(all.to_vec()),
            },
            grad: out.grad().to_vec(),
            hess: (0..n)
                .map(|i| match out.hess() {
                    Some(h) => h[i * n..(i + 1) * n].to_vec(),
                    None => vec![0.0; n],
                })
                .collect(),
        }
    }
}

/// Why `gapsim kernel` failed after its arguments were parsed. Each message
/// is one self-contained line (the underlying error is part of it, not a
/// separate `source`).
#[derive(Debug, thiserror::Error)]
pub enum KernelCommandError {
    /// `--nodes` does not hold the formulation's coordinate count.
    #[error(
        "--nodes: the {formulation} formulation expects {expected} comma-separated coordinates \
         ({names}), got {found}"
    )]
    CoordinateCount {
        /// The formulation asked for (a name or a file).
        formulation: String,
        /// Its coordinate count.
        expected: usize,
        /// Its coordinate names, comma-separated.
        names: String,
        /// The number of comma-separated fields given.
        found: usize,
    },
    /// `--xi-s` does not hold the formulation's parametric dimension.
    #[error(
        "--xi-s: the {formulation} formulation expects {expected} comma-separated value(s) \
         ({names}), got {found}"
    )]
    ParamCount {
        /// The formulation asked for (a name or a file).
        formulation: String,
        /// Its parametric dimension.
        expected: usize,
        /// The values' names.
        names: &'static str,
        /// The number given.
        found: usize,
    },
    /// A coordinate of `--nodes` is not a finite number.
    #[error("--nodes: coordinate {index} ({name}): {reason}")]
    Coordinate {
        /// 1-based position in `--nodes`.
        index: usize,
        /// Its name (e.g. `ys2`).
        name: String,
        /// Why it was rejected.
        reason: String,
    },
    /// The formulation's kernels are not in this build (the binary was
    /// built without the root feature of the formulation's name).
    #[error(
        "the {0} kernels are not compiled into this build of gapsim (build it with the \
         default features, or with `--features {0}`)"
    )]
    NotCompiled(Formulation),
    /// The kernel rejected the configuration.
    #[error("cannot evaluate the {formulation} Type {ty} kernel for this configuration: {reason}")]
    Kernel {
        /// The formulation asked for (a name or a file).
        formulation: String,
        /// The approximation type asked for.
        ty: ApproxType,
        /// The kernel's typed error.
        reason: KernelError,
    },
    /// The formulation file could not be read or generated.
    #[error(transparent)]
    File(#[from] GenerateError),
    /// Writing the result failed (e.g. a closed pipe).
    #[error("cannot write the result: {0}")]
    Output(std::io::Error),
    /// Serialising the result failed.
    #[error("cannot serialise the result: {0}")]
    Json(serde_json::Error),
}

/// Runs `gapsim kernel`: evaluates the kernel and prints one JSON line on
/// stdout.
pub fn run(args: &KernelArgs) -> CommandResult {
    let name = args.formulation.to_string();
    let kernel_error = |reason| KernelCommandError::Kernel {
        formulation: name.clone(),
        ty: args.ty,
        reason,
    };
    let out = match &args.formulation {
        FormulationArg::Compiled(f) => {
            let kernel = Kernel::new(*f, args.ty).map_err(|e| match e {
                KernelError::NotCompiled(f) => KernelCommandError::NotCompiled(f),
                e => kernel_error(e),
            })?;
            let q = parse_nodes(&args.nodes, &name, f.face_nodes(), kernel.coords())?;
            let xi_s = &args.xi_s.0;
            if xi_s.len() != kernel.param_dim() {
                return Err(KernelCommandError::ParamCount {
                    formulation: name.clone(),
                    expected: kernel.param_dim(),
                    names: if kernel.param_dim() == 2 {
                        "u,v"
                    } else {
                        "xi_s"
                    },
                    found: xi_s.len(),
                }
                .into());
            }
            let mut out = GapOut::new(&kernel);
            kernel.eval(&q, &xi_s[..], &mut out).map_err(kernel_error)?;
            out
        }
        FormulationArg::File(path) => {
            let kernels = interpreted(path)?;
            let n = contact_kernels::RuntimeKernels::coords(&kernels);
            let q = parse_nodes(&args.nodes, &name, None, n)?;
            let xi_s = match args.xi_s.0[..] {
                [x] => x,
                _ => {
                    return Err(KernelCommandError::ParamCount {
                        formulation: name.clone(),
                        expected: 1,
                        names: "xi_s",
                        found: args.xi_s.0.len(),
                    }
                    .into());
                }
            };
            let mut out = GapOut::with_coords(n);
            contact_kernels::eval_runtime(&kernels, args.ty, &q, xi_s, &mut out)
                .map_err(kernel_error)?;
            out
        }
    };
    let mut stdout = std::io::stdout().lock();
    serde_json::to_writer(&mut stdout, &KernelOutput::from(&out))
        .map_err(KernelCommandError::Json)?;
    writeln!(stdout).map_err(KernelCommandError::Output)?;
    stdout.flush().map_err(KernelCommandError::Output)?;
    Ok(())
}

/// Parses `--xi-s`: comma-separated finite numbers; a single one (a
/// segment's) must lie in [-1, 1] (a slave point on its segment). A face's
/// `u,v` is checked against its face by the kernel.
fn parse_xi(s: &str) -> Result<Xi, String> {
    let values: Vec<f64> = s.split(',').map(parse_finite).collect::<Result<_, _>>()?;
    if let [v] = values[..]
        && !(-1.0..=1.0).contains(&v)
    {
        return Err(format!(
            "`{s}` is outside [-1, 1]: the slave point must lie on its segment \
             (-1: slave node 1, 1: slave node 2)"
        ));
    }
    Ok(Xi(values))
}

/// The generated kernels of a formulation file (a segment pair: 4 or 6
/// points and `xi_s`), ready to interpret.
fn interpreted(path: &std::path::Path) -> Result<InterpretedKernels, GenerateError> {
    let file = read_source(path)?;
    let located = |e| locate(e, std::slice::from_ref(&file));
    let f = codegen::Formulation::parse(&file.source.name, &file.source.text).map_err(located)?;
    InterpretedKernels::new(&f).map_err(located)
}

/// Parses a finite number (rejects `nan`, `inf`).
fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("`{s}` is not a finite number"))
    }
}

/// Parses `--nodes`: exactly `n` comma-separated finite coordinates, the
/// coordinate count of `formulation`'s kernels.
fn parse_nodes(
    s: &str,
    formulation: &str,
    faces: Option<(usize, usize)>,
    n: usize,
) -> Result<Vec<f64>, KernelCommandError> {
    let names = match faces {
        Some((slave, master)) => face_coordinate_names(slave, master),
        None => coordinate_names(n),
    };
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != n {
        return Err(KernelCommandError::CoordinateCount {
            formulation: formulation.to_owned(),
            expected: n,
            names: names.join(","),
            found: parts.len(),
        });
    }
    parts
        .iter()
        .zip(names)
        .enumerate()
        .map(|(i, (part, name))| {
            parse_finite(part).map_err(|reason| KernelCommandError::Coordinate {
                index: i + 1,
                name,
                reason,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinate_names_follow_the_count() {
        assert_eq!(
            coordinate_names(8).join(","),
            "xs1,ys1,xs2,ys2,xm1,ym1,xm2,ym2"
        );
        assert_eq!(
            coordinate_names(12).join(","),
            "xs1,ys1,xs2,ys2,xs3,ys3,xm1,ym1,xm2,ym2,xm3,ym3"
        );
    }

    #[test]
    fn parses_nodes() {
        let sn = "slave-normal";
        assert_eq!(
            parse_nodes("0,1,2,3,4,5,6,-7.5", sn, None, 8).unwrap(),
            [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, -7.5]
        );
        assert_eq!(
            parse_nodes(" -0.1, 1e-3 ,2,3,4,5,6,7", sn, None, 8).unwrap()[..2],
            [-0.1, 1e-3]
        );
        let err = |s: &str, n: usize| parse_nodes(s, sn, None, n).unwrap_err().to_string();
        let e = err("1,2,3,4,5,6,7", 8);
        assert!(e.contains("expects 8") && e.contains("got 7"), "{e}");
        assert!(e.contains("(xs1,ys1,xs2,ys2,xm1,ym1,xm2,ym2)"), "{e}");
        assert!(err("1,2,3,4,5,6,7,8,", 8).contains("got 9"));
        assert!(err("1,2,3,x,5,6,7,8", 8).contains("coordinate 4 (ys2)"));
        assert!(err("1,2,3,4,NaN,6,7,8", 8).contains("not a finite number"));
        assert!(parse_nodes("1,2,3,4,5,6,7,inf", sn, None, 8).is_err());
        let quadratic = "0,0,2,0,1,0,2,-1,0,-1,1,-0.8";
        assert_eq!(parse_nodes(quadratic, sn, None, 12).unwrap().len(), 12);
        assert!(err(quadratic, 8).contains("got 12"));
        assert!(err("0,1,2,3,4,5,6,7,8,9,10,x", 12).contains("coordinate 12 (ym3)"));
    }

    #[test]
    fn a_formulation_not_compiled_in_says_how_to_get_it() {
        let msg = KernelCommandError::NotCompiled(Formulation::QuadraticSlaveNormal).to_string();
        assert!(
            msg.contains("quadratic-slave-normal kernels are not compiled")
                && msg.contains("--features quadratic-slave-normal"),
            "{msg}"
        );
    }

    #[test]
    fn type_1_prints_a_zero_hessian() {
        let kernel = Kernel::new(Formulation::SlaveNormal, ApproxType::Type1).unwrap();
        let mut out = GapOut::new(&kernel);
        let q = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
        kernel.eval(&q, 0.3, &mut out).unwrap();
        let printed = KernelOutput::from(&out);
        assert_eq!(printed.grad, out.grad());
        assert!(printed.grad.iter().any(|&g| g != 0.0));
        assert_eq!(printed.hess, vec![vec![0.0; 8]; 8]);
        let json = serde_json::to_string(&printed).unwrap();
        assert!(json.starts_with(r#"{"gap":"#), "{json}");
        assert!(json.ends_with(&format!(
            "\"hess\":[{}]}}",
            ["[0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0]"; 8].join(",")
        )));
    }
}
