//! Coulomb friction in 2D (`solver::contact::friction`) on the dragged
//! block, `scenes/dragged-block.toml`: a block pressed 0.01 onto a base and
//! dragged 0.5 across it (mu = 0.3, unilateral slave-normal contact).
//!
//! What holds, measured in the debug profile (each solve a fraction of a
//! second):
//!
//! * gross slip, with the complete formulation and Types 2–6: every
//!   pressed node slips with `|shear| = mu p` to round-off, against the
//!   drag; the drag (the reaction of `slide`) is mu times the press (the
//!   reaction of `press`) to 0.42 % (complete), the tilt of the deformed
//!   slave face; the accumulated slip is the drag less the block's
//!   elastic shear (0.49 of 0.5);
//! * a drag back to the start (load reversal): every node slips the other
//!   way and the slip accumulates along the path;
//! * a small tangential load (a tenth of `mu N`, mu = 0.6) sticks every
//!   node, balanced by the shear; a larger one (0.5 of 0.6) slips the
//!   leading corner first (partial slip); one above `mu N` has no
//!   equilibrium and the solve says so;
//! * `friction = 0` gives the frictionless solve bit for bit;
//! * bad coefficients, persistent pairs and Type 1 are refused with the
//!   key and the reason.

use contact_kernels::ApproxType;
use solver::{Method, Scene, Solution, SolveOptions, solve};

const DRAGGED: &str = include_str!("../../scenes/dragged-block.toml");

fn scene_with(edit: impl Fn(String) -> String) -> Scene {
    Scene::from_toml_str(&edit(DRAGGED.to_owned()), "dragged-block.toml")
        .unwrap_or_else(|e| panic!("{e}"))
}

fn solve_with(scene: &Scene, method: Method) -> Solution {
    let opts = SolveOptions {
        method,
        ..SolveOptions::from_scene(scene)
    };
    solve::<2>(scene, &opts).unwrap_or_else(|e| panic!("{method}: {e}"))
}

/// One row of `contact.csv` at the final state: pressure, tributary
/// length, shear, state and slip.
struct Row {
    pressure: f64,
    tributary: f64,
    shear: [f64; 2],
    state: String,
    slip: Option<f64>,
}

fn rows(sol: &Solution) -> Vec<Row> {
    let text = solver::report::contact_csv(sol, &sol.final_state).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[14..], ["shear_x", "shear_y", "state", "slip"]);
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 18, "{l}");
            let num = |k: usize| f[k].parse::<f64>().unwrap();
            Row {
                pressure: num(5),
                tributary: num(10),
                shear: [num(14), num(15)],
                state: f[16].to_owned(),
                slip: (!f[17].is_empty()).then(|| num(17)),
            }
        })
        .collect()
}

/// The final reactions of the support groups `press` and `slide`.
fn press_and_slide(sol: &Solution) -> ([f64; 2], [f64; 2]) {
    let last = sol.step_records.last().unwrap();
    let group = |name: &str| {
        let k = sol.support_groups.iter().position(|g| g == name).unwrap();
        last.reactions[k]
    };
    (group("press"), group("slide"))
}

#[test]
fn gross_slip_drags_with_mu_times_the_press_for_every_type_that_carries_friction() {
    let scene = scene_with(|s| s);
    let mu = 0.3;
    let mut methods = vec![Method::Complete];
    methods.extend([2, 3, 4, 5, 6].map(|t| Method::Approx(ApproxType::from_index(t).unwrap())));
    for method in methods {
        let sol = solve_with(&scene, method);
        let table = rows(&sol);
        assert_eq!(table.len(), 6);
        for r in &table {
            assert!(r.pressure > 0.0, "{method}");
            assert_eq!(r.state, "slip", "{method}");
            let shear = r.shear[0].hypot(r.shear[1]);
            assert!(
                (shear - mu * r.pressure).abs() <= 1e-12 * r.pressure,
                "{method}: |shear| {shear} against mu p {}",
                mu * r.pressure
            );
            // against the drag (+x)
            assert!(r.shear[0] < 0.0, "{method}");
            let slip = r.slip.unwrap();
            assert!((0.45..0.5).contains(&slip), "{method}: slip {slip}");
        }
        let (press, slide) = press_and_slide(&sol);
        let ratio = -slide[0] / press[1];
        assert!(
            (ratio - mu).abs() < 0.01 * mu,
            "{method}: drag / press = {ratio}"
        );
        assert_eq!(
            sol.final_state.friction.len(),
            6,
            "one tangential multiplier per slave node"
        );
    }
}

#[test]
fn a_drag_back_slips_the_other_way_and_the_slip_accumulates() {
    let scene = scene_with(|s| {
        s.replace(
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [1.0, 1.0]]",
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [0.6, 1.0], [1.0, 0.0]]",
        )
    });
    let sol = solve_with(&scene, Method::Complete);
    for r in rows(&sol) {
        assert_eq!(r.state, "slip");
        assert!(r.shear[0] > 0.0, "against the drag back (-x)");
        let slip = r.slip.unwrap();
        assert!((0.9..1.0).contains(&slip), "slip {slip}");
    }
}

/// The dragged block held by friction only: its top edge pressed 0.01 (x
/// free), then a traction `q` along x on it (`Q = q` over the unit width);
/// `N` is about 0.994.
fn held_by_friction(mu: f64, q: f64) -> Scene {
    scene_with(|s| {
        let i = s.find("[[prescribe]]\nname = \"slide\"").unwrap();
        let j = s.find("[[contact]]").unwrap();
        let traction = format!(
            "[[traction]]\nbody = \"block\"\nside = \"top\"\nforce_per_length = [{q:?}, 0.0]\namplitude = [[0.0, 0.0], [0.2, 0.0], [1.0, 1.0]]\n\n"
        );
        format!("{}{traction}{}", &s[..i], &s[j..])
            .replace("friction = 0.3", &format!("friction = {mu:?}"))
    })
}

#[test]
fn a_small_drag_sticks_every_node_and_a_larger_one_slips_the_corners_first() {
    // a tenth of mu N: every node sticks, the shear balances the load
    let sol = solve_with(&held_by_friction(0.6, 0.06), Method::Complete);
    let mut resultant = 0.0;
    for r in &rows(&sol) {
        assert_eq!(r.state, "stick");
        assert!(r.slip.unwrap() < 1e-12);
        assert!(r.shear[0].hypot(r.shear[1]) < 0.6 * r.pressure);
        resultant += r.shear[0] * r.tributary;
    }
    assert!((resultant + 0.06).abs() < 1e-3, "resultant {resultant}");
    // five sixths of mu N: partial slip, starting at the leading corner
    // (the most pressed node, x = 2)
    let sol = solve_with(&held_by_friction(0.6, 0.5), Method::Complete);
    let table = rows(&sol);
    let states: Vec<&str> = table.iter().map(|r| r.state.as_str()).collect();
    assert_eq!(states[5], "slip", "{states:?}");
    assert!(table.iter().all(|r| r.pressure <= table[5].pressure));
    assert!(states.contains(&"stick"), "{states:?}");
}

#[test]
fn a_drag_above_mu_n_has_no_equilibrium_and_the_solve_says_so() {
    let scene = held_by_friction(0.6, 0.62);
    let err = solve::<2>(&scene, &SolveOptions::from_scene(&scene)).unwrap_err();
    assert!(err.to_string().contains("no convergence"), "{err}");
}

#[test]
fn zero_friction_is_the_frictionless_solve_bit_for_bit() {
    let with = scene_with(|s| s.replace("friction = 0.3", "friction = 0.0"));
    let without = scene_with(|s| s.replace("friction = 0.3\n", ""));
    for method in [Method::Complete, Method::Approx(ApproxType::Type1)] {
        let (a, b) = (solve_with(&with, method), solve_with(&without, method));
        assert_eq!(a.strain_energy.to_bits(), b.strain_energy.to_bits());
        assert_eq!(a.final_state.displacements, b.final_state.displacements);
        assert_eq!(a.final_state.multipliers, b.final_state.multipliers);
        assert!(a.final_state.friction.is_empty());
        let text = solver::report::contact_csv(&a, &a.final_state).unwrap();
        assert_eq!(
            text,
            solver::report::contact_csv(&b, &b.final_state).unwrap()
        );
        // frictionless and pressed: sliding freely, no shear, no slip
        for r in rows(&a) {
            assert_eq!(
                (r.state.as_str(), r.shear, r.slip),
                ("slip", [0.0; 2], None)
            );
        }
    }
}

#[test]
fn bad_coefficients_persistent_pairs_and_type_1_are_refused_with_the_reason() {
    // refused when the scene is read
    let refusal = |text: String| match Scene::from_toml_str(&text, "dragged-block.toml") {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    for bad in ["-0.1", "nan", "inf"] {
        let text = refusal(DRAGGED.replace("friction = 0.3", &format!("friction = {bad}")));
        assert!(
            text.contains("contact[0].friction") && text.contains(">= 0"),
            "{bad}: {text}"
        );
    }
    let text = refusal(DRAGGED.replace("mode = \"unilateral\"", "mode = \"persistent\""));
    assert!(
        text.contains("contact[0].friction") && text.contains("unilateral"),
        "{text}"
    );
    let scene = scene_with(|s| s);
    let opts = SolveOptions {
        method: Method::Approx(ApproxType::Type1),
        ..SolveOptions::from_scene(&scene)
    };
    let err = solve::<2>(&scene, &opts).unwrap_err();
    assert!(
        matches!(err, solver::SolverError::NotApplicable(_))
            && err.to_string().contains("Type 1 cannot carry friction"),
        "{err}"
    );
}

#[test]
fn a_pair_that_never_touches_stays_open_without_shear() {
    // the block 0.1 above the base, pressed only 0.01: it never touches
    let scene = scene_with(|s| {
        s.replace("origin = [1.0, 1.0]", "origin = [1.0, 1.1]")
            .replace("y = 1.5", "y = 1.6")
    });
    let sol = solve_with(&scene, Method::Complete);
    for r in rows(&sol) {
        assert_eq!(r.state, "open");
        assert_eq!(r.shear, [0.0; 2]);
        assert_eq!(r.pressure, 0.0);
        assert_eq!(r.slip, Some(0.0));
    }
    assert!(sol.final_state.multipliers.iter().all(|&l| l == 0.0));
}

#[test]
fn a_node_leaving_contact_while_sliding_drops_its_shear() {
    // pressed, dragged, then lifted 0.02 while the drag goes on
    let scene = scene_with(|s| {
        s.replace(
            "uy = -0.01\namplitude = [[0.0, 0.0], [0.2, 1.0], [1.0, 1.0]]",
            "uy = -0.01\namplitude = [[0.0, 0.0], [0.2, 1.0], [0.6, 1.0], [1.0, -2.0]]",
        )
    });
    let sol = solve_with(&scene, Method::Complete);
    let middle = sol
        .step_records
        .iter()
        .position(|r| (r.load_factor - 0.6).abs() < 1e-12)
        .unwrap();
    // sliding before the lift, all open after it
    assert!(sol.step_records[middle].reactions[0][0].abs() > 0.05);
    for r in rows(&sol) {
        assert_eq!(
            (r.state.as_str(), r.shear, r.pressure),
            ("open", [0.0; 2], 0.0)
        );
        assert!(r.slip.unwrap() > 0.1);
    }
}

#[test]
fn a_reversal_within_one_step_converges_to_the_reversed_slip() {
    // four steps of 0.25: the third (0.5 to 0.75) drags forward to 0.6 and
    // back; at its end every node slips backwards
    let scene = scene_with(|s| {
        s.replace(
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [1.0, 1.0]]",
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [0.6, 1.0], [1.0, 0.0]]",
        )
        .replace("steps = [20]", "steps = [4]")
    });
    let sol = solve_with(&scene, Method::Complete);
    let third = &sol.step_records[2];
    assert!(
        (third.load_factor - 0.75).abs() < 1e-12,
        "{}",
        third.load_factor
    );
    for r in rows(&sol) {
        assert_eq!(r.state, "slip");
        assert!(r.shear[0] > 0.0);
    }
}
