//! The few PETSc objects the `petsc` linear solver uses, each an owning
//! wrapper whose every call returns a [`Result`].
//!
//! # How it binds PETSc
//!
//! Every PETSc call is made in a small C shim (`solver/c/petsc_shim.c`), one function per
//! wrapper method, compiled with `cc` against the PETSc found by pkg-config
//! (`solver/build.rs`). The C compiler checks each call against the installed
//! headers, the shim's static assertions check the sizes Rust assumes
//! (`PetscScalar` a real `f64`, `PetscInt` 32-bit), and PETSc's macros
//! (`PETSC_COMM_SELF`, type names, `KSPConvergedReasons`) stay in C. Rust
//! declares only the shim's plain-C functions ([`ffi`]): no bindgen, so no
//! libclang at build time.
//!
//! # Errors
//!
//! [`serial`] initialises PETSc once per process with an error handler that
//! keeps the failing call's message instead of printing a traceback; each
//! wrapper turns a nonzero error code into a [`PetscError`] holding it.
//!
//! # One thread at a time
//!
//! PETSc is not thread-safe. Every object is created, used and dropped while
//! the caller holds the process-wide guard of [`serial`] (the constructors
//! take it by reference; an owner that drops objects takes it in its own
//! `Drop`). MPI is initialised with `MPI_THREAD_SERIALIZED` for the same
//! reason: calls come from one thread at a time, not always the same one.

use std::ffi::{CStr, CString, c_char, c_int};
use std::sync::{Mutex, MutexGuard, OnceLock};

use super::ffi;
use ffi::PetscInt;

/// A PETSc call that failed: which call, PETSc's error code and message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("PETSc {call} failed (error {code}): {message}")]
pub struct PetscError {
    /// The wrapper method (the shim function without its prefix).
    pub call: &'static str,
    /// PETSc's error code.
    pub code: i32,
    /// PETSc's message for the failing call.
    pub message: String,
}

fn check(call: &'static str, code: ffi::PetscErrorCode) -> Result<(), PetscError> {
    if code == 0 {
        return Ok(());
    }
    // SAFETY: the shim returns a pointer to its static, NUL-terminated buffer
    let message = unsafe { CStr::from_ptr(ffi::gapsim_petsc_last_error()) }
        .to_string_lossy()
        .into_owned();
    Err(PetscError {
        call,
        code,
        message,
    })
}

fn index(call: &'static str, n: usize) -> Result<PetscInt, PetscError> {
    PetscInt::try_from(n).map_err(|_| PetscError {
        call,
        code: -1,
        message: format!("{n} exceeds PETSc's 32-bit index range"),
    })
}

/// Which ranks an object spans: this rank alone (`PETSC_COMM_SELF`) or
/// every rank of the launch (`PETSC_COMM_WORLD`, each holding its own
/// contiguous part of the rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comm {
    /// This rank alone.
    One,
    /// Every rank.
    World,
}

impl Comm {
    fn flag(self) -> c_int {
        match self {
            Comm::One => 0,
            Comm::World => 1,
        }
    }
}

static LOCK: Mutex<()> = Mutex::new(());
static INIT: OnceLock<Result<(), PetscError>> = OnceLock::new();

/// The process-wide guard every PETSc call is made under (module docs).
pub struct Serial {
    _guard: MutexGuard<'static, ()>,
}

/// Takes the process-wide PETSc guard, initialising PETSc (and MPI, unless
/// already initialised) on the first call; PETSc and MPI are finalised when
/// the process exits. A failed initialisation is reported by every call.
pub fn serial() -> Result<Serial, PetscError> {
    let guard = LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    // SAFETY: called under the lock; the shim initialises at most once
    INIT.get_or_init(|| check("initialize", unsafe { ffi::gapsim_petsc_initialize() }))
        .clone()?;
    Ok(Serial { _guard: guard })
}

impl Serial {
    /// PETSc's version `(major, minor, subminor)`, from its headers.
    pub fn version(&self) -> (i32, i32, i32) {
        let (mut a, mut b, mut c) = (0, 0, 0);
        // SAFETY: writes three ints
        unsafe { ffi::gapsim_petsc_version(&mut a, &mut b, &mut c) };
        (a, b, c)
    }

    /// The number of MPI ranks of `PETSC_COMM_WORLD`.
    pub fn world_size(&self) -> Result<usize, PetscError> {
        let mut n: c_int = 0;
        // SAFETY: writes one int
        check("comm_size", unsafe { ffi::gapsim_petsc_comm_size(&mut n) })?;
        Ok(n.max(0) as usize)
    }

    /// This process's rank in `PETSC_COMM_WORLD`.
    pub fn world_rank(&self) -> Result<usize, PetscError> {
        let mut r: c_int = 0;
        // SAFETY: writes one int
        check("comm_rank", unsafe { ffi::gapsim_petsc_comm_rank(&mut r) })?;
        Ok(r.max(0) as usize)
    }

    /// Every rank's `vals` summed entry by entry, on every rank (collective:
    /// every rank calls it with as many values).
    pub fn sum(&self, vals: &mut [f64]) -> Result<(), PetscError> {
        self.allreduce(vals, 0)
    }

    /// Every rank's `vals`' largest entry by entry, on every rank
    /// (collective).
    pub fn max(&self, vals: &mut [f64]) -> Result<(), PetscError> {
        self.allreduce(vals, 1)
    }

    fn allreduce(&self, vals: &mut [f64], op: c_int) -> Result<(), PetscError> {
        let n = index("allreduce", vals.len())?;
        // SAFETY: n values, reduced in place
        check("allreduce", unsafe {
            ffi::gapsim_petsc_allreduce(vals.as_mut_ptr(), n, op)
        })
    }

    /// The part (one per rank) of every vertex of a graph of `n_total`
    /// vertices, of which this rank passes the rows `first..first +
    /// row_ptr.len() - 1` (the ranks' rows in rank order, together every
    /// vertex once; compressed rows `row_ptr`, global `cols`, no self-loop;
    /// `weights`, one positive weight per row the rank passes, the parts
    /// balanced by their sums): PETSc's `MatPartitioning` (PT-Scotch, else
    /// ParMETIS; the option `-mat_partitioning_type` picks another).
    /// Collective.
    pub fn partition(
        &self,
        n_total: usize,
        row_ptr: &[PetscInt],
        cols: &[PetscInt],
        weights: &[PetscInt],
    ) -> Result<Vec<usize>, PetscError> {
        let call = "partition";
        let n_local = row_ptr.len().saturating_sub(1);
        let sound = !row_ptr.is_empty()
            && row_ptr[0] == 0
            && row_ptr.windows(2).all(|w| w[0] <= w[1])
            && row_ptr[n_local] as usize == cols.len()
            && cols.iter().all(|&c| c >= 0 && (c as usize) < n_total)
            && weights.len() == n_local
            && weights.iter().all(|&w| w > 0);
        if !sound {
            return Err(PetscError {
                call,
                code: -1,
                message: "the graph is not compressed rows of vertices in range with a positive weight each"
                    .into(),
            });
        }
        let mut part = vec![0 as PetscInt; n_total];
        // SAFETY: checked arrays; the shim copies them and writes n_total parts
        check(call, unsafe {
            ffi::gapsim_petsc_partition(
                index(call, n_local)?,
                index(call, n_total)?,
                row_ptr.as_ptr(),
                cols.as_ptr(),
                weights.as_ptr(),
                part.as_mut_ptr(),
            )
        })?;
        Ok(part.into_iter().map(|p| p.max(0) as usize).collect())
    }

    /// Empties PETSc's options database and fills it from `text` (PETSc's
    /// option syntax, `-ksp_type cg -pc_type gamg`); the solvers created or
    /// set up afterwards read them.
    pub fn replace_options(&self, text: &str) -> Result<(), PetscError> {
        let c = CString::new(text).map_err(|_| PetscError {
            call: "options_replace",
            code: -1,
            message: "the options contain a NUL character".into(),
        })?;
        // SAFETY: a NUL-terminated string
        check("options_replace", unsafe {
            ffi::gapsim_petsc_options_replace(c.as_ptr())
        })
    }
}

/// An AIJ matrix (`Mat`) on one rank or over every rank, preallocated by
/// row counts ([`Matrix::new`]) and filled row by row each time
/// ([`Matrix::fill`]).
pub struct Matrix {
    raw: ffi::Mat,
}

impl Matrix {
    /// A matrix on `comm`, `n_local` of its `n` rows on this rank (the
    /// ranks' rows contiguous, in rank order; all of them on
    /// [`Comm::One`]), with room for at most `d_nnz[i]` entries of its row
    /// `i` in this rank's columns and `o_nnz[i]` in the others' (upper
    /// bounds; what is not filled is released at the first assembly).
    /// Collective on `comm`.
    pub fn new(
        _: &Serial,
        comm: Comm,
        n_local: usize,
        n: usize,
        (d_nnz, o_nnz): (&[PetscInt], &[PetscInt]),
    ) -> Result<Matrix, PetscError> {
        let call = "mat_create_rows";
        if d_nnz.len() != n_local || o_nnz.len() != n_local || n_local > n {
            return Err(PetscError {
                call,
                code: -1,
                message: format!(
                    "{} and {} row counts for {n_local} rows of {n}",
                    d_nnz.len(),
                    o_nnz.len()
                ),
            });
        }
        let mut raw = std::ptr::null_mut();
        // SAFETY: two arrays of n_local counts; PETSc copies them
        let code = unsafe {
            ffi::gapsim_petsc_mat_create_rows(
                comm.flag(),
                index(call, n_local)?,
                index(call, n)?,
                d_nnz.as_ptr(),
                o_nnz.as_ptr(),
                &mut raw,
            )
        };
        let m = Matrix { raw };
        check(call, code)?;
        Ok(m)
    }

    /// The values: every entry zero, then the rows `add` adds
    /// ([`RowAdder::add`]: any rank's rows, in the preallocated pattern),
    /// every rank's contributions to an entry summed on its owner, the
    /// matrix marked changed so the solver sets its preconditioner up
    /// again. Collective.
    pub fn fill(
        &mut self,
        _: &Serial,
        add: impl FnOnce(&mut RowAdder<'_>) -> Result<(), PetscError>,
    ) -> Result<(), PetscError> {
        // SAFETY: a matrix of ours
        check("mat_zero", unsafe { ffi::gapsim_petsc_mat_zero(self.raw) })?;
        add(&mut RowAdder { matrix: self })?;
        // SAFETY: as above
        check("mat_assemble", unsafe {
            ffi::gapsim_petsc_mat_assemble(self.raw)
        })
    }
}

/// Adds rows to a [`Matrix`] being filled ([`Matrix::fill`]).
pub struct RowAdder<'a> {
    matrix: &'a mut Matrix,
}

impl RowAdder<'_> {
    /// Adds `vals` to row `row`'s columns `cols` (as many; a column given
    /// twice adds twice).
    pub fn add(&mut self, row: usize, cols: &[PetscInt], vals: &[f64]) -> Result<(), PetscError> {
        let call = "mat_add_row";
        if cols.len() != vals.len() {
            return Err(PetscError {
                call,
                code: -1,
                message: format!("{} columns for {} values", cols.len(), vals.len()),
            });
        }
        // SAFETY: two arrays of cols.len() entries, read during the call
        check(call, unsafe {
            ffi::gapsim_petsc_mat_add_row(
                self.matrix.raw,
                index(call, row)?,
                index(call, cols.len())?,
                cols.as_ptr(),
                vals.as_ptr(),
            )
        })
    }
}

impl Drop for Matrix {
    fn drop(&mut self) {
        // SAFETY: the owner holds the guard (module docs); a null is ignored
        unsafe { ffi::gapsim_petsc_mat_destroy(&mut self.raw) };
    }
}

/// A vector (`Vec`) on one rank or spread over every rank.
pub struct Vector {
    raw: ffi::Vec,
    /// The entries on this rank.
    len: usize,
}

impl Vector {
    /// A vector with `len` entries on this rank (on `Comm::World` the
    /// ranks' parts in rank order make the vector) and block size `bs`.
    /// Collective on `Comm::World`.
    pub fn new(_: &Serial, comm: Comm, len: usize, bs: usize) -> Result<Vector, PetscError> {
        let call = "vec_create";
        let mut raw = std::ptr::null_mut();
        // SAFETY: writes the handle
        let code = unsafe {
            ffi::gapsim_petsc_vec_create(comm.flag(), index(call, len)?, index(call, bs)?, &mut raw)
        };
        let v = Vector { raw, len };
        check(call, code)?;
        Ok(v)
    }

    /// Every rank's entries, `n` in all, on every rank. Collective.
    pub fn gather_all(&self, _: &Serial, n: usize) -> Result<Vec<f64>, PetscError> {
        let mut out = vec![0.0; n];
        let len = index("vec_gather_all", n)?;
        // SAFETY: the shim checks the length before copying
        check("vec_gather_all", unsafe {
            ffi::gapsim_petsc_vec_gather_all(self.raw, out.as_mut_ptr(), len)
        })?;
        Ok(out)
    }

    /// Copies `vals` (as many as the vector has entries on this rank) in.
    pub fn set(&mut self, _: &Serial, vals: &[f64]) -> Result<(), PetscError> {
        let n = index("vec_set", vals.len())?;
        // SAFETY: the shim checks the length before copying
        check("vec_set", unsafe {
            ffi::gapsim_petsc_vec_set(self.raw, vals.as_ptr(), n)
        })
    }

    /// The entries on this rank.
    pub fn get(&self, _: &Serial) -> Result<Vec<f64>, PetscError> {
        let mut out = vec![0.0; self.len];
        let n = index("vec_get", self.len)?;
        // SAFETY: the shim checks the length before copying
        check("vec_get", unsafe {
            ffi::gapsim_petsc_vec_get(self.raw, out.as_mut_ptr(), n)
        })?;
        Ok(out)
    }
}

impl Drop for Vector {
    fn drop(&mut self) {
        // SAFETY: the owner holds the guard
        unsafe { ffi::gapsim_petsc_vec_destroy(&mut self.raw) };
    }
}

/// A contiguous range of equations (`IS`), with a block size.
pub struct IndexSet {
    raw: ffi::Is,
}

impl IndexSet {
    /// The equations `first..first + len`, in blocks of `bs` (on
    /// `Comm::World`, this rank's part of the set).
    pub fn range(
        _: &Serial,
        comm: Comm,
        first: usize,
        len: usize,
        bs: usize,
    ) -> Result<IndexSet, PetscError> {
        let call = "is_create_range";
        let mut raw = std::ptr::null_mut();
        // SAFETY: writes the handle
        let code = unsafe {
            ffi::gapsim_petsc_is_create_range(
                comm.flag(),
                index(call, first)?,
                index(call, len)?,
                index(call, bs)?,
                &mut raw,
            )
        };
        let is = IndexSet { raw };
        check(call, code)?;
        Ok(is)
    }

    /// Gives `space` to this set's split as its near-null space (PCFIELDSPLIT
    /// hands it to the split's matrix, where algebraic multigrid finds it).
    pub fn attach_near_null_space(
        &mut self,
        _: &Serial,
        space: &NearNullSpace,
    ) -> Result<(), PetscError> {
        // SAFETY: both handles valid; PETSc takes its own reference
        check("is_compose_near_null_space", unsafe {
            ffi::gapsim_petsc_is_compose_near_null_space(self.raw, space.raw)
        })
    }
}

impl Drop for IndexSet {
    fn drop(&mut self) {
        // SAFETY: the owner holds the guard
        unsafe { ffi::gapsim_petsc_is_destroy(&mut self.raw) };
    }
}

/// The rigid-body modes of a set of nodes (`MatNullSpace`): 3 in 2D, 6 in
/// 3D, from their coordinates.
pub struct NearNullSpace {
    raw: ffi::NullSpace,
}

impl NearNullSpace {
    /// The rigid-body modes of nodes with coordinates `coords` (node-major,
    /// `dim` per node; on `Comm::World` this rank's nodes).
    pub fn rigid_body(
        s: &Serial,
        comm: Comm,
        coords: &[f64],
        dim: usize,
    ) -> Result<NearNullSpace, PetscError> {
        let mut v = Vector::new(s, comm, coords.len(), dim)?;
        v.set(s, coords)?;
        let mut raw = std::ptr::null_mut();
        // SAFETY: a vector of block size `dim`
        let code = unsafe { ffi::gapsim_petsc_nullspace_rigid_body(v.raw, &mut raw) };
        let sp = NearNullSpace { raw };
        check("nullspace_rigid_body", code)?;
        Ok(sp)
    }
}

impl Drop for NearNullSpace {
    fn drop(&mut self) {
        // SAFETY: the owner holds the guard
        unsafe { ffi::gapsim_petsc_nullspace_destroy(&mut self.raw) };
    }
}

/// How a Krylov solve ended.
#[derive(Debug, Clone, PartialEq)]
pub struct KrylovOutcome {
    /// Converged (PETSc's reason > 0).
    pub converged: bool,
    /// PETSc's reason, by name (`CONVERGED_RTOL`, `DIVERGED_ITS`, ...).
    pub reason: String,
    /// Iterations taken.
    pub iterations: usize,
    /// The last residual norm PETSc computed (preconditioned or not, as
    /// the method's norm type says).
    pub residual: f64,
    /// Ended by the stall test ([`Ksp::watch_stall`]; its reason is then
    /// `DIVERGED_ITS`).
    pub stalled: bool,
}

/// A linear solver (`KSP`): a Krylov method and its preconditioner.
pub struct Ksp {
    raw: ffi::Ksp,
}

impl Ksp {
    /// A solver of `a` (also its preconditioning matrix, on the ranks
    /// `comm`), configured from the options database.
    pub fn new(_: &Serial, comm: Comm, a: &Matrix) -> Result<Ksp, PetscError> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: writes the handle
        let code = unsafe { ffi::gapsim_petsc_ksp_create(comm.flag(), &mut raw) };
        let k = Ksp { raw };
        check("ksp_create", code)?;
        // SAFETY: valid handles
        check("ksp_set_operators", unsafe {
            ffi::gapsim_petsc_ksp_set_operators(k.raw, a.raw)
        })?;
        // SAFETY: valid handle
        check("ksp_set_from_options", unsafe {
            ffi::gapsim_petsc_ksp_set_from_options(k.raw)
        })?;
        Ok(k)
    }

    /// Whether the preconditioner is PCFIELDSPLIT.
    pub fn is_fieldsplit(&self, _: &Serial) -> Result<bool, PetscError> {
        let mut yes: c_int = 0;
        // SAFETY: writes one int
        check("ksp_pc_is_fieldsplit", unsafe {
            ffi::gapsim_petsc_ksp_pc_is_fieldsplit(self.raw, &mut yes)
        })?;
        Ok(yes != 0)
    }

    /// Adds the split `name` of the equations in `is` (PCFIELDSPLIT).
    pub fn add_split(&mut self, _: &Serial, name: &str, is: &IndexSet) -> Result<(), PetscError> {
        let c = CString::new(name).expect("split names have no NUL");
        // SAFETY: valid handles, NUL-terminated name
        check("ksp_fieldsplit_set_is", unsafe {
            ffi::gapsim_petsc_ksp_fieldsplit_set_is(self.raw, c.as_ptr(), is.raw)
        })
    }

    /// The Krylov method and preconditioner, `"fgmres/fieldsplit"`.
    pub fn describe(&self, _: &Serial) -> Result<String, PetscError> {
        let mut buf = vec![0 as c_char; 128];
        // SAFETY: the shim writes at most `len` bytes, NUL-terminated
        check("ksp_describe", unsafe {
            ffi::gapsim_petsc_ksp_describe(self.raw, buf.as_mut_ptr(), buf.len())
        })?;
        // SAFETY: NUL-terminated within the buffer
        Ok(unsafe { CStr::from_ptr(buf.as_ptr()) }
            .to_string_lossy()
            .into_owned())
    }

    /// Ends a solve whose residual norm has not fallen below `factor` times
    /// its value `window` iterations earlier, as not converged
    /// ([`KrylovOutcome::stalled`]), beside PETSc's own tests; for a solve
    /// that has a fallback, so that a stalled one does not run to
    /// `-ksp_max_it` first.
    pub fn watch_stall(
        &mut self,
        _: &Serial,
        window: usize,
        factor: f64,
    ) -> Result<(), PetscError> {
        let call = "ksp_watch_stall";
        // SAFETY: valid handle; the shim owns the test's context
        check(call, unsafe {
            ffi::gapsim_petsc_ksp_watch_stall(self.raw, index(call, window)?, factor)
        })
    }

    /// The relative residual the next solves stop at.
    pub fn set_rtol(&mut self, _: &Serial, rtol: f64) -> Result<(), PetscError> {
        // SAFETY: valid handle
        check("ksp_set_rtol", unsafe {
            ffi::gapsim_petsc_ksp_set_rtol(self.raw, rtol)
        })
    }

    /// Sets up the preconditioner for the matrix's current values (the
    /// setup of an algebraic multigrid, or a factorisation).
    pub fn set_up(&mut self, _: &Serial) -> Result<(), PetscError> {
        // SAFETY: valid handle
        check("ksp_setup", unsafe {
            ffi::gapsim_petsc_ksp_setup(self.raw)
        })
    }

    /// Solves `A x = b` from a zero guess.
    pub fn solve(
        &mut self,
        _: &Serial,
        b: &Vector,
        x: &mut Vector,
    ) -> Result<KrylovOutcome, PetscError> {
        let (mut reason, mut text, mut its, mut res) = (0, std::ptr::null(), 0, 0.0);
        // SAFETY: valid handles; the reason text is a static string of PETSc's
        check("ksp_solve", unsafe {
            ffi::gapsim_petsc_ksp_solve(
                self.raw,
                b.raw,
                x.raw,
                &mut reason,
                &mut text,
                &mut its,
                &mut res,
            )
        })?;
        let mut stalled: c_int = 0;
        // SAFETY: writes one int
        check("ksp_stalled", unsafe {
            ffi::gapsim_petsc_ksp_stalled(self.raw, &mut stalled)
        })?;
        let reason_text = if text.is_null() {
            format!("reason {reason}")
        } else {
            // SAFETY: PETSc's NUL-terminated reason name
            unsafe { CStr::from_ptr(text) }
                .to_string_lossy()
                .into_owned()
        };
        Ok(KrylovOutcome {
            converged: reason > 0,
            reason: reason_text,
            iterations: its.max(0) as usize,
            residual: res,
            stalled: stalled != 0,
        })
    }
}

impl Drop for Ksp {
    fn drop(&mut self) {
        // SAFETY: the owner holds the guard
        unsafe { ffi::gapsim_petsc_ksp_destroy(&mut self.raw) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D Laplacian (tridiagonal, SPD) solved by CG with Jacobi from the
    /// options database, and the exact solution of a known right-hand side.
    #[test]
    fn cg_solves_a_laplacian() {
        let s = serial().unwrap();
        assert!(s.version() >= (3, 18, 0));
        let n: usize = 50;
        let (mut rows, mut cols, mut vals) = (vec![], vec![], vec![]);
        for i in 0..n {
            for (j, v) in [(i.wrapping_sub(1), -1.0), (i, 2.0), (i + 1, -1.0)] {
                if j < n {
                    rows.push(i);
                    cols.push(j);
                    vals.push(v);
                }
            }
        }
        // x_i = i + 1: b = A x
        let x_true: Vec<f64> = (0..n).map(|i| i as f64 + 1.0).collect();
        let mut b = vec![0.0; n];
        for k in 0..rows.len() {
            b[rows[k]] += vals[k] * x_true[cols[k]];
        }
        s.replace_options("-ksp_type cg -pc_type jacobi").unwrap();
        let counts: Vec<i32> = (0..n)
            .map(|i| 3 - i32::from(i == 0 || i == n - 1))
            .collect();
        let zeros = vec![0; n];
        let mut a = Matrix::new(&s, Comm::One, n, n, (&counts, &zeros)).unwrap();
        // one triplet at a time: a row of one column, added
        a.fill(&s, |add| {
            for k in 0..rows.len() {
                add.add(rows[k], &[cols[k] as i32], &[vals[k]])?;
            }
            Ok(())
        })
        .unwrap();
        let mut ksp = Ksp::new(&s, Comm::One, &a).unwrap();
        assert_eq!(ksp.describe(&s).unwrap(), "cg/jacobi");
        ksp.set_rtol(&s, 1e-12).unwrap();
        ksp.set_up(&s).unwrap();
        let mut bv = Vector::new(&s, Comm::One, n, 1).unwrap();
        bv.set(&s, &b).unwrap();
        let mut xv = Vector::new(&s, Comm::One, n, 1).unwrap();
        let out = ksp.solve(&s, &bv, &mut xv).unwrap();
        assert!(out.converged, "{out:?}");
        assert!(out.iterations <= n);
        let x = xv.get(&s).unwrap();
        for i in 0..n {
            assert!((x[i] - x_true[i]).abs() < 1e-8, "{i}: {}", x[i]);
        }
        assert!(xv.set(&s, &[1.0]).is_err(), "a wrong length is an error");
        let short = Matrix::new(&s, Comm::One, 2, 2, (&[1], &[0, 0]));
        assert!(short.is_err(), "a row count missing is refused");
        let mismatched = a.fill(&s, |add| add.add(0, &[0, 1], &[1.0]));
        assert!(mismatched.is_err(), "two columns for one value are refused");
    }

    /// The stall test ends a solve whose residual stopped falling (a
    /// Richardson iteration damped to almost nothing) after its window, as
    /// not converged and marked stalled; without it the same solve runs to
    /// `-ksp_max_it`; a converging solve is not touched by it.
    #[test]
    fn a_stalled_solve_ends_after_its_window() {
        let s = serial().unwrap();
        let n = 20;
        let diag = vec![1; n];
        let zeros = vec![0; n];
        let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let solve = |options: &str, watch: bool| {
            s.replace_options(options).unwrap();
            let mut a = Matrix::new(&s, Comm::One, n, n, (&diag, &zeros)).unwrap();
            a.fill(&s, |add| {
                (0..n).try_for_each(|i| add.add(i, &[i as i32], &[2.0]))
            })
            .unwrap();
            let mut ksp = Ksp::new(&s, Comm::One, &a).unwrap();
            if watch {
                ksp.watch_stall(&s, 100, 0.9).unwrap();
            }
            ksp.set_rtol(&s, 1e-10).unwrap();
            ksp.set_up(&s).unwrap();
            let mut bv = Vector::new(&s, Comm::One, n, 1).unwrap();
            bv.set(&s, &b).unwrap();
            let mut xv = Vector::new(&s, Comm::One, n, 1).unwrap();
            ksp.solve(&s, &bv, &mut xv).unwrap()
        };
        let crawl = "-ksp_type richardson -ksp_richardson_scale 1e-6 -pc_type none -ksp_max_it 150";
        let stalled = solve(crawl, true);
        assert!(!stalled.converged && stalled.stalled, "{stalled:?}");
        assert_eq!(stalled.iterations, 100);
        let ran = solve(crawl, false);
        assert!(!ran.converged && !ran.stalled, "{ran:?}");
        assert_eq!(ran.iterations, 150);
        let fine = solve("-ksp_type cg -pc_type jacobi", true);
        assert!(fine.converged && !fine.stalled, "{fine:?}");
        s.replace_options("").unwrap();
    }

    /// A PETSc error comes back as a `PetscError` with PETSc's message, no
    /// traceback and no abort: an unknown Krylov type.
    #[test]
    fn errors_carry_petscs_message() {
        let s = serial().unwrap();
        s.replace_options("-ksp_type no_such_method").unwrap();
        let mut a = Matrix::new(&s, Comm::One, 1, 1, (&[1], &[0])).unwrap();
        a.fill(&s, |add| add.add(0, &[0], &[1.0])).unwrap();
        let e = Ksp::new(&s, Comm::One, &a)
            .err()
            .expect("an unknown KSP type is refused");
        assert_eq!(e.call, "ksp_set_from_options");
        assert!(e.message.contains("no_such_method"), "{e}");
        s.replace_options("").unwrap();
    }
}
