//! `gapsim run --linear petsc`: refused with how to build it in a build
//! without the `petsc` feature; with it, a 3D contact run through PETSc
//! (options from the command line reaching PETSc) and a launch across two
//! MPI ranks refused before any work.

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

/// Under `mpiexec -n 2` the solve is refused on every rank, naming the
/// ranks, before any step (distributed assembly is not built yet).
#[cfg(feature = "petsc")]
#[test]
fn two_ranks_are_refused_before_any_work() {
    let o = Command::new("mpiexec")
        .args([
            "-n",
            "2",
            env!("CARGO_BIN_EXE_gapsim"),
            "run",
            "scenes/block3d.toml",
        ])
        .args(["--linear", "petsc"])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("mpiexec runs (openmpi-bin)");
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(
        t.contains("one MPI rank") && t.contains("launched on 2"),
        "{t}"
    );
    assert!(!t.contains("step 1/"), "{t}");
}
