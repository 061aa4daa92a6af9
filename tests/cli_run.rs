//! `gapsim run --out DIR`, tested by running the binary on
//! `scenes/pressed-blocks.toml` (a block pressed onto a base with a total
//! load of 1 over a width of 1; see the scene file): `contact.csv` has its
//! header and one row per slave node, the pressure integrates to the load
//! and the closed nodes' gaps vanish, `final.vtu` carries the contact point
//! data, and a second run replaces every file without leaving a temporary
//! one behind.

use std::path::{Path, PathBuf};
use std::process::Command;

const HEADER: &str = "pair,node,x,y,gap,pressure,xi_m,master_segment,master_node_1,master_node_2,tributary_length,node_numbering,master_numbering,clamped,shear_x,shear_y,state,slip";

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/pressed-blocks.toml")
}

/// Runs `gapsim run SCENE --out DIR ARGS` and returns its stdout.
fn run(dir: &Path, args: &[&str]) -> String {
    run_scene(Some(&scene()), dir, args)
}

/// Runs `gapsim run [SCENE] --out DIR ARGS` (no scene: the embedded paper
/// scene) and returns its stdout.
fn run_scene(scene: Option<&Path>, dir: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("run")
        .args(scene)
        .arg("--out")
        .arg(dir)
        .args(args)
        .output()
        .expect("run gapsim");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn contact_csv_balances_the_load() {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-run-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = run(&dir, &[]);
    assert!(stdout.contains("contact.csv"), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some(HEADER));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // the block's bottom side: 4 elements, 5 nodes, one pair
    assert_eq!(rows.len(), 5, "{csv}");
    let mut integral = 0.0;
    for row in &rows {
        assert_eq!(row.len(), 18, "{row:?}");
        assert_eq!(row[0], "interface");
        assert_eq!(row[13], "0", "{row:?}");
        // frictionless and pressed: no shear, sliding freely, no slip
        assert_eq!(&row[14..], ["0", "0", "slip", ""], "{row:?}");
        // block bodies: internal node numbers
        assert_eq!((row[11], row[12]), ("internal", "internal"), "{row:?}");
        let num = |k: usize| row[k].parse::<f64>().unwrap();
        // closed: gap 0 up to Newton's tolerance (see the solver's
        // contact::segment::nodal tests for the bound), pressure 1 = F / width
        assert!(num(4).abs() < 1e-8, "{row:?}");
        assert!((num(5) - 1.0).abs() < 1e-8, "{row:?}");
        assert!(num(6).abs() <= 1.0 + 1e-9, "{row:?}");
        assert!(num(3) < 0.5, "{row:?}");
        integral += num(5) * num(10);
    }
    // sum of p T over the face = the total load (1), to Newton's
    // tolerance: sqrt(5) 1e-10 < 1e-9
    assert!((integral - 1.0).abs() < 1e-9, "{integral}");
    let vtu = std::fs::read_to_string(dir.join("final.vtu")).unwrap();
    for name in [
        "contact_pressure",
        "contact_gap",
        "contact_slave",
        "contact_paired",
    ] {
        assert!(vtu.contains(&format!("Name=\"{name}\"")), "{name}");
    }
    assert_eq!(entries(&dir), ["contact.csv", "final.vtu", "reactions.csv"]);

    // a second run replaces the files (atomically: no temporary is left);
    // the step files are the initial state and the two steps
    std::fs::write(dir.join("contact.csv"), "stale").unwrap();
    run(&dir, &["--every-step"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("contact.csv")).unwrap(),
        csv
    );
    assert_eq!(
        entries(&dir),
        [
            "contact.csv",
            "final.vtu",
            "reactions.csv",
            "step-0000.vtu",
            "step-0001.vtu",
            "step-0002.vtu",
            "steps.pvd"
        ]
    );
    // the time series: the initial state and the two steps at their load
    // factors, in order
    let pvd = std::fs::read_to_string(dir.join("steps.pvd")).unwrap();
    let sets: Vec<&str> = pvd.lines().filter(|l| l.contains("<DataSet")).collect();
    assert_eq!(
        sets,
        [
            r#"    <DataSet timestep="0" group="" part="0" file="step-0000.vtu"/>"#,
            r#"    <DataSet timestep="0.5" group="" part="0" file="step-0001.vtu"/>"#,
            r#"    <DataSet timestep="1" group="" part="0" file="step-0002.vtu"/>"#,
        ],
        "{pvd}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The paper scene's slave node at `x = 0`, fixed on the fixed master
/// node, is marked: `gapsim run` names it in a `clamped` line and its
/// `contact.csv` row ends in `1` (every other row in `0`); a scene without
/// such a node prints no such line.
#[test]
fn the_paper_scene_marks_its_clamped_slave_node() {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-clamped-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = run_scene(None, &dir, &["--steps", "4"]);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("clamped "))
        .unwrap_or_else(|| panic!("no clamped line: {stdout}"));
    assert!(
        line.contains("1 slave node(s) held by supports on both sides"),
        "{line}"
    );
    let csv = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 8, "{csv}");
    let clamped: Vec<&Vec<&str>> = rows.iter().filter(|r| r[13] == "1").collect();
    assert_eq!(clamped.len(), 1, "{csv}");
    assert_eq!(clamped[0][2], "0", "{csv}");
    let pressure: f64 = clamped[0][5].parse().unwrap();
    assert!(pressure < -100.0, "{csv}");
    assert!(rows.iter().all(|r| r[13] == "0" || r[13] == "1"), "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
    // pressed-blocks: its slave nodes are not held
    let dir = std::env::temp_dir().join(format!("gapsim-cli-unclamped-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = run(&dir, &[]);
    assert!(!stdout.contains("clamped "), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_scene_without_contact_writes_no_contact_csv() {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-run-nc-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(scene()).unwrap();
    let start = text.find("[[contact]]").unwrap();
    let end = text.find("[loading]").unwrap();
    // no contact: the block on rollers at its own bottom
    let fix = "[[fix]]\nbody = \"base\"\ny = 0.0\ndofs = \"y\"\n";
    assert!(text.contains(fix));
    let text = format!("{}{}", &text[..start], &text[end..]).replace(
        fix,
        &format!("{fix}\n[[fix]]\nbody = \"block\"\ny = 0.5\ndofs = \"y\"\n"),
    );
    let scene = dir.join("block.toml");
    std::fs::write(&scene, text).unwrap();
    let out_dir = dir.join("out");
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("run")
        .arg(&scene)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .expect("run gapsim");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(entries(&out_dir), ["final.vtu", "reactions.csv"]);
    // the method line says there is no contact (no empty formulation list)
    let stdout = String::from_utf8_lossy(&out.stdout);
    let method = stdout
        .lines()
        .find(|l| l.starts_with("method "))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(method.ends_with("load steps, no contact)"), "{method}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A 3D scene with a `[[contact]]` pair: a block pressed onto a base
/// (non-matching faces) is solved, and `--out` writes `contact.csv` with
/// the 3D header and a row per slave node (the block's 4 x 3 bottom
/// nodes), beside `final.vtu` and `reactions.csv`.
#[test]
fn a_3d_scene_with_contact_writes_the_3d_contact_csv() {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-run-3d-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("press3d.toml");
    std::fs::write(
        &scene,
        r#"name = "press3d"
[material]
young = 100.0
poisson = 0.3
kinematics = "small"

[[body]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [2.0, 1.0, 0.5]
nx = 2
ny = 1
nz = 1

[[body]]
name = "block"
origin = [0.0, 0.0, 0.5]
size = [2.0, 1.0, 0.5]
nx = 3
ny = 2
nz = 1

[[fix]]
name = "bottom"
body = "base"
z = 0.0

[[prescribe]]
name = "top"
body = "block"
z = 1.0
ux = 0.0
uy = 0.0
uz = -0.01

[[contact]]
slave = { body = "block", side = "bottom" }
master = { body = "base", side = "top" }
mode = "unilateral"

[loading]
load_factor_end = 1.0
steps = [2]
"#,
    )
    .unwrap();
    let out_dir = dir.join("out");
    let out = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("run")
        .arg(&scene)
        .arg("--out")
        .arg(&out_dir)
        .output()
        .expect("run gapsim");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("max penetration"))
        .unwrap_or_else(|| panic!("no penetration line: {stdout}"));
    let p: f64 = line.split_whitespace().nth(2).unwrap().parse().unwrap();
    // the mortar gap is zero on average, not node by node: small against
    // the press of 0.01
    assert!(p.abs() < 1e-4, "{line}");
    // every node with a projection counts, pressed or not
    assert!(
        line.contains("slave nodes with a projection")
            && line.contains(" of them with pressure, 0 without pressure inside the master)"),
        "{line}"
    );
    assert_eq!(
        entries(&out_dir),
        ["contact.csv", "final.vtu", "reactions.csv"]
    );
    let csv = std::fs::read_to_string(out_dir.join("contact.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(<solver::Dim<3> as solver::report::ContactTable<3>>::HEADER)
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12, "{csv}");
    for r in &rows {
        assert_eq!(r.len(), 23, "{r:?}");
        assert_eq!(r[17], "0", "{r:?}");
        let pressure: f64 = r[6].parse().unwrap();
        assert!(pressure > 0.0, "{r:?}");
        assert_eq!(r[15], "internal", "{r:?}");
    }
    // Types 1-6 in 3D: the step-end summary, with adaptive stepping
    let approx = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_gapsim"))
            .arg("run")
            .arg(&scene)
            .args(["--type", "3"])
            .args(args)
            .output()
            .expect("run gapsim")
    };
    let out = approx(&["--taylor-tolerance", "1e-3"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("step repeats    0"), "{stdout}");
    assert!(stdout.contains("Taylor remainder max"), "{stdout}");
    for bad in ["0", "-1e-3", "inf", "x"] {
        let out = approx(&[&format!("--taylor-tolerance={bad}")]);
        assert!(!out.status.success(), "--taylor-tolerance {bad} accepted");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("--taylor-tolerance"),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
