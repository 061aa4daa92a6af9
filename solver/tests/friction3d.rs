//! Coulomb friction in 3D (`solver::contact::friction`, the face slip of
//! `solver::contact::face`) on the 3D dragged block,
//! `scenes/dragged-block3d.toml`: a block pressed 0.01 onto a base and
//! dragged (0.3, 0.2) across it, along no mesh line (mu = 0.3, unilateral
//! slave-normal contact, non-matching faces).
//!
//! What holds, measured in the debug profile (each solve about a second):
//!
//! * gross slip, with the complete formulation and Types 2–6: every
//!   pressed node slips with `|shear| = mu p` to round-off, in the plane,
//!   against the drag; the drag (the reaction of `slide`) is mu times the
//!   press to 0.03 % (complete; Types 2–6 within 0.3 %) and along the
//!   prescribed direction; Newton takes at most 3 iterations per sliding
//!   step (the slip rows' linearisation is consistent);
//! * a drag back along the same line: every node slips the other way and
//!   the slip accumulates along the path;
//! * a small drag (with mu = 1.5, which holds the press's radial slip)
//!   sticks every pressed node but at most two singular corners, the
//!   shear resultant balancing the drag;
//! * `friction = 0` gives the frictionless solve bit for bit;
//! * hard cases: Type 1 and a negative, NaN or infinite coefficient are
//!   refused with the reason; a pair that never touches stays open
//!   without shear or multipliers; lifted while sliding, every node opens
//!   and drops its shear, keeping the slip it accumulated; a drag reversed
//!   within one step ends with every pressed node slipping backwards.

use contact_kernels::ApproxType;
use solver::{Method, Scene, Solution, SolveOptions, solve};

const DRAGGED: &str = include_str!("../../scenes/dragged-block3d.toml");

fn scene_with(edit: impl Fn(String) -> String) -> Scene {
    Scene::from_toml_str(&edit(DRAGGED.to_owned()), "dragged-block3d.toml")
        .unwrap_or_else(|e| panic!("{e}"))
}

fn solve_with(scene: &Scene, method: Method) -> Solution<3> {
    let opts = SolveOptions {
        method,
        ..SolveOptions::from_scene(scene)
    };
    solve::<3>(scene, &opts).unwrap_or_else(|e| panic!("{method}: {e}"))
}

/// One row of `contact.csv` at the final state.
struct Row {
    x: [f64; 2],
    pressure: f64,
    area: f64,
    shear: [f64; 3],
    state: String,
    slip: Option<f64>,
}

fn rows(sol: &Solution<3>) -> Vec<Row> {
    let text = solver::report::contact_csv(sol, &sol.final_state).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[18..],
        ["shear_x", "shear_y", "shear_z", "state", "slip"]
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 23, "{l}");
            let num = |k: usize| f[k].parse::<f64>().unwrap();
            Row {
                x: [num(2), num(3)],
                pressure: num(6),
                area: num(14),
                shear: [num(18), num(19), num(20)],
                state: f[21].to_owned(),
                slip: (!f[22].is_empty()).then(|| num(22)),
            }
        })
        .collect()
}

/// The final reactions of the support groups `press` and `slide`.
fn press_and_slide(sol: &Solution<3>) -> ([f64; 3], [f64; 3]) {
    let last = sol.step_records.last().unwrap();
    let group = |name: &str| {
        let k = sol.support_groups.iter().position(|g| g == name).unwrap();
        last.reactions[k]
    };
    (group("press"), group("slide"))
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[test]
fn gross_slip_drags_with_mu_times_the_press_along_the_drag_for_every_type() {
    let scene = scene_with(|s| s);
    let mu = 0.3;
    let drag = [0.3 / 0.13f64.sqrt(), 0.2 / 0.13f64.sqrt(), 0.0];
    let mut methods = vec![Method::Complete];
    methods.extend([2, 3, 4, 5, 6].map(|t| Method::Approx(ApproxType::from_index(t).unwrap())));
    for method in methods {
        let sol = solve_with(&scene, method);
        let table = rows(&sol);
        assert_eq!(table.len(), 25);
        let pressed: Vec<&Row> = table.iter().filter(|r| r.pressure > 1e-9).collect();
        assert!(pressed.len() >= 20, "{method}: {} pressed", pressed.len());
        for r in &pressed {
            assert_eq!(r.state, "slip", "{method}");
            let shear = norm(r.shear);
            assert!(
                (shear - mu * r.pressure).abs() <= 1e-10 * r.pressure,
                "{method}: |shear| {shear} against mu p {}",
                mu * r.pressure
            );
            // against the drag, in the (nearly flat) contact plane
            let along = r.shear[0] * drag[0] + r.shear[1] * drag[1];
            assert!(along < -0.999 * shear, "{method}: {:?}", r.shear);
            assert!(r.shear[2].abs() < 0.02 * shear, "{method}: {:?}", r.shear);
            let slip = r.slip.unwrap();
            assert!((0.33..0.3606).contains(&slip), "{method}: slip {slip}");
        }
        let (press, slide) = press_and_slide(&sol);
        let tangential = norm([slide[0], slide[1], 0.0]);
        let ratio = tangential / -press[2];
        assert!(
            (ratio - mu).abs() < 0.005 * mu,
            "{method}: drag / press = {ratio}"
        );
        let cos = (slide[0] * drag[0] + slide[1] * drag[1]) / tangential;
        assert!(cos > 1.0 - 1e-5, "{method}: drag along {slide:?}");
        assert_eq!(sol.final_state.friction.len(), 25, "every slave node");
        // a consistent linearisation: quadratic convergence while sliding
        for record in &sol.step_records[3..] {
            assert!(record.iterations <= 3, "{method}: {:?}", record.iterations);
        }
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
    let mut short = 0;
    for r in rows(&sol).iter().filter(|r| r.pressure > 1e-9) {
        assert_eq!(r.state, "slip");
        assert!(
            r.shear[0] > 0.0 && r.shear[1] > 0.0,
            "against the drag back: {:?}",
            r.shear
        );
        // there and back (2 x 0.3606 less the block's shear), but for the
        // corners that lifted off on the way there
        let slip = r.slip.unwrap();
        assert!(slip < 0.7212, "slip {slip}");
        if slip < 0.66 {
            short += 1;
        }
    }
    assert!(short <= 2, "{short} nodes slipped less than the path");
}

/// Whether a row's node is a corner of the block's unit square face.
fn corner(r: &Row) -> bool {
    r.x.iter()
        .all(|&c| (c - 1.0).abs() < 0.01 || (c - 2.0).abs() < 0.01)
}

#[test]
fn a_small_drag_sticks_every_pressed_node_but_the_corners_and_the_shear_balances_it() {
    // mu = 1.5 holds the press's radial slip (the block spreads over the
    // base) but at the corners, where the pressure is singular
    let scene = scene_with(|s| {
        s.replace("ux = 0.3\nuy = 0.2", "ux = 0.0006\nuy = 0.0004")
            .replace("friction = 0.3", "friction = 1.5")
    });
    let sol = solve_with(&scene, Method::Complete);
    let (press, slide) = press_and_slide(&sol);
    assert!(norm([slide[0], slide[1], 0.0]) < 1.5 * -press[2] / 10.0);
    let mut resultant = [0.0; 2];
    let mut corners_slipping = 0;
    for r in rows(&sol).iter().filter(|r| r.pressure > 1e-9) {
        if corner(r) && r.state == "slip" {
            corners_slipping += 1;
        } else {
            assert_eq!(r.state, "stick", "at {:?}", r.x);
            // what it slipped while the block was pressed, a fraction of
            // the drag (7.2e-4)
            assert!(r.slip.unwrap() < 1e-4, "slip {:?}", r.slip);
            assert!(norm(r.shear) <= 1.5 * r.pressure);
        }
        resultant[0] += r.shear[0] * r.area;
        resultant[1] += r.shear[1] * r.area;
    }
    assert!(corners_slipping <= 2, "{corners_slipping} corners slip");
    for c in 0..2 {
        assert!(
            (resultant[c] + slide[c]).abs() < 0.05 * slide[c].abs(),
            "shear resultant {resultant:?} against the drag {slide:?}"
        );
    }
}

#[test]
fn zero_friction_is_the_frictionless_solve_bit_for_bit() {
    let with = scene_with(|s| s.replace("friction = 0.3", "friction = 0.0"));
    let without = scene_with(|s| s.replace("friction = 0.3\n", ""));
    for method in [Method::Complete, Method::Approx(ApproxType::Type3)] {
        let (a, b) = (solve_with(&with, method), solve_with(&without, method));
        assert_eq!(a.strain_energy.to_bits(), b.strain_energy.to_bits());
        assert_eq!(a.final_state.displacements, b.final_state.displacements);
        assert_eq!(a.final_state.multipliers, b.final_state.multipliers);
        assert!(a.final_state.friction.is_empty());
    }
}

#[test]
fn ldlt_is_refused_with_friction_and_says_why() {
    let scene = scene_with(|s| s);
    let opts = SolveOptions {
        linear: solver::linear::LinearSolverKind::Ldlt,
        ..SolveOptions::from_scene(&scene)
    };
    let err = solve::<3>(&scene, &opts).unwrap_err().to_string();
    assert!(
        err.contains("interface") && err.contains("unsymmetric") && err.contains("lu"),
        "{err}"
    );
    // frictionless, the same scene takes LDLᵀ
    let frictionless = scene_with(|s| s.replace("friction = 0.3\n", ""));
    let opts = SolveOptions {
        linear: solver::linear::LinearSolverKind::Ldlt,
        ..SolveOptions::from_scene(&frictionless)
    };
    solve::<3>(&frictionless, &opts).unwrap();
}

#[test]
fn type_1_and_bad_coefficients_are_refused_in_3d_too() {
    let scene = scene_with(|s| s);
    let opts = SolveOptions {
        method: Method::Approx(ApproxType::Type1),
        ..SolveOptions::from_scene(&scene)
    };
    let err = solve::<3>(&scene, &opts).unwrap_err();
    assert!(
        matches!(err, solver::SolverError::NotApplicable(_))
            && err.to_string().contains("Type 1 cannot carry friction"),
        "{err}"
    );
    for bad in ["-0.1", "nan", "inf"] {
        let text = DRAGGED.replace("friction = 0.3", &format!("friction = {bad}"));
        let err = Scene::from_toml_str(&text, "bad.toml")
            .map(|s| solve::<3>(&s, &SolveOptions::from_scene(&s)).map(|_| ()))
            .map_or_else(|e| e.to_string(), |r| r.unwrap_err().to_string());
        assert!(err.contains("contact[0].friction"), "{bad}: {err}");
    }
}

#[test]
fn a_pair_that_never_touches_stays_open_without_shear() {
    // the block 0.1 above the base, pressed only 0.01: it never touches
    let scene = scene_with(|s| {
        s.replace("origin = [1.0, 1.0, 0.5]", "origin = [1.0, 1.0, 0.6]")
            .replace("z = 1.0", "z = 1.1")
    });
    let sol = solve_with(&scene, Method::Complete);
    let rows = rows(&sol);
    assert!(!rows.is_empty());
    for r in rows {
        assert_eq!(r.state, "open");
        assert_eq!(r.shear, [0.0; 3]);
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
            "uz = -0.01\namplitude = [[0.0, 0.0], [0.2, 1.0], [1.0, 1.0]]",
            "uz = -0.01\namplitude = [[0.0, 0.0], [0.2, 1.0], [0.6, 1.0], [1.0, -2.0]]",
        )
    });
    let sol = solve_with(&scene, Method::Complete);
    let middle = sol
        .step_records
        .iter()
        .position(|r| (r.load_factor - 0.6).abs() < 1e-12)
        .unwrap();
    // sliding before the lift (the drag's reaction), all open after it
    let k = sol
        .support_groups
        .iter()
        .position(|g| g == "slide")
        .unwrap();
    assert!(norm(sol.step_records[middle].reactions[k]) > 0.05);
    let rows = rows(&sol);
    assert!(!rows.is_empty());
    for r in &rows {
        assert_eq!(
            (r.state.as_str(), r.shear, r.pressure),
            ("open", [0.0; 3], 0.0)
        );
    }
    // every node slid before the lift but the trailing corner, which the
    // drag's tilting moment lifts off (its slip stays below 1e-3)
    let slid = rows.iter().filter(|r| r.slip.unwrap() > 0.2).count();
    assert_eq!(slid + 1, rows.len());
}

#[test]
fn a_reversal_within_one_step_converges_to_the_reversed_slip() {
    // four steps of 0.25: the third (0.5 to 0.75) drags forward to 0.6 and
    // back; at its end every pressed node slips backwards: its shear on the
    // slave points along the drag (+x, +y), against the block's motion
    let scene = scene_with(|s| {
        s.replace(
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [1.0, 1.0]]",
            "amplitude = [[0.0, 0.0], [0.2, 0.0], [0.6, 1.0], [1.0, 0.0]]",
        )
        .replace("steps = [10]", "steps = [4]")
    });
    let sol = solve_with(&scene, Method::Complete);
    assert!((sol.step_records[2].load_factor - 0.75).abs() < 1e-12);
    let pressed: Vec<Row> = rows(&sol)
        .into_iter()
        .filter(|r| r.pressure > 0.0)
        .collect();
    assert!(pressed.len() > 20, "{}", pressed.len());
    for r in &pressed {
        assert_eq!(r.state, "slip", "{:?}", r.x);
        let along = (0.3 * r.shear[0] + 0.2 * r.shear[1]) / (0.13f64.sqrt() * norm(r.shear));
        assert!(along > 0.99, "{:?}: {along}", r.x);
    }
}
