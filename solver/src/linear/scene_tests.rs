//! The LDL^T against the LU on whole solves: the paper scene with every
//! method, Newton's residual histories, unilateral contact with inactive
//! multipliers, and an unsupported model.

use crate::linear::LinearSolverKind;
use crate::{Method, Scene, Solution, SolveOptions, SolverError, solve};

fn paper_scene() -> Scene {
    Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml").unwrap()
}

fn run(scene: &Scene, method: Method, steps: usize, linear: LinearSolverKind) -> Solution {
    solve(
        scene,
        &SolveOptions {
            method,
            steps,
            linear,
            ..SolveOptions::from_scene(scene)
        },
    )
    .unwrap()
}

/// The final strain energy to 1e-10 relative, the same number of load
/// steps, and Newton converging alike: in every step from `from_step` on
/// the same iteration count, and every residual within a factor 10 of LU's
/// (or both at the round-off floor). The first iteration of a solve from the
/// unloaded state is ill-conditioned (a first contact, held by the
/// regularisation), so two backward-stable factorisations agree there only
/// to about 1e-7 and the iterates that follow are not bit-comparable.
fn assert_same_solve(lu: &Solution, ldlt: &Solution, from_step: usize, what: &str) {
    let rel = (ldlt.strain_energy / lu.strain_energy - 1.0).abs();
    assert!(rel <= 1e-10, "{what}: energy differs by {rel:e}");
    assert_eq!(lu.step_records.len(), ldlt.step_records.len(), "{what}");
    for (a, b) in lu.step_records.iter().zip(&ldlt.step_records) {
        if a.step < from_step {
            continue;
        }
        let (ra, rb) = (&a.residuals, &b.residuals);
        assert_eq!(
            a.iterations, b.iterations,
            "{what}, step {}: {ra:?} vs {rb:?}",
            a.step
        );
        for (&x, &y) in ra.iter().zip(rb) {
            let floor = x.max(y) < 1e-11;
            assert!(
                floor || (y <= 10.0 * x && x <= 10.0 * y),
                "{what}, step {}: {ra:?} vs {rb:?}",
                a.step
            );
        }
    }
}

/// Every method solves the paper scene with the LDL^T, with LU's iteration
/// counts and energy, and without falling back to LU.
#[test]
fn ldlt_solves_the_paper_scene_with_every_method() {
    let scene = paper_scene();
    for method in Method::ALL {
        let lu = run(&scene, method, 4, LinearSolverKind::Lu);
        let ldlt = run(&scene, method, 4, LinearSolverKind::Ldlt);
        assert_same_solve(&lu, &ldlt, 1, &format!("method {method}"));
        assert_eq!(ldlt.linear_fallbacks, 0, "method {method}");
        assert_eq!(lu.linear_fallbacks, 0);
        // the fill: L has at least its diagonal and at most the dense lower
        // triangle; faer's LU does not report one
        let fill = ldlt.factor_nonzeros.expect("the LDL^T reports its fill");
        let n = ldlt.equations;
        assert!(n < fill && fill < n * (n + 1) / 2, "{fill} for {n}");
        assert_eq!(lu.factor_nonzeros, None);
    }
}

/// The complete formulation stays quadratic with the LDL^T: the residual
/// histories of 4 and 20 steps match LU's, and the residual falls
/// superlinearly (each at most the square of the previous, scaled, once
/// below 1e-3 of the first).
#[test]
fn newton_stays_quadratic_with_ldlt() {
    let scene = paper_scene();
    for steps in [4, 20] {
        let lu = run(&scene, Method::Complete, steps, LinearSolverKind::Lu);
        let ldlt = run(&scene, Method::Complete, steps, LinearSolverKind::Ldlt);
        assert_same_solve(&lu, &ldlt, 1, &format!("{steps} steps"));
        // quadratic: once below 1e-2 of the step's first residual, each
        // residual is at most the square of the previous (relative to it),
        // times 1e3, until the round-off floor
        for rec in &ldlt.step_records {
            let r = &rec.residuals;
            let r0 = r[0].max(1.0);
            for w in r.windows(2) {
                let (a, b) = (w[0] / r0, w[1] / r0);
                if a < 1e-2 && b > 1e-11 {
                    assert!(b <= 1e3 * a * a, "{steps} steps: {r:?}");
                }
            }
        }
        assert_eq!(ldlt.linear_fallbacks, 0);
    }
}

/// Unilateral contact, where multipliers become inactive (their rows are
/// assembled unsymmetrically): the LDL^T refines to the assembled system, so
/// the solve equals LU's. The active set of the first step is decided on the
/// ill-conditioned first iterates (see [`assert_same_solve`]), so that step
/// may take a different path; the others converge alike.
#[test]
fn unilateral_contact_with_inactive_multipliers() {
    let text =
        crate::scenes::STACKED_CANTILEVER.replace("mode = \"persistent\"", "mode = \"unilateral\"");
    let scene = Scene::from_toml_str(&text, "unilateral.toml").unwrap();
    let lu = run(&scene, Method::Complete, 10, LinearSolverKind::Lu);
    let ldlt = run(&scene, Method::Complete, 10, LinearSolverKind::Ldlt);
    assert_same_solve(&lu, &ldlt, 2, "unilateral");
    assert_eq!(ldlt.linear_fallbacks, 0);
    let open = ldlt
        .final_state
        .multipliers
        .iter()
        .filter(|&&l| l == 0.0)
        .count();
    assert!(open > 0, "no inactive multiplier");
    assert_eq!(
        lu.final_state.multipliers.len(),
        ldlt.final_state.multipliers.len()
    );
    // lifted: every multiplier inactive
    let lifted = Scene::from_toml_str(
        &text.replace("force = [0.0, -0.08]", "force = [0.0, 0.08]"),
        "lift.toml",
    )
    .unwrap();
    let lu = run(&lifted, Method::Complete, 4, LinearSolverKind::Lu);
    let ldlt = run(&lifted, Method::Complete, 4, LinearSolverKind::Ldlt);
    assert_same_solve(&lu, &ldlt, 1, "lifted");
    assert!(ldlt.final_state.multipliers.iter().all(|&l| l == 0.0));
}

/// An unsupported model (no fixed dofs: `K` singular): the LDL^T falls back
/// and the solve ends with the singular-system error, not a panic.
#[test]
fn unsupported_model_is_singular_with_ldlt() {
    let text = crate::scenes::STACKED_CANTILEVER.replace("[[fix]]\nx = 0.0\ndofs = \"xy\"\n", "");
    assert_ne!(text, crate::scenes::STACKED_CANTILEVER);
    let scene = Scene::from_toml_str(&text, "free.toml").unwrap();
    let err = solve::<2>(
        &scene,
        &SolveOptions {
            max_cutbacks: 1,
            linear: LinearSolverKind::Ldlt,
            ..SolveOptions::from_scene(&scene)
        },
    )
    .unwrap_err();
    assert!(matches!(err, SolverError::Singular { .. }), "{err}");
}

/// The Hertz scenes (finite and small strain): the cylinder is held
/// vertically only by contact, and its stiffness is slightly indefinite
/// along that mode on many iterations (a negative last displacement pivot,
/// a positive multiplier pivot after it). The factorisation has the right
/// inertia, so the LDL^T solves every iteration without falling back to LU
/// (a per-row sign check fell back on 11 of the 19 and 7 of the 18), with
/// LU's iterations and energy. One solve is recorded as indefinite: the
/// finite-strain scene's second, in the attempt that inverts an element
/// and is cut back, where the stiffness has a negative eigenvalue that the
/// active constraints do not hold (one positive pivot fewer than the free
/// dofs and inactive multipliers); the LDL^T solves it too.
#[test]
fn hertz_cylinder_held_by_contact_without_fallback() {
    for (file, indefinite) in [("hertz.toml", 1), ("hertz-small-strain.toml", 0)] {
        let path = format!("{}/../scenes/{file}", env!("CARGO_MANIFEST_DIR"));
        let scene = Scene::from_file(&path).unwrap();
        let options = SolveOptions::from_scene(&scene);
        let lu = run(&scene, options.method, options.steps, LinearSolverKind::Lu);
        let ldlt = run(
            &scene,
            options.method,
            options.steps,
            LinearSolverKind::Ldlt,
        );
        assert_same_solve(&lu, &ldlt, 0, file);
        assert_eq!(ldlt.linear_fallbacks, 0, "{file}");
        assert_eq!(ldlt.linear_indefinite_log.len(), indefinite, "{file}");
        for i in &ldlt.linear_indefinite_log {
            assert_eq!(i.solve, 2, "{file}: {i}");
            assert_eq!(i.inertia.positive + 1, i.inertia.expected, "{file}: {i}");
        }
        assert_eq!(ldlt.cutbacks.len(), indefinite, "{file}");
    }
}
