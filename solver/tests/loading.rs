//! Load curves (`amplitude` on `[[load]]`, `[[traction]]`, `[[prescribe]]`)
//! and reaction forces (one support group per `[[fix]]` and
//! `[[prescribe]]`), issue #7: their validation, a plateau that changes
//! nothing to the bit, a curve that goes back, press-then-slide on two
//! blocks in contact, and the equilibrium of the reactions with the loads.

use solver::{Method, Scene, SceneError, Solution, SolveOptions, solve};

/// One element, 1 x 1, fixed at x = 0, its right edge prescribed in x and
/// its top-right node loaded, all with `{curve}` (a TOML fragment: empty or
/// `amplitude = ...`), to load factor 1 in `steps` steps.
fn one_element(curve: &str, steps: usize) -> String {
    format!(
        r#"
[material]
young = 100.0
poisson = 0.3

[[body]]
name = "a"
origin = [0.0, 0.0]
size = [1.0, 1.0]
nx = 1
ny = 1

[[fix]]
x = 0.0

[[prescribe]]
name = "right"
x = 1.0
ux = 0.02
{curve}

[[load]]
at = [1.0, 1.0]
force = [0.0, -0.5]
{curve}

[loading]
load_factor_end = 1.0
steps = [{steps}]
"#
    )
}

fn run(text: &str, origin: &str, method: Method, steps: usize) -> Solution {
    let scene = Scene::from_toml_str(text, origin).unwrap_or_else(|e| panic!("{e}"));
    let options = SolveOptions {
        method,
        steps,
        ..SolveOptions::from_scene(&scene)
    };
    solve(&scene, &options).unwrap_or_else(|e| panic!("{origin}, {method}, {steps} steps: {e}"))
}

fn invalid(text: &str) -> String {
    match Scene::from_toml_str(text, "bad.toml") {
        Err(e @ SceneError::Invalid { .. }) => e.to_string(),
        other => panic!("expected an invalid-value error, got {other:?}"),
    }
}

/// A bad curve names the file, the item and the point.
#[test]
fn bad_curves_name_the_item_and_the_point() {
    let base = one_element("", 1);
    let second_load = "[[load]]\nat = [1.0, 0.0]\nforce = [1.0, 0.0]\n";
    let with =
        |item: &str, curve: &str| base.replace("[loading]", &format!("{item}{curve}\n[loading]"));
    assert_eq!(
        invalid(&with(
            second_load,
            "amplitude = [[0.0, 0.0], [0.5, 1.0], [0.5, 2.0]]"
        )),
        "bad.toml: load[1].amplitude[2]: load factors must increase"
    );
    assert_eq!(
        invalid(&with(
            second_load,
            "amplitude = [[0.0, 0.0], [0.5, 1.0], [0.25, 2.0]]"
        )),
        "bad.toml: load[1].amplitude[2]: load factors must increase"
    );
    assert_eq!(
        invalid(&with(second_load, "amplitude = [[0.0, 0.0], [1.0, nan]]")),
        "bad.toml: load[1].amplitude[1]: load factor and value must be finite"
    );
    assert_eq!(
        invalid(&with(second_load, "amplitude = [[-inf, 0.0], [1.0, 1.0]]")),
        "bad.toml: load[1].amplitude[0]: load factor and value must be finite"
    );
    assert_eq!(
        invalid(&with(second_load, "amplitude = [[0.0, 1.0]]")),
        "bad.toml: load[1].amplitude: needs at least two points [load_factor, value] (got 1)"
    );
    assert_eq!(
        invalid(&with(second_load, "amplitude = []")),
        "bad.toml: load[1].amplitude: needs at least two points [load_factor, value] (got 0)"
    );
    let msg = invalid(&base.replace(
        "ux = 0.02",
        "ux = 0.02\namplitude = [[1.0, 0.0], [0.0, 1.0]]",
    ));
    assert_eq!(
        msg,
        "bad.toml: prescribe[0].amplitude[1]: load factors must increase"
    );
    // a point that is not a pair is a syntax error at the point
    let e = Scene::from_toml_str(
        &with(second_load, "amplitude = [[0.0, 0.0], [1.0, 1.0, 2.0]]"),
        "bad.toml",
    )
    .unwrap_err();
    assert!(
        matches!(&e, SceneError::Syntax { field, message, .. }
            if field == "load[1].amplitude"
            && message == "point 1: needs two numbers [load_factor, value], got 3"),
        "{e:?}"
    );
    // the same dof prescribed with two different curves
    let twice = "[[prescribe]]\nat = [1.0, 1.0]\nux = 0.02\namplitude = [[0.0, 0.0], [1.0, 2.0]]\n";
    let msg = invalid(&with(twice, ""));
    assert!(
        msg.starts_with("bad.toml: prescribe[1]: node ") && msg.contains("another load curve"),
        "{msg}"
    );
    // ... with equal curves it agrees
    let curve = "amplitude = [[0.0, 0.0], [1.0, 2.0]]";
    let agree = base.replace("ux = 0.02", &format!("ux = 0.02\n{curve}"));
    let agree = agree.replace(
        "[loading]",
        &format!("[[prescribe]]\nat = [1.0, 1.0]\nux = 0.02\n{curve}\n[loading]"),
    );
    Scene::from_toml_str(&agree, "agree.toml").unwrap();
    // support names are unique
    let msg = invalid(&base.replace("[[fix]]", "[[fix]]\nname = \"right\""));
    assert_eq!(
        msg,
        "bad.toml: prescribe[0].name: support group name `right` is already used (name each [[fix]] and [[prescribe]] uniquely)"
    );
}

/// Without a curve the load is proportional; a curve that rises to 1 at
/// load factor 0.5 and stays there gives, in 4 steps, exactly (to the bit)
/// the proportional solution of 2 steps, and its plateau steps take no
/// Newton iteration.
#[test]
fn a_plateau_gives_exactly_the_plateau_solution() {
    let proportional = run(&one_element("", 2), "p.toml", Method::Complete, 2);
    let curve = "amplitude = [[0.0, 0.0], [0.5, 1.0], [1.0, 1.0]]";
    let plateau = run(&one_element(curve, 4), "c.toml", Method::Complete, 4);
    assert_eq!(
        plateau.final_state.displacements,
        proportional.final_state.displacements
    );
    assert_eq!(plateau.strain_energy, proportional.strain_energy);
    assert!(proportional.strain_energy > 0.0);
    let iterations: Vec<usize> = plateau.step_records.iter().map(|r| r.iterations).collect();
    assert!(iterations[0] > 0 && iterations[1] > 0, "{iterations:?}");
    assert_eq!(iterations[2..], [0, 0]);
    // the plateau's steps keep the state and the reactions of its start
    assert_eq!(
        plateau.step_records[3].reactions,
        plateau.step_records[1].reactions
    );
    assert_eq!(
        plateau.step_records[1].reactions,
        proportional.step_records[1].reactions
    );
}

/// A curve that goes out and back (0 -> 1 -> 0) brings the element back to
/// its reference state: the prescribed increment is applied whatever its
/// sign.
#[test]
fn a_curve_that_goes_back_unloads() {
    let curve = "amplitude = [[0.0, 0.0], [0.5, 1.0], [1.0, 0.0]]";
    let sol = run(&one_element(curve, 6), "back.toml", Method::Complete, 6);
    let peak = sol.step_records[2].strain_energy;
    assert!(peak > 1e-5, "{peak}");
    assert!(sol.strain_energy.abs() < 1e-20, "{}", sol.strain_energy);
    for d in &sol.final_state.displacements {
        assert!(d[0].abs() < 1e-12 && d[1].abs() < 1e-12, "{d:?}");
    }
    // on the way back the state retraces the way out
    let u = |k: usize| sol.step_records[k].strain_energy;
    assert!((u(1) - u(3)).abs() < 1e-12 * peak, "{} {}", u(1), u(3));
}

/// Without contact the reactions of all groups and the applied loads sum
/// to zero at every converged step (to the Newton tolerance), and the CSV
/// has a row per step and two columns per group.
#[test]
fn reactions_balance_the_loads_without_contact() {
    let curve = "amplitude = [[0.0, 0.0], [0.3, 1.0], [1.0, -0.5]]";
    let text = one_element(curve, 1).replace("nx = 1\nny = 1", "nx = 3\nny = 2");
    let sol = run(&text, "r.toml", Method::Complete, 5);
    assert_eq!(sol.support_groups, ["fix[0]", "right"]);
    let force = [0.0, -0.5];
    let amp = |l: f64| {
        if l <= 0.3 {
            l / 0.3
        } else {
            1.0 - 1.5 * (l - 0.3) / 0.7
        }
    };
    for r in &sol.step_records {
        assert_eq!(r.reactions.len(), 2);
        let a = amp(r.load_factor);
        for c in 0..2 {
            let sum: f64 = r.reactions.iter().map(|g| g[c]).sum::<f64>() + a * force[c];
            let scale = r.reactions.iter().map(|g| g[c].abs()).fold(1e-3, f64::max);
            assert!(
                sum.abs() < 1e-9 * scale,
                "load factor {}: component {c} sums to {sum:e}",
                r.load_factor
            );
        }
        // the prescribed stretch pulls: the support at x = 0 pulls back
        assert!(r.reactions[0][0] * a < 0.0, "{:?}", r.reactions);
    }
    let csv = solver::report::reactions_csv(&sol);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "step,load_factor,fix[0]_x,fix[0]_y,right_x,right_y"
    );
    assert_eq!(lines.len(), 1 + sol.step_records.len());
    let last: Vec<f64> = lines[lines.len() - 1]
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last[1], 1.0);
    assert_eq!(
        last[2..],
        sol.step_records.last().unwrap().reactions.concat()[..]
    );
}

/// Two blocks: a base fixed at its bottom and a block whose top edge is
/// pressed down 0.05 over load factor 0..0.2 and then moved 0.6 in x over
/// 0.2..1 (two `[[prescribe]]` items with curves on the same nodes).
const PRESS_SLIDE: &str = r#"
[material]
young = 100.0
poisson = 0.3
model = "plane-strain"

[[body]]
name = "base"
origin = [0.0, 0.0]
size = [3.0, 0.5]
nx = 12
ny = 2

[[body]]
name = "block"
origin = [0.5, 0.5]
size = [0.6, 0.3]
nx = 3
ny = 2

[[fix]]
name = "bottom"
body = "base"
y = 0.0

[[prescribe]]
name = "press"
body = "block"
y = 0.8
uy = -0.05
amplitude = [[0.0, 0.0], [0.2, 1.0], [1.0, 1.0]]

[[prescribe]]
name = "slide"
body = "block"
y = 0.8
ux = 0.6
amplitude = [[0.0, 0.0], [0.2, 0.0], [1.0, 1.0]]

[[contact]]
slave = { body = "block", side = "bottom" }
master = { body = "base", side = "top" }
mode = "unilateral"

[loading]
load_factor_end = 1.0
steps = [10]
"#;

/// Press then slide: the top edge follows the curves exactly, the block
/// presses on the base throughout (compressive reaction at the top, the
/// base's supports balance it) and every converged step is in equilibrium:
/// the reactions of the top edge balance those of the base's bottom.
#[test]
fn press_then_slide_on_two_blocks() {
    for method in [Method::Complete, Method::ALL[6]] {
        let sol = run(PRESS_SLIDE, "press-slide.toml", method, 10);
        assert_eq!(sol.support_groups, ["bottom", "press", "slide"]);
        let top = sol.node_at("block", [1.1, 0.8]).unwrap();
        assert_eq!(sol.displacement(top), [0.6, -0.05], "{method}");
        for r in &sol.step_records {
            let [bottom, press, slide] = [r.reactions[0], r.reactions[1], r.reactions[2]];
            // press carries only y, slide only x
            assert_eq!((press[0], slide[1]), (0.0, 0.0));
            let scale = bottom[1].abs().max(1e-3);
            assert!(
                (bottom[0] + slide[0]).abs() < 1e-8 * scale,
                "{method} at {}: x {bottom:?} {slide:?}",
                r.load_factor
            );
            assert!(
                (bottom[1] + press[1]).abs() < 1e-8 * scale,
                "{method} at {}: y {bottom:?} {press:?}",
                r.load_factor
            );
            // pressed: the top edge is pushed down, the base pushed up
            assert!(press[1] < 0.0 && bottom[1] > 0.0, "{method}: {press:?}");
        }
        // the slide phase keeps the press: the normal reaction stays within
        // a few percent of that at the end of the press
        let at_press = sol.step_records[1].reactions[1][1];
        let at_end = sol.step_records.last().unwrap().reactions[1][1];
        assert!(
            ((at_end - at_press) / at_press).abs() < 0.05,
            "{method}: {at_press} -> {at_end}"
        );
    }
}

/// A curve on a `[[traction]]` (the Hertz scene's load edge) scales each
/// of its consistent nodal loads; the point loads and supports of the
/// scene are as without it. The support groups take the physical groups'
/// names, unless two items share one.
#[test]
fn traction_curve_scales_every_nodal_load() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/hertz-coarse.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let curve = "amplitude = [[0.0, 0.0], [0.5, 2.0], [1.0, 1.0]]";
    let with = text.replace(
        "force_per_length = [0.0, -0.4315]",
        &format!("force_per_length = [0.0, -0.4315]\n{curve}"),
    );
    assert_ne!(with, text, "the scene's traction line changed");
    let plain = Scene::from_toml_str(&text, path)
        .unwrap()
        .build_model::<2>()
        .unwrap();
    let curved = Scene::from_toml_str(&with, path)
        .unwrap()
        .build_model::<2>()
        .unwrap();
    assert_eq!(curved.amplitudes.len(), 1);
    assert!(plain.amplitudes.is_empty());
    assert_eq!(plain.loads.len(), curved.loads.len());
    assert!(!curved.loads.is_empty());
    for (p, c) in plain.loads.iter().zip(&curved.loads) {
        assert_eq!((p.dof, p.value, p.amplitude), (c.dof, c.value, None));
        let a = c.amplitude.expect("every traction load has the curve");
        assert_eq!(curved.factor(Some(a), 0.5), 2.0);
        assert_eq!(curved.factor(Some(a), 0.75), 1.5);
        assert_eq!(curved.factor(c.amplitude, 3.0), 1.0);
        assert_eq!(plain.factor(p.amplitude, 0.75), 0.75);
    }
    assert_eq!(plain.prescribed, curved.prescribed);
    let names: Vec<&str> = curved.supports.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["symmetry", "bottom"]);
    // a `group` two items share names neither
    let twice = text.replace(
        "[[traction]]",
        "[[fix]]\ngroup = \"bottom\"\ndofs = \"x\"\n[[traction]]",
    );
    let model = Scene::from_toml_str(&twice, path)
        .unwrap()
        .build_model::<2>()
        .unwrap();
    let names: Vec<&str> = model.supports.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["symmetry", "fix[1]", "fix[2]"]);
    // its dofs all belong to the first (`dofs = "xy"` there)
    assert!(model.supports[2].prescribed.is_empty());
}

/// The value of a reaction, not only its balance: a plane-stress block
/// (2 x 1, 4 x 2 elements, E = 100, nu = 0.3) held at x = 0 in x (and one
/// node in y), its right edge pulled by 0.2 along a curve. The deformation
/// is homogeneous uniaxial stress, which the elements reproduce exactly:
/// `F11 = 1 + e`, `S11 = E E11 = E ((1 + e)^2 - 1) / 2`, and the reaction
/// on the right edge is the first Piola-Kirchhoff stress times the height,
/// `F11 S11 H`, pulling (+x); the left edge's is its opposite.
#[test]
fn reaction_of_a_uniaxial_stretch_is_the_stress_times_the_area() {
    let text = r#"
[material]
young = 100.0
poisson = 0.3

[[body]]
name = "bar"
origin = [0.0, 0.0]
size = [2.0, 1.0]
nx = 4
ny = 2

[[fix]]
name = "left"
x = 0.0
dofs = "x"

[[fix]]
name = "pin"
at = [0.0, 0.0]
dofs = "y"

[[prescribe]]
name = "right"
x = 2.0
ux = 0.2
amplitude = [[0.0, 0.0], [0.5, 0.5], [1.0, 1.0]]

[loading]
load_factor_end = 1.0
steps = [3]
"#;
    let sol = run(text, "stretch.toml", Method::Complete, 3);
    assert_eq!(sol.support_groups, ["left", "pin", "right"]);
    for r in &sol.step_records {
        let e = 0.2 * r.load_factor / 2.0;
        let exact = (1.0 + e) * 100.0 * ((1.0 + e).powi(2) - 1.0) / 2.0 * 1.0;
        let [left, pin, right] = [r.reactions[0], r.reactions[1], r.reactions[2]];
        assert!(
            (right[0] - exact).abs() < 1e-9 * exact,
            "load factor {}: {} against {exact}",
            r.load_factor,
            right[0]
        );
        assert!((left[0] + exact).abs() < 1e-9 * exact, "{left:?}");
        assert!(pin[1].abs() < 1e-9 * exact && right[1].abs() < 1e-9 * exact);
    }
}

/// A dof prescribed by two items belongs to the first one's group, so the
/// groups partition the prescribed dofs.
#[test]
fn a_shared_dof_belongs_to_the_first_group() {
    let text = one_element("", 1).replace(
        "[[fix]]\nx = 0.0\n",
        "[[fix]]\nx = 0.0\n\n[[fix]]\ny = 0.0\ndofs = \"y\"\n",
    );
    let model = Scene::from_toml_str(&text, "shared.toml")
        .unwrap()
        .build_model::<2>()
        .unwrap();
    let groups: Vec<(&str, std::ops::Range<usize>)> = model
        .supports
        .iter()
        .map(|g| (g.name.as_str(), g.prescribed.clone()))
        .collect();
    // fix[0]: both nodes at x = 0 in x and y; fix[1]: only the node at
    // (1, 0) in y (the one at (0, 0) is fix[0]'s); right: two nodes in x
    assert_eq!(
        groups,
        [("fix[0]", 0..4), ("fix[1]", 4..5), ("right", 5..7)]
    );
    let sol = run(&text, "shared.toml", Method::Complete, 1);
    let r = &sol.step_records[0].reactions;
    let sum_y: f64 = r.iter().map(|g| g[1]).sum::<f64>() - 0.5;
    assert!(sum_y.abs() < 1e-9, "{r:?}");
}
