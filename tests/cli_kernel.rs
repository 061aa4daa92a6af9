//! The `gapsim kernel` contract (docs/conventions.md), tested by running the binary.
//!
//! * Output: one JSON object `{"gap":..,"xi_m":..,"grad":[n],"hess":[[n]xn]}`
//!   on stdout (`n` the formulation's coordinate count: 8 for two-node
//!   segments, 12 for `quadratic-slave-normal`), whose numbers round-trip **exactly** to the library's
//!   `f64` results (checked bit for bit, parsing the printed digits with
//!   Rust's correctly rounded `str::parse`), `hess` all zeros for Type 1.
//! * `--formulation` defaults to `slave-normal`; values starting with a
//!   minus are accepted both as `--nodes=-0.1,...` and `--nodes -0.1,...`.
//! * `--nodes` takes the formulation's coordinate count; a wrong count names
//!   the formulation, the count and the coordinates it expects.
//! * Bad input: a message on stderr, nothing on stdout, a non-zero exit
//!   status, never a panic.

use std::process::{Command, Output};

use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, evaluate};
use serde_json::Value;

const WORKED_NODES: &str = "0,1,2,1.1,2.1,0.9,-0.1,1.0";
const WORKED_Q: [f64; 8] = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];

fn gapsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gapsim"))
        .args(args)
        .output()
        .expect("run gapsim")
}

/// The printed numbers, in order, parsed from their digits with
/// `str::parse::<f64>` (correctly rounded), skipping the quoted keys.
fn numbers_in(json: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut in_string = false;
    let mut token = String::new();
    for c in json.chars() {
        if c == '"' {
            in_string = !in_string;
            continue;
        }
        if !in_string && (c.is_ascii_digit() || "+-.eE".contains(c)) {
            token.push(c);
        } else if !token.is_empty() {
            out.push(
                token
                    .parse()
                    .unwrap_or_else(|_| panic!("bad number `{token}` in {json}")),
            );
            token.clear();
        }
    }
    out
}

/// A successful run's JSON for 8 coordinates (see [`parse_success_n`]).
fn parse_success(out: &Output) -> Vec<f64> {
    parse_success_n(out, 8)
}

/// A successful run's JSON: checks the exact shape of the contract for `n`
/// coordinates and returns the 2 + n + n^2 numbers in order (gap, xi_m,
/// grad, hess rows).
fn parse_success_n(out: &Output, n: usize) -> Vec<f64> {
    let stdout = String::from_utf8(out.stdout.clone()).expect("utf-8 stdout");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "gapsim failed: {stderr}");
    assert_eq!(stdout.lines().count(), 1, "one line of output: {stdout}");
    let v: Value = serde_json::from_str(&stdout).expect("valid JSON");
    let obj = v.as_object().expect("a JSON object");
    let keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    let mut sorted = keys.clone();
    sorted.sort();
    assert_eq!(sorted, ["gap", "grad", "hess", "xi_m"], "keys of {stdout}");
    assert!(obj["gap"].is_f64() && obj["xi_m"].is_f64());
    let grad = obj["grad"].as_array().expect("grad is an array");
    assert_eq!(grad.len(), n);
    assert!(grad.iter().all(Value::is_number));
    let hess = obj["hess"].as_array().expect("hess is an array");
    assert_eq!(hess.len(), n);
    for row in hess {
        let row = row.as_array().expect("hess rows are arrays");
        assert_eq!(row.len(), n);
        assert!(row.iter().all(Value::is_number));
    }
    // The contract's field order, then the digits themselves.
    let pos = |k: &str| stdout.find(&format!("\"{k}\"")).unwrap();
    assert!(
        pos("gap") < pos("xi_m") && pos("xi_m") < pos("grad") && pos("grad") < pos("hess"),
        "{stdout}"
    );
    let nums = numbers_in(&stdout);
    assert_eq!(nums.len(), 2 + n + n * n, "{stdout}");
    nums
}

/// Asserts the printed numbers equal the library's result bit for bit.
#[track_caller]
fn assert_equals_library(nums: &[f64], f: Formulation, ty: ApproxType, q: &[f64; 8], xi_s: f64) {
    let lib = evaluate(f, ty, q, xi_s).expect("library evaluates");
    let mut expected = vec![lib.gap, lib.xi_m];
    expected.extend(lib.grad.iter());
    for i in 0..8 {
        for j in 0..8 {
            expected.push(lib.hess.map_or(0.0, |h| h[(i, j)]));
        }
    }
    for (k, (a, b)) in nums.iter().zip(&expected).enumerate() {
        assert_eq!(
            a.to_bits(),
            b.to_bits(),
            "{f} type {ty}: printed number {k} is {a:e}, library has {b:e}"
        );
    }
}

/// A published worked example: formulation, g, xi_m, g', first row of g''.
type Published = (&'static str, f64, f64, [f64; 8], [f64; 8]);

/// the worked example of docs/conventions.md, Type 6, both formulations: the published
/// digits (relative 1e-10 per entry, absolute 1e-13 for printed zeros).
#[test]
fn worked_example() {
    let published: [Published; 2] = [
        (
            "slave-normal",
            0.129090446096668,
            -0.278587699316629,
            [
                0.0162732380162,
                0.345075719401,
                0.0293417606046,
                0.658454250255,
                -0.0291613880704,
                -0.641550537549,
                -0.0164536105503,
                -0.361979432107,
            ],
            [
                0.00046515059696,
                -0.00462332803342,
                -0.000356320738686,
                0.00701758491545,
                -0.00741001952566,
                -0.163020429564,
                0.00730118966738,
                0.160626172682,
            ],
        ),
        (
            "closest-point",
            0.128503680399779,
            -0.267422680412371,
            [
                0.0158926813215,
                0.349638989074,
                0.0295149795971,
                0.649329551137,
                -0.0287753496564,
                -0.63305769244,
                -0.0166323112623,
                -0.36591084777,
            ],
            [
                0.0,
                0.0,
                0.0,
                0.0,
                -0.00720905132111,
                -0.158599129064,
                0.00720905132111,
                0.158599129064,
            ],
        ),
    ];
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * b.abs() + 1e-13;
    for (name, gap, xi_m, grad, row0) in published {
        let nums = parse_success(&gapsim(&[
            "kernel",
            "--formulation",
            name,
            "--type",
            "6",
            "--xi-s",
            "0.3",
            "--nodes",
            WORKED_NODES,
        ]));
        assert!(close(nums[0], gap), "{name}: gap {}", nums[0]);
        assert!(close(nums[1], xi_m), "{name}: xi_m {}", nums[1]);
        for i in 0..8 {
            assert!(
                close(nums[2 + i], grad[i]),
                "{name}: grad[{i}] {}",
                nums[2 + i]
            );
            assert!(
                close(nums[10 + i], row0[i]),
                "{name}: hess[0][{i}] {}",
                nums[10 + i]
            );
        }
        assert_equals_library(
            &nums,
            name.parse().unwrap(),
            ApproxType::Type6,
            &WORKED_Q,
            0.3,
        );
    }
}

/// Every formulation and type prints exactly the library's values (full
/// round-trip precision), Type 1 with an all-zero Hessian.
#[test]
fn every_kernel_round_trips() {
    for f in contact_kernels::pair_formulations() {
        for ty in ApproxType::ALL {
            let t = ty.index().to_string();
            let nums = parse_success(&gapsim(&[
                "kernel",
                "--formulation",
                f.name(),
                "--type",
                &t,
                "--xi-s",
                "0.3",
                "--nodes",
                WORKED_NODES,
            ]));
            assert_equals_library(&nums, f, ty, &WORKED_Q, 0.3);
            let hess_zero = nums[10..].iter().all(|&v| v == 0.0);
            assert_eq!(
                hess_zero,
                ty == ApproxType::Type1,
                "{f} type {ty}: Hessian all zero only for Type 1"
            );
        }
    }
}

/// `--formulation` defaults to slave-normal.
#[test]
fn formulation_defaults_to_slave_normal() {
    let implicit = gapsim(&[
        "kernel",
        "--type",
        "4",
        "--xi-s",
        "0.3",
        "--nodes",
        WORKED_NODES,
    ]);
    let explicit = gapsim(&[
        "kernel",
        "--formulation",
        "slave-normal",
        "--type",
        "4",
        "--xi-s",
        "0.3",
        "--nodes",
        WORKED_NODES,
    ]);
    assert_eq!(parse_success(&implicit), parse_success(&explicit));
    let other = gapsim(&[
        "kernel",
        "--formulation",
        "closest-point",
        "--type",
        "4",
        "--xi-s",
        "0.3",
        "--nodes",
        WORKED_NODES,
    ]);
    assert_ne!(parse_success(&implicit), parse_success(&other));
}

/// Negative values work with `=` and as a separate argument, in any order.
#[test]
fn negative_values() {
    let nodes = "-0.1,1,2,1.1,2.1,0.9,-0.3,1.05";
    let q = [-0.1, 1.0, 2.0, 1.1, 2.1, 0.9, -0.3, 1.05];
    let runs = [
        gapsim(&[
            "kernel",
            "--type",
            "6",
            &format!("--xi-s={}", -0.5),
            &format!("--nodes={nodes}"),
        ]),
        gapsim(&["kernel", "--type", "6", "--xi-s", "-0.5", "--nodes", nodes]),
        gapsim(&["kernel", "--nodes", nodes, "--xi-s", "-0.5", "--type", "6"]),
        gapsim(&[
            "kernel",
            "--nodes",
            nodes,
            "--type=6",
            "--xi-s=-0.5",
            "--formulation=slave-normal",
        ]),
    ];
    for out in &runs {
        assert_equals_library(
            &parse_success(out),
            Formulation::SlaveNormal,
            ApproxType::Type6,
            &q,
            -0.5,
        );
    }
}

/// A failed run: non-zero exit (not a signal), nothing on stdout, no panic,
/// and a message on stderr mentioning every string in `expect`.
#[track_caller]
fn assert_fails(args: &[&str], expect: &[&str]) {
    let out = gapsim(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} should fail");
    assert!(
        out.status.code().is_some_and(|c| c != 0),
        "{args:?}: exit status {:?}",
        out.status
    );
    assert!(
        out.stdout.is_empty(),
        "{args:?}: stdout {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    for e in expect {
        assert!(
            stderr.contains(e),
            "{args:?}: stderr should mention `{e}`: {stderr}"
        );
    }
}

#[test]
fn bad_input_is_reported() {
    let k = |ty: &'static str, xi: &'static str, nodes: &'static str| {
        ["kernel", "--type", ty, "--xi-s", xi, "--nodes", nodes]
    };
    // Wrong number of coordinates.
    assert_fails(
        &k("6", "0.3", "0,1,2,1.1,2.1,0.9,-0.1"),
        &[
            "--nodes",
            "slave-normal",
            "expects 8",
            "xs1,ys1,xs2,ys2,xm1,ym1,xm2,ym2",
            "got 7",
        ],
    );
    assert_fails(
        &k("6", "0.3", "0,1,2,1.1,2.1,0.9,-0.1,1,5"),
        &["--nodes", "got 9"],
    );
    assert_fails(&k("6", "0.3", ""), &["--nodes"]);
    // Unparsable or non-finite numbers.
    assert_fails(
        &k("6", "0.3", "0,1,2,abc,2.1,0.9,-0.1,1"),
        &["--nodes", "coordinate 4 (ys2)", "abc"],
    );
    assert_fails(
        &k("6", "0.3", "0,1,2,1.1,NaN,0.9,-0.1,1"),
        &["--nodes", "coordinate 5", "finite"],
    );
    assert_fails(
        &k("6", "0.3", "0,1,2,1.1,2.1,0.9,-0.1,inf"),
        &["--nodes", "finite"],
    );
    assert_fails(&k("6", "nan", WORKED_NODES), &["--xi-s", "finite"]);
    assert_fails(&k("6", "x", WORKED_NODES), &["--xi-s"]);
    // Type out of range or not a number, unknown formulation.
    for ty in ["0", "7", "-1", "six"] {
        assert_fails(&k(ty, "0.3", WORKED_NODES), &["--type"]);
    }
    assert_fails(
        &[
            "kernel",
            "--formulation",
            "nearest",
            "--type",
            "6",
            "--xi-s",
            "0.3",
            "--nodes",
            WORKED_NODES,
        ],
        &["--formulation", "slave-normal", "closest-point"],
    );
    // Missing arguments, unknown subcommand.
    assert_fails(&["kernel", "--type", "6", "--xi-s", "0.3"], &["--nodes"]);
    assert_fails(
        &["kernel", "--type", "6", "--nodes", WORKED_NODES],
        &["--xi-s"],
    );
    assert_fails(&["frobnicate"], &["frobnicate"]);
    // Degenerate geometry, reported by the kernel's typed error.
    assert_fails(
        &k("6", "0.3", "1,1,1,1,2.1,0.9,-0.1,1"),
        &["degenerate slave segment"],
    );
    assert_fails(
        &k("3", "0.3", "0,1,2,1.1,0.5,0.5,0.5,0.5"),
        &["degenerate master segment"],
    );
    assert_fails(&k("6", "0.3", "0,1,2,1,1.5,0.5,1.5,-0.5"), &["projection"]);
}

/// The 3-node example of `gapsim kernel --help` (contact-kernels'
/// tests/quadratic.rs hand-computes it: `g = 0.85`, `xi_m = -0.5`).
const QUADRATIC_NODES: &str = "0,0,2,0,1,0,2,-1,0,-1,1,-0.8";
const QUADRATIC_Q: [f64; 12] = [
    0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 1.0, -0.8,
];

/// `quadratic-slave-normal` takes 12 coordinates and prints a gradient of
/// 12 and a 12 x 12 Hessian, every type exactly [`Kernel::eval`]'s values.
#[test]
fn quadratic_kernel_takes_twelve_coordinates() {
    let f = Formulation::QuadraticSlaveNormal;
    assert_eq!(f.coords(), Some(12));
    for ty in ApproxType::ALL {
        let t = ty.index().to_string();
        let nums = parse_success_n(
            &gapsim(&[
                "kernel",
                "--formulation",
                "quadratic-slave-normal",
                "--type",
                &t,
                "--xi-s",
                "0.5",
                "--nodes",
                QUADRATIC_NODES,
            ]),
            12,
        );
        let kernel = Kernel::new(f, ty).unwrap();
        let mut out = GapOut::new(&kernel);
        kernel.eval(&QUADRATIC_Q, 0.5, &mut out).unwrap();
        let mut expected = vec![out.gap(), out.xi_m()];
        expected.extend(out.grad());
        match out.hess() {
            Some(h) => expected.extend(h),
            None => expected.extend([0.0; 144]),
        }
        assert_eq!(nums.len(), expected.len());
        for (k, (a, b)) in nums.iter().zip(&expected).enumerate() {
            assert_eq!(
                a.to_bits(),
                b.to_bits(),
                "type {ty}: number {k}: {a:e} vs {b:e}"
            );
        }
        assert!((nums[0] - 0.85).abs() < 1e-12, "gap {}", nums[0]);
        assert!((nums[1] + 0.5).abs() < 1e-12, "xi_m {}", nums[1]);
        assert_eq!(
            nums[14..].iter().all(|&v| v == 0.0),
            ty == ApproxType::Type1
        );
    }
}

/// A coordinate count that is not the formulation's names what it expects.
#[test]
fn wrong_coordinate_count_names_the_expected_one() {
    let run = |f: &'static str, nodes: &'static str| {
        [
            "kernel",
            "--formulation",
            f,
            "--type",
            "6",
            "--xi-s",
            "0.5",
            "--nodes",
            nodes,
        ]
    };
    assert_fails(
        &run("quadratic-slave-normal", WORKED_NODES),
        &[
            "--nodes",
            "quadratic-slave-normal",
            "expects 12",
            "xs1,ys1,xs2,ys2,xs3,ys3,xm1,ym1,xm2,ym2,xm3,ym3",
            "got 8",
        ],
    );
    assert_fails(
        &run("closest-point", QUADRATIC_NODES),
        &["--nodes", "closest-point", "expects 8", "got 12"],
    );
    // The names follow the formulation's count.
    assert_fails(
        &run("quadratic-slave-normal", "0,0,2,0,1,0,2,-1,0,-1,1,nan"),
        &["--nodes", "coordinate 12 (ym3)", "finite"],
    );
    // The 3-node kernels' own refusals: a folded slave segment (its mid
    // node a quarter chord from the chord's midpoint, along it).
    assert_fails(
        &run("quadratic-slave-normal", "0,0,2,0,1.5,0,2,-1,0,-1,1,-0.8"),
        &["quadratic-slave-normal", "folded slave segment"],
    );
}

/// Messages that say what is wrong: a slave point outside its segment is
/// refused; coordinates whose squared differences overflow or underflow
/// are reported as out of range (not "length inf is below 2e290" or
/// "length 0e0 is below 0e0").
#[test]
fn out_of_range_input_is_said_as_such() {
    let k = |xi: &'static str, nodes: &'static str| {
        ["kernel", "--type", "6", "--xi-s", xi, "--nodes", nodes]
    };
    for xi in ["2", "-1.5", "1.0000001"] {
        assert_fails(&k(xi, WORKED_NODES), &["--xi-s", "outside [-1, 1]"]);
    }
    for xi in ["1", "-1", "1.0", "-0"] {
        assert!(gapsim(&k(xi, WORKED_NODES)).status.success(), "{xi}");
    }
    let huge = "0,1e300,2e300,1.1e300,2.1e300,0.9e300,-0.1e300,1e300";
    assert_fails(
        &k("0.3", huge),
        &[
            "slave segment out of range",
            "overflows",
            "scale the coordinates",
        ],
    );
    let tiny = "0,1e-310,2e-310,1.1e-310,2.1e-310,0.9e-310,-0.1e-310,1e-310";
    assert_fails(
        &k("0.3", tiny),
        &["slave segment out of range", "spans only"],
    );
    let zero = "0,0,0,0,0,0,0,0";
    assert_fails(&k("0.3", zero), &["every point coincides"]);
    let small = "0,1e-200,2e-200,1.1e-200,2.1e-200,0.9e-200,-0.1e-200,1e-200";
    assert_fails(
        &k("0.3", small),
        &[
            "slave segment out of range",
            "spans only",
            "scale the coordinates",
        ],
    );
    for out in [gapsim(&k("0.3", huge)), gapsim(&k("0.3", tiny))] {
        let e = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(!e.contains("is below"), "{e}");
    }
}

/// `--formulation FILE.rs`: a formulation file evaluated from the command
/// line. The shipped files, given as files, print exactly what their
/// compiled kernels print (every type; values, projections and errors),
/// and a file of the user's is evaluated the same way.
#[test]
fn a_formulation_file_evaluates_as_the_compiled_kernels() {
    let root = env!("CARGO_MANIFEST_DIR");
    let cases: [(&str, &[(&str, &str)]); 3] = [
        (
            "slave-normal",
            &[
                ("0.3", WORKED_NODES),
                ("-0.77", "0,0,1,0,1.2,-0.01,-0.3,0.02"),
                (
                    "1.0",
                    "1e6,1e6,1000001,1e6,1000001.3,999999.9,999999.8,1000000.2",
                ),
                ("0.1", "0,0,1,0,0.5,1,0.5,-1"),
                ("0.2", "0,0,0,0,1,1,0,1"),
                ("0.3", "1,2,3"),
            ],
        ),
        (
            "closest-point",
            &[("0.3", WORKED_NODES), ("-1", "0,0,3,4,5,1,-2,2")],
        ),
        (
            "quadratic-slave-normal",
            &[
                ("0.5", QUADRATIC_NODES),
                ("0.2", "0,0,2,0,1.7,0,2,-1,0,-1,1,-0.8"),
            ],
        ),
    ];
    for (name, configs) in cases {
        let file = format!("{root}/contact-kernels/formulations/{name}.rs");
        for ty in ["1", "2", "3", "4", "5", "6"] {
            for (xi, nodes) in configs {
                let run = |f: &str| {
                    gapsim(&[
                        "kernel",
                        "--formulation",
                        f,
                        "--type",
                        ty,
                        "--xi-s",
                        xi,
                        "--nodes",
                        nodes,
                    ])
                };
                let (compiled, interpreted) = (run(name), run(&file));
                let what = format!("{name} type {ty} at {nodes}");
                assert_eq!(compiled.status.code(), interpreted.status.code(), "{what}");
                assert_eq!(
                    String::from_utf8_lossy(&compiled.stdout),
                    String::from_utf8_lossy(&interpreted.stdout),
                    "{what}"
                );
                assert_eq!(
                    String::from_utf8_lossy(&compiled.stderr),
                    String::from_utf8_lossy(&interpreted.stderr).replace(&file, name),
                    "{what}"
                );
            }
        }
    }
    // Both kinds of outcome were compared.
    let ok = gapsim(&[
        "kernel",
        "--formulation",
        &format!("{root}/contact-kernels/formulations/slave-normal.rs"),
        "--type",
        "6",
        "--xi-s",
        "0.3",
        "--nodes",
        WORKED_NODES,
    ]);
    assert_equals_library(
        &parse_success(&ok),
        Formulation::SlaveNormal,
        ApproxType::Type6,
        &WORKED_Q,
        0.3,
    );
}

/// A user's own file: evaluated (its own kernels), and a broken one
/// reported at its position.
#[test]
fn a_users_formulation_file_is_evaluated_or_its_error_located() {
    let dir = std::env::temp_dir().join(format!("gapsim-kernel-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shipped = include_str!("../contact-kernels/formulations/slave-normal.rs");
    let mine = dir.join("averaged.rs");
    std::fs::write(
        &mine,
        shipped.replace(
            "let t_s = xs2 - xs1;",
            "let t_s = (xs2 - xs1) * 0.5 + (xm1 - xm2) * 0.5;",
        ),
    )
    .unwrap();
    let args = |f: &str| {
        [
            "kernel",
            "--formulation",
            f,
            "--type",
            "6",
            "--xi-s",
            "0.3",
            "--nodes",
            WORKED_NODES,
        ]
        .map(str::to_owned)
    };
    let run = |f: &str| {
        let a = args(f);
        gapsim(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let nums = parse_success(&run(mine.to_str().unwrap()));
    let shipped_nums = parse_success(&run("slave-normal"));
    assert_eq!(nums.len(), shipped_nums.len());
    assert_ne!(nums[0], shipped_nums[0], "another formulation, another gap");
    let broken = dir.join("broken.rs");
    std::fs::write(&broken, shipped.replace("norm(t_s)", "norm(t_s) / 0.0")).unwrap();
    let a = args(broken.to_str().unwrap());
    assert_fails(
        &a.iter().map(String::as_str).collect::<Vec<_>>(),
        &[&format!("{}:", broken.display()), "non-finite constant"],
    );
    let a = args(dir.join("absent.rs").to_str().unwrap());
    assert_fails(
        &a.iter().map(String::as_str).collect::<Vec<_>>(),
        &["cannot read"],
    );
}

/// The worked quad4 pair of docs/conventions.md ("3D faces").
const QUAD_NODES: &str =
    "0,0,1,0,1,1.1,1,1,1,1,0,0.9,-0.2,-0.1,0.8,1.2,0,0.85,1.1,1.3,0.75,-0.1,1.2,0.8";

/// A face kernel: `--xi-s u,v` (negative values parse), `xi_m` printed as
/// `[u, v]`, 3 (ns + nm) gradient entries and Hessian rows, the library's
/// bits; a wrong `--xi-s` length names what the formulation expects.
#[test]
fn a_face_kernel_prints_xi_m_as_a_pair() {
    let q: Vec<f64> = QUAD_NODES.split(',').map(|v| v.parse().unwrap()).collect();
    for f in ["quad4-slave-normal", "quad4-closest-point"] {
        for ty in ["1", "6"] {
            let out = gapsim(&[
                "kernel",
                "--formulation",
                f,
                "--type",
                ty,
                "--xi-s",
                "0.2,-0.1",
                "--nodes",
                QUAD_NODES,
            ]);
            let stdout = String::from_utf8(out.stdout.clone()).unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let v: Value = serde_json::from_str(&stdout).unwrap();
            let obj = v.as_object().unwrap();
            let keys: Vec<&str> = obj.keys().map(String::as_str).collect();
            assert_eq!(keys.len(), 4);
            let xi_m = obj["xi_m"].as_array().expect("xi_m is [u, v]");
            assert_eq!(xi_m.len(), 2);
            let nums = numbers_in(&stdout);
            assert_eq!(nums.len(), 3 + 24 + 24 * 24, "{stdout}");
            let kernel = Kernel::new(f.parse().unwrap(), ty.parse().unwrap()).unwrap();
            let mut lib = GapOut::new(&kernel);
            kernel.eval(&q, [0.2, -0.1], &mut lib).unwrap();
            let mut expected = vec![lib.gap()];
            expected.extend(lib.xi_m_all());
            expected.extend(lib.grad());
            match lib.hess() {
                Some(h) => expected.extend(h),
                None => expected.extend(vec![0.0; 24 * 24]),
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&nums), bits(&expected), "{f} type {ty}");
        }
    }
    let out = gapsim(&[
        "kernel",
        "--formulation",
        "quad4-slave-normal",
        "--type",
        "6",
        "--xi-s",
        "0.2",
        "--nodes",
        QUAD_NODES,
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--xi-s") && stderr.contains("expects 2") && stderr.contains("(u,v)"),
        "{stderr}"
    );
    let out = gapsim(&[
        "kernel",
        "--formulation",
        "tri3-closest-point",
        "--type",
        "2",
        "--xi-s",
        "0.2,0.1",
        "--nodes",
        QUAD_NODES,
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("expects 18") && stderr.contains("zm3") && stderr.contains("got 24"),
        "{stderr}"
    );
}
