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
//!   approximation). Their energies are far off at few steps (10 steps:
//!   Type 1 1.939 after 9 cut-backs, Type 2 2.236, Types 3/5 0.1726,
//!   Types 4/6 0.1713, i.e. -62 %; Type 6 at 20 steps 0.361, -20 %): the
//!   failure issue #8 is about, not asserted here so that its fix can
//!   change it.

use solver::{Method, Scene, Solution, SolveOptions, solve};

const SLIDING: &str = include_str!("../../scenes/sliding.toml");

fn scene() -> Scene {
    Scene::from_toml_str(SLIDING, "sliding.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn run(scene: &Scene, method: Method, steps: usize) -> Solution {
    let options = SolveOptions {
        method,
        steps,
        ..SolveOptions::from_scene(scene)
    };
    solve(scene, &options).unwrap_or_else(|e| panic!("sliding, {method}, {steps} steps: {e}"))
}

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
/// and the balanced reactions.
#[test]
fn complete_formulation_is_step_count_independent() {
    let scene = scene();
    let runs: Vec<Solution> = [10, 20, 40]
        .iter()
        .map(|&n| run(&scene, Method::Complete, n))
        .collect();
    for sol in &runs {
        assert_balanced(sol, &format!("complete, {} steps", sol.steps));
        assert!(sol.cutbacks.is_empty(), "{:?}", sol.cutbacks);
    }
    // the energy at the load factors every run reaches (k / 10)
    let mut worst: f64 = 0.0;
    for k in 1..=10 {
        let energies: Vec<f64> = runs
            .iter()
            .map(|sol| {
                let stride = sol.steps / 10;
                let r = &sol.step_records[k * stride - 1];
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
