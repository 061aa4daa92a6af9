/*
 * The PETSc linear solver's C shim: every PETSc call gapsim makes, one small function
 * each, so that the C compiler checks each call against the installed
 * headers and Rust binds only these plain-C functions (solver/src/linear/petsc/ffi.rs).
 *
 * Every function returns a PetscErrorCode (0 on success). The error handler
 * pushed by gapsim_petsc_initialize keeps the first message of the failing
 * call in a buffer (gapsim_petsc_last_error) instead of printing a
 * traceback, so that the Rust side turns it into a Result.
 */
#include <petscksp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if !PETSC_VERSION_GE(3, 18, 0)
#error "gapsim's petsc feature needs PETSc 3.18 or newer"
#endif
#if !defined(PETSC_USE_REAL_DOUBLE) || defined(PETSC_USE_COMPLEX)
#error "gapsim's petsc feature needs a PETSc whose scalar is real double (PetscScalar = double): use a real build such as Debian's libpetsc-real-dev"
#endif
_Static_assert(sizeof(PetscInt) == 4, "gapsim binds PetscInt as 32 bits: this PETSc was configured --with-64-bit-indices");
_Static_assert(sizeof(PetscScalar) == 8 && sizeof(PetscReal) == 8, "PetscScalar and PetscReal must be double");
_Static_assert(sizeof(PetscErrorCode) == sizeof(int), "PetscErrorCode must be int");
_Static_assert(sizeof(PetscCount) == 8, "PetscCount must be 64 bits");

static char last_error[4096];
static int owns_mpi = 0;

static PetscErrorCode keep_message(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n,
                                   PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm;
  (void)ctx;
  if (p == PETSC_ERROR_INITIAL) {
    const char *text = NULL;
    PetscErrorMessage(n, &text, NULL);
    snprintf(last_error, sizeof last_error, "%s%s%s (in %s, %s:%d)", text ? text : "PETSc error",
             (mess && mess[0]) ? ": " : "", mess ? mess : "", func ? func : "?", file ? file : "?", line);
  }
  return n;
}

const char *gapsim_petsc_last_error(void) { return last_error; }

static void finalize_at_exit(void)
{
  PetscBool done = PETSC_FALSE;
  PetscFinalized(&done);
  if (!done) PetscFinalize();
  if (owns_mpi) {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  }
}

/* MPI with MPI_THREAD_SERIALIZED (the Rust side calls PETSc from one thread
 * at a time, not always the same one), PETSc without its signal handler
 * (Rust keeps its own), the error handler above, finalisation at exit. */
int gapsim_petsc_initialize(void)
{
  PetscBool init = PETSC_FALSE;
  int mpi_init = 0, provided = 0;
  PetscErrorCode ierr;
  PetscInitialized(&init);
  if (init) return 0;
  MPI_Initialized(&mpi_init);
  if (!mpi_init) {
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
      snprintf(last_error, sizeof last_error, "MPI_Init_thread failed");
      return PETSC_ERR_LIB;
    }
    owns_mpi = 1;
  }
  ierr = PetscOptionsSetValue(NULL, "-no_signal_handler", NULL);
  if (ierr) return ierr;
  ierr = PetscInitializeNoArguments();
  if (ierr) {
    snprintf(last_error, sizeof last_error, "PetscInitialize failed with code %d", (int)ierr);
    return ierr;
  }
  ierr = PetscPushErrorHandler(keep_message, NULL);
  if (ierr) return ierr;
  atexit(finalize_at_exit);
  return 0;
}

int gapsim_petsc_version(int *major, int *minor, int *subminor)
{
  *major = PETSC_VERSION_MAJOR;
  *minor = PETSC_VERSION_MINOR;
  *subminor = PETSC_VERSION_SUBMINOR;
  return 0;
}

int gapsim_petsc_comm_size(int *size) { return MPI_Comm_size(PETSC_COMM_WORLD, size) == MPI_SUCCESS ? 0 : PETSC_ERR_MPI; }

/* The options database: emptied, then given `text` (PETSc's option syntax). */
int gapsim_petsc_options_replace(const char *text)
{
  PetscErrorCode ierr = PetscOptionsClear(NULL);
  if (ierr) return ierr;
  return PetscOptionsInsertString(NULL, text);
}

/* ---- Mat: sequential AIJ of a compressed-row pattern (row_ptr, cols:
 * sorted, unique columns per row), its values written in place ---- */
int gapsim_petsc_mat_create_csr(PetscInt n, const PetscInt *row_ptr, const PetscInt *cols, Mat *out)
{
  Mat a;
  PetscErrorCode ierr = MatCreate(PETSC_COMM_SELF, &a);
  if (ierr) return ierr;
  *out = a;
  ierr = MatSetSizes(a, n, n, n, n);
  if (ierr) return ierr;
  ierr = MatSetType(a, MATSEQAIJ);
  if (ierr) return ierr;
  return MatSeqAIJSetPreallocationCSR(a, row_ptr, cols, NULL);
}

/* The values in the pattern's order, to be written and handed back with
 * gapsim_petsc_mat_restore_values (which marks the matrix changed). */
int gapsim_petsc_mat_get_values(Mat a, PetscScalar **vals) { return MatSeqAIJGetArray(a, vals); }

int gapsim_petsc_mat_restore_values(Mat a, PetscScalar **vals) { return MatSeqAIJRestoreArray(a, vals); }

int gapsim_petsc_mat_destroy(Mat *a) { return MatDestroy(a); }

/* ---- Vec ---- */
int gapsim_petsc_vec_create(PetscInt n, PetscInt bs, Vec *out)
{
  PetscErrorCode ierr = VecCreateSeq(PETSC_COMM_SELF, n, out);
  if (ierr) return ierr;
  return bs > 1 ? VecSetBlockSize(*out, bs) : 0;
}

int gapsim_petsc_vec_set(Vec v, const PetscScalar *vals, PetscInt n)
{
  PetscScalar *a;
  PetscInt len;
  PetscErrorCode ierr = VecGetLocalSize(v, &len);
  if (ierr) return ierr;
  if (len != n) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "vector of %d entries given %d values", (int)len, (int)n);
  ierr = VecGetArray(v, &a);
  if (ierr) return ierr;
  memcpy(a, vals, (size_t)n * sizeof(PetscScalar));
  return VecRestoreArray(v, &a);
}

int gapsim_petsc_vec_get(Vec v, PetscScalar *vals, PetscInt n)
{
  const PetscScalar *a;
  PetscInt len;
  PetscErrorCode ierr = VecGetLocalSize(v, &len);
  if (ierr) return ierr;
  if (len != n) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "vector of %d entries read into %d values", (int)len, (int)n);
  ierr = VecGetArrayRead(v, &a);
  if (ierr) return ierr;
  memcpy(vals, a, (size_t)n * sizeof(PetscScalar));
  return VecRestoreArrayRead(v, &a);
}

int gapsim_petsc_vec_destroy(Vec *v) { return VecDestroy(v); }

/* ---- IS: a contiguous range of equations, with a block size ---- */
int gapsim_petsc_is_create_range(PetscInt first, PetscInt n, PetscInt bs, IS *out)
{
  PetscErrorCode ierr = ISCreateStride(PETSC_COMM_SELF, n, first, 1, out);
  if (ierr) return ierr;
  return bs > 1 ? ISSetBlockSize(*out, bs) : 0;
}

int gapsim_petsc_is_destroy(IS *is) { return ISDestroy(is); }

/* ---- MatNullSpace: the rigid-body modes of nodal coordinates (a Vec of
 * block size = dimension), attached to an IS for PCFIELDSPLIT, which gives
 * it to the split's matrix ("nearnullspace"). ---- */
int gapsim_petsc_nullspace_rigid_body(Vec coords, MatNullSpace *out) { return MatNullSpaceCreateRigidBody(coords, out); }

int gapsim_petsc_is_compose_near_null_space(IS is, MatNullSpace sp)
{
  return PetscObjectCompose((PetscObject)is, "nearnullspace", (PetscObject)sp);
}

int gapsim_petsc_nullspace_destroy(MatNullSpace *sp) { return MatNullSpaceDestroy(sp); }

/* ---- KSP ---- */
int gapsim_petsc_ksp_create(KSP *out) { return KSPCreate(PETSC_COMM_SELF, out); }

int gapsim_petsc_ksp_set_operators(KSP ksp, Mat a) { return KSPSetOperators(ksp, a, a); }

int gapsim_petsc_ksp_set_from_options(KSP ksp) { return KSPSetFromOptions(ksp); }

/* Whether the preconditioner is PCFIELDSPLIT (after set_from_options). */
int gapsim_petsc_ksp_pc_is_fieldsplit(KSP ksp, int *yes)
{
  PC pc;
  PetscBool match = PETSC_FALSE;
  PetscErrorCode ierr = KSPGetPC(ksp, &pc);
  if (ierr) return ierr;
  ierr = PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &match);
  *yes = match ? 1 : 0;
  return ierr;
}

int gapsim_petsc_ksp_fieldsplit_set_is(KSP ksp, const char *name, IS is)
{
  PC pc;
  PetscErrorCode ierr = KSPGetPC(ksp, &pc);
  if (ierr) return ierr;
  return PCFieldSplitSetIS(pc, name, is);
}

/* The KSP and PC types in use, "ksp/pc", into buf. */
int gapsim_petsc_ksp_describe(KSP ksp, char *buf, size_t len)
{
  PC pc;
  KSPType kt;
  PCType pt;
  PetscErrorCode ierr = KSPGetPC(ksp, &pc);
  if (ierr) return ierr;
  ierr = KSPGetType(ksp, &kt);
  if (ierr) return ierr;
  ierr = PCGetType(pc, &pt);
  if (ierr) return ierr;
  snprintf(buf, len, "%s/%s", kt ? kt : "?", pt ? pt : "?");
  return 0;
}

int gapsim_petsc_ksp_set_rtol(KSP ksp, PetscReal rtol) { return KSPSetTolerances(ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT); }

int gapsim_petsc_ksp_setup(KSP ksp) { return KSPSetUp(ksp); }

/* Solves; reason > 0 converged, < 0 diverged (reason_text its name). */
int gapsim_petsc_ksp_solve(KSP ksp, Vec b, Vec x, int *reason, const char **reason_text, PetscInt *iterations,
                           PetscReal *residual)
{
  KSPConvergedReason r;
  PetscErrorCode ierr = KSPSolve(ksp, b, x);
  if (ierr) return ierr;
  ierr = KSPGetConvergedReason(ksp, &r);
  if (ierr) return ierr;
  *reason = (int)r;
  *reason_text = KSPConvergedReasons[r];
  ierr = KSPGetIterationNumber(ksp, iterations);
  if (ierr) return ierr;
  return KSPGetResidualNorm(ksp, residual);
}

int gapsim_petsc_ksp_destroy(KSP *ksp) { return KSPDestroy(ksp); }
