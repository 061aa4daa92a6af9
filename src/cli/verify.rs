//! `gapsim verify`: every type of a formulation's generated kernels
//! against num-dual hyper-dual numbers of the same formulation.
//!
//! ```text
//! gapsim verify FILE.rs [--flip-sign TYPE:INSTR]
//! ```
//!
//! The kernels are generated from the file and run by codegen's
//! instruction-list interpreter (the formulation is not compiled into the
//! binary); the reference evaluates the file's expressions over num-dual
//! numbers ([`gapsim::verify`]). Prints a Markdown table of the worst
//! scaled error per type and output over seeded random configurations and
//! the hard families, and exits non-zero when any exceeds the tolerance.
//! `--flip-sign` first turns one addition of a kernel into a subtraction
//! (or back): a deliberately broken kernel, to see the verifier catch it.

use std::path::PathBuf;

use clap::Args;
use gapsim::verify::{self, VerifyError};

use super::CommandResult;
use super::generate::{GenerateError, locate, read_source};

/// Arguments of `gapsim verify`.
#[derive(Debug, Clone, Args)]
#[command(after_help = "Example:\n  gapsim verify my-normal.rs\n  \
gapsim verify my-normal.rs --flip-sign 3:138  # break one instruction of Type 3: must FAIL\n  (a non-addition index is refused with a list of indices that are additions)\n\n\
Scaled errors: g: |dg|/max(|g|, L); xi_m: |dxi|/(1+|xi|); g': |dg'|/max(|g'|, 1); \
g'': |dg''|_F/max(|g''|_F, 1/L), L the configuration's size. Tolerance 1e-10.\n\
Families: worked example, 400 random, 400 uniform, 100 far (1e6), 80 scaled (1e-6, 1e6), \
60 rotations, 100 steep masters (80-89 deg), segment ends, penetration.")]
pub struct VerifyArgs {
    /// The formulation file (`NAME.rs`).
    #[arg(value_name = "FILE.rs")]
    pub file: PathBuf,

    /// Break the kernel on purpose: flip the sign of instruction INSTR
    /// (an addition or subtraction) of type TYPE's program.
    #[arg(long, value_name = "TYPE:INSTR", value_parser = parse_flip)]
    pub flip_sign: Option<(usize, usize)>,
}

/// Parses `TYPE:INSTR`.
fn parse_flip(s: &str) -> Result<(usize, usize), String> {
    let (t, i) = s
        .split_once(':')
        .ok_or_else(|| format!("`{s}` is not TYPE:INSTR (e.g. 3:40)"))?;
    let ty: usize = t
        .trim()
        .parse()
        .map_err(|_| format!("`{t}` is not a type number"))?;
    if !(1..=6).contains(&ty) {
        return Err(format!("type {ty} is not 1 to 6"));
    }
    let instr = i
        .trim()
        .parse()
        .map_err(|_| format!("`{i}` is not an instruction index"))?;
    Ok((ty, instr))
}

/// Why `gapsim verify` failed.
#[derive(Debug, thiserror::Error)]
pub enum VerifyCommandError {
    /// The file could not be read or parsed.
    #[error(transparent)]
    File(#[from] GenerateError),
    /// The verifier could not run.
    #[error("{path}: {reason}")]
    Verifier {
        /// The file.
        path: PathBuf,
        /// The verifier's error.
        reason: VerifyError,
    },
    /// Some kernel disagrees with the reference.
    #[error("verification failed: {0}")]
    Failed(String),
}

/// Runs `gapsim verify`.
pub fn run(args: &VerifyArgs) -> CommandResult {
    let file = read_source(&args.file)?;
    let result = verify::verify_source(&file.source.name, &file.source.text, args.flip_sign);
    let source = match result {
        Ok(r) => r,
        Err(VerifyError::Formulation(e)) => {
            return Err(VerifyCommandError::File(locate(e, std::slice::from_ref(&file))).into());
        }
        Err(reason) => {
            return Err(VerifyCommandError::Verifier {
                path: args.file.clone(),
                reason,
            }
            .into());
        }
    };
    if let Some(f) = &source.flip {
        println!(
            "mutated on purpose: type {} instruction {}: {} -> {}\n",
            f.ty, f.instr, f.before, f.after
        );
    }
    print!("{}", source.gap);
    if let Some(slip) = &source.slip {
        println!();
        print!("{slip}");
    }
    if source.passed() {
        return Ok(());
    }
    let mut why = Vec::new();
    if !source.gap.passed() {
        why.push(failure(&source.gap));
    }
    if let Some(slip) = source.slip.as_ref().filter(|r| !r.passed()) {
        why.push(format!("the slip's {}", failure(slip)));
    }
    Err(VerifyCommandError::Failed(why.join("; ")).into())
}

/// Why `report` fails, type by type (types failing for the same reason
/// named together).
fn failure(report: &verify::Report) -> String {
    let why: Vec<(usize, String)> = report
        .failures()
        .iter()
        .map(|r| {
            let worst = [
                ("g", &r.gap),
                ("xi_m", &r.xi_m),
                ("g'", &r.grad),
                ("g''", &r.hess),
            ]
            .into_iter()
            .max_by(|a, b| a.1.error.total_cmp(&b.1.error))
            .expect("four outputs");
            let mut what = Vec::new();
            if worst.1.error > report.tol {
                what.push(format!(
                    "{} off by {:.1e} (> {:e}) at {}",
                    worst.0, worst.1.error, report.tol, worst.1.at
                ));
            }
            if let Some(first) = r.refused.first() {
                what.push(format!(
                    "the kernels' projection (Newton from xi = 0, at most 20 steps) failed on \
                     {} of the {} configurations the reference projects (first: {first}); a \
                     residual whose root is double (dr/dxi = 0 there) converges too slowly",
                    r.refused.len(),
                    report.checked
                ));
            }
            (r.ty, what.join("; "))
        })
        .collect();
    // Types failing for the same reason are named together.
    let mut grouped: Vec<(Vec<usize>, String)> = Vec::new();
    for (ty, what) in why {
        match grouped.iter_mut().find(|(_, w)| *w == what) {
            Some((types, _)) => types.push(ty),
            None => grouped.push((vec![ty], what)),
        }
    }
    let why: Vec<String> = grouped
        .into_iter()
        .map(|(types, what)| {
            let names: Vec<String> = types.iter().map(usize::to_string).collect();
            let label = if types.len() == 1 { "type" } else { "types" };
            format!("{label} {}: {what}", names.join(", "))
        })
        .collect();
    if report.checked == 0 {
        "no configuration could be projected".to_owned()
    } else {
        why.join("; ")
    }
}
