//! `gapsim run --linear petsc`: refused with how to build it in a build
//! without the `petsc` feature; with it, a 3D contact run through PETSc
//! (options from the command line reaching PETSc) and the same runs across
//! two MPI ranks against one; any other solver refused across ranks.

use std::process::{Command, Output};

fn gapsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("gapsim runs")
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[cfg(not(feature = "petsc"))]
#[test]
fn petsc_is_refused_saying_how_to_build_it() {
    let o = gapsim(&["run", "scenes/block3d.toml", "--linear", "petsc"]);
    assert!(!o.status.success());
    assert!(text(&o).contains("--features petsc"), "{}", text(&o));
}

#[cfg(feature = "petsc")]
#[test]
fn a_3d_contact_run_through_petsc() {
    let o = gapsim(&["run", "scenes/pressed-block3d.toml", "--linear", "petsc"]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("krylov          fgmres/fieldsplit"), "{t}");
    // the same energy as the LDL^T to the digits printed
    let ldlt = gapsim(&["run", "scenes/pressed-block3d.toml", "--linear", "ldlt"]);
    let energy = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("strain energy"))
            .map(str::to_owned)
    };
    assert_eq!(energy(&t), energy(&text(&ldlt)));
    // options from the command line reach PETSc: MUMPS's LU, one iteration
    let o = gapsim(&[
        "run",
        "scenes/pressed-block3d.toml",
        "--linear",
        "petsc",
        "--petsc-options",
        "-pc_type lu -pc_factor_mat_solver_type mumps",
    ]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("fgmres/lu") && t.contains("at most 1)"), "{t}");
}

/// `mpiexec -n 2` with the PETSc options of the CI's Open MPI as root.
#[cfg(feature = "petsc")]
fn mpiexec(args: &[&str]) -> Output {
    Command::new("mpiexec")
        .args(["-n", "2", env!("CARGO_BIN_EXE_gapsim")])
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("mpiexec runs (openmpi-bin)")
}

/// Every number of two CSV files of the same rows and columns agrees to
/// `1e-8` of its column's largest magnitude (a column all below `1e-6` of
/// the file's largest number, a zero to round-off, to `1e-12` of that
/// number: the paper scene's zero reaction differs by 2e-13 between two
/// partitions, as much as its non-zero reaction's last digits); the words
/// are equal.
#[cfg(feature = "petsc")]
fn assert_same_csv(a: &str, b: &str, what: &str) {
    let table = |t: &str| -> Vec<Vec<String>> {
        t.lines()
            .map(|l| l.split(',').map(str::to_owned).collect())
            .collect()
    };
    let (ta, tb) = (table(a), table(b));
    assert_eq!(ta.len(), tb.len(), "{what}: rows");
    assert!(ta.len() > 1, "{what}: no data rows");
    let columns = ta[0].len();
    let scale: Vec<f64> = (0..columns)
        .map(|c| {
            ta.iter()
                .filter_map(|r| r.get(c)?.parse::<f64>().ok())
                .fold(0.0_f64, |m, v| m.max(v.abs()))
        })
        .collect();
    let largest = scale.iter().fold(0.0_f64, |m, &v| m.max(v));
    let scale: Vec<f64> = scale
        .iter()
        .map(|&c| {
            if c < 1e-6 * largest {
                1e-4 * largest
            } else {
                c
            }
        })
        .collect();
    for (ra, rb) in ta.iter().zip(&tb) {
        assert_eq!(ra.len(), rb.len(), "{what}: {ra:?} against {rb:?}");
        for (c, (x, y)) in ra.iter().zip(rb).enumerate() {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => assert!(
                    (x - y).abs() <= 1e-8 * scale[c].max(f64::MIN_POSITIVE),
                    "{what}, column {}: {x} against {y}",
                    ta[0][c]
                ),
                _ => assert_eq!(x, y, "{what}"),
            }
        }
    }
}

/// `mpiexec -n 2 gapsim run SCENE --linear petsc --out DIR` gives the
/// one-rank run's energy to the digits printed and its `contact.csv` and
/// `reactions.csv` to 1e-8, on a 3D scene (hexahedra, non-matching faces)
/// and the 2D paper scene; only rank 0 reports (one step line) and writes.
#[cfg(feature = "petsc")]
#[test]
fn two_ranks_give_the_one_rank_result() {
    let dir = std::env::temp_dir().join(format!("gapsim-two-ranks-{}", std::process::id()));
    for (name, scene) in [
        ("pressed-block3d", Some("scenes/pressed-block3d.toml")),
        ("paper", None),
    ] {
        let (one, two) = (dir.join(format!("{name}-1")), dir.join(format!("{name}-2")));
        let run = |out: &std::path::Path| -> Vec<String> {
            let mut args: Vec<String> = vec!["run".into()];
            args.extend(scene.map(str::to_owned));
            args.extend(["--linear", "petsc", "--out"].map(str::to_owned));
            args.push(out.display().to_string());
            args
        };
        let a1 = run(&one);
        let o1 = gapsim(&a1.iter().map(String::as_str).collect::<Vec<_>>());
        let t1 = text(&o1);
        assert!(o1.status.success(), "{t1}");
        let a2 = run(&two);
        let o2 = mpiexec(&a2.iter().map(String::as_str).collect::<Vec<_>>());
        let t2 = text(&o2);
        assert!(o2.status.success(), "{t2}");
        assert!(t2.contains("on 2 MPI ranks"), "{t2}");
        assert_eq!(t2.matches("strain energy").count(), 1, "{t2}");
        assert_eq!(
            t1.lines().filter(|l| l.starts_with("step ")).count(),
            t2.lines().filter(|l| l.starts_with("step ")).count(),
            "{t2}"
        );
        let energy = |t: &str| {
            t.lines()
                .find(|l| l.starts_with("strain energy"))
                .map(str::to_owned)
        };
        assert_eq!(energy(&t1), energy(&t2), "{name}");
        for file in ["contact.csv", "reactions.csv"] {
            let read = |d: &std::path::Path| std::fs::read_to_string(d.join(file)).unwrap();
            assert_same_csv(&read(&one), &read(&two), &format!("{name} {file}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Across two ranks each checks its own elements for inversion and the
/// ranks take the worst: the 2D Hertz scene's first attempt inverts an
/// element and is cut back, and two ranks name the element one rank names,
/// then converge to its energy after as many cut-backs.
#[cfg(feature = "petsc")]
#[test]
fn two_ranks_cut_back_at_the_element_one_rank_finds_inverted() {
    let args = ["run", "scenes/hertz.toml", "--linear", "petsc"];
    let (o1, o2) = (gapsim(&args), mpiexec(&args));
    let (t1, t2) = (text(&o1), text(&o2));
    assert!(o1.status.success(), "{t1}");
    assert!(o2.status.success(), "{t2}");
    let inverted = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("step 1/1: cut back"))
            .and_then(|l| l.split(" is inverted").next())
            .map(str::to_owned)
    };
    assert!(
        inverted(&t1).is_some_and(|l| l.contains("element ")),
        "{t1}"
    );
    assert_eq!(inverted(&t1), inverted(&t2), "{t2}");
    for key in ["strain energy", "cut-backs"] {
        let line = |t: &str| t.lines().find(|l| l.starts_with(key)).map(str::to_owned);
        assert_eq!(line(&t1), line(&t2), "{key}: {t2}");
    }
}

/// Only the petsc solver runs across ranks: another under `mpiexec -n 2`
/// is refused on every rank before any step.
#[cfg(feature = "petsc")]
#[test]
fn other_solvers_are_refused_across_ranks() {
    let o = mpiexec(&["run", "scenes/block3d.toml", "--linear", "ldlt"]);
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(
        t.contains("launched on 2 MPI ranks") && t.contains("only the petsc linear solver"),
        "{t}"
    );
    assert!(!t.contains("step 1/"), "{t}");
}

/// The launch is read from the launcher's environment, so a build without
/// MPI refuses it too.
#[test]
fn a_launch_on_several_ranks_is_seen_without_mpi() {
    for var in ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"] {
        let o = Command::new(env!("CARGO_BIN_EXE_gapsim"))
            .args(["run", "scenes/block3d.toml", "--linear", "lu"])
            .env(var, "3")
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("gapsim runs");
        let t = text(&o);
        assert!(!o.status.success(), "{var}: {t}");
        assert!(t.contains("launched on 3 MPI ranks"), "{var}: {t}");
    }
}
