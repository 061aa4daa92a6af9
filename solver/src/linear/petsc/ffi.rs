//! The C shim's functions (`solver/c/petsc_shim.c`), declared by hand: plain C types
//! only (`PetscInt` is `i32`, `PetscScalar` and `PetscReal` `f64`,
//! `PetscErrorCode` `i32`: the shim's static assertions
//! check each at build time), PETSc's objects as opaque pointers.

use std::ffi::{c_char, c_int, c_void};

pub type PetscInt = i32;
pub type PetscErrorCode = c_int;
pub type Mat = *mut c_void;
pub type Vec = *mut c_void;
pub type Is = *mut c_void;
pub type NullSpace = *mut c_void;
pub type Ksp = *mut c_void;

unsafe extern "C" {
    pub fn gapsim_petsc_initialize() -> PetscErrorCode;
    pub fn gapsim_petsc_last_error() -> *const c_char;
    pub fn gapsim_petsc_version(
        major: *mut c_int,
        minor: *mut c_int,
        sub: *mut c_int,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_comm_size(size: *mut c_int) -> PetscErrorCode;
    pub fn gapsim_petsc_comm_rank(rank: *mut c_int) -> PetscErrorCode;
    pub fn gapsim_petsc_allreduce(vals: *mut f64, n: PetscInt, op: c_int) -> PetscErrorCode;
    pub fn gapsim_petsc_partition(
        n_local: PetscInt,
        n_total: PetscInt,
        ia: *const PetscInt,
        ja: *const PetscInt,
        weights: *const PetscInt,
        part: *mut PetscInt,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_options_replace(text: *const c_char) -> PetscErrorCode;

    pub fn gapsim_petsc_mat_destroy(a: *mut Mat) -> PetscErrorCode;
    pub fn gapsim_petsc_mat_create_rows(
        world: c_int,
        n_local: PetscInt,
        n: PetscInt,
        d_nnz: *const PetscInt,
        o_nnz: *const PetscInt,
        out: *mut Mat,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_mat_zero(a: Mat) -> PetscErrorCode;
    pub fn gapsim_petsc_mat_add_row(
        a: Mat,
        row: PetscInt,
        len: PetscInt,
        cols: *const PetscInt,
        vals: *const f64,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_mat_assemble(a: Mat) -> PetscErrorCode;

    pub fn gapsim_petsc_vec_create(
        world: c_int,
        n: PetscInt,
        bs: PetscInt,
        out: *mut Vec,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_vec_gather_all(v: Vec, vals: *mut f64, n: PetscInt) -> PetscErrorCode;
    pub fn gapsim_petsc_vec_set(v: Vec, vals: *const f64, n: PetscInt) -> PetscErrorCode;
    pub fn gapsim_petsc_vec_get(v: Vec, vals: *mut f64, n: PetscInt) -> PetscErrorCode;
    pub fn gapsim_petsc_vec_destroy(v: *mut Vec) -> PetscErrorCode;

    pub fn gapsim_petsc_is_create_range(
        world: c_int,
        first: PetscInt,
        n: PetscInt,
        bs: PetscInt,
        out: *mut Is,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_is_destroy(is: *mut Is) -> PetscErrorCode;

    pub fn gapsim_petsc_nullspace_rigid_body(coords: Vec, out: *mut NullSpace) -> PetscErrorCode;
    pub fn gapsim_petsc_is_compose_near_null_space(is: Is, sp: NullSpace) -> PetscErrorCode;
    pub fn gapsim_petsc_nullspace_destroy(sp: *mut NullSpace) -> PetscErrorCode;

    pub fn gapsim_petsc_ksp_create(world: c_int, out: *mut Ksp) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_set_operators(ksp: Ksp, a: Mat) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_set_from_options(ksp: Ksp) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_pc_is_fieldsplit(ksp: Ksp, yes: *mut c_int) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_fieldsplit_set_is(
        ksp: Ksp,
        name: *const c_char,
        is: Is,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_describe(ksp: Ksp, buf: *mut c_char, len: usize) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_set_rtol(ksp: Ksp, rtol: f64) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_setup(ksp: Ksp) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_solve(
        ksp: Ksp,
        b: Vec,
        x: Vec,
        reason: *mut c_int,
        reason_text: *mut *const c_char,
        iterations: *mut PetscInt,
        residual: *mut f64,
    ) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_watch_stall(ksp: Ksp, window: PetscInt, factor: f64) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_stalled(ksp: Ksp, stalled: *mut c_int) -> PetscErrorCode;
    pub fn gapsim_petsc_ksp_destroy(ksp: *mut Ksp) -> PetscErrorCode;
}
