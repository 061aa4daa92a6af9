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

int gapsim_petsc_comm_rank(int *rank) { return MPI_Comm_rank(PETSC_COMM_WORLD, rank) == MPI_SUCCESS ? 0 : PETSC_ERR_MPI; }

/* The communicator of an object: one rank (0) or every rank (1). */
static MPI_Comm comm_of(int world) { return world ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }

/* Every rank's `vals` summed (op 0) or their maximum taken (op 1), entry by
 * entry, in place on every rank. */
int gapsim_petsc_allreduce(double *vals, PetscInt n, int op)
{
  if (MPI_Allreduce(MPI_IN_PLACE, vals, (int)n, MPI_DOUBLE, op ? MPI_MAX : MPI_SUM, PETSC_COMM_WORLD) != MPI_SUCCESS) {
    snprintf(last_error, sizeof last_error, "MPI_Allreduce of %d values failed", (int)n);
    return PETSC_ERR_MPI;
  }
  return 0;
}

/* ---- MatPartitioning: the graph whose rows first..first+n_local this rank
 * holds (ia, ja: compressed rows, global columns, no self-loops; weights, one
 * per row, or NULL) cut into one part per rank, the parts' weights balanced
 * (PT-Scotch, else ParMETIS, unless -mat_partitioning_type says
 * otherwise); every row's part, all n_total of them, into part on every
 * rank. ---- */
int gapsim_petsc_partition(PetscInt n_local, PetscInt n_total, const PetscInt *ia, const PetscInt *ja, const PetscInt *weights, PetscInt *part)
{
  Mat adj;
  MatPartitioning mp;
  IS local, all;
  const PetscInt *ids;
  PetscInt *i, *j, nnz = ia[n_local], k;
  int size;
  PetscErrorCode ierr;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ierr = PetscMalloc1(n_local + 1, &i);
  if (ierr) return ierr;
  ierr = PetscMalloc1(nnz > 0 ? nnz : 1, &j);
  if (ierr) return ierr;
  for (k = 0; k <= n_local; k++) i[k] = ia[k];
  for (k = 0; k < nnz; k++) j[k] = ja[k];
  /* the adjacency matrix owns i and j from here */
  ierr = MatCreateMPIAdj(PETSC_COMM_WORLD, n_local, n_total, i, j, NULL, &adj);
  if (ierr) return ierr;
  ierr = MatPartitioningCreate(PETSC_COMM_WORLD, &mp);
  if (ierr) return ierr;
  ierr = MatPartitioningSetAdjacency(mp, adj);
  if (ierr) return ierr;
  ierr = MatPartitioningSetNParts(mp, size);
  if (ierr) return ierr;
  if (weights) {
    PetscInt *w;
    ierr = PetscMalloc1(n_local > 0 ? n_local : 1, &w);
    if (ierr) return ierr;
    for (k = 0; k < n_local; k++) w[k] = weights[k];
    /* the partitioning owns w from here */
    ierr = MatPartitioningSetVertexWeights(mp, w);
    if (ierr) return ierr;
  }
#if defined(PETSC_HAVE_PTSCOTCH)
  ierr = MatPartitioningSetType(mp, MATPARTITIONINGPTSCOTCH);
#elif defined(PETSC_HAVE_PARMETIS)
  ierr = MatPartitioningSetType(mp, MATPARTITIONINGPARMETIS);
#endif
  if (ierr) return ierr;
  ierr = MatPartitioningSetFromOptions(mp);
  if (ierr) return ierr;
  ierr = MatPartitioningApply(mp, &local);
  if (ierr) return ierr;
  ierr = ISAllGather(local, &all);
  if (ierr) return ierr;
  ierr = ISGetIndices(all, &ids);
  if (ierr) return ierr;
  for (k = 0; k < n_total; k++) part[k] = ids[k];
  ierr = ISRestoreIndices(all, &ids);
  if (ierr) return ierr;
  ierr = ISDestroy(&all);
  if (ierr) return ierr;
  ierr = ISDestroy(&local);
  if (ierr) return ierr;
  ierr = MatPartitioningDestroy(&mp);
  if (ierr) return ierr;
  return MatDestroy(&adj);
}

/* The options database: emptied, then given `text` (PETSc's option syntax). */
int gapsim_petsc_options_replace(const char *text)
{
  PetscErrorCode ierr = PetscOptionsClear(NULL);
  if (ierr) return ierr;
  return PetscOptionsInsertString(NULL, text);
}

int gapsim_petsc_mat_destroy(Mat *a) { return MatDestroy(a); }

/* ---- Mat: an AIJ matrix on this rank alone (world = 0) or over every rank
 * (world = 1), n_local of its n rows on this rank (the ranks' rows
 * contiguous in rank order), preallocated with at most d_nnz[i] entries of
 * this rank's row i in its own columns and o_nnz[i] in the others' (upper
 * bounds: space not filled is released at the first assembly). ---- */
int gapsim_petsc_mat_create_rows(int world, PetscInt n_local, PetscInt n, const PetscInt *d_nnz, const PetscInt *o_nnz, Mat *out)
{
  Mat a;
  PetscErrorCode ierr = MatCreate(world ? PETSC_COMM_WORLD : PETSC_COMM_SELF, &a);
  if (ierr) return ierr;
  *out = a;
  ierr = MatSetSizes(a, n_local, n_local, n, n);
  if (ierr) return ierr;
  ierr = MatSetType(a, MATAIJ);
  if (ierr) return ierr;
  return MatXAIJSetPreallocation(a, 1, d_nnz, o_nnz, NULL, NULL);
}

/* Every entry zero (the pattern kept), before the rows are added. */
int gapsim_petsc_mat_zero(Mat a) { return MatZeroEntries(a); }

/* Adds vals to row `row`'s columns `cols` (len of them, any rank's row). */
int gapsim_petsc_mat_add_row(Mat a, PetscInt row, PetscInt len, const PetscInt *cols, const PetscScalar *vals)
{
  return MatSetValues(a, 1, &row, len, cols, vals, ADD_VALUES);
}

/* Sends the added rows to their owners and sums them there. Collective. */
int gapsim_petsc_mat_assemble(Mat a)
{
  PetscErrorCode ierr = MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY);
  if (ierr) return ierr;
  return MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY);
}

/* ---- Vec ---- */
int gapsim_petsc_vec_create(int world, PetscInt n, PetscInt bs, Vec *out)
{
  PetscErrorCode ierr = world ? VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, out) : VecCreateSeq(PETSC_COMM_SELF, n, out);
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

/* Every rank's entries, in order, into vals (n: the global size) on every rank. */
int gapsim_petsc_vec_gather_all(Vec v, PetscScalar *vals, PetscInt n)
{
  VecScatter ctx;
  Vec all;
  const PetscScalar *a;
  PetscInt len;
  PetscErrorCode ierr = VecScatterCreateToAll(v, &ctx, &all);
  if (ierr) return ierr;
  ierr = VecScatterBegin(ctx, v, all, INSERT_VALUES, SCATTER_FORWARD);
  if (ierr) return ierr;
  ierr = VecScatterEnd(ctx, v, all, INSERT_VALUES, SCATTER_FORWARD);
  if (ierr) return ierr;
  ierr = VecGetLocalSize(all, &len);
  if (ierr) return ierr;
  if (len != n) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "gathered vector of %d entries read into %d values", (int)len, (int)n);
  ierr = VecGetArrayRead(all, &a);
  if (ierr) return ierr;
  memcpy(vals, a, (size_t)n * sizeof(PetscScalar));
  ierr = VecRestoreArrayRead(all, &a);
  if (ierr) return ierr;
  ierr = VecScatterDestroy(&ctx);
  if (ierr) return ierr;
  return VecDestroy(&all);
}

int gapsim_petsc_vec_destroy(Vec *v) { return VecDestroy(v); }

/* ---- IS: a contiguous range of equations, with a block size ---- */
int gapsim_petsc_is_create_range(int world, PetscInt first, PetscInt n, PetscInt bs, IS *out)
{
  PetscErrorCode ierr = ISCreateStride(comm_of(world), n, first, 1, out);
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
int gapsim_petsc_ksp_create(int world, KSP *out) { return KSPCreate(comm_of(world), out); }

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

/* ---- The stall test: PETSc's default convergence test, and a solve whose
 * residual norm has not fallen below `factor` times its value `window`
 * iterations earlier ends as DIVERGED_ITS, marked stalled. ---- */
typedef struct {
  void *dflt;
  PetscInt window;
  PetscReal factor;
  PetscReal *history; /* the last window + 1 norms, a ring */
  int stalled;
} Stall;

static PetscErrorCode stall_test(KSP ksp, PetscInt n, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
  Stall *st = (Stall *)ctx;
  PetscErrorCode ierr = KSPConvergedDefault(ksp, n, rnorm, reason, st->dflt);
  if (ierr) return ierr;
  if (n == 0) st->stalled = 0;
  st->history[n % (st->window + 1)] = rnorm;
  if (*reason == KSP_CONVERGED_ITERATING && n >= st->window &&
      !(rnorm < st->factor * st->history[(n - st->window) % (st->window + 1)])) {
    *reason = KSP_DIVERGED_ITS;
    st->stalled = 1;
  }
  return 0;
}

static PetscErrorCode stall_destroy(void *ctx)
{
  Stall *st = (Stall *)ctx;
  PetscErrorCode ierr = KSPConvergedDefaultDestroy(st->dflt);
  if (ierr) return ierr;
  ierr = PetscFree(st->history);
  if (ierr) return ierr;
  return PetscFree(st);
}

/* Installs the stall test (after set_from_options, which would replace it). */
int gapsim_petsc_ksp_watch_stall(KSP ksp, PetscInt window, PetscReal factor)
{
  Stall *st;
  PetscErrorCode ierr;
  if (window < 1) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "a stall window of %d iterations", (int)window);
  ierr = PetscNew(&st);
  if (ierr) return ierr;
  st->window = window;
  st->factor = factor;
  ierr = PetscCalloc1(window + 1, &st->history);
  if (ierr) return ierr;
  ierr = KSPConvergedDefaultCreate(&st->dflt);
  if (ierr) return ierr;
  return KSPSetConvergenceTest(ksp, stall_test, st, stall_destroy);
}

/* Whether the last solve ended on the stall test (0 without one). */
int gapsim_petsc_ksp_stalled(KSP ksp, int *stalled)
{
  void *ctx = NULL;
  PetscErrorCode (*test)(KSP, PetscInt, PetscReal, KSPConvergedReason *, void *) = NULL;
  PetscErrorCode ierr = KSPGetConvergenceTest(ksp, &test, &ctx, NULL);
  if (ierr) return ierr;
  *stalled = (test == stall_test && ctx) ? ((Stall *)ctx)->stalled : 0;
  return 0;
}
