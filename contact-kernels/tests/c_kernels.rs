//! The checked-in C kernels (`contact-kernels/c/`) against the Rust kernels,
//! bit for bit.
//!
//! The test compiles the C files, the shared runtime they call
//! (`c/gapsim_runtime.c`) and a driver (`tests/c/driver.c`) with the
//! system C compiler (`$CC`, else `cc`) as C99 with `-O2 -ffp-contract=off`
//! and `-Wall -Wextra -pedantic -Werror`, feeds it configurations as the
//! bits of each double, and compares every output of the projection and of
//! every type of both formulations (status code, gap, `xi_m`, gradient,
//! Hessian) with [`Projector::project`] and [`Kernel::eval`]: equal bits, or
//! the same error code. The configurations are the verifier's (the
//! workspace crate `gapsim-families`, the one generator that `gapsim verify`
//! and `tests/kernels_ad.rs` at the workspace root draw from: same
//! families, seeds and order), constructed along both normals, each also
//! translated, plus degenerate, non-finite and over- or underflowing input;
//! every configuration is evaluated under both formulations.
//!
//! With the crate feature `quadratic-slave-normal` (on in `cargo test
//! --workspace`), the 3-node formulation's C files are compared the same
//! way (`tests/c/driver_quadratic.c`, 12 coordinates) on curved, straight,
//! uniform, far, scaled, degenerate (zero chord, folded segments, vanishing
//! slave tangent, no root) and non-finite 3-node configurations and on the
//! verifier's 3-node families (`gapsim_families::quadratic`).
//!
//! The formulations of 3D faces (tri3 and quad4, every pair of kinds, both
//! readings) are compared the same way through `tests/c/driver_faces.c`
//! (the projection and types 1..=6, `xi_m` of two values) on the
//! verifier's face families (`gapsim_families::faces`) plus non-finite
//! input, slave points outside and on the edges of their face, degenerate
//! and folded faces, a master along the slave normal, projections out of
//! reach and extreme scales (`tests/common/faces.rs`); every status of the
//! face path occurs. The face sources are compiled one object each, as
//! many at once as the machine has cores.
//!
//! The test is skipped, with a message, only when no C compiler is found.
//! It also compiles and runs `examples/c/evaluate.c`.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use contact_kernels::Formulation;
use contact_kernels::{
    ApproxType, DEGENERATE_LENGTH, GapOut, Kernel, KernelError, OutputKind, Projector, Segment,
    SlipOut, XI_M_LIMIT,
};
#[cfg(feature = "quadratic-slave-normal")]
use gapsim_families::seeded;
#[cfg(feature = "quadratic-slave-normal")]
use rand::Rng;
#[cfg(feature = "quadratic-slave-normal")]
use rand_chacha::ChaCha8Rng;

mod common;
use common::faces::{FACES, FaceConfig, face_configurations};
use common::{BOTH, Config, configurations};
use gapsim_families::faces::FaceKind;

// ---------------------------------------------------------------------------
// The two sides.
// ---------------------------------------------------------------------------

/// The C status code of a Rust error (gapsim.h's `enum gapsim_status`).
fn code(e: &KernelError) -> i32 {
    match e {
        KernelError::DegenerateFace {
            face: Segment::Slave,
            ..
        } => 12,
        KernelError::DegenerateFace {
            face: Segment::Master,
            ..
        } => 13,
        KernelError::FoldedFace {
            face: Segment::Slave,
            ..
        } => 14,
        KernelError::FoldedFace {
            face: Segment::Master,
            ..
        } => 15,
        KernelError::SlavePointOutside { .. } => 16,
        KernelError::NonFinite { .. } => 1,
        KernelError::DegenerateSegment {
            segment: Segment::Slave,
            ..
        } => 2,
        KernelError::DegenerateSegment {
            segment: Segment::Master,
            ..
        } => 3,
        KernelError::NoProjection { .. } => 4,
        KernelError::ProjectionOutOfReach { .. } => 5,
        KernelError::ProjectionDiverged { .. } => 6,
        KernelError::NonFiniteOutput { output, .. } => match output {
            OutputKind::Gap => 7,
            OutputKind::Gradient => 8,
            OutputKind::Hessian => 9,
            OutputKind::Slip => 17,
        },
        KernelError::FoldedSegment {
            segment: Segment::Slave,
            ..
        } => 10,
        KernelError::FoldedSegment {
            segment: Segment::Master,
            ..
        } => 11,
        other => panic!("{other:?} has no C counterpart"),
    }
}

/// One function's result: the status and, on success, the output bits
/// (gap, xi_m, grad, hess).
#[derive(Debug, PartialEq)]
struct Outcome {
    status: i32,
    bits: Vec<u64>,
}

/// The last converged projection the slip functions get for configuration
/// `k` of slave point `xi_s`: a value near the segment, or NaN for every
/// 29th configuration (a non-finite input of the slip's own).
fn previous(k: usize, xi_s: f64) -> f64 {
    if k % 29 == 7 {
        f64::NAN
    } else {
        0.3 * xi_s - 0.1
    }
}

/// [`previous`] for a face's slave point: `INFINITY` in the second
/// component for every 29th.
fn previous_face(k: usize, [u, v]: [f64; 2]) -> [f64; 2] {
    if k % 29 == 7 {
        [0.1, f64::INFINITY]
    } else {
        [0.3 * u - 0.1, 0.2 * v + 0.05]
    }
}

/// The Rust side of the slip of type `ty` of `f`: status and bits of the
/// slip's components, `xi_m`, the gradients and the Hessians.
fn rust_slip(f: Formulation, ty: ApproxType, q: &[f64], xi_s: &[f64], xi_m0: &[f64]) -> Outcome {
    let slip = Kernel::new(f, ty).unwrap().slip().unwrap();
    let mut o = SlipOut::new(&slip);
    match slip.eval(q, xi_s, xi_m0, &mut o) {
        Ok(()) => {
            let c = slip.components();
            let mut bits: Vec<u64> = o.slip().iter().map(|v| v.to_bits()).collect();
            bits.extend(o.xi_m_all().iter().map(|v| v.to_bits()));
            for i in 0..c {
                bits.extend(o.grad(i).iter().map(|v| v.to_bits()));
            }
            for i in 0..c {
                if let Some(h) = o.hess(i) {
                    bits.extend(h.iter().map(|v| v.to_bits()));
                }
            }
            Outcome { status: 0, bits }
        }
        Err(e) => Outcome {
            status: code(&e),
            bits: Vec::new(),
        },
    }
}

/// The Rust side: per formulation (slave-normal, closest-point), the
/// projection, types 1..=6 and the slip's types 1..=6 (at `xi_m0`), in
/// the driver's order.
fn rust_outcomes(c: &Config, xi_m0: f64) -> Vec<Outcome> {
    let mut out = Vec::new();
    let mut scratch = [0.0; 8];
    for f in BOTH {
        out.push(
            match Projector::new(f)
                .unwrap()
                .project(&c.q, c.xi_s, &mut scratch)
            {
                Ok(p) => Outcome {
                    status: 0,
                    bits: vec![p.gap.to_bits(), p.xi_m.to_bits()],
                },
                Err(e) => Outcome {
                    status: code(&e),
                    bits: Vec::new(),
                },
            },
        );
        for ty in ApproxType::ALL {
            let kernel = Kernel::new(f, ty).unwrap();
            let mut g = GapOut::new(&kernel);
            out.push(match kernel.eval(&c.q, c.xi_s, &mut g) {
                Ok(()) => {
                    let mut bits = vec![g.gap().to_bits(), g.xi_m().to_bits()];
                    bits.extend(g.grad().iter().map(|v| v.to_bits()));
                    if let Some(h) = g.hess() {
                        bits.extend(h.iter().map(|v| v.to_bits()));
                    }
                    Outcome { status: 0, bits }
                }
                Err(e) => Outcome {
                    status: code(&e),
                    bits: Vec::new(),
                },
            });
        }
        for ty in ApproxType::ALL {
            out.push(rust_slip(f, ty, &c.q, &[c.xi_s], &[xi_m0]));
        }
    }
    out
}

fn parse_outcome(line: &str) -> Outcome {
    let mut words = line.split_whitespace();
    let status = words.next().expect("a status").parse().expect("an integer");
    let bits = words
        .map(|w| u64::from_str_radix(w, 16).expect("16 hex digits"))
        .collect();
    Outcome { status, bits }
}

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn compiler() -> String {
    std::env::var("CC").unwrap_or_else(|_| "cc".into())
}

/// Whether the C compiler runs at all.
fn have_compiler() -> bool {
    match Command::new(compiler()).arg("--version").output() {
        Ok(_) => true,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
        Err(e) => panic!("cannot run {}: {e}", compiler()),
    }
}

/// The test's C flags.
const FLAGS: [&str; 7] = [
    "-std=c99",
    "-O2",
    "-ffp-contract=off",
    "-Wall",
    "-Wextra",
    "-pedantic",
    "-Werror",
];

/// Compiles `sources` and the shared runtime (`c/gapsim_runtime.c`) with
/// the test's flags into `out`.
fn compile(sources: &[PathBuf], out: &Path) {
    let c_dir = manifest().join("c");
    let output = Command::new(compiler())
        .args(FLAGS)
        .arg("-I")
        .arg(&c_dir)
        .args(sources)
        .arg(c_dir.join("gapsim_runtime.c"))
        .arg("-o")
        .arg(out)
        .arg("-lm")
        .output()
        .expect("run the C compiler");
    assert!(
        output.status.success(),
        "{} failed on {sources:?}:\n{}",
        compiler(),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Compiles each of `sources` with the test's flags into an object file in
/// `dir` (as many compilers at once as the machine has cores: the face
/// kernels are large), then links them into `out`.
fn compile_each(sources: &[PathBuf], dir: &Path, out: &Path) {
    let c_dir = manifest().join("c");
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let objects: Vec<PathBuf> = sources
        .iter()
        .map(|s| dir.join(s.file_name().unwrap()).with_extension("o"))
        .collect();
    let pending: Vec<(&PathBuf, &PathBuf)> = sources.iter().zip(&objects).collect();
    for batch in pending.chunks(jobs) {
        let children: Vec<_> = batch
            .iter()
            .map(|(src, obj)| {
                let child = Command::new(compiler())
                    .args(FLAGS)
                    .arg("-I")
                    .arg(&c_dir)
                    .arg("-c")
                    .arg(src)
                    .arg("-o")
                    .arg(obj)
                    .stderr(Stdio::piped())
                    .spawn()
                    .expect("run the C compiler");
                (src, child)
            })
            .collect();
        for (src, child) in children {
            let output = child.wait_with_output().expect("wait for the C compiler");
            assert!(
                output.status.success(),
                "{} failed on {}:\n{}",
                compiler(),
                src.display(),
                String::from_utf8_lossy(&output.stderr)
            );
        }
    }
    let output = Command::new(compiler())
        .args(&objects)
        .arg("-o")
        .arg(out)
        .arg("-lm")
        .output()
        .expect("run the linker");
    assert!(
        output.status.success(),
        "linking {objects:?} failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The driver's functions per configuration, in its order.
fn names() -> Vec<String> {
    let mut names = Vec::new();
    for f in ["slave-normal", "closest-point"] {
        names.push(format!("{f} project"));
        names.extend((1..=6).map(|t| format!("{f} type {t}")));
        names.extend((1..=6).map(|t| format!("{f} slip type {t}")));
    }
    names
}

#[test]
fn c_kernels_equal_rust_kernels_bit_for_bit() {
    if !have_compiler() {
        eprintln!(
            "SKIPPED: no C compiler (`{}` not found); the C kernels were not compared",
            compiler()
        );
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_kernels");
    std::fs::create_dir_all(&dir).unwrap();
    let driver = dir.join("driver");
    let c_dir = manifest().join("c");
    compile(
        &[
            manifest().join("tests/c/driver.c"),
            c_dir.join("gapsim_slave_normal.c"),
            c_dir.join("gapsim_closest_point.c"),
        ],
        &driver,
    );

    let configs = configurations();
    let names = names();
    let mut input = String::new();
    for (k, c) in configs.iter().enumerate() {
        input.push_str(&format!(
            "{:016x} {:016x}",
            c.xi_s.to_bits(),
            previous(k, c.xi_s).to_bits()
        ));
        for v in c.q {
            input.push_str(&format!(" {:016x}", v.to_bits()));
        }
        input.push('\n');
    }
    let mut child = Command::new(&driver)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run the driver");
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(output.status.success(), "the driver failed");
    let text = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines.len(),
        configs.len() * names.len(),
        "driver output lines"
    );

    let (mut values, mut errors, mut differences) = (0usize, 0usize, Vec::new());
    let mut statuses = [0usize; 18];
    for (k, c) in configs.iter().enumerate() {
        let rust = rust_outcomes(c, previous(k, c.xi_s));
        for (j, r) in rust.into_iter().enumerate() {
            let cside = parse_outcome(lines[k * names.len() + j]);
            statuses[r.status as usize] += 1;
            if r.status == 0 {
                values += r.bits.len();
            } else {
                errors += 1;
            }
            if cside != r {
                differences.push(format!(
                    "{} #{k} ({}, q = {:?}, xi_s = {}): C {cside:?}, Rust {r:?}",
                    names[j], c.label, c.q, c.xi_s
                ));
            }
        }
    }
    eprintln!(
        "{} configurations x {} functions: {values} output values compared bit for bit, \
         {errors} error codes compared; statuses (0..=17) {statuses:?}; {} differences",
        configs.len(),
        names.len(),
        differences.len()
    );
    assert!(
        differences.is_empty(),
        "{} differences between the C and the Rust kernels, e.g.:\n{}",
        differences.len(),
        differences[..differences.len().min(10)].join("\n")
    );
    // The hard families must exercise the error paths too.
    for s in [1, 2, 3, 4, 5, 9] {
        assert!(statuses[s] > 0, "no configuration gave status {s}");
    }
}

/// The limits `gapsim.h` applies are contact-kernels' constants.
#[test]
fn c_limits_are_the_rust_constants() {
    let header = std::fs::read_to_string(manifest().join("c/gapsim.h")).unwrap();
    let define = |name: &str| -> f64 {
        let prefix = format!("#define {name} ");
        let line = header
            .lines()
            .find_map(|l| l.strip_prefix(&prefix))
            .unwrap_or_else(|| panic!("gapsim.h defines {name}"));
        line.trim().parse().unwrap()
    };
    assert_eq!(
        define("GAPSIM_DEGENERATE_LENGTH").to_bits(),
        DEGENERATE_LENGTH.to_bits()
    );
    assert_eq!(define("GAPSIM_XI_M_LIMIT").to_bits(), XI_M_LIMIT.to_bits());
}

/// `examples/c/evaluate.c` builds with its documented command and prints
/// the worked example's gap.
#[test]
fn c_example_runs() {
    if !have_compiler() {
        eprintln!(
            "SKIPPED: no C compiler (`{}` not found); examples/c/evaluate.c was not built",
            compiler()
        );
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_kernels");
    std::fs::create_dir_all(&dir).unwrap();
    let exe = dir.join("evaluate");
    compile(
        &[
            manifest().join("../examples/c/evaluate.c"),
            manifest().join("c/gapsim_slave_normal.c"),
        ],
        &exe,
    );
    let out = Command::new(&exe).output().expect("run the example");
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("gap  = 0.129090446096668"), "{text}");
    assert!(
        text.contains("zero-length slave: GAPSIM_DEGENERATE_SLAVE"),
        "{text}"
    );
}

// ---------------------------------------------------------------------------
// The 3-node formulation (12 coordinates).
// ---------------------------------------------------------------------------

/// 3-node configurations (label, `q`, `xi_s`) for the C comparison:
/// statuses of every kind, values of curved segments, then the verifier's
/// 3-node families (`gapsim_families::quadratic`).
#[cfg(feature = "quadratic-slave-normal")]
fn quadratic_configurations() -> Vec<(String, [f64; 12], f64)> {
    let mut out: Vec<(&'static str, [f64; 12], f64)> = Vec::new();
    let mut rng = seeded(0x6a95_2001);
    // A slave with its mid node bowed and shifted, and a master facing it
    // across a gap (reversed, offset along the slave's chord normal,
    // perturbed): mostly projecting, some not.
    let curved = |rng: &mut ChaCha8Rng, spread: f64| -> ([f64; 12], f64) {
        let a = [rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0)];
        let len = rng.random_range(0.2..5.0);
        let th: f64 = rng.random_range(-3.1..3.1);
        let (s, c) = th.sin_cos();
        let b = [a[0] + len * c, a[1] + len * s];
        let normal = [s, -c];
        let node = |p: [f64; 2], bow: f64, shift: f64| {
            [
                p[0] + len * (shift * c - bow * s),
                p[1] + len * (shift * s + bow * c),
            ]
        };
        let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let m = node(
            mid,
            spread * rng.random_range(-0.3..0.3),
            spread * rng.random_range(-0.2..0.2),
        );
        let gap = len * rng.random_range(-0.3..0.3);
        let off = |p: [f64; 2], rng: &mut ChaCha8Rng| {
            [
                p[0] + gap * normal[0] + len * spread * rng.random_range(-0.2..0.2),
                p[1] + gap * normal[1] + len * spread * rng.random_range(-0.2..0.2),
            ]
        };
        let (ma, mb) = (off(b, rng), off(a, rng));
        let mm = off(mid, rng);
        let q = [
            a[0], a[1], b[0], b[1], m[0], m[1], ma[0], ma[1], mb[0], mb[1], mm[0], mm[1],
        ];
        (q, rng.random_range(-1.0..=1.0))
    };
    for _ in 0..400 {
        let (q, xi_s) = curved(&mut rng, 1.0);
        out.push(("curved", q, xi_s));
    }
    for _ in 0..100 {
        let (q, xi_s) = curved(&mut rng, 1e-6);
        out.push(("near-straight", q, xi_s));
    }
    for _ in 0..400 {
        let q: [f64; 12] = std::array::from_fn(|_| rng.random_range(-2.0..2.0));
        out.push(("uniform", q, rng.random_range(-1.5..=1.5)));
    }
    for _ in 0..100 {
        let (q, xi_s) = curved(&mut rng, 1.0);
        let shift = [1e6 + rng.random_range(-1.0..1.0), -1e6];
        out.push(("far", std::array::from_fn(|i| q[i] + shift[i % 2]), xi_s));
    }
    for _ in 0..40 {
        let (q, xi_s) = curved(&mut rng, 1.0);
        for scale in [1e-6, 1e6] {
            out.push(("scales", q.map(|v| v * scale), xi_s));
        }
    }
    // Straight along +x, master curved towards it (tests/quadratic.rs).
    const CURVED: [f64; 12] = [
        0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 1.0, -0.8,
    ];
    out.push(("hand-computed", CURVED, 0.5));
    let with = |changes: &[(usize, f64)]| {
        let mut q = CURVED;
        for &(i, v) in changes {
            q[i] = v;
        }
        q
    };
    out.push(("zero-length slave", with(&[(2, 0.0), (3, 0.0)]), 0.5));
    out.push(("zero-length master", with(&[(8, 2.0), (9, -1.0)]), 0.5));
    for mid_x in [1.5, 0.5, 3.0, 1.0 + 0.5 * (1.0 - 1e-6)] {
        out.push(("folded slave", with(&[(4, mid_x)]), 0.5));
    }
    out.push(("folded master", with(&[(10, 0.5)]), 0.5));
    out.push(("zero slave tangent", with(&[(4, 1.25)]), 2.0));
    let no_root = [0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 4.0, 1.0, 4.0, -1.0, 3.0, 0.0];
    for xi_s in [0.0, 0.3] {
        out.push(("no root", no_root, xi_s));
    }
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for i in 0..12 {
            out.push(("non-finite input", with(&[(i, bad)]), 0.5));
        }
        out.push(("non-finite input", CURVED, bad));
    }
    for e in (-170..=-90).chain(90..=170).step_by(5) {
        let s = 10f64.powi(e);
        out.push(("extreme scale", CURVED.map(|v| v * s), 0.5));
    }
    let mut out: Vec<(String, [f64; 12], f64)> = out
        .into_iter()
        .map(|(family, q, xi_s)| (family.to_owned(), q, xi_s))
        .collect();
    for c in gapsim_families::quadratic() {
        let q: [f64; 12] = c.q.try_into().expect("3-node families have 12 coordinates");
        out.push((format!("verifier {}", c.label), q, c.params[0]));
    }
    out
}

/// The Rust side for one 3-node configuration: the projection and types
/// 1..=6, in the driver's order.
#[cfg(feature = "quadratic-slave-normal")]
fn rust_quadratic_outcomes(q: &[f64; 12], xi_s: f64, xi_m0: f64) -> Vec<Outcome> {
    let f = Formulation::QuadraticSlaveNormal;
    let mut out = vec![
        match Projector::new(f).unwrap().project(q, xi_s, &mut [0.0; 12]) {
            Ok(p) => Outcome {
                status: 0,
                bits: vec![p.gap.to_bits(), p.xi_m.to_bits()],
            },
            Err(e) => Outcome {
                status: code(&e),
                bits: Vec::new(),
            },
        },
    ];
    for ty in ApproxType::ALL {
        let kernel = Kernel::new(f, ty).unwrap();
        let mut g = GapOut::new(&kernel);
        out.push(match kernel.eval(q, xi_s, &mut g) {
            Ok(()) => {
                let mut bits = vec![g.gap().to_bits(), g.xi_m().to_bits()];
                bits.extend(g.grad().iter().map(|v| v.to_bits()));
                if let Some(h) = g.hess() {
                    bits.extend(h.iter().map(|v| v.to_bits()));
                }
                Outcome { status: 0, bits }
            }
            Err(e) => Outcome {
                status: code(&e),
                bits: Vec::new(),
            },
        });
    }
    for ty in ApproxType::ALL {
        out.push(rust_slip(f, ty, q, &[xi_s], &[xi_m0]));
    }
    out
}

#[cfg(feature = "quadratic-slave-normal")]
#[test]
fn c_quadratic_kernels_equal_rust_kernels_bit_for_bit() {
    if !have_compiler() {
        eprintln!(
            "SKIPPED: no C compiler (`{}` not found); the C kernels were not compared",
            compiler()
        );
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_kernels");
    std::fs::create_dir_all(&dir).unwrap();
    let driver = dir.join("driver_quadratic");
    compile(
        &[
            manifest().join("tests/c/driver_quadratic.c"),
            manifest().join("c/gapsim_quadratic_slave_normal.c"),
        ],
        &driver,
    );
    let configs = quadratic_configurations();
    let mut input = String::new();
    for (k, (_, q, xi_s)) in configs.iter().enumerate() {
        input.push_str(&format!(
            "{:016x} {:016x}",
            xi_s.to_bits(),
            previous(k, *xi_s).to_bits()
        ));
        for v in q {
            input.push_str(&format!(" {:016x}", v.to_bits()));
        }
        input.push('\n');
    }
    let mut child = Command::new(&driver)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run the driver");
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(output.status.success(), "the driver failed");
    let text = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), configs.len() * 13, "driver output lines");
    let (mut values, mut differences) = (0usize, Vec::new());
    let mut statuses = [0usize; 18];
    for (k, (family, q, xi_s)) in configs.iter().enumerate() {
        let rust = rust_quadratic_outcomes(q, *xi_s, previous(k, *xi_s));
        for (j, r) in rust.into_iter().enumerate() {
            let cside = parse_outcome(lines[k * 13 + j]);
            statuses[r.status as usize] += 1;
            values += r.bits.len();
            if cside != r {
                differences.push(format!(
                    "function {j} #{k} ({family}, q = {q:?}, xi_s = {xi_s}): C {cside:?}, Rust {r:?}"
                ));
            }
        }
    }
    eprintln!(
        "quadratic-slave-normal: {} configurations x 13 functions: {values} output values \
         compared bit for bit; statuses (0..=17) {statuses:?}; {} differences",
        configs.len(),
        differences.len()
    );
    assert!(
        differences.is_empty(),
        "{} differences between the C and the Rust kernels, e.g.:\n{}",
        differences.len(),
        differences[..differences.len().min(10)].join("\n")
    );
    for s in [0, 1, 2, 3, 4, 10, 11] {
        assert!(statuses[s] > 0, "no configuration gave status {s}");
    }
}

// ---------------------------------------------------------------------------
// 3D faces (18 to 24 coordinates, xi_s and xi_m of two values).
// ---------------------------------------------------------------------------

/// The Rust side for one face configuration of formulation `f`: the
/// projection, types 1..=6 and the slip's types 1..=6 (at `xi_m0`), in the
/// face driver's order.
fn rust_face_outcomes(f: Formulation, c: &FaceConfig, xi_m0: [f64; 2]) -> Vec<Outcome> {
    let projector = Projector::new(f).unwrap();
    let mut scratch = vec![0.0; projector.coords()];
    let mut out = vec![match projector.project(&c.q, c.xi_s, &mut scratch) {
        Ok(p) => Outcome {
            status: 0,
            bits: std::iter::once(p.gap)
                .chain(p.xi_m_all().iter().copied())
                .map(f64::to_bits)
                .collect(),
        },
        Err(e) => Outcome {
            status: code(&e),
            bits: Vec::new(),
        },
    }];
    for ty in ApproxType::ALL {
        let kernel = Kernel::new(f, ty).unwrap();
        let mut g = GapOut::new(&kernel);
        out.push(match kernel.eval(&c.q, c.xi_s, &mut g) {
            Ok(()) => {
                let mut bits = vec![g.gap().to_bits()];
                bits.extend(g.xi_m_all().iter().map(|v| v.to_bits()));
                bits.extend(g.grad().iter().map(|v| v.to_bits()));
                if let Some(h) = g.hess() {
                    bits.extend(h.iter().map(|v| v.to_bits()));
                }
                Outcome { status: 0, bits }
            }
            Err(e) => Outcome {
                status: code(&e),
                bits: Vec::new(),
            },
        });
    }
    for ty in ApproxType::ALL {
        out.push(rust_slip(f, ty, &c.q, &c.xi_s, &xi_m0));
    }
    out
}

#[test]
fn c_face_kernels_equal_rust_kernels_bit_for_bit() {
    if !have_compiler() {
        eprintln!(
            "SKIPPED: no C compiler (`{}` not found); the C face kernels were not compared",
            compiler()
        );
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_kernels_faces");
    std::fs::create_dir_all(&dir).unwrap();
    let driver = dir.join("driver_faces");
    let mut sources = vec![
        manifest().join("tests/c/driver_faces.c"),
        manifest().join("c/gapsim_runtime.c"),
    ];
    sources.extend(
        FACES
            .iter()
            .map(|(_, id, _, _)| manifest().join(format!("c/gapsim_{id}.c"))),
    );
    compile_each(&sources, &dir, &driver);

    let configs: Vec<(usize, FaceConfig)> = FACES
        .iter()
        .enumerate()
        .flat_map(|(i, &(_, _, s, m))| face_configurations(s, m).into_iter().map(move |c| (i, c)))
        .collect();
    let mut input = String::new();
    for (k, (i, c)) in configs.iter().enumerate() {
        input.push_str(&i.to_string());
        let xi_m0 = previous_face(k, c.xi_s);
        for v in c.xi_s.iter().chain(&xi_m0).chain(&c.q) {
            input.push_str(&format!(" {:016x}", v.to_bits()));
        }
        input.push('\n');
    }
    let mut child = Command::new(&driver)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run the face driver");
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(output.status.success(), "the face driver failed");
    let text = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), configs.len() * 13, "driver output lines");

    let (mut values, mut errors, mut differences) = (0usize, 0usize, Vec::new());
    let mut statuses = [[0usize; 18]; 8];
    for (k, (i, c)) in configs.iter().enumerate() {
        let f = FACES[*i].0;
        let xi_m0 = previous_face(k, c.xi_s);
        for (j, r) in rust_face_outcomes(f, c, xi_m0).into_iter().enumerate() {
            let cside = parse_outcome(lines[k * 13 + j]);
            statuses[*i][r.status as usize] += 1;
            values += r.bits.len();
            errors += usize::from(r.status != 0);
            if cside != r {
                differences.push(format!(
                    "{} function {j} #{k} ({}, q = {:?}, xi_s = {:?}): C {cside:?}, Rust {r:?}",
                    f.name(),
                    c.label,
                    c.q,
                    c.xi_s
                ));
            }
        }
    }
    for (i, (f, ..)) in FACES.iter().enumerate() {
        eprintln!("{}: statuses (0..=17) {:?}", f.name(), statuses[i]);
    }
    eprintln!(
        "faces: {} configurations x 13 functions: {values} output values compared bit for bit, \
         {errors} error codes compared; {} differences",
        configs.len(),
        differences.len()
    );
    assert!(
        differences.is_empty(),
        "{} differences between the C and the Rust face kernels, e.g.:\n{}",
        differences.len(),
        differences[..differences.len().min(10)].join("\n")
    );
    // Every formulation: values, non-finite input, a slave point outside,
    // degenerate faces on both sides; quad4 faces also folded; every
    // slave-normal formulation a master along the slave normal; the master
    // moved far away: a tri3's closed-form projection out of reach, a
    // quad4's Newton projection diverged.
    for (i, &(f, _, s, m)) in FACES.iter().enumerate() {
        let mut expected = vec![0, 1, 12, 13, 16];
        if s == FaceKind::Quad4 {
            expected.push(14);
        }
        if m == FaceKind::Quad4 {
            expected.extend([15, 6]);
        } else {
            expected.push(5);
        }
        if f.name().ends_with("slave-normal") {
            expected.push(4);
        }
        for code in expected {
            assert!(
                statuses[i][code] > 0,
                "{}: no configuration gave status {code}",
                f.name()
            );
        }
    }
}
