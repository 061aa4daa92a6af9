//! The large-sliding benchmark (issue #8 §1), `scenes/sliding.toml`: a
//! block pressed 0.1 into a base over load factor 0..0.2, then dragged 6.0
//! (24 master segments) along it over 0.2..1, with load curves on its top
//! edge; unilateral, slave-normal contact.
//!
//! What holds, measured in the debug profile (a few seconds in all):
//!
//! * the complete formulation is step-count independent: at 10, 20 and 40
//!   steps its strain energy at every common load factor (k / 10) agrees
//!   to a relative spread of at most 2.3e-14 (the target: 1e-7;
//!   final energy 0.45333524, the slide adds at most 1.7 % to the press's
//!   energy);
//! * the scene is mirror-symmetric about x = 4 at the end (the block ends
//!   where the mirror image of its pressed start is), so the complete
//!   formulation's final energy equals the energy after the press, and the
//!   normal reaction too, with the tangential one reversed;
//! * every approximation type runs it and records the reactions, which
//!   balance at every converged step (equilibrium holds whatever the gap
//!   approximation);
//! * with the expansions at the step's predictor (`[newton] expand_at`,
//!   the default; `solver::newton`, "Where the expansions are taken") a
//!   point that slides across a node in a steady step is on its end
//!   segment at the predictor already: 3 step repeats at 20 steps instead
//!   of 40. Types 3–6 at 20 steps: energy errors -4.9e-6, -4.0e-4, +4.9e-5,
//!   -3.0e-4; at 40 steps +2.6e-6, +1.5e-4, -2.9e-6, +1.5e-4; reactions
//!   within 0.073 %. Held out: Types 3 / 6 -1.3e-4 / -1.3e-4 at 20 steps,
//!   -1.4e-5 / +4.8e-6 at 40; closest-point at 20 steps -1.1e-4 / +7.2e-4.
//!   The bullets below were measured with the expansions at the step start
//!   (`expand_at = "start"`, the paper's scheme, which the tests that
//!   describe it set):
//! * with the step-end re-pairing (issue #8 §2, `solver::newton`,
//!   "Re-pairing at the step end", with the anchor iteration: a point that
//!   crossed a node gets its new segment's expansion at the attempt's end,
//!   re-taken until it reproduces the gap there) Types 3–6 follow the
//!   complete formulation: energy errors at 20 steps below 1e-8 relative
//!   (every point crosses a node in every sliding step, so every point is
//!   re-anchored), at 40 steps -1.0e-5 to -1.3e-5; reactions within 3e-6
//!   (20 steps) and 0.36 % (40) of the complete formulation's largest
//!   reaction. The target (0.05 % at 20 steps) holds at 20 and 40.
//!   What is left at 40 steps is at the points that cycle at a concave
//!   master node (listed as unsettled), where the complete formulation
//!   ties the point to the node. Without re-pairing (`repair = false`)
//!   Type 6 at 20 steps is -20 % off;
//! * held out: the closest-point formulation on the same scene (Types 3
//!   and 6, 20 steps: reactions within 3e-6, energy within 1e-9);
//! * held out too: `scenes/sliding-held-out.toml` (another block, mesh,
//!   material, slide direction): Types 3 / 6 energy errors 2.9e-9 / 4.3e-10
//!   at 20 steps, -2.4e-4 / -1.7e-4 at 40, -1.5e-5 / -2.3e-5 at 80
//!   (falling from 40 steps on, where some points stay on their segment in
//!   a step and keep the type's step-start expansion), reactions within
//!   0.03 %;
//! * `taylor_tolerance = 1e-4` on the held-out scene at 40 steps: Types
//!   3 / 6 energy error -2.4e-4 / -1.7e-4 -> -2.6e-6 / -1.3e-5 with the
//!   points above it re-taken at the step end (no step halved; 351 / 341
//!   linear solves against the complete formulation's 151). Halving the
//!   steps instead, the first cure, gave -1.7e-5 / -2.2e-5 with 10
//!   halvings each and 570 / 580 solves; every accepted step within the
//!   tolerance either way.

use contact_kernels::ApproxType;
use solver::{ExpansionPoint, Formulation, Method, Scene, Solution, SolveOptions, solve};

const SLIDING: &str = include_str!("../../scenes/sliding.toml");

fn scene() -> Scene {
    Scene::from_toml_str(SLIDING, "sliding.toml").unwrap_or_else(|e| panic!("{e}"))
}

/// `scenes/sliding-held-out.toml`.
fn held_out() -> Scene {
    Scene::from_toml_str(
        include_str!("../../scenes/sliding-held-out.toml"),
        "sliding-held-out.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

fn run(scene: &Scene, method: Method, steps: usize) -> Solution {
    run_with(
        scene,
        &SolveOptions {
            method,
            steps,
            ..SolveOptions::from_scene(scene)
        },
    )
}

fn run_with(scene: &Scene, options: &SolveOptions) -> Solution {
    solve(scene, options)
        .unwrap_or_else(|e| panic!("sliding, {}, {} steps: {e}", options.method, options.steps))
}

/// Types 3 to 6.
const TYPES_3_TO_6: [Method; 4] = [
    Method::Approx(ApproxType::Type3),
    Method::Approx(ApproxType::Type4),
    Method::Approx(ApproxType::Type5),
    Method::Approx(ApproxType::Type6),
];

/// The reactions of `sol` balance at every converged step: the base's
/// support against the block's top edge (press: y, slide: x), relative to
/// the normal reaction.
fn assert_balanced(sol: &Solution, what: &str) {
    assert_eq!(sol.support_groups, ["base", "press", "slide"], "{what}");
    assert_eq!(sol.step_records.last().unwrap().load_factor, 1.0);
    for r in &sol.step_records {
        let [base, press, slide] = [r.reactions[0], r.reactions[1], r.reactions[2]];
        assert_eq!((press[0], slide[1]), (0.0, 0.0), "{what}");
        let scale = base[1].abs().max(1e-3);
        let x = (base[0] + slide[0]).abs() / scale;
        let y = (base[1] + press[1]).abs() / scale;
        assert!(
            x < 1e-8 && y < 1e-8,
            "{what} at load factor {}: unbalanced by {x:e} (x), {y:e} (y)",
            r.load_factor
        );
    }
}

/// Complete: the same energy at every load factor whatever the step count,
/// and the balanced reactions. At 10 steps the first slide step (0.75, 3
/// master segments and three quarters of the block's width) from the
/// linearised Dirichlet predictor (`solver::newton`, "Prescribed
/// increments") needs one cut-back (none without the predictor, which
/// took 122 iterations to its 95); 20 and 40 steps need none.
#[test]
fn complete_formulation_is_step_count_independent() {
    let scene = scene();
    let runs: Vec<Solution> = [10, 20, 40]
        .iter()
        .map(|&n| run(&scene, Method::Complete, n))
        .collect();
    for sol in &runs {
        assert_balanced(sol, &format!("complete, {} steps", sol.steps));
        let allowed = usize::from(sol.steps == 10);
        assert!(sol.cutbacks.len() <= allowed, "{:?}", sol.cutbacks);
    }
    // the energy at the load factors every run reaches (k / 10)
    let mut worst: f64 = 0.0;
    for k in 1..=10 {
        let energies: Vec<f64> = runs
            .iter()
            .map(|sol| {
                // the record of scheduled step k * steps / 10 (a cut-back
                // adds records of sub-steps before it)
                let step = k * sol.steps / 10;
                let r = sol.step_records.iter().rfind(|r| r.step == step).unwrap();
                assert_eq!(r.load_factor, k as f64 / 10.0);
                r.strain_energy
            })
            .collect();
        let max = energies.iter().copied().fold(f64::MIN, f64::max);
        let min = energies.iter().copied().fold(f64::MAX, f64::min);
        let spread = (max - min) / max;
        println!(
            "load factor {:.1}: energies {energies:?}, relative spread {spread:.2e}",
            k as f64 / 10.0
        );
        worst = worst.max(spread);
    }
    println!("largest relative spread of the complete formulation's energy: {worst:.2e}");
    assert!(worst < 1e-7, "relative spread {worst:e}");
    let final_energy = runs[0].strain_energy;
    assert!((final_energy - 0.45333524).abs() < 1e-8, "{final_energy}");
}

/// The end state is the mirror image of the pressed start (about x = 4):
/// the same energy and normal reaction, the tangential reaction reversed.
#[test]
fn complete_formulation_ends_in_the_mirror_image_of_the_press() {
    let sol = run(&scene(), Method::Complete, 20);
    let pressed = &sol.step_records[3];
    assert_eq!(pressed.load_factor, 0.2);
    let last = sol.step_records.last().unwrap();
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(
        rel(last.strain_energy, pressed.strain_energy) < 1e-9,
        "{} vs {}",
        last.strain_energy,
        pressed.strain_energy
    );
    let (p, l) = (pressed.reactions[1][1], last.reactions[1][1]);
    assert!(rel(l, p) < 1e-9, "normal reaction {p} -> {l}");
    let (p, l) = (pressed.reactions[2][0], last.reactions[2][0]);
    assert!(p.abs() > 1e-4, "tangential reaction {p}");
    assert!(rel(-l, p) < 1e-6, "tangential reaction {p} -> {l}");
}

/// Every approximation type runs the scene at 10 steps, reaches the end
/// and records balanced reactions at every step.
#[test]
fn every_type_runs_and_records_the_reactions() {
    let scene = scene();
    for method in &Method::ALL[1..] {
        let sol = run(&scene, *method, 10);
        assert_balanced(&sol, &method.to_string());
        let top = sol.node_at("block", [1.5, 1.5]).unwrap();
        assert_eq!(sol.displacement(top), [6.0, -0.1], "{method}");
        assert!(sol.strain_energy > 0.0, "{method}");
        println!(
            "{method}: strain energy {:.8} after 10 steps ({} cut-backs)",
            sol.strain_energy,
            sol.cutbacks.len()
        );
    }
}

/// The largest difference between the reactions of `sol` and `complete`
/// (at the load factors of `complete`'s steps, which `sol` reaches too) at any step and any support
/// group component, relative to the largest reaction magnitude of
/// `complete` over all steps (the normal reaction of the press).
fn reaction_error(sol: &Solution, complete: &Solution) -> f64 {
    let scale = complete
        .step_records
        .iter()
        .flat_map(|r| r.reactions.iter())
        .map(|[x, y]| x.hypot(*y))
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for b in &complete.step_records {
        let a = sol
            .step_records
            .iter()
            .find(|a| a.load_factor == b.load_factor)
            .unwrap_or_else(|| panic!("no step at load factor {}", b.load_factor));
        for (ra, rb) in a.reactions.iter().zip(&b.reactions) {
            worst = worst.max((ra[0] - rb[0]).abs()).max((ra[1] - rb[1]).abs());
        }
    }
    worst / scale
}

/// The relative strain-energy error of `sol` against `complete`.
fn energy_error(sol: &Solution, complete: &Solution) -> f64 {
    sol.strain_energy / complete.strain_energy - 1.0
}

/// Re-pairing at the step end (issue #8 §2): Types 3–6 follow the complete
/// formulation across master nodes. At 20 steps every point crosses one
/// or two master nodes per sliding step and every sliding step is
/// repeated (once for the new segments, once for the anchor iteration);
/// at 20 and 40 steps the reactions stay within 1 % of the complete
/// formulation's at every step and the energy within 0.05 % (issue #8's
/// target).
#[test]
fn repairing_types_follow_the_complete_formulation() {
    let scene = scene();
    let complete: Vec<Solution> = [20, 40]
        .iter()
        .map(|&n| run(&scene, Method::Complete, n))
        .collect();
    for method in TYPES_3_TO_6 {
        let mut errors = Vec::new();
        for c in &complete {
            let sol = run(&scene, method, c.steps);
            assert_balanced(&sol, &method.to_string());
            let (e, r) = (energy_error(&sol, c), reaction_error(&sol, c));
            println!(
                "type {method}, {} steps: energy error {e:+.3e}, reaction error {r:.3e}, \
                 {} repeats, {} cut-backs",
                c.steps,
                sol.repeats,
                sol.cutbacks.len()
            );
            assert!(
                r < 1e-2,
                "type {method}, {} steps: reactions {r:e}",
                c.steps
            );
            assert!(sol.repeats > 0, "type {method}");
            errors.push(e.abs());
        }
        // issue #8's target: within 0.05 % of the complete strain energy
        assert!(
            errors.iter().all(|&e| e < 5e-4),
            "type {method}: {errors:?}"
        );
    }
}

/// Without re-pairing (`[newton] repair = false`) and with the expansions
/// at the step start (the paper's scheme) the failure of issue #8 is back
/// (Type 6, 20 steps: -20 %) and the points that ended on another master
/// segment are listed; the Taylor remainder shows it.
#[test]
fn without_repairing_the_kink_error_is_back_and_reported() {
    let scene = scene();
    let complete = run(&scene, Method::Complete, 20);
    let options = |repair| SolveOptions {
        method: Method::Approx(ApproxType::Type6),
        steps: 20,
        repair,
        expand_at: ExpansionPoint::Start,
        ..SolveOptions::from_scene(&scene)
    };
    let off = run_with(&scene, &options(false));
    let on = run_with(&scene, &options(true));
    let (e_off, e_on) = (energy_error(&off, &complete), energy_error(&on, &complete));
    println!("type 6, 20 steps: energy error {e_off:+.3e} without re-pairing, {e_on:+.3e} with");
    assert!(e_off.abs() > 0.1 && e_on.abs() < 0.1 * e_off.abs());
    assert_eq!(off.repeats, 0);
    assert!(off.step_records.iter().any(|r| !r.unsettled.is_empty()));
    let worst = |s: &Solution| {
        s.step_records
            .iter()
            .filter_map(|r| r.taylor_remainder)
            .fold(0.0, f64::max)
    };
    assert!(
        worst(&off) > 5.0 * worst(&on),
        "{} vs {}",
        worst(&off),
        worst(&on)
    );
}

/// Held out (not used to design the scheme): the closest-point
/// formulation on the same scene, 20 steps: the reactions of Types 3 and
/// 6 within 1 % of the complete formulation's.
#[test]
fn repairing_holds_with_the_closest_point_formulation() {
    let scene = scene();
    let options = |method| SolveOptions {
        method,
        steps: 20,
        formulation: Some(Formulation::ClosestPoint),
        ..SolveOptions::from_scene(&scene)
    };
    let complete = run_with(&scene, &options(Method::Complete));
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let sol = run_with(&scene, &options(Method::Approx(ty)));
        let (e, r) = (
            energy_error(&sol, &complete),
            reaction_error(&sol, &complete),
        );
        println!(
            "closest-point, type {ty}, 20 steps: energy error {e:+.3e}, reaction error {r:.3e}"
        );
        assert!(r < 1e-2, "type {ty}: {r:e}");
        assert!(e.abs() < 1e-2, "type {ty}: {e:e}");
    }
}

/// Adaptive accuracy (`[newton] taylor_tolerance`) on the held-out scene
/// with 40 scheduled steps and the expansions at the step start (where
/// some points keep their step-start expansion: remainders up to 2.6e-4):
/// Types 3 and 6 re-take the expansions of the points above the tolerance
/// at the converged end and solve the step again, instead of halving it.
/// Every accepted step ends within the tolerance with no step halved, the
/// energy within 5e-4 (measured 2.6e-6 and 1.3e-5; the plain runs are
/// 2.4e-4 and 1.7e-4 off), at most 2.5 times the complete formulation's
/// linear solves (measured 351 and 341 against 151; halving the steps
/// took 570 and 580).
#[test]
fn re_taking_the_points_above_the_taylor_tolerance_meets_it_without_halving() {
    let scene = held_out();
    let complete = run(&scene, Method::Complete, 40);
    let tolerance = 1e-4;
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let options = |taylor_tolerance| SolveOptions {
            method: Method::Approx(ty),
            steps: 40,
            taylor_tolerance,
            expand_at: ExpansionPoint::Start,
            ..SolveOptions::from_scene(&scene)
        };
        let sol = run_with(&scene, &options(Some(tolerance)));
        let plain = run_with(&scene, &options(None));
        let (e, r) = (
            energy_error(&sol, &complete),
            reaction_error(&sol, &complete),
        );
        let cost = |s: &Solution| {
            (
                s.newton_iterations + s.failed_iterations + s.repeated_iterations,
                s.kernel_counts.evaluate + s.kernel_counts.project + s.step_end_projections,
            )
        };
        println!(
            "type {ty}, 40 steps, tolerance {tolerance:e}: energy error {e:+.3e} (without: {:+.3e}), \
             reaction error {r:.3e}, {} halvings, {} steps; cost (iterations, kernel calls) {:?} \
             against complete {:?}",
            energy_error(&plain, &complete),
            sol.accuracy_halvings.len(),
            sol.step_records.len(),
            cost(&sol),
            cost(&complete)
        );
        assert!(sol.accuracy_halvings.is_empty(), "type {ty}");
        // the plain run is above the tolerance somewhere: points were re-taken
        let worst = |s: &Solution| {
            s.step_records
                .iter()
                .filter_map(|r| r.taylor_remainder)
                .fold(0.0, f64::max)
        };
        assert!(worst(&plain) > tolerance, "type {ty}: {:e}", worst(&plain));
        for rec in &sol.step_records {
            let t = rec.taylor_remainder.unwrap_or(0.0);
            assert!(t <= tolerance, "type {ty} at {}: {t:e}", rec.load_factor);
        }
        assert!(e.abs() < 5e-4, "type {ty}: {e:e}");
        assert!(
            e.abs() < 0.2 * energy_error(&plain, &complete).abs(),
            "type {ty}: {e:e}"
        );
        assert!(r < 1e-2, "type {ty}: {r:e}");
        assert!(
            cost(&sol).0 as f64 <= 2.5 * cost(&complete).0 as f64,
            "type {ty}: {:?}",
            cost(&sol)
        );
    }
}

/// Held out: `scenes/sliding-held-out.toml` (another block, mesh, material
/// and slide direction), 20 and 40 steps: the reactions of Types 3 and 6
/// within 1 % of the complete formulation's at every step, every step
/// re-paired, and the energy error falling with the step count.
#[test]
fn repairing_holds_on_the_held_out_scene() {
    let scene = held_out();
    let complete: Vec<Solution> = [20, 40]
        .iter()
        .map(|&n| run(&scene, Method::Complete, n))
        .collect();
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let mut errors = Vec::new();
        for c in &complete {
            let sol = run(&scene, Method::Approx(ty), c.steps);
            let (e, r) = (energy_error(&sol, c), reaction_error(&sol, c));
            println!(
                "held out, type {ty}, {} steps: energy error {e:+.3e}, reaction error {r:.3e}, \
                 {} repeats",
                c.steps, sol.repeats
            );
            assert!(r < 1e-2, "type {ty}, {} steps: {r:e}", c.steps);
            assert!(sol.repeats > 0);
            errors.push(e.abs());
        }
        assert!(errors.iter().all(|&e| e < 5e-4), "type {ty}: {errors:?}");
    }
}

/// Held out, from 40 steps on (where some points no longer cross a node
/// in a step and keep their step-start expansion): with the expansions at
/// the step start, the energy error of Types 3 and 6 falls as steps are
/// added.
#[test]
fn held_out_error_falls_from_40_steps() {
    let scene = held_out();
    let complete = run(&scene, Method::Complete, 40);
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let at_start = |steps| SolveOptions {
            method: Method::Approx(ty),
            steps,
            expand_at: ExpansionPoint::Start,
            ..SolveOptions::from_scene(&scene)
        };
        let errors: Vec<f64> = [40, 80]
            .iter()
            .map(|&n| energy_error(&run_with(&scene, &at_start(n)), &complete).abs())
            .collect();
        println!("held out, type {ty}: energy errors at 40 / 80 steps {errors:?}");
        assert!(errors[1] < 0.5 * errors[0], "type {ty}: {errors:?}");
    }
}

/// Points that cycle at a concave master node (converged on one segment
/// they project into the other, and back): at 40 steps the complete
/// formulation ties 4 points to a node; Types 3 and 6 tie them too
/// (`repair.rs`, "Points cycling at a node") instead of leaving them on
/// one segment's line (before: 9–10 unsettled points, reactions 0.35 %
/// off; 1.5 % at 160 steps). Measured: reactions within 0.036 %, no point
/// unsettled.
#[test]
fn points_cycling_at_a_node_are_tied() {
    let scene = scene();
    let complete = run(&scene, Method::Complete, 40);
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let sol = run(&scene, Method::Approx(ty), 40);
        let ties: usize = sol.step_records.iter().map(|r| r.node_ties.len()).sum();
        let unsettled: usize = sol.step_records.iter().map(|r| r.unsettled.len()).sum();
        let r = reaction_error(&sol, &complete);
        println!(
            "type {ty}, 40 steps: {ties} tied points over the steps, {unsettled} unsettled, reaction error {r:.3e}"
        );
        assert!(ties > 0, "type {ty}");
        assert_eq!(unsettled, 0, "type {ty}");
        assert!(r < 1e-3, "type {ty}: {r:e}");
    }
}

/// Issue #8's targets at every step count of the safety map (10, 20, 40,
/// 80, 160) on both sliding scenes, Types 3–6: the final strain energy
/// within 0.05 % of the complete formulation's and the reactions within
/// 1 % at every step. Measured: energy errors at most 2.4e-2 % (held out,
/// 40 steps), reactions at most 0.043 %. About a minute in the dev
/// profile; run it with `cargo test --release -p gapsim-solver --test
/// sliding -- --ignored`.
#[test]
#[ignore = "the full step-count sweep; run in release"]
fn targets_hold_at_every_step_count() {
    for scene in [scene(), held_out()] {
        for steps in [10, 20, 40, 80, 160] {
            let complete = run(&scene, Method::Complete, steps);
            for method in TYPES_3_TO_6 {
                let sol = run(&scene, method, steps);
                let (e, r) = (
                    energy_error(&sol, &complete),
                    reaction_error(&sol, &complete),
                );
                println!(
                    "{}, type {method}, {steps} steps: energy error {e:+.3e}, reaction error {r:.3e}",
                    scene.name.as_deref().unwrap_or("?")
                );
                assert!(e.abs() < 5e-4, "type {method}, {steps} steps: {e:e}");
                assert!(r < 1e-2, "type {method}, {steps} steps: {r:e}");
            }
        }
    }
}

/// Re-pairing is the default: `scenes/sliding.toml` without its `[newton]
/// repair = true` parses to `repair = true`, and Types 3 and 6 at 20 steps
/// are then within 0.05 % of the complete formulation's energy (without
/// re-pairing Type 6 is 20 % off, above); the paper scene sets `repair =
/// false` (the paper's scheme) and keeps it.
#[test]
fn repairing_is_the_default() {
    let without_key = SLIDING.replace("repair = true", "");
    assert_ne!(without_key, SLIDING);
    let scene = Scene::from_toml_str(&without_key, "sliding.toml").unwrap();
    assert!(scene.newton.repair);
    assert!(SolveOptions::from_scene(&scene).repair);
    assert!(SolveOptions::default().repair);
    let complete = run(&scene, Method::Complete, 20);
    for ty in [ApproxType::Type3, ApproxType::Type6] {
        let sol = run(&scene, Method::Approx(ty), 20);
        let e = energy_error(&sol, &complete);
        println!("type {ty}, 20 steps, no repair key: energy error {e:+.3e}");
        assert!(sol.repeats > 0 && e.abs() < 5e-4, "type {ty}: {e:e}");
    }
    let paper = Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )
    .unwrap();
    assert!(!paper.newton.repair);
    assert!(!SolveOptions::from_scene(&paper).repair);
}
