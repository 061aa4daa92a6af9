//! The command-line application: one clap parser with one subcommand per
//! module.
//!
//! To add a subcommand, write `src/cli/NAME.rs` with an `Args` struct
//! (`#[derive(clap::Args)]`) and a `run(args) -> CommandResult` function,
//! declare the module here, and add a variant to [`Command`] and an arm to
//! [`Cli::run`].

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub mod generate;
pub mod interrupt;
pub mod kernel;
pub mod out_dir;
pub mod run;
pub mod safety_map;
pub mod study;
pub mod verify;

/// What a subcommand returns: `Err` carries the message printed on stderr
/// before exiting with a non-zero status.
pub type CommandResult = Result<(), Box<dyn std::error::Error + Send + Sync>>;

/// gapsim: approximate contact constraint formulations for
/// large-displacement structural analysis.
#[derive(Debug, Parser)]
#[command(name = "gapsim", version, about, long_about = None, propagate_version = true)]
pub struct Cli {
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Evaluate one generated contact kernel and print the gap, xi_m,
    /// gradient and Hessian as one JSON object.
    Kernel(kernel::KernelArgs),
    /// Solve one scene (default: the embedded paper scene) and print a
    /// summary; optionally write `.vtu` files.
    Run(run::RunArgs),
    /// Run the paper's study: every approximation type and the complete
    /// formulation for every step count; writes study.csv, plots and
    /// results.md.
    Study(study::StudyArgs),
    /// Generate the kernels (Rust or C99) of formulation files.
    Generate(generate::GenerateArgs),
    /// Verify every type of a formulation file's kernels against num-dual
    /// automatic differentiation; prints the worst errors, fails on any
    /// above the tolerance.
    Verify(verify::VerifyArgs),
    /// Run the benchmark scenes (complete formulation and every type at
    /// each scene's step counts) and write the safety map: which type is
    /// safe on which scene, and its cost against complete
    /// (safety-map.csv, safety-map.md).
    SafetyMap(safety_map::SafetyMapArgs),
}

impl Cli {
    /// Runs the chosen subcommand; on error prints `gapsim: error: ...`
    /// (with the error's causes) on stderr and returns a failure status.
    pub fn run(self) -> ExitCode {
        let result = match self.command {
            Command::Kernel(args) => kernel::run(&args),
            Command::Run(args) => run::run(&args),
            Command::Study(args) => study::run(&args),
            Command::Generate(args) => generate::run(&args),
            Command::Verify(args) => verify::run(&args),
            Command::SafetyMap(args) => safety_map::run(&args),
        };
        match result {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                let mut msg = format!("gapsim: error: {e}");
                let mut source = e.source();
                while let Some(s) = source {
                    // a cause the message above already quotes is not repeated
                    let cause = s.to_string();
                    if !msg.contains(&cause) {
                        msg.push_str(&format!("\n  caused by: {cause}"));
                    }
                    source = s.source();
                }
                eprintln!("{msg}");
                ExitCode::FAILURE
            }
        }
    }
}
