//! Solver-level tests: global tangent against finite differences, patch
//! test, large-deflection cantilever against the elastica, cut-back
//! recovery, and the paper scene (complete formulation and Types 1–6).

use contact_kernels::ApproxType;

use crate::assembly::{DofMap, System, add_external, assemble_contact, assemble_solid};
use crate::contact::{ContactLayout, PointEval, Taylor};
use crate::material::{Material, PlaneModel};
use crate::mesh::{Block, Mesh};
use crate::model::{Model, PointLoad, Prescribed};
use crate::testutil::Lcg;
use crate::{Method, Scene, SolveOptions, SolverError, solve, solve_model};

/// Residual and dense tangent of the full system at `(u, lambda)`, with
/// contact evaluated by `evals_at(u)`.
fn system_at(
    model: &Model,
    layout: &ContactLayout,
    dofs: &DofMap,
    u: &[f64],
    lambda: &[f64],
    load_factor: f64,
    evals_at: &dyn Fn(&[f64]) -> Vec<Option<PointEval>>,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let evals = evals_at(u);
    let active = layout.active_multipliers(&evals, lambda, model.mesh.size());
    let mut sys = System::new(dofs.n_eq());
    assemble_contact(layout, &evals, lambda, &active, dofs, &mut sys);
    assemble_solid(model, dofs, u, &mut sys);
    add_external(model, dofs, load_factor, &mut sys);
    let n = dofs.n_eq();
    let mut k = vec![vec![0.0; n]; n];
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        k[r][c] += v;
    }
    (sys.residual, k)
}

/// Compares the assembled tangent with central differences of the residual
/// in every unknown (free dofs and multipliers); returns the largest error
/// relative to the largest tangent entry.
fn tangent_error(
    model: &Model,
    layout: &ContactLayout,
    u: &[f64],
    lambda: &[f64],
    evals_at: &dyn Fn(&[f64]) -> Vec<Option<PointEval>>,
) -> f64 {
    let dofs = DofMap::new(model, layout.multipliers.len());
    let (_, k) = system_at(model, layout, &dofs, u, lambda, 1.0, evals_at);
    let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    let h = 1e-6;
    let mut worst = 0.0_f64;
    let perturb = |j: usize, s: f64| {
        let mut u = u.to_vec();
        let mut l = lambda.to_vec();
        if j < dofs.n_free {
            let dof = (0..u.len()).find(|&d| dofs.eq(d) == Some(j)).unwrap();
            u[dof] += s;
        } else {
            l[j - dofs.n_free] += s;
        }
        system_at(model, layout, &dofs, &u, &l, 1.0, evals_at).0
    };
    for j in 0..dofs.n_eq() {
        let rp = perturb(j, h);
        let rm = perturb(j, -h);
        for i in 0..dofs.n_eq() {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            worst = worst.max((fd - k[i][j]).abs() / scale);
        }
    }
    worst
}

fn block_model(nx: usize, ny: usize, length: f64, height: f64, material: Material) -> Model {
    let mut mesh = Mesh::new();
    mesh.add_block("beam", material, Block { origin: [0.0, -height / 2.0], size: [length, height], nx, ny }).unwrap();
    let prescribed = mesh
        .select_nodes(None, Some(0.0), None)
        .into_iter()
        .flat_map(|n| [Prescribed { dof: 2 * n, value: 0.0 }, Prescribed { dof: 2 * n + 1, value: 0.0 }])
        .collect();
    Model { mesh, prescribed, loads: Vec::new(), contacts: Vec::new(), load_factor_end: 1.0 }
}

/// Solid alone: the assembled tangent equals central differences of the
/// residual at random deformed states (h = 1e-6, tolerance 1e-7 relative to
/// the largest tangent entry).
#[test]
fn solid_tangent_matches_finite_differences() {
    let mat = Material { young: 1000.0, poisson: 0.3, model: PlaneModel::PlaneStress };
    let model = block_model(3, 2, 3.0, 1.0, mat);
    let layout = ContactLayout::new(&model, None);
    let mut rng = Lcg::new(11);
    for _ in 0..3 {
        let u: Vec<f64> = (0..2 * model.mesh.node_count()).map(|_| rng.uniform(-0.1, 0.1)).collect();
        let err = tangent_error(&model, &layout, &u, &[], &|_| Vec::new());
        assert!(err < 1e-7, "relative tangent error {err:e}");
    }
}

/// MacNeal–Harder patch of five distorted elements: prescribing the
/// boundary nodes by a homogeneous deformation `x = (I + H) X` reproduces
/// it exactly at the interior nodes, with the same stress in every element
/// (tolerance 1e-10 relative), geometrically nonlinear.
#[test]
fn patch_test_reproduces_constant_stress_on_distorted_mesh() {
    let nodes = [
        [0.0, 0.0],
        [0.24, 0.0],
        [0.24, 0.12],
        [0.0, 0.12],
        [0.04, 0.02],
        [0.18, 0.03],
        [0.16, 0.08],
        [0.08, 0.08],
    ];
    let elements = [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7], [4, 5, 6, 7]];
    let mat = Material { young: 1.0e6, poisson: 0.25, model: PlaneModel::PlaneStress };
    let mut mesh = Mesh::new();
    mesh.add_body("patch", mat, &nodes, &elements).unwrap();
    let h = [[0.08, 0.03], [-0.02, 0.05]];
    let mut prescribed = Vec::new();
    for n in 0..4 {
        for i in 0..2 {
            prescribed.push(Prescribed { dof: 2 * n + i, value: h[i][0] * nodes[n][0] + h[i][1] * nodes[n][1] });
        }
    }
    let model = Model { mesh, prescribed, loads: Vec::new(), contacts: Vec::new(), load_factor_end: 1.0 };
    let sol = solve_model(&model, &SolveOptions { steps: 2, ..SolveOptions::default() }).unwrap();
    for n in 4..8 {
        for i in 0..2 {
            let exact = h[i][0] * nodes[n][0] + h[i][1] * nodes[n][1];
            assert!((sol.displacement(n)[i] - exact).abs() < 1e-12, "node {n}");
        }
    }
    let s = sol.element_stresses(&sol.final_state);
    for e in &s {
        for c in 0..3 {
            assert!((e.pk2[c] - s[0].pk2[c]).abs() < 1e-10 * s[0].pk2[0].abs());
            assert!((e.cauchy[c] - s[0].cauchy[c]).abs() < 1e-10 * s[0].cauchy[0].abs());
        }
    }
    assert!(s[0].pk2[0].abs() > 1e3);
}

/// Tip position of the inextensible elastica cantilever under a vertical
/// end load with `alpha = P L^2 / (E I)`: returns `(u/L, v/L)`, the
/// horizontal shortening and the vertical deflection. Shooting on
/// `theta'' = -alpha cos(theta)`, `theta(0) = 0`, `theta'(1) = 0` with RK4
/// (4000 steps) and bisection on `theta'(0)`.
fn elastica_tip(alpha: f64) -> (f64, f64) {
    let n = 4000;
    let ds = 1.0 / n as f64;
    // state: theta, theta', x, y
    let rhs = |s: [f64; 4]| [s[1], -alpha * s[0].cos(), s[0].cos(), s[0].sin()];
    let shoot = |k0: f64| {
        let mut s = [0.0, k0, 0.0, 0.0];
        for _ in 0..n {
            let add = |a: [f64; 4], b: [f64; 4], f: f64| std::array::from_fn::<f64, 4, _>(|i| a[i] + f * b[i]);
            let k1 = rhs(s);
            let k2 = rhs(add(s, k1, ds / 2.0));
            let k3 = rhs(add(s, k2, ds / 2.0));
            let k4 = rhs(add(s, k3, ds));
            s = std::array::from_fn(|i| s[i] + ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        }
        s
    };
    let (mut lo, mut hi) = (0.0, alpha);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid)[1] < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let s = shoot(0.5 * (lo + hi));
    (1.0 - s[2], s[3])
}

/// The shooting solution reproduces Mattiasson's tabulated tip deflections
/// (5 digits).
#[test]
fn elastica_reference_matches_mattiasson() {
    for (alpha, u, v) in [(1.0, 0.05643, 0.30172), (2.0, 0.16064, 0.49346), (5.0, 0.38763, 0.71379)] {
        let (uc, vc) = elastica_tip(alpha);
        assert!((uc - u).abs() < 1e-5 && (vc - v).abs() < 1e-5, "alpha {alpha}: {uc} {vc}");
    }
}

/// A slender cantilever (L/h = 25, 400 x 2 elements, nu = 0, end load at
/// the mid node) against the elastica for P L^2/(EI) = 1, 2 and 5: tip
/// displacements within 1 % of the reference.
#[test]
fn large_deflection_cantilever_matches_elastica() {
    let (length, height, young): (f64, f64, f64) = (10.0, 0.4, 1.0e4);
    let ei = young * height.powi(3) / 12.0;
    let mat = Material { young, poisson: 0.0, model: PlaneModel::PlaneStress };
    let mut model = block_model(400, 2, length, height, mat);
    let tip = model.mesh.select_nodes(None, Some(length), Some(0.0))[0];
    model.loads.push(PointLoad { dof: 2 * tip + 1, value: -ei / (length * length) });
    model.load_factor_end = 5.0;
    let opts = SolveOptions { steps: 10, record_steps: true, ..SolveOptions::default() };
    let sol = solve_model(&model, &opts).unwrap();
    assert!(sol.cutbacks.is_empty());
    for alpha in [1.0, 2.0, 5.0] {
        let state = sol.snapshots.iter().find(|s| (s.load_factor - alpha).abs() < 1e-12).unwrap();
        let d = state.displacements[tip];
        let (u_ref, v_ref) = elastica_tip(alpha);
        let (u, v) = (-d[0] / length, -d[1] / length);
        assert!((u / u_ref - 1.0).abs() < 0.01, "alpha {alpha}: u/L {u} vs {u_ref}");
        assert!((v / v_ref - 1.0).abs() < 0.01, "alpha {alpha}: v/L {v} vs {v_ref}");
    }
}

/// One step to a large load fails at full size; bisection recovers, the
/// cut-backs are reported, and the final state equals that of a 20-step
/// solve (the elastic problem is path independent).
#[test]
fn cutback_recovers_a_too_large_step() {
    let (length, height, young): (f64, f64, f64) = (10.0, 0.5, 1.0e4);
    let ei = young * height.powi(3) / 12.0;
    let mat = Material { young, poisson: 0.3, model: PlaneModel::PlaneStress };
    let mut model = block_model(40, 2, length, height, mat);
    let tip = model.mesh.select_nodes(None, Some(length), Some(0.0))[0];
    model.loads.push(PointLoad { dof: 2 * tip + 1, value: -ei / (length * length) });
    model.load_factor_end = 10.0;
    let one = solve_model(&model, &SolveOptions { steps: 1, max_iterations: 15, ..SolveOptions::default() }).unwrap();
    assert!(!one.cutbacks.is_empty(), "expected the full step to fail");
    assert_eq!(one.load_factor, 10.0);
    assert!(one.cutbacks.iter().all(|c| c.step == 1 && c.from_load_factor < c.attempted_load_factor));
    let many = solve_model(&model, &SolveOptions { steps: 20, ..SolveOptions::default() }).unwrap();
    assert!(many.cutbacks.is_empty());
    let (a, b) = (one.displacement(tip), many.displacement(tip));
    assert!((a[0] - b[0]).abs() < 1e-8 && (a[1] - b[1]).abs() < 1e-8, "{a:?} vs {b:?}");
    assert!((one.strain_energy / many.strain_energy - 1.0).abs() < 1e-9);
}

/// A body without supports: singular system, reported as such (no panic,
/// bounded number of attempts).
#[test]
fn unsupported_body_is_singular() {
    let mat = Material { young: 1.0, poisson: 0.3, model: PlaneModel::PlaneStress };
    let mut model = block_model(2, 1, 2.0, 1.0, mat);
    model.prescribed.clear();
    model.loads.push(PointLoad { dof: 1, value: 1.0 });
    let err = solve_model(&model, &SolveOptions { max_cutbacks: 2, ..SolveOptions::default() }).unwrap_err();
    assert!(matches!(err, SolverError::Singular { cutbacks: 2, .. }), "{err}");
}

#[test]
fn zz_debug_residuals() {
    let (length, height, young): (f64, f64, f64) = (10.0, 0.4, 1.0e4);
    let ei = young * height.powi(3) / 12.0;
    let mat = Material { young, poisson: 0.0, model: PlaneModel::PlaneStress };
    let mut model = block_model(400, 2, length, height, mat);
    let tip = model.mesh.select_nodes(None, Some(length), Some(0.0))[0];
    model.loads.push(PointLoad { dof: 2 * tip + 1, value: -ei / (length * length) });
    model.load_factor_end = 5.0;
    let opts = SolveOptions { steps: 10, record_steps: true, max_cutbacks: 3, ..SolveOptions::default() };
    match solve_model(&model, &opts) {
        Ok(sol) => { for r in &sol.step_records { println!("{} {:?}", r.load_factor, r.residuals); } for c in &sol.cutbacks { println!("{:?}", c.residuals); } }
        Err(e) => println!("{e}"),
    }
}
