//! With the `petsc` feature: finds PETSc (and its MPI) with pkg-config and
//! compiles the C shim `c/petsc_shim.c` against them. Without it: nothing.
//!
//! PETSc: `PETSc.pc` (the name PETSc installs; `petsc.pc` also tried), at
//! least 3.18. A PETSc of one's own is found through `PKG_CONFIG_PATH`
//! (`$PETSC_DIR/$PETSC_ARCH/lib/pkgconfig`). MPI: `mpi.pc` or `ompi-c.pc`
//! (Debian's PETSc.pc does not carry MPI's include directory); the shim
//! includes `mpi.h` through PETSc's headers. The shim's `#error`s and
//! `_Static_assert`s check at build time that the scalar is real `f64` and
//! `PetscInt` 32-bit, as `src/linear/petsc/ffi.rs` declares them.

fn main() {
    #[cfg(feature = "petsc")]
    petsc();
}

#[cfg(feature = "petsc")]
fn petsc() {
    println!("cargo:rerun-if-changed=c/petsc_shim.c");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    let petsc = ["PETSc", "petsc"]
        .iter()
        .find_map(|name| {
            pkg_config::Config::new()
                .atleast_version("3.18")
                .cargo_metadata(false)
                .probe(name)
                .ok()
        })
        .unwrap_or_else(|| {
            panic!(
                "the `petsc` feature needs PETSc >= 3.18 found by pkg-config (PETSc.pc): \
                 on Debian `apt-get install libpetsc-real-dev openmpi-bin pkgconf`; a PETSc of \
                 your own: PKG_CONFIG_PATH=$PETSC_DIR/$PETSC_ARCH/lib/pkgconfig (docs/petsc.md)"
            )
        });
    // MPI's headers and library, unless PETSc's flags already hold them (a
    // PETSc built with --download-mpich lists them in PETSc.pc)
    let mpi = ["mpi", "ompi-c", "mpich"].iter().find_map(|name| {
        pkg_config::Config::new()
            .cargo_metadata(false)
            .probe(name)
            .ok()
    });
    let mut build = cc::Build::new();
    build.file("c/petsc_shim.c").warnings(true);
    for path in petsc
        .include_paths
        .iter()
        .chain(mpi.iter().flat_map(|m| m.include_paths.iter()))
    {
        build.include(path);
    }
    build.compile("gapsim_petsc_shim");
    // after the shim (which needs them), in pkg-config's order
    for lib in std::iter::once(&petsc).chain(mpi.iter()) {
        for path in &lib.link_paths {
            println!("cargo:rustc-link-search=native={}", path.display());
        }
        for name in &lib.libs {
            println!("cargo:rustc-link-lib={name}");
        }
    }
}
