//! The solver's contact faces are two-node segments: the 3-node
//! formulation `quadratic-slave-normal` (compiled in for the workspace's
//! tests through the root's dev-dependency) is refused with a clear error
//! in a scene, as a solve option and on the command line — never run with
//! its kernels silently failing at every point (which would look like no
//! contact).

use std::path::Path;
use std::process::Command;

use contact_kernels::Formulation;

fn scene_text() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/pressed-blocks.toml");
    std::fs::read_to_string(path).expect("the scene")
}

#[test]
fn a_scene_naming_the_three_node_formulation_is_refused() {
    assert_eq!(Formulation::QuadraticSlaveNormal.coords(), Some(12));
    let text = scene_text().replace(
        "formulation = \"slave-normal\"",
        "formulation = \"quadratic-slave-normal\"",
    );
    let e = solver::Scene::from_toml_str(&text, "pressed-blocks.toml")
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("quadratic-slave-normal") && e.contains("two-node segments"),
        "{e}"
    );
}

#[test]
fn the_solve_option_is_refused() {
    let scene = solver::Scene::from_toml_str(&scene_text(), "pressed-blocks.toml").unwrap();
    let options = solver::SolveOptions {
        formulation: Some(Formulation::QuadraticSlaveNormal),
        ..solver::SolveOptions::default()
    };
    let e = solver::solve::<2>(&scene, &options)
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("invalid solve options") && e.contains("3-node segments"),
        "{e}"
    );
}

#[test]
fn the_command_line_option_is_refused() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/pressed-blocks.toml");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("quadratic_refused");
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("run")
        .arg(&scene)
        .arg("--out")
        .arg(&dir)
        .args(["--formulation", "quadratic-slave-normal"])
        .output()
        .expect("run gapsim");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("3-node segments"), "{err}");
}

/// The 3D face formulations are kernels only: a scene or solve option
/// naming one is refused, saying it is for faces (not "4-node segments").
#[test]
fn the_face_formulations_are_refused_as_faces() {
    for (f, kind) in [
        (
            Formulation::Tri3SlaveNormal,
            "3-node slave face, 3-node master face",
        ),
        (
            Formulation::Quad4Tri3ClosestPoint,
            "4-node slave face, 3-node master face",
        ),
    ] {
        let text = scene_text().replace(
            "formulation = \"slave-normal\"",
            &format!("formulation = \"{}\"", f.name()),
        );
        let e = solver::Scene::from_toml_str(&text, "pressed-blocks.toml")
            .expect_err("refused")
            .to_string();
        assert!(
            e.contains("3D faces") && e.contains(kind) && e.contains("two-node segments"),
            "{e}"
        );
        let scene = solver::Scene::from_toml_str(&scene_text(), "pressed-blocks.toml").unwrap();
        let options = solver::SolveOptions {
            formulation: Some(f),
            ..solver::SolveOptions::default()
        };
        let e = solver::solve::<2>(&scene, &options)
            .expect_err("refused")
            .to_string();
        assert!(e.contains("3D faces") && e.contains(kind), "{e}");
    }
}
