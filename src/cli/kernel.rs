//! `gapsim kernel`: evaluate one generated contact kernel and print the
//! result as JSON.
//!
//! ```text
//! gapsim kernel --formulation F --type T --xi-s XI --nodes a,b,c,d,e,f,g,h
//! ```
//!
//! prints one line, a JSON object
//! `{"gap":..,"xi_m":..,"grad":[8 numbers],"hess":[8 rows of 8]}` whose
//! numbers round-trip to the kernel's exact `f64` values; `hess` is all zeros
//! for Type 1, which has no second-order term.

use std::io::Write;

use clap::Args;
use contact_kernels::{ApproxType, Formulation, GapDerivatives, KernelError};
use serde::Serialize;

use super::CommandResult;

/// Names of the eight node coordinates, in kernel order.
const COORDINATE_NAMES: [&str; 8] = ["xs1", "ys1", "xs2", "ys2", "xm1", "ym1", "xm2", "ym2"];

/// Arguments of `gapsim kernel`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Example:\n  gapsim kernel --type 6 --xi-s 0.3 --nodes 0,1,2,1.1,2.1,0.9,-0.1,1.0\n\n\
Output: one JSON object {\"gap\":..,\"xi_m\":..,\"grad\":[8],\"hess\":[[8]x8]} \
(derivatives with respect to the 8 coordinates; hess is all zeros for Type 1)."
)]
pub struct KernelArgs {
    /// Contact formulation: `slave-normal` (projection along the slave
    /// normal, the paper's) or `closest-point` (orthogonal projection onto
    /// the master segment).
    #[arg(long, value_name = "F", default_value = "slave-normal")]
    pub formulation: Formulation,

    /// Approximation type, 1 to 6 (6: exact gradient and Hessian; 1: no
    /// Hessian).
    #[arg(long = "type", value_name = "T")]
    pub ty: ApproxType,

    /// Parametric coordinate of the slave integration point on the slave
    /// segment (-1: slave node 1, 1: slave node 2).
    #[arg(long = "xi-s", value_name = "XI", allow_negative_numbers = true, value_parser = parse_finite)]
    pub xi_s: f64,

    /// Current coordinates of slave node 1, slave node 2, master node 1 and
    /// master node 2, comma-separated: xs1,ys1,xs2,ys2,xm1,ym1,xm2,ym2.
    #[arg(
        long,
        value_name = "XS1,YS1,XS2,YS2,XM1,YM1,XM2,YM2",
        allow_hyphen_values = true,
        value_parser = parse_nodes
    )]
    pub nodes: [f64; 8],
}

/// The JSON printed by `gapsim kernel` (field order as in the contract).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KernelOutput {
    /// The gap `g` (negative when penetrating).
    pub gap: f64,
    /// The master parametric coordinate of the projection.
    pub xi_m: f64,
    /// `dg/dq`.
    pub grad: [f64; 8],
    /// `d2g/dq2`, row by row (all zeros for Type 1).
    pub hess: [[f64; 8]; 8],
}

impl From<&GapDerivatives> for KernelOutput {
    fn from(d: &GapDerivatives) -> Self {
        KernelOutput {
            gap: d.gap,
            xi_m: d.xi_m,
            grad: std::array::from_fn(|i| d.grad[i]),
            hess: std::array::from_fn(|i| {
                std::array::from_fn(|j| d.hess.map_or(0.0, |h| h[(i, j)]))
            }),
        }
    }
}

/// Why `gapsim kernel` failed after its arguments were parsed. Each message
/// is one self-contained line (the underlying error is part of it, not a
/// separate `source`).
#[derive(Debug, thiserror::Error)]
pub enum KernelCommandError {
    /// The kernel rejected the configuration.
    #[error("cannot evaluate the {formulation} Type {ty} kernel for this configuration: {reason}")]
    Kernel {
        /// The formulation asked for.
        formulation: Formulation,
        /// The approximation type asked for.
        ty: ApproxType,
        /// The kernel's typed error.
        reason: KernelError,
    },
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
    let out = contact_kernels::evaluate(args.formulation, args.ty, &args.nodes, args.xi_s)
        .map_err(|reason| KernelCommandError::Kernel {
            formulation: args.formulation,
            ty: args.ty,
            reason,
        })?;
    let mut stdout = std::io::stdout().lock();
    serde_json::to_writer(&mut stdout, &KernelOutput::from(&out))
        .map_err(KernelCommandError::Json)?;
    writeln!(stdout).map_err(KernelCommandError::Output)?;
    stdout.flush().map_err(KernelCommandError::Output)?;
    Ok(())
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

/// Parses exactly eight comma-separated finite coordinates.
fn parse_nodes(s: &str) -> Result<[f64; 8], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 8 {
        return Err(format!(
            "expected 8 comma-separated coordinates ({}), got {}",
            COORDINATE_NAMES.join(","),
            parts.len()
        ));
    }
    let mut q = [0.0; 8];
    for (i, part) in parts.iter().enumerate() {
        q[i] = parse_finite(part)
            .map_err(|e| format!("coordinate {} ({}): {e}", i + 1, COORDINATE_NAMES[i]))?;
    }
    Ok(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_nodes() {
        assert_eq!(
            parse_nodes("0,1,2,3,4,5,6,-7.5").unwrap(),
            [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, -7.5]
        );
        assert_eq!(
            parse_nodes(" -0.1, 1e-3 ,2,3,4,5,6,7").unwrap()[..2],
            [-0.1, 1e-3]
        );
        assert!(parse_nodes("1,2,3,4,5,6,7").unwrap_err().contains("got 7"));
        assert!(
            parse_nodes("1,2,3,4,5,6,7,8,")
                .unwrap_err()
                .contains("got 9")
        );
        assert!(
            parse_nodes("1,2,3,x,5,6,7,8")
                .unwrap_err()
                .contains("coordinate 4 (ys2)")
        );
        assert!(
            parse_nodes("1,2,3,4,NaN,6,7,8")
                .unwrap_err()
                .contains("not a finite number")
        );
        assert!(parse_nodes("1,2,3,4,5,6,7,inf").is_err());
    }

    #[test]
    fn type_1_prints_a_zero_hessian() {
        let d = GapDerivatives {
            gap: 0.5,
            xi_m: -0.25,
            grad: nalgebra::SVector::from([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]),
            hess: None,
        };
        let json = serde_json::to_string(&KernelOutput::from(&d)).unwrap();
        assert!(json.starts_with(
            r#"{"gap":0.5,"xi_m":-0.25,"grad":[1.0,2.0,3.0,4.0,5.0,6.0,7.0,8.0],"hess":[[0.0,"#
        ));
        assert_eq!(json.matches("0.0").count(), 64);
    }
}
