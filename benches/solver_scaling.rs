//! Solver scaling benchmark: the three phases of one Newton iteration of the
//! complete formulation on refined versions of the paper scene, from about
//! 1e3 to 1e5 equations.
//!
//! ```text
//! cargo bench --bench solver_scaling
//! cargo bench --bench solver_scaling -- 'solid_assembly'   # one phase
//! GAPSIM_LINEAR=ldlt cargo bench --bench solver_scaling     # the LDL^T
//! ```
//!
//! For each refinement `(x, y)` of `scenes/stacked-cantilever.toml` the first
//! of the scene's load steps is solved; from that converged state
//! [`solver::newton::IterationProbe`] evaluates the first Newton iteration of
//! the second step (the same code as a solve's iteration). Benchmarks, in the
//! group `solver_scaling` with the equation count as parameter:
//!
//! * `solid_assembly/<n>`: solid element forces and tangents, scatter into
//!   triplets, external force;
//! * `contact_evaluation/<n>`: re-projection and Type 6 kernel at every slave
//!   integration point, active set, contact scatter into a fresh system;
//! * `linear_solve/<n>`: regularisation, numeric LU with the symbolic
//!   factorisation reused (computed once before measuring), and the solve.
//!
//! The group `solver_scaling_3d` times `solid_assembly/<n>` and
//! `linear_solve/<n>` the same way on `scenes/block3d.toml` refined 9-fold
//! (18 x 18 x 9 hexahedra, about 1e4 equations, no contact), and
//! `solid_assembly_block/<n>`: the same assembly into the solid block a
//! PETSc solve takes (`solver::linear::Block`) instead of triplets. `cargo run --release --example scaling_table -- --3d` gives
//! the 3D sizes up to 3e5 equations.
//!
//! The group `friction_cost` times what Coulomb friction adds to an
//! iteration: the contact phase, and the contact phase with the solid
//! assembly, on the Mindlin scene in partial slip with `mu = 0.3` and with
//! the same model and state frictionless
//! (`cargo bench --bench solver_scaling -- friction_cost`); the group
//! `friction_cost_3d` the same on the 3D Mindlin scene's coarse half model
//! (`cargo bench --bench solver_scaling -- friction_cost_3d`).
//!
//! Each routine's input (the system after the previous phase) is cloned in
//! an untimed setup. Flat sampling, 10 samples, 1 s warm-up and 2 s
//! measurement, raised for the linear solve to 12 times one solve (the
//! largest size's LU takes about 1.2 s, so that benchmark takes about
//! 15 s); the whole run takes about three minutes on two cores. `cargo run --release --example scaling_table`
//! prints the same measurement as a table without criterion.

use std::hint::black_box;
use std::sync::Arc;
use std::time::{Duration, Instant};

use criterion::{BatchSize, BenchmarkId, Criterion, SamplingMode, criterion_group, criterion_main};
use solver::assembly::solid_pattern;
use solver::linear::Block;
use solver::newton::IterationProbe;
use solver::system::DofMap;
use solver::{Dim, Method, Model, Scene, SolveOptions, SpaceDim, State, solve_model};

/// Measurement time per benchmark (the linear solve's is raised to fit 10
/// samples of one iteration at the larger sizes).
const MEASUREMENT: Duration = Duration::from_secs(2);

/// Refine factors giving about 1e3, 3e3, 1e4, 3e4 and 1e5 equations.
const SIZES: [(usize, usize); 5] = [(8, 4), (14, 7), (26, 13), (46, 23), (84, 42)];

/// The 3D refine factor of `solver_scaling_3d` (every direction).
const REFINE_3D: usize = 9;

/// The `GAPSIM_LINEAR` solver (default LU).
fn linear() -> solver::LinearSolverKind {
    std::env::var("GAPSIM_LINEAR")
        .map(|v| v.parse().expect("GAPSIM_LINEAR is `lu` or `ldlt`"))
        .unwrap_or_default()
}

/// A refined model, its options, the converged state after the first load
/// step and the load factor of the second.
fn setup(refine: (usize, usize)) -> (Model, SolveOptions, State, f64) {
    let scene = Scene::from_toml_str(
        solver::scenes::STACKED_CANTILEVER,
        "stacked-cantilever.toml",
    )
    .expect("the paper scene parses")
    .refined(refine.0, refine.1);
    let model = scene.build_model().expect("the refined scene builds");
    converged_first_step(&scene, model)
}

/// `scenes/block3d.toml` refined `n`-fold in every direction, as
/// [`setup`].
fn setup_3d(n: usize) -> (Model<3>, SolveOptions, State<3>, f64) {
    let mut scene = Scene::from_toml_str(include_str!("../scenes/block3d.toml"), "block3d.toml")
        .expect("the 3D block parses");
    scene.refine.x *= n;
    scene.refine.y *= n;
    scene.refine.z = Some(scene.refine.z.unwrap_or(1) * n);
    let model = scene.build_model::<3>().expect("the refined block builds");
    converged_first_step(&scene, model)
}

/// The model, the complete formulation's options with the scene's steps,
/// the converged state after the first load step and the second's load
/// factor.
fn converged_first_step<const D: usize>(
    scene: &Scene,
    model: Model<D>,
) -> (Model<D>, SolveOptions, State<D>, f64)
where
    Dim<D>: SpaceDim<D>,
{
    let opts = SolveOptions {
        method: Method::Complete,
        linear: linear(),
        ..SolveOptions::from_scene(scene)
    };
    let step = model.load_factor_end / opts.steps as f64;
    let mut first = model.clone();
    first.load_factor_end = step;
    let solution = solve_model(
        &first,
        &SolveOptions {
            steps: 1,
            ..opts.clone()
        },
    )
    .expect("the first load step converges");
    (model, opts, solution.final_state, 2.0 * step)
}

fn solver_scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("solver_scaling");
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(MEASUREMENT);
    for refine in SIZES {
        let (model, opts, state, load_factor) = setup(refine);
        let mut probe =
            IterationProbe::new(&model, &opts, &state, load_factor).expect("probe builds");
        let n = probe.equations();
        // inputs of the later phases, and the symbolic LU (built once)
        let after_contact = probe.contact().expect("contact evaluates");
        let mut assembled = after_contact.clone();
        probe.solid(&mut assembled.system);
        probe
            .linear_solve(assembled.clone())
            .expect("the system solves");
        // one numeric solve, to size the measurement time of that benchmark
        let t = Instant::now();
        probe
            .linear_solve(assembled.clone())
            .expect("the system solves");
        let lu_time = t.elapsed();

        group.bench_with_input(BenchmarkId::new("solid_assembly", n), &n, |b, _| {
            b.iter_batched(
                || after_contact.system.clone(),
                |mut system| {
                    probe.solid(&mut system);
                    system
                },
                BatchSize::LargeInput,
            )
        });
        group.bench_with_input(BenchmarkId::new("contact_evaluation", n), &n, |b, _| {
            b.iter(|| black_box(probe.contact().expect("contact evaluates")))
        });
        // 10 flat samples of one iteration at least, with some slack
        group.measurement_time(MEASUREMENT.max(lu_time * 12));
        group.bench_with_input(BenchmarkId::new("linear_solve", n), &n, |b, _| {
            b.iter_batched(
                || assembled.clone(),
                |input| probe.linear_solve(input).expect("the system solves"),
                BatchSize::LargeInput,
            )
        });
        group.measurement_time(MEASUREMENT);
        assert_eq!(
            probe.symbolic_factorisations(),
            1,
            "the pattern must not change between iterations"
        );
    }
    group.finish();
}

/// The solid assembly and the linear solve of one 3D iteration (the
/// contact phase is empty in 3D).
fn solver_scaling_3d(c: &mut Criterion) {
    let mut group = c.benchmark_group("solver_scaling_3d");
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(MEASUREMENT);
    let (model, opts, state, load_factor) = setup_3d(REFINE_3D);
    let mut probe = IterationProbe::new(&model, &opts, &state, load_factor).expect("probe builds");
    let n = probe.equations();
    let empty = probe.contact().expect("contact evaluates");
    let mut assembled = empty.clone();
    probe.solid(&mut assembled.system);
    probe
        .linear_solve(assembled.clone())
        .expect("the system solves");
    let t = Instant::now();
    probe
        .linear_solve(assembled.clone())
        .expect("the system solves");
    let solve_time = t.elapsed();
    group.bench_with_input(BenchmarkId::new("solid_assembly", n), &n, |b, _| {
        b.iter_batched(
            || empty.system.clone(),
            |mut system| {
                probe.solid(&mut system);
                system
            },
            BatchSize::LargeInput,
        )
    });
    // the same assembly into the solid block a PETSc solve takes
    // (`solver::linear::Block`) instead of triplets
    let dofs = DofMap::new(&model, 0);
    assert_eq!(dofs.n_eq(), n, "no contact, no multipliers");
    let pattern = solid_pattern(&model, &dofs, None).expect("the pattern builds");
    let mut blocked = empty.system.clone();
    blocked.block = Some(Block::new(Arc::new(pattern)));
    group.bench_with_input(BenchmarkId::new("solid_assembly_block", n), &n, |b, _| {
        b.iter_batched(
            || blocked.clone(),
            |mut system| {
                probe.solid(&mut system);
                system
            },
            BatchSize::LargeInput,
        )
    });
    group.measurement_time(MEASUREMENT.max(solve_time * 12));
    group.bench_with_input(BenchmarkId::new("linear_solve", n), &n, |b, _| {
        b.iter_batched(
            || assembled.clone(),
            |input| probe.linear_solve(input).expect("the system solves"),
            BatchSize::LargeInput,
        )
    });
    assert_eq!(probe.symbolic_factorisations(), 1);
    group.finish();
}

/// A Mindlin scene (`scenes/mindlin.toml`, h = 0.1, or
/// `scenes/mindlin3d.toml` on `mesh`) at load factor `to` solved in
/// `steps` steps with its friction, and the same model without friction:
/// `(frictional model, frictionless model, options, the frictional state,
/// the same state without the tangential multipliers)`.
#[allow(clippy::type_complexity)] // the two models, the options and two states
fn mindlin_states<const D: usize>(
    file: &str,
    mesh: Option<&str>,
    to: f64,
    steps: usize,
) -> (Model<D>, Model<D>, SolveOptions, State<D>, State<D>)
where
    Dim<D>: SpaceDim<D> + solver::SceneDim<D>,
{
    let path = format!("{}/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::from_file(path).expect("the Mindlin scene parses");
    if let Some(mesh) = mesh {
        scene.mesh = Some(solver::scene::MeshSpec {
            file: mesh.to_owned(),
        });
    }
    let mut model = scene.build_model::<D>().expect("the Mindlin scene builds");
    let opts = SolveOptions {
        method: Method::Complete,
        linear: linear(),
        ..SolveOptions::from_scene(&scene)
    };
    let mut partial = model.clone();
    partial.load_factor_end = to;
    let solution = solve_model(
        &partial,
        &SolveOptions {
            steps,
            ..opts.clone()
        },
    )
    .expect("the Mindlin scene converges");
    let state = solution.final_state;
    let frictionless_state = State {
        multipliers: state.multipliers[..solution.multiplier_dofs.len()].to_vec(),
        friction: Vec::new(),
        ..state.clone()
    };
    let frictional = model.clone();
    for pair in &mut model.contacts {
        pair.friction = 0.0;
    }
    (frictional, model, opts, state, frictionless_state)
}

/// Times the contact phase and the contact phase with the solid assembly
/// of `states` (`mindlin_states`) with friction and without, in `group`.
fn friction_phases<const D: usize>(
    c: &mut Criterion,
    group: &str,
    states: (Model<D>, Model<D>, SolveOptions, State<D>, State<D>),
) where
    Dim<D>: SpaceDim<D>,
{
    let mut group = c.benchmark_group(group);
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(MEASUREMENT);
    let (frictional, frictionless, opts, state, state0) = states;
    for (name, model, state) in [
        ("mu0", &frictionless, &state0),
        ("mu0.3", &frictional, &state),
    ] {
        let probe = IterationProbe::new(model, &opts, state, 0.8).expect("probe builds");
        group.bench_function(BenchmarkId::new("contact_evaluation", name), |b| {
            b.iter(|| black_box(probe.contact().expect("contact evaluates")))
        });
        group.bench_function(BenchmarkId::new("contact_and_solid", name), |b| {
            b.iter(|| {
                let mut phase = probe.contact().expect("contact evaluates");
                probe.solid(&mut phase.system);
                black_box(phase)
            })
        });
    }
    group.finish();
}

/// What friction costs per Newton iteration (issue 32's item 5, in 2D): on
/// the Mindlin scene in partial slip (load factor 0.75 of the press-then-
/// shift schedule), the contact phase (re-projection, the Type 6 gap and,
/// with friction, slip kernels, the active set with the stick/slip
/// states, the contact scatter) and the contact phase with the solid
/// assembly, with `mu = 0.3` and with the same model and state
/// frictionless (`.../mu0`). The linear solve is `solver_scaling`'s.
fn friction_cost(c: &mut Criterion) {
    friction_phases::<2>(
        c,
        "friction_cost",
        mindlin_states("mindlin.toml", None, 0.75, 6),
    );
}

/// The same on the 3D Mindlin scene's coarse half model
/// (`scenes/mindlin3d.toml` on `mindlin3d-coarse.msh`, load factor 0.75 in
/// 6 steps; the solve that makes the state takes about half a minute).
fn friction_cost_3d(c: &mut Criterion) {
    friction_phases::<3>(
        c,
        "friction_cost_3d",
        mindlin_states("mindlin3d.toml", Some("mindlin3d-coarse.msh"), 0.75, 6),
    );
}

criterion_group!(
    benches,
    solver_scaling,
    solver_scaling_3d,
    friction_cost,
    friction_cost_3d
);
criterion_main!(benches);
