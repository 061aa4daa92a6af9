//! The PETSc solver against the LU: a saddle point through the layout,
//! whole contact solves in 2D and 3D (energy, Newton iterations), options
//! from the scene, and PETSc's failures as errors.

use super::*;
use crate::SceneDim;
use crate::linear::LinearSolverKind;
use crate::model::Dim;
use crate::{Method, Scene, Solution, SolveOptions, solve};

fn run<const D: usize>(
    scene: &Scene,
    linear: LinearSolverKind,
    petsc_options: &str,
) -> Result<Solution<D>, crate::SolverError>
where
    Dim<D>: SceneDim<D>,
{
    solve(
        scene,
        &SolveOptions {
            method: Method::Complete,
            linear,
            petsc_options: petsc_options.to_owned(),
            ..SolveOptions::from_scene(scene)
        },
    )
}

/// A 2-node bar in 2D (node 0 fixed in x, node 1 free) with one constraint
/// row: the field split gets whole nodes, the prescribed dof a decoupled row,
/// and the solution in Newton's numbering.
#[test]
fn layout_renumbers_and_decouples() {
    // unknowns: u0y (dof 1), u1x (dof 2), u1y (dof 3), lambda
    let layout = SystemLayout {
        dim: 2,
        free_dofs: vec![1, 2, 3],
        coordinates: vec![0.0, 0.0, 1.0, 0.0],
        node_rank: vec![],
    };
    // K = diag(2, 3, 4), G = [0, 1, 0]: u1x fixed to 0.5 by the constraint
    let rows = [0, 1, 2, 3, 1];
    let cols = [0, 1, 2, 1, 3];
    let vals = [2.0, 3.0, 4.0, 1.0, 1.0];
    let b = [1.0, 0.0, 2.0, 0.5];
    let mut s = PetscKrylov::new("-ksp_rtol 1e-12");
    s.set_layout(&layout);
    s.set_forcing(1e-12);
    let x = s.solve_system(4, &rows, &cols, &vals, &b).unwrap();
    let expect = [0.5, 0.5, 0.5, -1.5];
    for (a, e) in x.iter().zip(expect) {
        assert!((a - e).abs() < 1e-9, "{x:?}");
    }
    let k = s.krylov().unwrap();
    assert_eq!(k.solves, 1);
    assert_eq!(k.method, "fgmres/fieldsplit");
}

/// The matrix handed over as a solid block beside triplets is the matrix of
/// the same contributions as triplets, bit for bit (the same solution to
/// the last bit), the pattern is analysed once while the block and the
/// triplets stay, and a block over another pattern is refused.
#[test]
fn a_block_fills_the_matrix_of_its_triplets() {
    use crate::ids::EquationIndex;
    use crate::linear::{Block, BlockPattern};
    use std::sync::Arc;
    let layout = SystemLayout {
        dim: 2,
        // dof 0 prescribed: a decoupled row
        free_dofs: vec![1, 2, 3],
        coordinates: vec![0.0, 0.0, 1.0, 0.0],
        node_rank: vec![],
    };
    // a symmetric K over the free dofs (contributions that round), G = [0, 1, 0]
    let contributions = [
        (0, 0, 2.1),
        (1, 1, 3.3),
        (0, 1, -0.7),
        (1, 0, -0.7),
        (3, 1, 1.0),
        (1, 3, 1.0),
        (1, 1, 0.1),
        (2, 2, 4.7),
        (1, 2, 0.3),
        (2, 1, 0.3),
        (2, 2, 1e-3),
    ];
    let b = [1.0, 0.0, 2.0, 0.5];
    let plain = {
        let (r, c, v): (Vec<u32>, Vec<u32>, Vec<f64>) = (
            contributions.iter().map(|t| t.0).collect(),
            contributions.iter().map(|t| t.1).collect(),
            contributions.iter().map(|t| t.2).collect(),
        );
        let mut s = PetscKrylov::new("-ksp_rtol 1e-12");
        s.set_layout(&layout);
        s.set_forcing(1e-12);
        s.solve_system(4, &r, &c, &v, &b).unwrap()
    };
    let pattern =
        Arc::new(BlockPattern::from_rows(&[vec![0, 1], vec![0, 1, 2], vec![1, 2]]).unwrap());
    let mut block = Block::new(pattern.clone());
    let (mut r, mut c, mut v) = (vec![], vec![], vec![]);
    for &(i, j, x) in &contributions {
        if !block.add(
            EquationIndex::new(i as usize),
            EquationIndex::new(j as usize),
            x,
        ) {
            r.push(i);
            c.push(j);
            v.push(x);
        }
    }
    assert_eq!(r.len(), 2, "G and its transpose outside the block");
    let mut s = PetscKrylov::new("-ksp_rtol 1e-12");
    s.set_layout(&layout);
    s.set_forcing(1e-12);
    for _ in 0..2 {
        let x = s
            .solve_system_with(4, Some(&block), (&r, &c, &v), &b)
            .unwrap();
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&x), bits(&plain));
    }
    assert_eq!(s.symbolic_factorisations(), 1);
    // analysed with one pattern, factored with another's block: refused
    let other = Block::new(Arc::new(
        BlockPattern::from_rows(&[vec![0, 1], vec![0, 1, 2], vec![1, 2]]).unwrap(),
    ));
    s.analyse_with_block(4, &pattern, &r, &c).unwrap();
    assert!(s.factor_with_block(&other, &v).is_err());
}

/// The paper scene (2D, persistent contact, multipliers) and a 3D block
/// pressed on a base: the PETSc default's energy within 1e-8 of the LU's,
/// at most one Newton iteration more per step, the Krylov iterations
/// reported.
#[test]
fn contact_solves_match_the_lu() {
    let paper =
        Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml").unwrap();
    compare::<2>(&paper, "paper");
    let cube = Scene::from_toml_str(
        include_str!("../../../../scenes/block3d.toml"),
        "block3d.toml",
    )
    .unwrap();
    compare::<3>(&cube, "block3d");
}

fn compare<const D: usize>(scene: &Scene, what: &str)
where
    Dim<D>: SceneDim<D>,
{
    {
        let lu = run::<D>(scene, LinearSolverKind::Lu, "").unwrap();
        let petsc = run::<D>(scene, LinearSolverKind::Petsc, "").unwrap();
        let rel = (petsc.strain_energy / lu.strain_energy - 1.0).abs();
        assert!(rel <= 1e-8, "{what}: energy differs by {rel:e}");
        assert_eq!(lu.step_records.len(), petsc.step_records.len(), "{what}");
        for (a, b) in lu.step_records.iter().zip(&petsc.step_records) {
            assert!(
                b.iterations <= a.iterations + 1,
                "{what}, step {}: {:?} vs {:?}",
                a.step,
                a.residuals,
                b.residuals
            );
        }
        let k = petsc.krylov.expect("iterations reported");
        assert!(
            k.solves >= petsc.newton_iterations && k.iterations >= k.solves,
            "{what}: {k:?}"
        );
        assert!(lu.krylov.is_none());
    }
}

/// Options from the scene reach PETSc (a direct LU through PETSc gives one
/// iteration per solve), and a Krylov solve held to too few iterations is
/// an error that names PETSc's reason, never a step taken.
#[test]
fn options_reach_petsc_and_failures_are_errors() {
    let scene =
        Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml").unwrap();
    let direct = run::<2>(
        &scene,
        LinearSolverKind::Petsc,
        "-pc_type lu -pc_factor_mat_solver_type mumps",
    )
    .unwrap();
    let k = direct.krylov.unwrap();
    assert_eq!(k.method, "fgmres/lu");
    assert_eq!(k.max_iterations, 1, "{k:?}");
    let err = run::<2>(
        &scene,
        LinearSolverKind::Petsc,
        "-ksp_max_it 1 -pc_type jacobi",
    )
    .expect_err("one Jacobi iteration cannot solve the saddle point");
    let text = err.to_string();
    assert!(text.contains("DIVERGED_ITS"), "{text}");
    // the user's own preconditioner is not retried with another
    assert!(!text.contains("retried"), "{text}");
    // refused at once: no cut-back, PETSc's own message
    let bad = run::<2>(&scene, LinearSolverKind::Petsc, "-pc_type no_such_pc")
        .expect_err("an unknown preconditioner is refused");
    assert!(
        matches!(&bad, crate::SolverError::Linear(LinearError::Refused(m)) if m.contains("no_such_pc")),
        "{bad:?}"
    );
}

/// A PETSc error inside a Krylov solve (here the inner CG of `-pc_type
/// ksp` meeting an indefinite matrix, told to fail when it does not
/// converge) leaves PETSc's solver mid-solve; the solver drops it, so the
/// failure is the matrix's and a later system solves (kept, the third
/// solve would fail with "Cannot embed PCPreSolve() more than twice").
#[test]
fn a_failed_petsc_call_does_not_poison_the_next_solve() {
    let mut s = PetscKrylov::new(
        "-pc_type ksp -ksp_ksp_type cg -ksp_pc_type none -ksp_ksp_error_if_not_converged",
    );
    s.set_forcing(1e-10);
    let n = 6;
    let rows: Vec<u32> = (0..n as u32).collect();
    let b = vec![1.0; n];
    // CG's first curvature (b, A b) is 0: indefinite
    let indefinite = [1.0, -1.0, 2.0, -2.0, 3.0, -3.0];
    for attempt in 0..2 {
        let err = s
            .solve_system(n, &rows, &rows, &indefinite, &b)
            .expect_err("CG refuses an indefinite matrix");
        assert!(
            matches!(&err, LinearError::Petsc(m) if m.contains("error 91")),
            "attempt {attempt}: {err:?}"
        );
    }
    // a multiple of the identity: one CG iteration is exact
    let x = s
        .solve_system(n, &rows, &rows, &[2.0; 6], &b)
        .expect("the next system solves");
    assert!(x.iter().all(|v| (v - 0.5).abs() < 1e-9), "{x:?}");
}

/// A solve the default's GAMG does not converge (here made to stall by
/// Chebyshev bounds far below the displacement block's spectrum, which
/// only GAMG's smoothers read) is retried with BoomerAMG on the
/// displacements, which the run keeps: the default's energy and Newton
/// path, the switch reported at solve 1. A solve BoomerAMG does not
/// converge either (one iteration allowed) is retried with MUMPS's LU,
/// again the default's energy and Newton path. A solve that fails on every
/// stage (no iteration allowed) is the error naming each.
#[test]
fn a_solve_the_default_does_not_converge_climbs_its_ladder() {
    let scene =
        Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml").unwrap();
    let default = run::<2>(&scene, LinearSolverKind::Petsc, "").unwrap();
    let counts = default.krylov.clone().unwrap();
    assert_eq!((counts.switched_at, counts.direct_at), (None, None));
    let same_as_default = |sol: &Solution<2>| {
        let rel = (sol.strain_energy / default.strain_energy - 1.0).abs();
        assert!(rel <= 1e-8, "energy differs by {rel:e}");
        assert_eq!(sol.newton_iterations, default.newton_iterations);
    };
    let stalled = run::<2>(
        &scene,
        LinearSolverKind::Petsc,
        "-ksp_max_it 60 -fieldsplit_u_mg_levels_ksp_chebyshev_esteig 0,0.0001,0,0.0002",
    )
    .unwrap();
    same_as_default(&stalled);
    let k = stalled.krylov.clone().unwrap();
    assert_eq!((k.switched_at, k.direct_at), (Some(1), None), "{k:?}");
    assert_eq!(k.solves, counts.solves + 1, "{k:?}");
    let direct = run::<2>(&scene, LinearSolverKind::Petsc, "-ksp_max_it 1").unwrap();
    same_as_default(&direct);
    let k = direct.krylov.clone().unwrap();
    assert_eq!((k.switched_at, k.direct_at), (Some(1), Some(2)), "{k:?}");
    assert_eq!(k.solves, counts.solves + 2, "{k:?}");
    // the run's error is its last attempt's, on the stage it reached
    let err = run::<2>(&scene, LinearSolverKind::Petsc, "-ksp_max_it 0")
        .expect_err("no iteration cannot solve the saddle point");
    let text = err.to_string();
    assert!(
        text.contains("DIVERGED_ITS")
            && text.contains("with MUMPS's LU, the default's since solve 2"),
        "{text}"
    );
    // a first solve that fails on every stage names each
    let mut s = PetscKrylov::new("-ksp_max_it 0");
    let rows: Vec<u32> = (0..6).collect();
    let err = s
        .solve_system(6, &rows, &rows, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], &[1.0; 6])
        .expect_err("no iteration solves nothing");
    let text = err.to_string();
    for said in [
        "DIVERGED_ITS after 0 iterations",
        "with GAMG on the displacements; retried: PETSc's",
        "with BoomerAMG on the displacements; retried: PETSc's fgmres/lu",
        "with MUMPS's LU",
    ] {
        assert!(text.contains(said), "{said}: {text}");
    }
    let k = s.krylov().unwrap();
    assert_eq!(
        (k.switched_at, k.direct_at, k.solves),
        (Some(1), Some(2), 3),
        "{k:?}"
    );
}

/// MUMPS's working memory bound: 90 % of what is available, split among
/// the ranks, in MiB; none where the available memory is unknown.
#[test]
fn the_direct_stage_bounds_mumps_by_the_available_memory() {
    let gib = 1024 * 1024 * 1024;
    assert_eq!(direct_bound(Some(10 * gib), 1), Some(9216));
    assert_eq!(direct_bound(Some(10 * gib), 2), Some(4608));
    assert_eq!(direct_bound(Some(1), 4), Some(1));
    assert_eq!(direct_bound(None, 2), None);
    assert_eq!(
        direct_options(direct_bound(Some(10 * gib), 2)),
        format!("{DIRECT_OPTIONS} -mat_mumps_icntl_23 4608")
    );
    assert_eq!(direct_options(None), DIRECT_OPTIONS);
}

/// The direct stage's bound is the one read when the run reached it, kept
/// in the counts: a later solve, whose own factorisation holds memory that
/// is no longer available, installs the same bound.
#[test]
fn the_direct_stage_keeps_the_bound_it_was_given() {
    let mut counts = KrylovCounts::default();
    Stage::BoomerAmg.record(&mut counts, 1);
    Stage::Direct.record(&mut counts, 1);
    assert_eq!(Stage::of(&counts), Stage::Direct);
    assert_eq!(counts.direct_at, Some(0));
    assert_eq!(
        counts.direct_memory_mib.is_some(),
        crate::meminfo::available().is_some(),
        "{counts:?}"
    );
    counts.direct_memory_mib = Some(1234);
    for constrained in [true, false] {
        let installed = options_for("", constrained, &counts);
        assert!(
            installed.contains(&format!("{DIRECT_OPTIONS} -mat_mumps_icntl_23 1234")),
            "{installed}"
        );
    }
    counts.direct_memory_mib = None;
    assert!(!options_for("", true, &counts).contains("icntl_23"));
}

/// The 3D paper scene (slender plates in persistent contact, bending along
/// their length), where no multigrid V-cycle of the default converges
/// (docs/petsc.md, "Where the multigrid does not converge"): the default
/// climbs to MUMPS's LU and gives the LDLᵀ's energy and Newton path.
#[test]
fn the_3d_paper_scene_solves_with_the_default_through_its_last_stage() {
    let scene = Scene::from_toml_str(
        include_str!("../../../../scenes/stacked-plates.toml"),
        "stacked-plates.toml",
    )
    .unwrap();
    let ldlt = run::<3>(&scene, LinearSolverKind::Ldlt, "").unwrap();
    let petsc = run::<3>(&scene, LinearSolverKind::Petsc, "").unwrap();
    let rel = (petsc.strain_energy / ldlt.strain_energy - 1.0).abs();
    assert!(rel <= 1e-8, "energy differs by {rel:e}");
    assert_eq!(petsc.newton_iterations, ldlt.newton_iterations);
    let k = petsc.krylov.unwrap();
    assert!(k.switched_at.is_some() && k.direct_at.is_some(), "{k:?}");
}
