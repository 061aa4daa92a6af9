//! What `gapsim run` does around the solve, tested by running the binary:
//! `--out DIR` holds the whole old result set or the whole new one (an
//! interrupted run leaves the old set, a completed run replaces it and
//! leaves no file of the old set behind), `--out` is checked before the
//! solve, every load step prints a progress line on stderr, the summary
//! reports the penetration of the contact set, and a model too large for
//! the memory is refused before it is built.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

/// A fresh scratch path for test `name` (removed, not created).
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gapsim-cli-out-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn gapsim(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(args)
        .output()
        .expect("run gapsim")
}

/// `gapsim run SCENE --out DIR EXTRA...`, which must succeed.
fn run_ok(scene: &Path, dir: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "run".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        dir.as_os_str(),
    ];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    let out = gapsim(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Every entry of `dir` (hidden ones included) with its contents, sorted.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            let bytes = std::fs::read(e.path()).unwrap_or_else(|_| b"<directory>".to_vec());
            (name, bytes)
        })
        .collect();
    v.sort();
    v
}

fn names(dir: &Path) -> Vec<String> {
    snapshot(dir).into_iter().map(|(n, _)| n).collect()
}

/// Starts `gapsim run SCENE --steps STEPS --out DIR`, waits for its first
/// progress line on stderr (the first load step has converged, the solve
/// goes on), sends SIGINT and returns the finished process's output and
/// that line.
fn interrupt_after_first_step(scene: &Path, steps: &str, dir: &Path) -> (Output, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .arg("run")
        .arg(scene)
        .args(["--steps", steps, "--every-step", "--out"])
        .arg(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start gapsim");
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    stderr.read_line(&mut first).unwrap();
    assert!(first.starts_with("step 1/"), "{first}");
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(kill.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let mut out = child.wait_with_output().unwrap();
    out.stderr = rest.into_bytes();
    (out, first)
}

/// SIGINT during the solve: the run exits with an error saying so, and
/// `--out` holds the earlier run's files exactly (no new file, no
/// temporary, no staging directory); a directory that did not exist is
/// not left behind.
#[test]
fn an_interrupted_run_leaves_the_old_result_set() {
    let dir = scratch("interrupt");
    let scene = scene("pressed-blocks.toml");
    run_ok(&scene, &dir, &["--every-step"]);
    let before = snapshot(&dir);
    assert_eq!(
        names(&dir),
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
    // 20000 steps take far longer than the signal does to arrive
    let (out, first) = interrupt_after_first_step(&scene, "20000", &dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{first}{stderr}");
    assert!(
        stderr.contains("gapsim: error: interrupted at load factor")
            && stderr.contains(&format!(
                "nothing written, {} left as it was",
                dir.display()
            )),
        "{stderr}"
    );
    assert_eq!(snapshot(&dir), before);

    let fresh = dir.join("new/deeper");
    let (out, _) = interrupt_after_first_step(&scene, "20000", &fresh);
    assert!(!out.status.success());
    assert!(!dir.join("new").exists());
    assert_eq!(snapshot(&dir), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A completed run replaces the whole set: the step files of an earlier
/// run with more steps and a temporary an earlier version left go, a file
/// of the user's stays.
#[test]
fn a_completed_run_replaces_the_whole_set() {
    let dir = scratch("replace");
    let scene = scene("pressed-blocks.toml");
    run_ok(&scene, &dir, &["--every-step", "--steps", "4"]);
    assert_eq!(names(&dir).len(), 3 + 5 + 1); // + steps.pvd
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join(".step-0000.vtu.27215.0.tmp.vtu"), "partial").unwrap();
    std::fs::write(dir.join("contact.csv"), "stale").unwrap();
    let out = run_ok(&scene, &dir, &[]);
    assert_eq!(
        names(&dir),
        ["contact.csv", "final.vtu", "notes.txt", "reactions.csv"]
    );
    let csv = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    assert!(csv.starts_with("pair,node,"), "{csv}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains(&format!(
            "wrote           {}",
            dir.join("contact.csv").display()
        )),
        "{stdout}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A file as `--out`, or a path below a file, is refused before the solve
/// (nothing on stdout, no progress line), naming the file; for `study`
/// and `safety-map` too.
#[test]
fn out_is_checked_before_the_solve() {
    let dir = scratch("check");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("a-file");
    std::fs::write(&file, "").unwrap();
    let pressed = scene("pressed-blocks.toml");
    for out_dir in [file.clone(), file.join("sub")] {
        for command in ["run", "study", "safety-map"] {
            let out = gapsim(&[
                command.as_ref(),
                pressed.as_os_str(),
                "--out".as_ref(),
                out_dir.as_os_str(),
            ]);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{command}: {stderr}");
            assert!(out.stdout.is_empty(), "{command}");
            assert_eq!(
                stderr.trim_end(),
                format!(
                    "gapsim: error: --out {}: {} is a file, not a directory",
                    out_dir.display(),
                    file.display()
                ),
                "{command}"
            );
        }
    }
    assert_eq!(names(&dir), ["a-file"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every converged load step prints one line on stderr, none on stdout;
/// piped, stderr gets no live iteration line (no carriage return).
#[test]
fn each_load_step_prints_a_progress_line_on_stderr() {
    let out = gapsim(&[
        "run".as_ref(),
        scene("pressed-blocks.toml").as_os_str(),
        "--steps".as_ref(),
        "3".as_ref(),
    ]);
    assert!(out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 3, "{stderr}");
    assert!(!stderr.contains('\r'), "{stderr:?}");
    for (k, line) in lines.iter().enumerate() {
        let lf = ["0.3333333333333333", "0.6666666666666666", "1"][k];
        assert!(
            line.starts_with(&format!("step {}/3: load factor {lf}, ", k + 1))
                && line.contains(" iterations, 0 cut-backs, "),
            "{line}"
        );
    }
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(!stdout.contains("step 1/3"), "{stdout}");
}

/// On the Hertz cylinder most slave points are open (gaps up to about
/// 1.5): the summary reports the largest penetration of the points in
/// contact, not the largest |gap| of all points.
#[test]
fn the_summary_reports_the_penetration_of_the_contact_set() {
    let dir = scratch("penetration");
    let out = run_ok(&scene("hertz-coarse.toml"), &dir, &[]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(!stdout.contains("max |gap|"), "{stdout}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("max penetration "))
        .unwrap_or_else(|| panic!("{stdout}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let penetration: f64 = words[2].parse().unwrap();
    let active: usize = words[7].parse().unwrap();
    assert!(line.contains("integration points in contact"), "{line}");
    // the open nodes of contact.csv: far larger gaps than the penetration
    let csv = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    let gaps: Vec<f64> = csv
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').nth(4).and_then(|g| g.parse().ok()))
        .collect();
    let max_gap = gaps.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    let open = gaps.iter().filter(|&&g| g > 1e-3).count();
    assert!(max_gap > 0.1 && open > 10, "{max_gap} {open}");
    assert!((0.0..1e-2).contains(&penetration), "{line}");
    assert!(max_gap > 100.0 * penetration, "{max_gap} {line}");
    assert!(active > 0 && active < gaps.len(), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 100 blocks of 9 million elements each (every one under the block
/// limit): refused at once with the estimate and the available memory,
/// before any of them is built.
#[test]
fn a_model_too_large_for_the_memory_is_refused_before_it_is_built() {
    let meminfo = std::fs::read_to_string("/proc/meminfo").expect("this test needs Linux");
    assert!(meminfo.contains("MemAvailable:"), "{meminfo}");
    let dir = scratch("memory");
    std::fs::create_dir_all(&dir).unwrap();
    let mut text = String::from("[material]\nyoung = 100.0\npoisson = 0.3\n");
    for i in 0..100 {
        text.push_str(&format!(
            "[[body]]\nname = \"b{i}\"\norigin = [{}.0, 0.0]\nsize = [1.0, 1.0]\nnx = 3000\nny = 3000\n",
            2 * i
        ));
    }
    text.push_str(
        "[[fix]]\ny = 0.0\ndofs = \"xy\"\n[loading]\nload_factor_end = 1.0\nsteps = [1]\n",
    );
    let path = dir.join("huge.toml");
    std::fs::write(&path, text).unwrap();
    let out = gapsim(&["run".as_ref(), path.as_os_str()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    let equations = 100 * 2 * 3001 * 3001_u64;
    assert!(
        stderr.contains(&format!(
            "not enough memory: {equations} equations of 2D elements need at least "
        )) && stderr.contains("MiB are available (MemAvailable in /proc/meminfo)"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
