//! The `gapsim` command line: see `gapsim --help`.
//!
//! Each subcommand lives in its own module under `src/cli/`; `cli/mod.rs`
//! only lists them and dispatches.

mod cli;

use clap::Parser;

fn main() -> std::process::ExitCode {
    cli::Cli::parse().run()
}
