//! `gapsim generate`: kernels for any formulation file.
//!
//! ```text
//! gapsim generate FILE.rs... --lang rust|c --out DIR
//! ```
//!
//! parses each formulation file (its stem names the formulation: `my-normal.rs`
//! gives `my_normal_type1`..`_type6`), derives every approximation type and
//! writes the generated files into `DIR`: `kernels.rs` (Rust, the module
//! contact-kernels `include!`s) or `gapsim.h`, the shared runtime
//! `gapsim_runtime.h/.c` and `gapsim_{name}.h/.c` per
//! formulation (C99). Each written path is printed on stdout; the Rust
//! file's header names the files it came from. A malformed file is
//! reported as `FILE:LINE:COLUMN: message` (or `FILE: message` where no
//! line applies, e.g. a name two files share) with a non-zero exit, and
//! nothing is written.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::CommandResult;

/// The target language.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Lang {
    /// Rust: one `kernels.rs`.
    Rust,
    /// C99: `gapsim.h`, the shared runtime and a header and source per
    /// formulation.
    C,
}

/// Arguments of `gapsim generate`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Example:\n  gapsim generate my-normal.rs --lang c --out generated/\n\n\
A formulation file is Rust syntax: inputs!(xs1, xs2, xm1, xm2; xi_s); let ... = implicit!(xi => ...); \
entity!(...); gap!(...) (reference: docs/formulations.md; example: contact-kernels/formulations/slave-normal.rs); 3D faces: \
inputs!(dim 3; xs1, xs2, xs3; xm1, xm2, xm3; xi_s: 2), implicit!(xi: 2 => [r1, r2]) \
(see contact-kernels/formulations/tri3-slave-normal.rs)."
)]
pub struct GenerateArgs {
    /// Formulation files (`NAME.rs`; the stem names the formulation).
    #[arg(required = true, value_name = "FILE.rs")]
    pub files: Vec<PathBuf>,

    /// Language of the generated kernels.
    #[arg(long, value_enum, default_value_t = Lang::Rust)]
    pub lang: Lang,

    /// Directory to write the generated files into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// Why `gapsim generate` (or `gapsim verify`) failed.
#[derive(Debug, thiserror::Error)]
pub enum GenerateError {
    /// A formulation file could not be read.
    #[error("cannot read {path}: {reason}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        reason: std::io::Error,
    },
    /// The file's stem is not a formulation name.
    #[error(
        "{path}: the file name must be NAME.rs with NAME made of letters, digits, `-` and `_`, \
         starting with a letter"
    )]
    Name {
        /// The file.
        path: PathBuf,
    },
    /// Two files give the same formulation name.
    #[error("{path}: a formulation named `{name}` is already given")]
    Duplicate {
        /// The second file.
        path: PathBuf,
        /// The name.
        name: String,
    },
    /// A malformed formulation, at `file:line:column`.
    #[error("{path}:{line}:{column}: {message}")]
    Formulation {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A formulation that does not fit the generator.
    #[error("{path}: {message}")]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// Writing a generated file failed.
    #[error("cannot write {path}: {reason}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        reason: std::io::Error,
    },
}

/// A formulation file read from disk.
#[derive(Debug, Clone)]
pub struct FileSource {
    /// Where it was read from.
    pub path: PathBuf,
    /// The formulation (named by the file stem).
    pub source: codegen::Source,
}

/// Reads a formulation file; its stem is the formulation's name.
pub fn read_source(path: &Path) -> Result<FileSource, GenerateError> {
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| {
            path.extension().is_some_and(|e| e == "rs")
                && s.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
                && s.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        })
        .ok_or_else(|| GenerateError::Name {
            path: path.to_owned(),
        })?
        .to_owned();
    let text = std::fs::read_to_string(path).map_err(|reason| GenerateError::Read {
        path: path.to_owned(),
        reason,
    })?;
    Ok(FileSource {
        path: path.to_owned(),
        source: codegen::Source {
            name,
            text,
            compiled: true,
        },
    })
}

/// A generator error with the formulation's name (`NAME.rs`) replaced by
/// the path it was read from.
pub fn locate(e: codegen::Error, files: &[FileSource]) -> GenerateError {
    let path_of = |file: &str| {
        files
            .iter()
            .find(|f| format!("{}.rs", f.source.name) == file)
            .map_or_else(|| PathBuf::from(file), |f| f.path.clone())
    };
    match e {
        codegen::Error::Formulation {
            file,
            line,
            column,
            message,
        } => GenerateError::Formulation {
            path: path_of(&file),
            line,
            column,
            message,
        },
        codegen::Error::Truncation { file, message } => GenerateError::Unsupported {
            path: path_of(&file),
            message,
        },
    }
}

/// Runs `gapsim generate`.
pub fn run(args: &GenerateArgs) -> CommandResult {
    let mut files: Vec<FileSource> = Vec::new();
    for path in &args.files {
        let f = read_source(path)?;
        if files.iter().any(|g| g.source.name == f.source.name) {
            return Err(GenerateError::Duplicate {
                path: path.clone(),
                name: f.source.name,
            }
            .into());
        }
        files.push(f);
    }
    let sources: Vec<codegen::Source> = files.iter().map(|f| f.source.clone()).collect();
    let origin: Vec<String> = files.iter().map(|f| f.path.display().to_string()).collect();
    let plan = codegen::KernelPlan::build(&sources)
        .map_err(|e| locate(e, &files))?
        .with_origin(origin.join(", "));
    let emitted = match args.lang {
        Lang::Rust => codegen::Emitter::emit(&codegen::emit::RustEmitter, &plan),
        Lang::C => codegen::Emitter::emit(&codegen::emit::CEmitter, &plan),
    };
    std::fs::create_dir_all(&args.out).map_err(|reason| GenerateError::Write {
        path: args.out.clone(),
        reason,
    })?;
    for file in &emitted {
        let path = args.out.join(&file.name);
        solver::report::write_atomic(&path, &file.contents).map_err(|reason| {
            GenerateError::Write {
                path: path.clone(),
                reason,
            }
        })?;
        println!("{}", path.display());
    }
    Ok(())
}
