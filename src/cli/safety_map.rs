//! `gapsim safety-map`: runs the benchmark scenes (complete formulation and
//! Types 1–6 at each scene's step counts) and writes the safety map. See
//! [`gapsim::study::safety_map`].
//!
//! ```text
//! gapsim safety-map [SCENE.toml[:N,N,...] ...] [--out DIR] [--repeats R]
//!                   [--energy-tolerance PCT] [--reaction-tolerance PCT]
//! ```
//!
//! Without scenes it runs [`DEFAULT_SCENES`] from `scenes/` (run it from the
//! repository root). `:N,N,...` after a scene replaces its
//! `loading.steps`.

use std::path::{Path, PathBuf};

use clap::Args;
use gapsim::study::{
    self,
    safety_map::{self, MapOptions, MapScene},
};
use solver::Scene;

use super::CommandResult;
use super::interrupt::Interrupt;
use super::out_dir::OutDir;

/// Whether `name` is a file of the safety map's result set.
pub fn is_result_file(name: &str) -> bool {
    matches!(
        name,
        "safety-map.csv" | "safety-map-runs.csv" | "safety-map.md"
    )
}

/// The benchmark scenes of the default map (files under `scenes/`), each at
/// its own `loading.steps`. The fine Hertz meshes are left out
/// (hertz-coarse and hertz-small-strain cover the Hertz contact).
pub const DEFAULT_SCENES: [&str; 6] = [
    "stacked-cantilever",
    "sliding",
    "pressed-blocks",
    "patch-test",
    "hertz-coarse",
    "hertz-small-strain",
];

/// Arguments of `gapsim safety-map`.
#[derive(Debug, Clone, Args)]
pub struct SafetyMapArgs {
    /// Scene files (TOML), each optionally followed by `:N,N,...` (its step
    /// counts); default: the benchmark scenes under `scenes/` at their own
    /// `loading.steps`.
    #[arg(value_name = "SCENE[:N,...]")]
    pub scenes: Vec<String>,

    /// Output directory for safety-map.csv, safety-map-runs.csv and
    /// safety-map.md.
    #[arg(long, value_name = "DIR", default_value = "safety-map-out")]
    pub out: PathBuf,

    /// Solves per configuration; times are medians.
    #[arg(long, value_name = "R", default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=1000))]
    pub repeats: u64,

    /// A safe type's strain-energy error bound, percent.
    #[arg(long, value_name = "PCT", default_value_t = safety_map::ENERGY_TOLERANCE_PERCENT)]
    pub energy_tolerance: f64,

    /// A safe type's reaction error bound, percent.
    #[arg(long, value_name = "PCT", default_value_t = safety_map::REACTION_TOLERANCE_PERCENT)]
    pub reaction_tolerance: f64,
}

/// Splits `path[:N,N,...]` into the path and its step counts.
fn parse_scene_arg(arg: &str) -> Result<(PathBuf, Option<Vec<usize>>), String> {
    match arg.rsplit_once(':') {
        Some((path, steps))
            if !path.is_empty() && steps.chars().all(|c| c.is_ascii_digit() || c == ',') =>
        {
            let counts: Result<Vec<usize>, _> = steps
                .split(',')
                .map(|s| s.trim().parse::<usize>())
                .collect();
            match counts {
                Ok(c) if !c.is_empty() && !c.contains(&0) => Ok((PathBuf::from(path), Some(c))),
                _ => Err(format!(
                    "`{arg}`: step counts after `:` must be positive integers separated by commas"
                )),
            }
        }
        _ => Ok((PathBuf::from(arg), None)),
    }
}

fn label_of(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Runs `gapsim safety-map`.
pub fn run(args: &SafetyMapArgs) -> CommandResult {
    let specs: Vec<String> = if args.scenes.is_empty() {
        DEFAULT_SCENES
            .iter()
            .map(|s| format!("scenes/{s}.toml"))
            .collect()
    } else {
        args.scenes.clone()
    };
    for (name, v) in [
        ("--energy-tolerance", args.energy_tolerance),
        ("--reaction-tolerance", args.reaction_tolerance),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("{name}: expected a positive percentage, got {v}").into());
        }
    }
    let mut scenes = Vec::new();
    for spec in &specs {
        let (path, steps) = parse_scene_arg(spec)?;
        if args.scenes.is_empty() && !path.exists() {
            return Err(format!(
                "{} not found: run `gapsim safety-map` from the repository root or name the scenes",
                path.display()
            )
            .into());
        }
        let scene = Scene::from_file(&path)?;
        let steps = steps.unwrap_or_else(|| scene.loading.steps.clone());
        scenes.push(MapScene {
            label: label_of(&path),
            scene,
            steps,
        });
    }
    let options = MapOptions {
        repeats: args.repeats as usize,
        energy_tolerance_percent: args.energy_tolerance,
        reaction_tolerance_percent: args.reaction_tolerance,
    };
    let out = OutDir::check(&args.out, is_result_file)?;

    let bar = super::study::progress_bar();
    let map = safety_map::run_map(&scenes, &options, &bar as &dyn study::Progress)?;
    bar.finish_and_clear();

    let command = format!(
        "gapsim {}",
        std::env::args().skip(1).collect::<Vec<_>>().join(" ")
    );
    // From here on Ctrl-C lets the result set be written or not at all
    // (before, it ends the process with nothing written).
    let interrupt = Interrupt::install().map_err(|e| format!("cannot catch Ctrl-C: {e}"))?;
    let staging = out.stage()?;
    for (name, text) in [
        ("safety-map.csv", safety_map::csv(&map)),
        ("safety-map-runs.csv", safety_map::runs_csv(&map)),
        ("safety-map.md", safety_map::markdown(&map, &command)),
    ] {
        solver::report::write_atomic(staging.path().join(name), text)
            .map_err(|e| format!("cannot write {}: {e}", args.out.join(name).display()))?;
    }
    staging.commit(Some(&interrupt))?;
    print!("{}", safety_map::reading(&map));
    println!(
        "\nwrote safety-map.csv, safety-map-runs.csv and safety-map.md to {}",
        args.out.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_arguments_split_off_their_step_counts() {
        assert_eq!(
            parse_scene_arg("scenes/a.toml:4,8").unwrap(),
            (PathBuf::from("scenes/a.toml"), Some(vec![4, 8]))
        );
        assert_eq!(
            parse_scene_arg("scenes/a.toml").unwrap(),
            (PathBuf::from("scenes/a.toml"), None)
        );
        assert!(parse_scene_arg("a.toml:4,0").is_err());
        assert!(parse_scene_arg("a.toml:,").is_err());
    }
}
