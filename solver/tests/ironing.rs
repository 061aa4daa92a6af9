//! The ironing benchmark, `scenes/ironing.toml`: a half-disc punch
//! (radius 1, 60 arc segments) pressed 0.1 into a 10 x 1 strip over load
//! factor 0..0.2 and slid 5 along it over 0.2..1; frictionless,
//! unilateral slave-normal contact, the punch the slave. The complete
//! formulation used to fail right after the slide started (20 and 40
//! steps); what made it robust is in `solver::newton` ("Prescribed
//! increments") and `solver::contact` ("Pairing": facing segments only;
//! "Points stuck at a master node": a tie off its node is released).
//!
//! The cheap test runs the press and the first two slide steps of the
//! 20-step schedule; the full runs are in the release profile:
//!
//! ```text
//! cargo test --release -p gapsim-solver --test ironing -- --ignored --nocapture
//! ```
//!
//! and the curves and the steady-sliding table in `docs/ironing/` come
//! from `cargo run --release --example sliding_curves -- --steps 40
//! --steady 0.5 4.5 --out docs/ironing scenes/ironing.toml`.

use solver::{Method, Scene, Solution, SolveOptions, solve};

fn scene() -> Scene {
    Scene::from_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/ironing.toml"
    ))
    .unwrap_or_else(|e| panic!("{e}"))
}

fn run(scene: &Scene, method: Method, steps: usize) -> Solution {
    solve(
        scene,
        &SolveOptions {
            method,
            steps,
            ..SolveOptions::from_scene(scene)
        },
    )
    .unwrap_or_else(|e| panic!("ironing, {method}, {steps} steps: {e}"))
}

/// The support groups: the strip's bottom, the punch top's vertical
/// (`press`) and horizontal (`slide`) prescribed displacements.
const PRESS: usize = 1;
const SLIDE: usize = 2;

/// Every converged step balances: the reactions sum to zero (no external
/// load), to the solver tolerance relative to the normal reaction.
fn assert_balanced(sol: &Solution) {
    assert_eq!(sol.support_groups, ["bottom", "press", "slide"]);
    for r in &sol.step_records {
        let scale = r.reactions[PRESS][1].abs().max(1.0);
        for c in 0..2 {
            let sum: f64 = r.reactions.iter().map(|g| g[c]).sum();
            assert!(sum.abs() < 1e-7 * scale, "step {}: sum {sum:e}", r.step);
        }
    }
}

/// The press and the first two slide steps of the 20-step schedule (load
/// factor 0.3 of 1; each slide step moves the punch 0.3125, three strip
/// elements): the complete formulation converges without a cut-back, and
/// the normal reaction after the two slide steps is that after the press
/// within 2 % (frictionless sliding on an elastic strip).
#[test]
fn the_press_and_the_slide_start_converge_without_cutbacks() {
    let mut scene = scene();
    scene.loading.load_factor_end = 0.3;
    let sol = run(&scene, Method::Complete, 6);
    assert_balanced(&sol);
    assert!(sol.cutbacks.is_empty(), "{:?}", sol.cutbacks);
    let normal = |k: usize| sol.step_records[k].reactions[PRESS][1];
    let drag = |k: usize| sol.step_records[k].reactions[SLIDE][0];
    println!(
        "normal reaction {:.6} after the press, {:.6} / {:.6} after the slide steps; drag \
         {:.3e} / {:.3e}; {} iterations",
        normal(3),
        normal(4),
        normal(5),
        drag(4),
        drag(5),
        sol.newton_iterations
    );
    assert!(normal(3).abs() > 1.0);
    for k in [4, 5] {
        assert!((normal(k) / normal(3) - 1.0).abs() < 0.02, "step {k}");
        assert!(drag(k).abs() < 0.02 * normal(3).abs(), "step {k}");
    }
}

/// Complete and every type, 20 and 40 steps: each runs with at most 2
/// cut-backs; over the steady slide (distance 0.5 to 4.5) the normal
/// reaction's ripple and the drag stay below 2 % of the mean normal
/// reaction, and the final energy of Types 3–6 is within 0.05 % of the
/// complete formulation's (Types 1 and 2, unsafe on sliding in the safety
/// map, are not held to it: Type 2 at 20 steps is 0.057 % low).
#[test]
#[ignore = "release profile, minutes: cargo test --release -p gapsim-solver --test ironing -- --ignored"]
fn every_method_irons_with_few_cutbacks() {
    let scene = scene();
    for steps in [20, 40] {
        let complete = run(&scene, Method::Complete, steps);
        for method in Method::ALL {
            let sol = if method == Method::Complete {
                complete.clone()
            } else {
                run(&scene, method, steps)
            };
            assert_balanced(&sol);
            // slide distance 5 (lf - 0.2) / 0.8
            let rows: Vec<[f64; 2]> = sol
                .step_records
                .iter()
                .filter(|r| (0.28..=0.92).contains(&r.load_factor))
                .map(|r| [r.reactions[PRESS][1], r.reactions[SLIDE][0]])
                .collect();
            let mean = rows.iter().map(|r| r[0]).sum::<f64>() / rows.len() as f64;
            let ripple = rows.iter().map(|r| (r[0] - mean).abs()).fold(0.0, f64::max);
            let drag = rows.iter().map(|r| r[1].abs()).fold(0.0, f64::max);
            let e = sol.strain_energy / complete.strain_energy - 1.0;
            println!(
                "{method}, {steps} steps: {} cut-backs, mean normal reaction {mean:.6}, ripple \
                 {:.3} %, drag {:.3} %, energy error {e:+.2e}",
                sol.cutbacks.len(),
                100.0 * ripple / mean.abs(),
                100.0 * drag / mean.abs()
            );
            assert!(sol.cutbacks.len() <= 2, "{method}, {steps} steps");
            assert!(ripple < 0.02 * mean.abs(), "{method}, {steps} steps");
            assert!(drag < 0.02 * mean.abs(), "{method}, {steps} steps");
            if let Method::Approx(ty) = method
                && ty.index() >= 3
            {
                assert!(e.abs() < 5e-4, "{method}, {steps} steps: {e:e}");
            }
        }
    }
}

/// `scenes/ironing-friction.toml`: the same punch and strip with Coulomb
/// friction, mu = 0.3.
fn frictional() -> Scene {
    Scene::from_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenes/ironing-friction.toml"
    ))
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The drag over the press at every converged step from load factor
/// `from` on.
fn drag_ratios(sol: &Solution, from: f64) -> Vec<f64> {
    sol.step_records
        .iter()
        .filter(|r| r.load_factor > from)
        .map(|r| -r.reactions[SLIDE][0] / r.reactions[PRESS][1])
        .collect()
}

/// The press and the slide's start with friction (load factor 0.3 of the
/// 40-step schedule: four slide steps of 0.156): the reactions balance,
/// and once sliding the drag is mu times the press less the arc's tilt
/// under the contact (0.29 to 0.30); every slave node in contact slips.
#[test]
fn frictional_ironing_drags_at_mu_times_the_press_once_sliding() {
    let mut scene = frictional();
    scene.loading.load_factor_end = 0.3;
    let sol = run(&scene, Method::Complete, 12);
    assert_balanced(&sol);
    let ratios = drag_ratios(&sol, 0.2 + 1e-9);
    assert!(!ratios.is_empty());
    for r in &ratios {
        assert!((0.29..0.3).contains(r), "drag / press {r}: {ratios:?}");
    }
    let text = solver::report::contact_csv(&sol, &sol.final_state).unwrap();
    let states: Vec<&str> = text
        .lines()
        .skip(1)
        .filter(|l| {
            l.split(',')
                .nth(5)
                .is_some_and(|p| p.parse::<f64>().unwrap() > 0.0)
        })
        .map(|l| l.split(',').nth(16).unwrap())
        .collect();
    assert!(!states.is_empty());
    assert!(states.iter().all(|s| *s == "slip"), "{states:?}");
}

/// The whole frictional slide at 40 steps, the complete formulation and
/// Type 6: the drag over the press between 0.29 and 0.30 at every sliding
/// step, and Type 6's mean drag and press within 0.5 % of the complete
/// formulation's (measured: 0.05 % and 0.19 %).
#[test]
#[ignore = "the whole frictional slide, about a minute in the release profile"]
fn frictional_ironing_whole_slide_complete_and_type_6() {
    let scene = frictional();
    let mean = |sol: &Solution, c: usize, k: usize| {
        let v: Vec<f64> = sol
            .step_records
            .iter()
            .filter(|r| r.load_factor > 0.3)
            .map(|r| r.reactions[k][c])
            .collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let complete = run(&scene, Method::Complete, 40);
    let six = run(
        &scene,
        Method::Approx(contact_kernels::ApproxType::Type6),
        40,
    );
    for sol in [&complete, &six] {
        assert_balanced(sol);
        for r in drag_ratios(sol, 0.2 + 1e-9) {
            assert!((0.29..0.3).contains(&r), "{r}");
        }
    }
    let (drag, press) = (mean(&complete, 0, SLIDE), mean(&complete, 1, PRESS));
    let (drag6, press6) = (mean(&six, 0, SLIDE), mean(&six, 1, PRESS));
    println!("complete: drag {drag}, press {press}; Type 6: drag {drag6}, press {press6}");
    assert!((drag6 - drag).abs() < 5e-3 * drag.abs());
    assert!((press6 - press).abs() < 5e-3 * press.abs());
}
