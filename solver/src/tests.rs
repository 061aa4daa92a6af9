//! Solver-level tests: global tangent against finite differences, patch
//! test, large-deflection cantilever against the elastica, cut-back
//! recovery, and the paper scene (complete formulation and Types 1–6).

use contact_kernels::ApproxType;

use crate::assembly::{add_external, assemble_solid, solid_pattern};
use crate::contact::assemble_contact;
use crate::contact::{ContactLayout, ContactSpace, PointEval, SegmentTaylor, Taylor};
use crate::ids::{ContactPointIndex, DofId, EquationIndex, MasterSegmentIndex, NodeId, PairId};
use crate::material::{Material, PlaneModel};
use crate::mesh::{Block, Mesh};
use crate::model::{Model, PointLoad, Prescribed};
use crate::scene::Coords;
use crate::system::{DofMap, System};
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
    let active = layout
        .active_set_view()
        .active_multipliers(&evals, lambda, model.mesh.size());
    let mut sys = System::new(dofs.n_eq());
    assemble_contact(&layout.points, &evals, lambda, &active, dofs, &mut sys);
    assemble_solid(model, dofs, u, &mut sys).unwrap();
    add_external(model, dofs, load_factor, &mut sys);
    let n = dofs.n_eq();
    let mut k = vec![vec![0.0; n]; n];
    for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
        k[r as usize][c as usize] += v;
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
            let dof = (0..u.len())
                .find(|&d| dofs.eq(DofId::new(d)) == Some(EquationIndex::new(j)))
                .unwrap();
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

/// `model` solved in `steps` equal load steps (the other options the
/// defaults).
fn solve_in_steps(model: &Model, steps: usize) -> crate::Solution {
    solve_model(
        model,
        &SolveOptions {
            steps,
            ..SolveOptions::default()
        },
    )
    .unwrap()
}

/// A finite-strain plane-stress material.
fn plane_stress(young: f64, poisson: f64) -> Material {
    Material {
        young,
        poisson,
        model: PlaneModel::PlaneStress,
        kinematics: crate::material::Kinematics::Finite,
    }
}

/// The length of [`tip_loaded_cantilever`].
const CANTILEVER_LENGTH: f64 = 10.0;

/// A cantilever of length [`CANTILEVER_LENGTH`], height `height`, Young's
/// modulus 1e4 and Poisson's ratio `poisson` ([`block_model`]: `nx` x 2
/// elements, clamped at x = 0), loaded at its bottom tip node by
/// `-EI / L^2` along y, so that the load factor is `P L^2 / (EI)`: the
/// model and the tip node.
fn tip_loaded_cantilever(nx: usize, height: f64, poisson: f64) -> (Model, NodeId) {
    let (length, young) = (CANTILEVER_LENGTH, 1.0e4);
    let ei = young * height.powi(3) / 12.0;
    let mut model = block_model(nx, 2, length, height, plane_stress(young, poisson));
    let tip = model.mesh.select_nodes(None, Some(length), Some(0.0))[0];
    model.loads.push(PointLoad {
        dof: DofId::of(tip, 1),
        value: -ei / (length * length),
        amplitude: None,
    });
    (model, tip)
}

fn block_model(nx: usize, ny: usize, length: f64, height: f64, material: Material) -> Model {
    let mut mesh = Mesh::new();
    mesh.add_block(
        "beam",
        material,
        Block {
            origin: [0.0, -height / 2.0],
            size: [length, height],
            cells: [nx, ny],
        },
    )
    .unwrap();
    let prescribed = mesh
        .select_nodes(None, Some(0.0), None)
        .into_iter()
        .flat_map(|n| {
            [
                Prescribed {
                    dof: DofId::of(n, 0),
                    value: 0.0,
                    amplitude: None,
                },
                Prescribed {
                    dof: DofId::of(n, 1),
                    value: 0.0,
                    amplitude: None,
                },
            ]
        })
        .collect();
    Model {
        mesh,
        prescribed,
        loads: Vec::new(),
        contacts: Vec::new(),
        load_factor_end: 1.0,
        amplitudes: Vec::new(),
        supports: Vec::new(),
    }
}

/// Solid alone: the assembled tangent equals central differences of the
/// residual at random deformed states (h = 1e-6, tolerance 1e-7 relative to
/// the largest tangent entry).
#[test]
fn solid_tangent_matches_finite_differences() {
    let mat = plane_stress(1000.0, 0.3);
    let model = block_model(3, 2, 3.0, 1.0, mat);
    let layout = ContactLayout::new(&model, None);
    let mut rng = Lcg::new(11);
    for _ in 0..3 {
        let u: Vec<f64> = (0..2 * model.mesh.node_count())
            .map(|_| rng.uniform(-0.1, 0.1))
            .collect();
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
    let elements = [
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
        [4, 5, 6, 7],
    ];
    let mat = plane_stress(1.0e6, 0.25);
    let mut mesh = Mesh::new();
    mesh.add_body("patch", mat, &nodes, &elements).unwrap();
    let h = [[0.08, 0.03], [-0.02, 0.05]];
    let mut prescribed = Vec::new();
    for n in 0..4 {
        for i in 0..2 {
            prescribed.push(Prescribed {
                dof: DofId::of(NodeId::new(n), i),
                value: h[i][0] * nodes[n][0] + h[i][1] * nodes[n][1],
                amplitude: None,
            });
        }
    }
    let model = Model {
        mesh,
        prescribed,
        loads: Vec::new(),
        contacts: Vec::new(),
        load_factor_end: 1.0,
        amplitudes: Vec::new(),
        supports: Vec::new(),
    };
    let sol = solve_in_steps(&model, 2);
    for n in 4..8 {
        for i in 0..2 {
            let exact = h[i][0] * nodes[n][0] + h[i][1] * nodes[n][1];
            assert!(
                (sol.displacement(NodeId::new(n))[i] - exact).abs() < 1e-12,
                "node {n}"
            );
        }
    }
    let s = sol.element_stresses(&sol.final_state).unwrap();
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
            let add = |a: [f64; 4], b: [f64; 4], f: f64| {
                std::array::from_fn::<f64, 4, _>(|i| a[i] + f * b[i])
            };
            let k1 = rhs(s);
            let k2 = rhs(add(s, k1, ds / 2.0));
            let k3 = rhs(add(s, k2, ds / 2.0));
            let k4 = rhs(add(s, k3, ds));
            s = std::array::from_fn(|i| {
                s[i] + ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            });
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
    for (alpha, u, v) in [
        (1.0, 0.05643, 0.30172),
        (2.0, 0.16064, 0.49346),
        (5.0, 0.38763, 0.71379),
    ] {
        let (uc, vc) = elastica_tip(alpha);
        assert!(
            (uc - u).abs() < 1e-5 && (vc - v).abs() < 1e-5,
            "alpha {alpha}: {uc} {vc}"
        );
    }
}

/// A slender cantilever (L/h = 25, 400 x 2 elements, nu = 0, end load at
/// the mid node) against the elastica for P L^2/(EI) = 1, 2 and 5: tip
/// displacements within 1 % of the reference.
#[test]
fn large_deflection_cantilever_matches_elastica() {
    let (mut model, tip) = tip_loaded_cantilever(400, 0.4, 0.0);
    let length = CANTILEVER_LENGTH;
    model.load_factor_end = 5.0;
    let opts = SolveOptions {
        steps: 10,
        record_steps: true,
        ..SolveOptions::default()
    };
    let sol = solve_model(&model, &opts).unwrap();
    assert!(sol.cutbacks.is_empty());
    for alpha in [1.0, 2.0, 5.0] {
        let state = sol
            .snapshots
            .iter()
            .find(|s| (s.load_factor - alpha).abs() < 1e-12)
            .unwrap();
        let d = state.displacements[tip.index()];
        let (u_ref, v_ref) = elastica_tip(alpha);
        let (u, v) = (-d[0] / length, -d[1] / length);
        println!(
            "alpha {alpha}: u/L {u:.5} (elastica {u_ref:.5}, {:+.2} %), v/L {v:.5} (elastica {v_ref:.5}, {:+.2} %)",
            100.0 * (u / u_ref - 1.0),
            100.0 * (v / v_ref - 1.0)
        );
        assert!(
            (u / u_ref - 1.0).abs() < 0.01,
            "alpha {alpha}: u/L {u} vs {u_ref}"
        );
        assert!(
            (v / v_ref - 1.0).abs() < 0.01,
            "alpha {alpha}: v/L {v} vs {v_ref}"
        );
    }
}

/// One step to a large load (tip rotation about 70 degrees) needs 14
/// Newton iterations; with an iteration limit of 8 the full step fails,
/// bisection recovers, the cut-backs are reported with their reason and
/// residual history, and the final state equals that of a 20-step solve
/// (the elastic problem is path independent).
#[test]
fn cutback_recovers_a_too_large_step() {
    let (mut model, tip) = tip_loaded_cantilever(40, 0.5, 0.3);
    model.load_factor_end = 10.0;
    let full = solve_in_steps(&model, 1);
    assert!(full.cutbacks.is_empty() && full.newton_iterations > 8);
    let one = solve_model(
        &model,
        &SolveOptions {
            steps: 1,
            max_iterations: 8,
            ..SolveOptions::default()
        },
    )
    .unwrap();
    assert!(!one.cutbacks.is_empty(), "expected the full step to fail");
    let first = &one.cutbacks[0];
    assert_eq!(
        (first.from_load_factor, first.attempted_load_factor),
        (0.0, 10.0)
    );
    assert!(matches!(
        first.reason,
        crate::CutbackReason::MaxIterations { .. }
    ));
    assert_eq!(first.residuals.len(), 9);
    assert!(one.step_records.len() > 1);
    assert_eq!(one.load_factor, 10.0);
    assert!(
        one.cutbacks
            .iter()
            .all(|c| c.step == 1 && c.from_load_factor < c.attempted_load_factor)
    );
    let many = solve_in_steps(&model, 20);
    assert!(many.cutbacks.is_empty());
    let (a, b) = (one.displacement(tip), many.displacement(tip));
    assert!(
        (a[0] - b[0]).abs() < 1e-8 && (a[1] - b[1]).abs() < 1e-8,
        "{a:?} vs {b:?}"
    );
    assert!((one.strain_energy / many.strain_energy - 1.0).abs() < 1e-9);
}

/// A body without supports: singular system, reported as such (no panic,
/// bounded number of attempts).
#[test]
fn unsupported_body_is_singular() {
    let mat = plane_stress(1.0, 0.3);
    let mut model = block_model(2, 1, 2.0, 1.0, mat);
    model.prescribed.clear();
    model.loads.push(PointLoad {
        dof: DofId::new(1),
        value: 1.0,
        amplitude: None,
    });
    let err = solve_model(
        &model,
        &SolveOptions {
            max_cutbacks: 2,
            ..SolveOptions::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(err, SolverError::Singular { cutbacks: 2, .. }),
        "{err}"
    );
}

fn paper_model() -> Model {
    Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml")
        .unwrap()
        .build_model()
        .unwrap()
}

/// A random state near the reference: displacements `amp`-sized, multipliers `lam`-sized.
fn random_state(
    model: &Model,
    layout: &ContactLayout,
    rng: &mut Lcg,
    amp: f64,
    lam: f64,
) -> (Vec<f64>, Vec<f64>) {
    let mut u: Vec<f64> = (0..2 * model.mesh.node_count())
        .map(|_| rng.uniform(-amp, amp))
        .collect();
    for p in &model.prescribed {
        u[p.dof.index()] = 0.0;
    }
    let l = (0..layout.multipliers.len())
        .map(|_| rng.uniform(-lam, lam))
        .collect();
    (u, l)
}

/// Contact with frozen Taylor coefficients (each type) and the complete
/// formulation: the assembled tangent of the whole saddle-point system
/// equals central differences of the residual at random states (seeded;
/// tolerance 1e-7 relative to the largest tangent entry).
#[test]
fn contact_tangent_matches_finite_differences() {
    let model = paper_model();
    let layout = ContactLayout::new(&model, None);
    let mut rng = Lcg::new(42);
    for ty in ApproxType::ALL {
        let (u0, _) = random_state(&model, &layout, &mut rng, 0.05, 0.0);
        let none = vec![None; layout.points.len()];
        let (evals0, _) = layout.evaluate_all(&model.mesh, &u0, &none, ty).unwrap();
        let taylor: Vec<Option<SegmentTaylor>> = evals0
            .iter()
            .map(|e| e.map(|at_start| Taylor::at(at_start, &u0)))
            .collect();
        assert!(taylor.iter().all(|t| t.is_some()));
        let (d, lam) = random_state(&model, &layout, &mut rng, 0.02, 50.0);
        let u: Vec<f64> = u0.iter().zip(&d).map(|(a, b)| a + b).collect();
        let frozen = |u: &[f64]| taylor.iter().map(|t| t.map(|t| t.expand(u))).collect();
        let err = tangent_error(&model, &layout, &u, &lam, &frozen);
        assert!(err < 1e-7, "type {ty}: relative tangent error {err:e}");
    }
    for formulation in contact_kernels::pair_formulations() {
        let layout = ContactLayout::new(&model, Some(formulation));
        for _ in 0..3 {
            let (u, lam) = random_state(&model, &layout, &mut rng, 0.05, 50.0);
            let none = vec![None; layout.points.len()];
            let (paired, _) = layout.project_all(&model.mesh, &u, &none).unwrap();
            let pairing: Vec<Option<MasterSegmentIndex>> =
                paired.iter().map(|p| p.map(|(m, _)| m)).collect();
            assert!(pairing.iter().all(|p| p.is_some()));
            let complete = |u: &[f64]| {
                layout
                    .evaluate_all(&model.mesh, u, &pairing, ApproxType::Type6)
                    .unwrap()
                    .0
            };
            let err = tangent_error(&model, &layout, &u, &lam, &complete);
            assert!(
                err < 1e-7,
                "complete {formulation}: relative tangent error {err:e}"
            );
        }
    }
}

/// The solid block ([`crate::linear::Block`]) takes every contribution to
/// an entry of its pattern, the contact's included: each entry is the sum
/// of the same terms in the same order as the triplets it replaces (bit for
/// bit), the triplets left are the others in their order, and the largest
/// contribution and the residual are those of the triplets.
#[test]
fn the_solid_block_sums_as_the_triplets_do() {
    use std::collections::BTreeMap;
    let model = paper_model();
    let layout = ContactLayout::new(&model, None);
    let mut rng = Lcg::new(7);
    let (u, lam) = random_state(&model, &layout, &mut rng, 0.05, 50.0);
    let dofs = DofMap::new(&model, layout.multipliers.len());
    let none = vec![None; layout.points.len()];
    let (evals, _) = layout
        .evaluate_all(&model.mesh, &u, &none, ApproxType::Type6)
        .unwrap();
    let active = layout
        .active_set_view()
        .active_multipliers(&evals, &lam, model.mesh.size());
    assert!(active.iter().any(|&a| a), "some contact contributes");
    let pattern = std::sync::Arc::new(solid_pattern(&model, &dofs, None).unwrap());
    pattern.check_invariants().unwrap();
    assert_eq!(pattern.rows(), dofs.n_free);
    let assemble = |sys: &mut System| {
        assemble_contact(&layout.points, &evals, &lam, &active, &dofs, sys);
        assemble_solid(&model, &dofs, &u, sys).unwrap();
    };
    let mut plain = System::new(dofs.n_eq());
    assemble(&mut plain);
    let mut blocked = System::with_block(dofs.n_eq(), pattern.clone());
    assemble(&mut blocked);
    let eq = |i: u32| EquationIndex::new(i as usize);
    let triplets = |s: &System| -> Vec<(u32, u32, u64)> {
        s.rows
            .iter()
            .zip(&s.cols)
            .zip(&s.vals)
            .map(|((&r, &c), &v)| (r, c, v.to_bits()))
            .collect()
    };
    let (mut sums, mut inside_max) = (BTreeMap::new(), 0.0_f64);
    let mut outside = Vec::new();
    for (r, c, v) in triplets(&plain) {
        let v = f64::from_bits(v);
        if pattern.find(eq(r), eq(c)).is_some() {
            *sums.entry((r, c)).or_insert(0.0) += v;
            inside_max = inside_max.max(v.abs());
        } else {
            outside.push((r, c, v.to_bits()));
        }
    }
    assert!(
        !outside.is_empty(),
        "the contact couples outside the pattern"
    );
    assert_eq!(triplets(&blocked), outside);
    let block = blocked.block.as_ref().unwrap();
    let from_block: BTreeMap<(u32, u32), u64> = pattern
        .entry_rows()
        .zip(pattern.cols())
        .zip(&block.values)
        .map(|((r, &c), v)| ((r, c), v.to_bits()))
        .collect();
    let summed: BTreeMap<(u32, u32), u64> = sums.iter().map(|(&k, v)| (k, v.to_bits())).collect();
    // the solid elements add to every entry of their pattern
    assert_eq!(from_block, summed);
    assert_eq!(block.max_abs.to_bits(), inside_max.to_bits());
    assert_eq!(plain.residual, blocked.residual);
    assert_eq!(plain.energy.to_bits(), blocked.energy.to_bits());
    // a reset keeps the pattern and zeroes the values
    blocked.reset(dofs.n_eq());
    let block = blocked.block.as_ref().unwrap();
    assert!(block.values.iter().all(|&v| v == 0.0) && block.max_abs == 0.0);
}

fn paper_scene() -> Scene {
    Scene::from_toml_str(crate::scenes::STACKED_CANTILEVER, "stacked-cantilever.toml").unwrap()
}

fn run(scene: &Scene, method: Method, steps: usize) -> crate::Solution {
    solve(
        scene,
        &SolveOptions {
            method,
            steps,
            ..SolveOptions::from_scene(scene)
        },
    )
    .unwrap()
}

/// Two solves of the paper scene end in the same state: strain energy
/// (relative) and tip displacement within 1e-8.
fn assert_same_end(a: &crate::Solution, b: &crate::Solution) {
    assert!(
        (a.strain_energy / b.strain_energy - 1.0).abs() < 1e-8,
        "{} vs {}",
        a.strain_energy,
        b.strain_energy
    );
    let (ta, tb) = (tip(a), tip(b));
    assert!((ta[0] - tb[0]).abs() < 1e-8 && (ta[1] - tb[1]).abs() < 1e-8);
}

fn tip(sol: &crate::Solution) -> [f64; 2] {
    sol.displacement(sol.node_at("slave", [7.0, 1.0]).unwrap())
}

/// The paper scene, complete formulation: strain energy at load factor 10
/// within 0.1 % of the sanity anchor of docs/conventions.md, 0.56498, loaded node displacement
/// within 1e-3 of (-0.100, -1.447); every integration point stays inside
/// its master segment; no cut-backs.
#[test]
fn paper_scene_matches_the_sanity_anchor() {
    let sol = run(&paper_scene(), Method::Complete, 4);
    assert_eq!(sol.load_factor, 10.0);
    assert!(
        (sol.strain_energy / 0.56498 - 1.0).abs() < 1e-3,
        "U = {}",
        sol.strain_energy
    );
    let d = tip(&sol);
    assert!(
        (d[0] + 0.100).abs() < 1e-3 && (d[1] + 1.447).abs() < 1e-3,
        "{d:?}"
    );
    assert!(sol.cutbacks.is_empty());
    assert_eq!(sol.contact_points.len(), 14);
    assert!(sol.unpaired_points().is_empty());
    let (lo, hi) = sol.xi_m_range().unwrap();
    assert!(lo >= -1.0 && hi <= 1.0);
    assert_eq!(sol.multiplier_dofs.len(), 8);
    assert_eq!(sol.iterations_per_step().len(), 4);
    assert!(sol.kernel_counts.evaluate > 0);
}

/// Complete formulation: the same final energy and state for 4 and 20 steps
/// (relative 1e-8).
#[test]
fn complete_formulation_is_path_independent() {
    let scene = paper_scene();
    let a = run(&scene, Method::Complete, 4);
    let b = run(&scene, Method::Complete, 20);
    assert_same_end(&a, &b);
}

/// Every type solves the paper scene with 4 and 20 steps without
/// cut-backs; energies lie within 1 % of the complete formulation's, and
/// Type 6 with 20 steps is within 0.1 %.
#[test]
fn every_type_solves_the_paper_scene() {
    let scene = paper_scene();
    let complete = run(&scene, Method::Complete, 20).strain_energy;
    for ty in ApproxType::ALL {
        for steps in [4, 20] {
            let sol = run(&scene, Method::Approx(ty), steps);
            let err = sol.strain_energy / complete - 1.0;
            assert!(
                sol.cutbacks.is_empty(),
                "type {ty}, {steps} steps: {:?}",
                sol.cutbacks
            );
            assert!(err.abs() < 1e-2, "type {ty}, {steps} steps: error {err:e}");
            if ty == ApproxType::Type6 && steps == 20 {
                assert!(err.abs() < 1e-3);
            }
            assert_eq!(sol.kernel_counts.evaluate, 14 * steps as u64);
        }
    }
}

/// The closest-point formulation (override) also solves the paper scene,
/// complete and every type, and the complete result is path independent.
#[test]
fn closest_point_formulation_solves_the_paper_scene() {
    let scene = paper_scene();
    let opts = |method, steps| SolveOptions {
        method,
        steps,
        formulation: Some(crate::Formulation::ClosestPoint),
        ..SolveOptions::from_scene(&scene)
    };
    let a = solve::<2>(&scene, &opts(Method::Complete, 4)).unwrap();
    let b = solve::<2>(&scene, &opts(Method::Complete, 20)).unwrap();
    assert!((a.strain_energy / b.strain_energy - 1.0).abs() < 1e-8);
    assert_eq!(a.formulations, vec![crate::Formulation::ClosestPoint]);
    for ty in ApproxType::ALL {
        let s = solve::<2>(&scene, &opts(Method::Approx(ty), 4)).unwrap();
        assert!((s.strain_energy / b.strain_energy - 1.0).abs() < 1e-2);
    }
}

/// A slave face longer than the master face: the integration points of the
/// overhanging slave segment project into no master segment; they are
/// inactive, reported at every step and in the final contact report, and
/// the multiplier of the overhanging end node gets no constraint.
#[test]
fn unpaired_points_are_inactive_and_reported() {
    let text = crate::scenes::STACKED_CANTILEVER.replace(
        "size = [7.0, 0.5]\nnx = 7\nny = 1\n\n[[body]]\nname = \"slave\"",
        "size = [6.0, 0.5]\nnx = 6\nny = 1\n\n[[body]]\nname = \"slave\"",
    );
    let scene = Scene::from_toml_str(&text, "overhang.toml").unwrap();
    assert_eq!(scene.bodies[0].nx, Some(6));
    for method in [Method::Complete, Method::Approx(ApproxType::Type3)] {
        let sol = run(&scene, method, 4);
        let unpaired = sol.unpaired_points();
        assert_eq!(unpaired.len(), 2, "{method}");
        assert!(unpaired.iter().all(|p| p.slave_segment == 6));
        assert!(
            sol.step_records
                .iter()
                .all(|r| r.unpaired.len() == 2 && r.active_multipliers == 7)
        );
        let end = sol.node_at("slave", [7.0, 0.5]).unwrap();
        let m = sol
            .multiplier_dofs
            .iter()
            .position(|d| d.node == end.index())
            .unwrap();
        assert_eq!(sol.final_state.multipliers[m], 0.0);
    }
}

/// Unilateral contact on the paper scene: at the converged state the
/// pressure `p = -lambda` is non-negative, active multiplier nodes have a
/// zero weighted gap, inactive ones a zero multiplier and a non-negative
/// weighted gap; some nodes open (persistent contact would pull there).
/// With the load reversed the layers separate completely and the slave
/// layer behaves like a free cantilever.
#[test]
fn unilateral_contact_opens_and_closes() {
    let text =
        crate::scenes::STACKED_CANTILEVER.replace("mode = \"persistent\"", "mode = \"unilateral\"");
    let scene = Scene::from_toml_str(&text, "unilateral.toml").unwrap();
    let sol = run(&scene, Method::Complete, 10);
    let n = sol.multiplier_dofs.len();
    let mut weight = vec![0.0; n];
    let mut wgap = vec![0.0; n];
    let rule = crate::contact::gauss_legendre(2);
    for p in &sol.contact_points {
        let len = 1.0;
        let nsh = crate::contact::shape2(p.xi_s);
        for a in 0..2 {
            let m = sol
                .multiplier_dofs
                .iter()
                .position(|d| d.node == p.slave_nodes[a])
                .unwrap();
            let w = rule[p.gauss].1 * len / 2.0 * nsh[a];
            weight[m] += w;
            wgap[m] += w * p.gap.unwrap();
        }
    }
    let lam = &sol.final_state.multipliers;
    let scale = lam.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let (mut open, mut closed) = (0, 0);
    for m in 0..n {
        let g = wgap[m] / weight[m];
        assert!(
            -lam[m] >= -1e-9 * scale,
            "tensile multiplier {m}: {}",
            lam[m]
        );
        if lam[m] == 0.0 {
            open += 1;
            assert!(g >= -1e-9, "open node {m} penetrates: {g}");
        } else {
            closed += 1;
            assert!(g.abs() < 1e-9, "closed node {m} has gap {g}");
        }
    }
    assert!(open > 0 && closed > 0, "open {open}, closed {closed}");
    let last = sol.step_records.last().unwrap();
    assert_eq!(last.active_multipliers, closed);

    let lifted = Scene::from_toml_str(
        &text.replace("force = [0.0, -0.08]", "force = [0.0, 0.08]"),
        "lift.toml",
    )
    .unwrap();
    let up = run(&lifted, Method::Complete, 4);
    assert!(up.final_state.multipliers.iter().all(|&l| l == 0.0));
    assert!(
        up.contact_points
            .iter()
            .all(|p| p.gap.is_none_or(|g| g > 0.0))
    );
    let free = text
        .replace("force = [0.0, -0.08]", "force = [0.0, 0.08]")
        .split("[[contact]]")
        .next()
        .unwrap()
        .to_owned()
        + "[loading]\nload_factor_end = 10.0\nsteps = [4]\n";
    let free = run(
        &Scene::from_toml_str(&free, "free.toml").unwrap(),
        Method::Complete,
        4,
    );
    let (a, b) = (tip(&up), tip(&free));
    assert!(
        (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9,
        "{a:?} vs {b:?}"
    );
}

/// The VTK file has one value per point / cell in every array, quads of
/// type 9, and the final displacement field.
#[test]
fn vtu_output_is_consistent() {
    let sol = solve(
        &paper_scene(),
        &SolveOptions {
            record_steps: true,
            ..SolveOptions::default()
        },
    )
    .unwrap();
    assert_eq!(sol.snapshots.len(), 5);
    let text = crate::report::vtu_string(&sol, &sol.final_state).unwrap();
    assert!(text.starts_with("<?xml") && text.trim_end().ends_with("</VTKFile>"));
    assert!(text.contains("NumberOfPoints=\"32\" NumberOfCells=\"14\""));
    let array = |name: &str| -> Vec<String> {
        let start = text.find(&format!("Name=\"{name}\"")).unwrap();
        let body = &text[start..];
        let open = body.find('>').unwrap() + 1;
        let close = body.find("</DataArray>").unwrap();
        body[open..close]
            .split_whitespace()
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(array("displacement").len(), 96);
    assert_eq!(array("contact_pressure").len(), 32);
    assert_eq!(array("cauchy_stress").len(), 42);
    assert_eq!(array("connectivity").len(), 56);
    assert!(array("types").iter().all(|t| t == "9"));
    let tip_node = sol.node_at("slave", [7.0, 1.0]).unwrap();
    let uy: f64 = array("displacement")[3 * tip_node.index() + 1]
        .parse()
        .unwrap();
    assert_eq!(uy, sol.displacement(tip_node)[1]);
    let dir = std::env::temp_dir().join(format!("gapsim-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("final.vtu");
    crate::report::write_vtu(&path, &sol).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The shipped paper scene is the definition in docs/conventions.md.
#[test]
fn paper_scene_file_is_the_design_scene() {
    let scene = paper_scene();
    let model = scene.build_model::<2>().unwrap();
    assert_eq!(scene.bodies.len(), 2);
    for (b, y0) in scene.bodies.iter().zip([0.0, 0.5]) {
        assert_eq!(
            (b.nx, b.ny, b.origin, b.size),
            (
                Some(7),
                Some(1),
                Some(Coords::Xy([0.0, y0])),
                Some(Coords::Xy([7.0, 0.5]))
            )
        );
    }
    let mat = scene.material.unwrap().material();
    assert_eq!(
        (mat.young, mat.poisson, mat.model),
        (1000.0, 0.3, PlaneModel::PlaneStress)
    );
    assert_eq!(model.mesh.node_count(), 32);
    // every node at x = 0 fixed in x and y (both layers: 4 nodes)
    assert_eq!(model.prescribed.len(), 8);
    assert!(
        model
            .prescribed
            .iter()
            .all(|p| model.mesh.node_ref(p.dof.node())[0] == 0.0 && p.value == 0.0)
    );
    let tip = model.mesh.select_nodes(Some(1), Some(7.0), Some(1.0))[0];
    assert_eq!(
        model.loads,
        vec![
            PointLoad {
                dof: DofId::of(tip, 0),
                value: 0.0,
                amplitude: None
            },
            PointLoad {
                dof: DofId::of(tip, 1),
                value: -0.08,
                amplitude: None
            }
        ]
    );
    let c = &model.contacts[0];
    assert_eq!(
        (c.formulation, c.mode, c.gauss_points),
        (
            crate::Formulation::SlaveNormal,
            crate::ContactMode::Persistent,
            Some(2)
        )
    );
    // slave: bottom of the slave layer left to right; master: top of the master layer right to left
    let x = |n: NodeId| model.mesh.node_ref(n);
    assert!(
        c.slave
            .iter()
            .enumerate()
            .all(|(i, s)| x(s[0]) == [i as f64, 0.5] && x(s[1]) == [i as f64 + 1.0, 0.5])
    );
    assert!(
        c.master
            .iter()
            .all(|m| x(m[0])[0] == x(m[1])[0] + 1.0 && x(m[0])[1] == 0.5)
    );
    assert!(
        c.slave
            .iter()
            .flatten()
            .all(|&n| model.mesh.bodies[1].has_node(n))
    );
    assert_eq!(scene.loading.steps, vec![4, 6, 8, 10, 12, 14, 16, 18, 20]);
    assert_eq!(
        (scene.loading.load_factor_end, scene.loading.method),
        (10.0, Method::Complete)
    );
}

#[test]
fn method_names_parse() {
    assert_eq!("complete".parse::<Method>().unwrap(), Method::Complete);
    assert_eq!(
        "3".parse::<Method>().unwrap(),
        Method::Approx(ApproxType::Type3)
    );
    assert_eq!(
        "type6".parse::<Method>().unwrap(),
        Method::Approx(ApproxType::Type6)
    );
    assert!("7".parse::<Method>().is_err());
    assert_eq!(Method::Approx(ApproxType::Type2).to_string(), "2");
    assert_eq!(Method::Complete.to_string(), "complete");
}

/// The paper scene refined 2 x 1 (14 + 14 elements), complete formulation,
/// 4 steps: it used to stop in step 3 (load factor 7.48 -> 7.49, 8
/// cut-backs) because slave segment 4, Gauss point 0 reached the node
/// between master segments 9 and 10 and the re-pairing at every iteration
/// made Newton cycle between them. Now it converges without cut-backs; at
/// load factor 7.5 that point is tied to the node (it projects exactly onto
/// it from both segments, with the same gap); the final state is the same
/// for 4 and 8 steps (path independence), where every point projects into
/// its master segment; and every type solves the scene too.
#[test]
fn refined_paper_scene_converges_across_master_nodes() {
    let scene = paper_scene().refined(2, 1);
    let opts = |method, steps| SolveOptions {
        method,
        steps,
        record_steps: true,
        ..SolveOptions::from_scene(&scene)
    };
    let four = solve(&scene, &opts(Method::Complete, 4)).unwrap();
    assert!(four.cutbacks.is_empty(), "{:?}", four.cutbacks);
    assert_eq!(four.step_records.len(), 4);
    assert!(four.step_records.iter().all(|r| r.kept_outside.is_empty()));
    let third = &four.step_records[2];
    assert_eq!(third.load_factor, 7.5);
    assert_eq!(third.node_ties.len(), 1, "{:?}", third.node_ties);
    let tie = third.node_ties[0];
    assert_eq!((tie.slave_segment, tie.gauss), (4, 0));
    let paired = tie.master_segment.unwrap();
    assert!(paired == 9 || paired == 10, "{tie:?}");

    // at the tied state the point projects onto the shared master node
    let model = scene.build_model().unwrap();
    let layout = ContactLayout::new(&model, None);
    let i = layout
        .points
        .iter()
        .position(|p| p.slave_segment == 4 && p.gauss == 0)
        .unwrap();
    let pt = layout.points[i];
    let other = 19 - paired;
    assert!(
        layout
            .shared_node(
                PairId::new(0),
                MasterSegmentIndex::new(paired),
                MasterSegmentIndex::new(other)
            )
            .is_some()
    );
    let state = &four.snapshots[3];
    assert_eq!(state.load_factor, 7.5);
    let project = |m: usize| {
        let nodes = [
            pt.slave_nodes[0],
            pt.slave_nodes[1],
            layout.masters[0][m][0],
            layout.masters[0][m][1],
        ];
        let q: [f64; 8] = std::array::from_fn(|k| {
            model.mesh.node_ref(nodes[k / 2])[k % 2]
                + state.displacements[nodes[k / 2].index()][k % 2]
        });
        contact_kernels::project(crate::Formulation::SlaveNormal, &q, pt.xi_s).unwrap()
    };
    let (p, o) = (project(paired), project(other));
    assert!(
        (p.xi_m.abs() - 1.0).abs() < 1e-9 && (o.xi_m.abs() - 1.0).abs() < 1e-9,
        "{p:?} {o:?}"
    );
    assert!(p.xi_m * o.xi_m < 0.0);
    assert!((p.gap - o.gap).abs() < 1e-12, "{p:?} {o:?}");

    let eight = solve(&scene, &opts(Method::Complete, 8)).unwrap();
    assert!(eight.cutbacks.is_empty());
    assert_same_end(&four, &eight);
    let (lo, hi) = four.xi_m_range().unwrap();
    assert!(lo >= -1.0 && hi <= 1.0);
    assert!(four.unpaired_points().is_empty());

    for ty in ApproxType::ALL {
        let sol = solve::<2>(&scene, &opts(Method::Approx(ty), 4)).unwrap();
        assert!(sol.cutbacks.is_empty(), "type {ty}: {:?}", sol.cutbacks);
        let err = sol.strain_energy / four.strain_energy - 1.0;
        assert!(err.abs() < 3e-2, "type {ty}: error {err:e}");
        assert!(sol.step_records.iter().all(|r| r.node_ties.is_empty()));
    }
}

/// The node tie's contributions (`mu (g_o - g_p)`, see
/// [`crate::contact::assemble_ties`]): the assembled tangent of the whole
/// system with ties equals central differences of its residual in every
/// unknown (displacements, multipliers and the ties' `mu`), at random
/// states of the paper scene with points tied across the nodes between
/// adjacent master segments.
#[test]
fn node_tie_tangent_matches_finite_differences() {
    use crate::contact::NodeTie;
    use crate::contact::assemble_ties;
    let model = paper_model();
    let mut rng = Lcg::new(7);
    for formulation in contact_kernels::pair_formulations() {
        let layout = ContactLayout::new(&model, Some(formulation));
        let dofs = DofMap::new(&model, layout.multipliers.len());
        let (u, lam) = random_state(&model, &layout, &mut rng, 0.05, 50.0);
        // Gauss point 1 of slave segment s paired with master s, tied
        // towards master s + 1 (they share a node); another point tied the
        // other way
        let pick = |seg: usize, gauss: usize| {
            layout
                .points
                .iter()
                .position(|p| p.slave_segment == seg && p.gauss == gauss)
                .map(ContactPointIndex::new)
                .unwrap()
        };
        let ties = vec![
            NodeTie {
                point: pick(2, 1),
                paired: MasterSegmentIndex::new(2),
                other: MasterSegmentIndex::new(3),
                mu: rng.uniform(-5.0, 5.0),
            },
            NodeTie {
                point: pick(5, 0),
                paired: MasterSegmentIndex::new(5),
                other: MasterSegmentIndex::new(4),
                mu: rng.uniform(-5.0, 5.0),
            },
        ];
        for t in &ties {
            assert!(
                layout
                    .shared_node(PairId::new(0), t.paired, t.other)
                    .is_some()
            );
        }
        let pairing: Vec<Option<MasterSegmentIndex>> = layout
            .points
            .iter()
            .map(|p| Some(MasterSegmentIndex::new(p.slave_segment)))
            .collect();
        let n_eq = dofs.n_eq();
        let n = n_eq + ties.len();
        let system = |u: &[f64], lam: &[f64], mus: &[f64]| {
            let (evals, _) = layout
                .evaluate_paired(&model.mesh, u, &pairing, ApproxType::Type6)
                .unwrap();
            let ties: Vec<NodeTie> = ties
                .iter()
                .zip(mus)
                .map(|(t, &mu)| NodeTie { mu, ..*t })
                .collect();
            let mut counts = crate::contact::KernelCounts::default();
            let others: Vec<PointEval> = ties
                .iter()
                .map(|t| {
                    layout
                        .evaluate_on(
                            &model.mesh,
                            u,
                            t.point,
                            t.other,
                            ApproxType::Type6,
                            &mut counts,
                        )
                        .unwrap()
                })
                .collect();
            let active =
                layout
                    .active_set_view()
                    .active_multipliers(&evals, lam, model.mesh.size());
            let mut sys = System::new(n);
            assemble_contact(&layout.points, &evals, lam, &active, &dofs, &mut sys);
            assemble_ties(&ties, &evals, &others, &dofs, &mut sys);
            assemble_solid(&model, &dofs, u, &mut sys).unwrap();
            add_external(&model, &dofs, 1.0, &mut sys);
            let mut k = vec![vec![0.0; n]; n];
            for ((&r, &c), &v) in sys.rows.iter().zip(&sys.cols).zip(&sys.vals) {
                k[r as usize][c as usize] += v;
            }
            (sys.residual, k)
        };
        let mus: Vec<f64> = ties.iter().map(|t| t.mu).collect();
        let (_, k) = system(&u, &lam, &mus);
        let scale = k.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        let tie_scale = (n_eq..n)
            .flat_map(|t| k[t].iter().copied())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let h = 1e-6;
        let (mut worst, mut worst_tie) = (0.0_f64, 0.0_f64);
        for j in 0..n {
            let perturbed = |s: f64| {
                let (mut u, mut l, mut m) = (u.clone(), lam.clone(), mus.clone());
                if j < dofs.n_free {
                    let dof = (0..u.len())
                        .find(|&d| dofs.eq(DofId::new(d)) == Some(EquationIndex::new(j)))
                        .unwrap();
                    u[dof] += s;
                } else if j < n_eq {
                    l[j - dofs.n_free] += s;
                } else {
                    m[j - n_eq] += s;
                }
                system(&u, &l, &m).0
            };
            let (rp, rm) = (perturbed(h), perturbed(-h));
            for i in 0..n {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                let e = (fd - k[i][j]).abs();
                worst = worst.max(e / scale);
                if i >= n_eq || j >= n_eq {
                    worst_tie = worst_tie.max(e / tie_scale);
                }
            }
        }
        assert!(
            worst < 1e-7,
            "{formulation}: relative tangent error {worst:e}"
        );
        // the tie rows and columns on their own scale (the segments are not
        // collinear, so they are not empty)
        assert!(tie_scale > 1e-2, "{formulation}: tie rows {tie_scale:e}");
        assert!(
            worst_tie < 1e-7,
            "{formulation}: relative tie tangent error {worst_tie:e}"
        );
    }
}
