//! The safety map on small scenes (dev profile): one row per scene and
//! type with the expected columns, the files `gapsim safety-map` writes,
//! and a failing type recorded rather than fatal.

use std::path::{Path, PathBuf};
use std::process::Command;

use gapsim::study::safety_map::{self, MAP_HEADER, MapOptions, MapScene, Safety};
use gapsim::study::{self, StudyError};
use solver::{ApproxType, Method, Scene};

fn scene_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"))
}

fn map_scene(name: &str, steps: &[usize]) -> MapScene {
    MapScene {
        scene: Scene::from_file(scene_file(name)).unwrap(),
        label: name.to_owned(),
        steps: steps.to_vec(),
    }
}

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn one_row_per_scene_and_type_with_the_expected_columns() {
    let scenes = [
        map_scene("pressed-blocks", &[1, 2]),
        map_scene("patch-test", &[1, 2]),
    ];
    let map = safety_map::run_map(&scenes, &MapOptions::default(), &study::Silent).unwrap();
    assert_eq!(map.rows.len(), 2 * 6);
    for (scene, chunk) in ["pressed-blocks", "patch-test"]
        .iter()
        .zip(map.rows.chunks(6))
    {
        for (row, ty) in chunk.iter().zip(ApproxType::ALL) {
            assert_eq!((row.scene.as_str(), row.ty), (*scene, ty));
            assert_eq!(row.step_counts, [1, 2]);
            assert_eq!(row.steps, 2);
            // both scenes are solved exactly by every type (a flat
            // interface in a patch-test state): safe, with defined errors
            assert_eq!(row.safety, Safety::Safe, "{row:?}");
            assert!(row.energy_error_percent.unwrap().abs() < 1e-6);
            assert!(row.reaction_error_percent.unwrap() < 1e-6);
            assert!(row.newton_ratio.unwrap() > 0.0 && row.kernel_ratio.unwrap() > 0.0);
            assert!(row.failure.is_none());
        }
    }
    let text = safety_map::csv(&map);
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert_eq!(header, MAP_HEADER);
    let columns: Vec<&str> = header.split(',').collect();
    for c in [
        "scene",
        "type",
        "steps",
        "energy_error_percent",
        "reaction_error_percent",
        "verdict",
        "newton_ratio",
        "wall_time_ratio",
    ] {
        assert!(columns.contains(&c), "{c}");
    }
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12);
    assert!(rows.iter().all(|r| r.len() == columns.len()));
    let verdict = columns.iter().position(|c| *c == "verdict").unwrap();
    assert!(rows.iter().all(|r| r[verdict] == "safe"));
    let md = safety_map::markdown(&map, "test");
    assert!(md.contains("| pressed-blocks (1–2) |") && md.contains("| patch-test (1–2) |"));
    assert!(md.contains("- Type 6: safe on every scene"));
}

#[test]
fn a_failing_type_is_recorded_not_fatal() {
    // The sliding benchmark at 10 steps without re-pairing and with the
    // expansions at the step start (the paper's scheme), with at most 20
    // Newton iterations per step and one cut-back: the complete formulation
    // converges (one cut-back in the first slide step), Types 3-6 too (at
    // most 9 iterations per step), while Type 1, whose frozen expansion
    // drops the terms that turn the force with the sliding, does not
    // converge and fails.
    let text = std::fs::read_to_string(scene_file("sliding"))
        .unwrap()
        .replace(
            "repair = true",
            "repair = false\nexpand_at = \"start\"\nmax_iterations = 20\nmax_cutbacks = 1",
        );
    let scene = Scene::from_toml_str(&text, "sliding (capped Newton)").unwrap();
    let scenes = [MapScene {
        scene,
        label: "sliding-capped".into(),
        steps: vec![10],
    }];
    let map = safety_map::run_map(&scenes, &MapOptions::default(), &study::Silent).unwrap();
    assert_eq!(map.rows.len(), 6);
    let study = &map.studies[0].1;
    assert!(study.run(Method::Complete, 10).unwrap().failure.is_none());
    let failed: Vec<_> = study.runs.iter().filter(|r| r.failure.is_some()).collect();
    assert!(!failed.is_empty(), "a type was expected to fail");
    for r in &failed {
        let Method::Approx(ty) = r.method else {
            unreachable!()
        };
        let row = map.rows.iter().find(|row| row.ty == ty).unwrap();
        assert_eq!(row.safety, Safety::Fails);
        assert!(row.failure.as_deref().unwrap().starts_with("10 steps: "));
        assert!(row.energy_error_percent.is_none());
    }
    // the CSV records it
    let csv = safety_map::csv(&map);
    assert_eq!(
        csv.lines()
            .skip(1)
            .filter(|line| line.contains(",fails,") && line.contains("no convergence"))
            .count(),
        failed.len(),
        "{csv}"
    );
}

#[test]
fn a_scene_without_contact_is_a_clear_error() {
    let mut scene = Scene::from_file(scene_file("pressed-blocks")).unwrap();
    scene.contacts.clear();
    let scenes = [MapScene {
        scene,
        label: "no-contact".into(),
        steps: vec![1],
    }];
    let err = safety_map::run_map(&scenes, &MapOptions::default(), &study::Silent).unwrap_err();
    assert!(
        matches!(err, StudyError::NoContact(ref s) if s == "no-contact"),
        "{err}"
    );
}

#[test]
fn the_command_writes_the_map_and_is_listed_in_help() {
    let help = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("--help")
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&help.stdout).contains("safety-map"));

    let dir = temp_dir("safety-map");
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("safety-map")
        .arg(format!("{}:1,2", scene_file("pressed-blocks").display()))
        .args(["--repeats", "1", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("safety-map.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 6);
    let runs = std::fs::read_to_string(dir.join("safety-map-runs.csv")).unwrap();
    assert_eq!(runs.lines().count(), 1 + 2 * 7);
    let md = std::fs::read_to_string(dir.join("safety-map.md")).unwrap();
    assert!(md.contains("| pressed-blocks (1–2) |"));
    // written atomically: no temporary file is left
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().all(|n| !n.starts_with('.')), "{names:?}");

    // bad step counts and a scene without contact: clear errors
    let bad = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(["safety-map", "x.toml:0", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("step counts"));
    std::fs::remove_dir_all(&dir).ok();
}

/// On the sliding benchmark with re-pairing, steps are repeated: the Newton
/// ratio counts the iterations spent, the discarded attempts included.
#[test]
fn the_newton_ratio_counts_repeated_steps() {
    let scenes = [map_scene("sliding", &[10])];
    let map = safety_map::run_map(&scenes, &MapOptions::default(), &study::Silent).unwrap();
    let study = &map.studies[0].1;
    let complete = study.run(Method::Complete, 10).unwrap();
    let t6 = study.run(Method::Approx(ApproxType::Type6), 10).unwrap();
    assert!(t6.repeated_iterations > 0, "{t6:?}");
    assert_eq!(complete.repeated_iterations, 0);
    let row = map.rows.iter().find(|r| r.ty == ApproxType::Type6).unwrap();
    let spent = (t6.newton_iterations + t6.repeated_iterations) as f64;
    assert_eq!(
        row.newton_ratio,
        Some(spent / complete.newton_iterations as f64)
    );
    assert!(
        row.newton_ratio.unwrap() > t6.newton_iterations as f64 / complete.newton_iterations as f64
    );
}
