//! `gapsim study`: the paper's study (error against load steps, speed
//! against error) for the complete formulation and every approximation
//! type, on any scene with contact. See [`gapsim::study`]. Besides the
//! paper's files it writes `study-errors.csv` (energy and reaction errors,
//! cost against complete: [`gapsim::study::errors`]).
//!
//! ```text
//! gapsim study [SCENE.toml] [--out DIR] [--repeats R] [--linear lu|ldlt|petsc]
//!     [--expand-at predictor|start] [--readme PAGE.md]
//! ```
//!
//! `--readme` splices the results section into any Markdown page that has
//! the study markers, e.g. `--readme docs/study.md`.

use std::path::PathBuf;

use clap::Args;
use gapsim::study::{self, StudyOptions, errors, plots, report};

use super::CommandResult;
use super::interrupt::Interrupt;
use super::out_dir::OutDir;
use super::run::load_scene;

/// Whether `name` is a file of the study's result set: `study.csv`,
/// `study-*.csv`, `results.md` and the plots (`deformed.*`,
/// `error-vs-*.*`, PNG and SVG).
pub fn is_result_file(name: &str) -> bool {
    let csv = name == "study.csv" || (name.starts_with("study-") && name.ends_with(".csv"));
    let plot = name
        .strip_suffix(".png")
        .or_else(|| name.strip_suffix(".svg"))
        .is_some_and(|stem| stem == "deformed" || stem.starts_with("error-vs-"));
    csv || plot || name == "results.md"
}

/// Arguments of `gapsim study`.
#[derive(Debug, Clone, Args)]
pub struct StudyArgs {
    /// Scene file (TOML); default: the embedded paper scene.
    pub scene: Option<PathBuf>,

    /// Output directory for `study.csv`, the plots and `results.md`.
    #[arg(long, value_name = "DIR", default_value = "study-out")]
    pub out: PathBuf,

    /// Solves per configuration; times are medians.
    #[arg(long, value_name = "R", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=1000))]
    pub repeats: u64,

    /// Step counts (comma-separated; default: the scene's `loading.steps`).
    #[arg(long, value_name = "N,N,...", value_delimiter = ',')]
    pub steps: Vec<usize>,

    /// Only the scene's formulation (skip the other projection reading).
    #[arg(long)]
    pub only_scene_formulation: bool,

    /// Skip the contact-heavy variant.
    #[arg(long)]
    pub no_heavy: bool,

    /// The linear solver of every solve, the contact-heavy variant's too
    /// (default: the scene's `[newton] linear`, LU unless set). With the
    /// LDLᵀ the linear solve hides less of what the types save.
    #[arg(long, value_name = "lu|ldlt|petsc")]
    pub linear: Option<solver::LinearSolverKind>,

    /// Types 1-6: where a step's Taylor expansions are taken, the step's
    /// predictor or its start (the paper's scheme; default: the scene's
    /// `[newton] expand_at`, the predictor unless set).
    #[arg(long, value_name = "predictor|start")]
    pub expand_at: Option<solver::ExpansionPoint>,

    /// Replace the section between `<!-- study:begin -->` and
    /// `<!-- study:end -->` of this Markdown file with the results.
    #[arg(long, value_name = "FILE")]
    pub readme: Option<PathBuf>,
}

/// Runs `gapsim study`.
pub fn run(args: &StudyArgs) -> CommandResult {
    let mut scene = load_scene(args.scene.as_ref())?;
    if let Some(kind) = args.linear {
        scene.newton.linear = kind;
    }
    if let Some(e) = args.expand_at {
        scene.newton.expand_at = e;
    }
    if args.steps.contains(&0) {
        return Err("--steps: step counts must be at least 1".into());
    }
    let options = StudyOptions {
        repeats: args.repeats as usize,
        steps: (!args.steps.is_empty()).then(|| args.steps.clone()),
        all_formulations: !args.only_scene_formulation,
        heavy_steps: if args.no_heavy {
            Vec::new()
        } else {
            StudyOptions::default().heavy_steps
        },
        ..StudyOptions::default()
    };
    let out = OutDir::check(&args.out, is_result_file)?;

    let bar = progress_bar();
    let results = study::run_study(&scene, &options, &bar)?;
    bar.finish_and_clear();

    // From here on Ctrl-C lets the result set be written or not at all
    // (before, it ends the process with nothing written).
    let interrupt = Interrupt::install().map_err(|e| format!("cannot catch Ctrl-C: {e}"))?;
    let staging = out.stage()?;
    let write = |name: &str, text: &str| -> CommandResult {
        solver::report::write_atomic(staging.path().join(name), text)
            .map_err(|e| format!("cannot write {}: {e}", args.out.join(name).display()))?;
        Ok(())
    };
    for (i, s) in results.formulations.iter().enumerate() {
        let name = if i == 0 {
            "study.csv".to_owned()
        } else {
            format!("study-{}.csv", s.formulation)
        };
        write(&name, &report::csv(s))?;
    }
    if let Some(h) = &results.heavy {
        write("study-contact-heavy.csv", &report::csv(&h.study))?;
    }
    // Energy and reaction errors and the cost against complete, every
    // formulation (a companion of study.csv, whose columns stay as they are).
    write("study-errors.csv", &errors::csv(&results.formulations))?;
    plots::write_all(&results, staging.path())?;

    let command = std::env::args().skip(1).collect::<Vec<_>>().join(" ");
    let command = format!("gapsim {command}");
    write("results.md", &report::markdown(&results, "", &command))?;
    staging.commit(Some(&interrupt))?;
    print!("{}", report::terminal_summary(&results));
    print!("{}", errors::reaction_summary(&results.formulations[0]));
    if let Some(why) = &results.heavy_failure {
        println!("\ncontact-heavy variant left out: {why}");
    }
    println!(
        "\nwrote study.csv, study-errors.csv, plots and results.md to {}",
        args.out.display()
    );

    if let Some(readme) = &args.readme {
        let text = std::fs::read_to_string(readme)
            .map_err(|e| format!("cannot read {}: {e}", readme.display()))?;
        let base = readme
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        let prefix = relative_prefix(base, &args.out);
        let section = report::markdown(&results, &prefix, &command);
        let new = report::splice_readme(&text, &section).ok_or_else(|| {
            format!(
                "{} has no `{}` ... `{}` section",
                readme.display(),
                report::README_BEGIN,
                report::README_END
            )
        })?;
        solver::report::write_atomic(readme, new)
            .map_err(|e| format!("cannot write {}: {e}", readme.display()))?;
        println!("updated the results section of {}", readme.display());
    }
    Ok(())
}

/// The link prefix from `base` (the page's directory) to `out`.
fn relative_prefix(base: &std::path::Path, out: &std::path::Path) -> String {
    let (Ok(b), Ok(o)) = (base.canonicalize(), out.canonicalize()) else {
        return format!("{}/", out.display());
    };
    match o.strip_prefix(&b) {
        Ok(rel) if rel.as_os_str().is_empty() => String::new(),
        Ok(rel) => format!("{}/", rel.display()),
        Err(_) => format!("{}/", o.display()),
    }
}

/// The progress bar of a long command (`study`, `safety-map`): elapsed
/// time, bar, runs done of all, the current run.
pub(super) fn progress_bar() -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(0);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every file of the committed study output is one of the study's
    /// own (so a new study into that directory replaces each), and files
    /// of other names are not.
    #[test]
    fn the_committed_study_files_are_the_study_result_set() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/study");
        let names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(names.len() > 10, "{names:?}");
        for name in &names {
            assert!(is_result_file(name), "{name}");
        }
        for name in [
            "README.md",
            "notes.txt",
            "study.txt",
            "deformed.pdf",
            "plot.png",
        ] {
            assert!(!is_result_file(name), "{name}");
        }
    }
}
