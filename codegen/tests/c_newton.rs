//! The C emitter's Newton path and `powi`, which the shipped formulations
//! (projections in closed form, no `powi`) do not exercise.
//!
//! A test formulation whose projection residual is not affine in `xi` and
//! whose gap uses `powi` with positive and negative exponents is emitted as
//! C (its Newton projection: the shared runtime's `gapsim_newton_segment`),
//! compiled with the system C compiler (`$CC`, else `cc`; `-O2
//! -ffp-contract=off -Wall -Wextra -pedantic -Werror`) and run on seeded
//! configurations. Its outputs must equal, bit for bit, the same instruction
//! lists run by [`codegen::Program::run`] (the reference semantics, with
//! Rust's `f64::powi`) inside a copy of contact-kernels' Newton projection
//! (`projection::solve`: from `xi = 0`, at most 20 steps, tolerance `1e-12
//! (1 + |xi|)`). Skipped, with a message, only when no C compiler is found.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use codegen::plan::KernelSetPlan;
use codegen::{KernelPlan, Source};

/// Slave-normal projection with the residual multiplied by `2 + xi^4` (same
/// root, not affine) and the normal scaled by `|t_s|^-2` through `powi`.
const NEWTON: &str = "//! Test formulation: a residual that is not affine in xi.
inputs!(xs1, xs2, xm1, xm2; xi_s);
let x_s = lerp(xs1, xs2, xi_s);
let t_s = xs2 - xs1;
let xi_m = implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_s) * (2.0 + powi(xi, 4)));
let x_ms = entity!(lerp(xm1, xm2, xi_m) - x_s);
let n = entity!(perp(t_s) * powi(norm(t_s), -3));
gap!(dot(n, x_ms));
";

const DRIVER: &str = r#"#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "gapsim_newton_test.h"

typedef int (*type_fn)(const double q[8], double xi_s, double *gap, double *xi_m,
                       double grad[8], double *hess);

static void bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    printf(" %016" PRIx64, u);
}

int main(void)
{
    static const type_fn types[6] = {
        gapsim_newton_test_type1, gapsim_newton_test_type2, gapsim_newton_test_type3,
        gapsim_newton_test_type4, gapsim_newton_test_type5, gapsim_newton_test_type6,
    };
    char line[512];
    while (fgets(line, sizeof line, stdin) != NULL) {
        double v[9], gap = 0.0, xi_m = 0.0, grad[8], hess[64];
        char *at = line;
        int i, t, status;
        for (i = 0; i < 9; ++i) {
            uint64_t u = (uint64_t)strtoull(at, &at, 16);
            memcpy(&v[i], &u, sizeof u);
        }
        status = gapsim_newton_test_project(v + 1, v[0], &gap, &xi_m);
        printf("%d", status);
        if (status == GAPSIM_OK) {
            bits(gap);
            bits(xi_m);
        }
        printf("\n");
        for (t = 0; t < 6; ++t) {
            status = types[t](v + 1, v[0], &gap, &xi_m, grad, hess);
            printf("%d", status);
            if (status == GAPSIM_OK) {
                bits(gap);
                bits(xi_m);
                for (i = 0; i < 8; ++i) {
                    bits(grad[i]);
                }
                if (t > 0) {
                    for (i = 0; i < 64; ++i) {
                        bits(hess[i]);
                    }
                }
            }
            printf("\n");
        }
    }
    return 0;
}
"#;

/// SplitMix64: a seeded stream of uniform doubles in `[lo, hi)`.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The Rust reference: relative coordinates, contact-kernels' Newton
/// projection on the residual program, then each function's program.
/// `None` when the projection fails (the C side must then fail too).
fn reference(set: &KernelSetPlan, q: &[f64; 8], xi_s: f64) -> Option<Vec<Vec<u64>>> {
    let d: Vec<f64> = (0..8).map(|i| q[i] - q[i % 2]).collect();
    let mut xi = 0.0_f64;
    let mut converged = false;
    for _ in 0..20 {
        let rr = set.residual.program.run(&d, &[xi_s], xi);
        let step = rr[0] / rr[1];
        if !step.is_finite() {
            return None;
        }
        xi -= step;
        if xi.abs() > 1e6 {
            return None;
        }
        if step.abs() <= 1e-12 * (1.0 + xi.abs()) {
            converged = true;
            break;
        }
    }
    if !converged {
        return None;
    }
    let g = set.gap.program.run(&d, &[xi_s], xi)[0];
    let mut out = vec![vec![g.to_bits(), xi.to_bits()]];
    for (t, k) in set.kernels.iter().enumerate() {
        let v = k.program.run(&d, &[xi_s], xi);
        let mut bits = vec![v[0].to_bits(), xi.to_bits()];
        bits.extend(v[1..9].iter().map(|x| x.to_bits()));
        if t > 0 {
            let mut hess = [0.0; 64];
            let mut at = 9;
            for j in 0..8 {
                for k in j..8 {
                    hess[j * 8 + k] = v[at];
                    hess[k * 8 + j] = v[at];
                    at += 1;
                }
            }
            bits.extend(hess.iter().map(|x| x.to_bits()));
        }
        out.push(bits);
    }
    Some(out)
}

#[test]
fn newton_projection_and_powi_match_the_instruction_lists() {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    if let Err(e) = Command::new(&cc).arg("--version").output() {
        assert_eq!(
            e.kind(),
            std::io::ErrorKind::NotFound,
            "cannot run {cc}: {e}"
        );
        eprintln!("SKIPPED: no C compiler (`{cc}` not found); the Newton C path was not compared");
        return;
    }
    let src = Source {
        name: "newton-test".into(),
        text: NEWTON.into(),
        compiled: true,
    };
    let plan = KernelPlan::build(std::slice::from_ref(&src)).expect("the test formulation");
    let set = plan.formulations[0].kernels.as_ref().unwrap();
    assert!(
        !set.closed_form_projection,
        "the residual must not be affine"
    );
    let files = codegen::generate_c(&[src]).unwrap();
    let c = &files
        .iter()
        .find(|f| f.name == "gapsim_newton_test.c")
        .unwrap()
        .contents;
    assert!(
        c.contains("gapsim_powi(") && c.contains("gapsim_newton_segment(newton_test_residual,")
    );

    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_newton");
    std::fs::create_dir_all(&dir).unwrap();
    for f in &files {
        std::fs::write(dir.join(&f.name), &f.contents).unwrap();
    }
    std::fs::write(dir.join("driver.c"), DRIVER).unwrap();
    let exe = dir.join("driver");
    let out = Command::new(&cc)
        .args(["-std=c99", "-O2", "-ffp-contract=off"])
        .args(["-Wall", "-Wextra", "-pedantic", "-Werror", "-I"])
        .arg(&dir)
        .arg(dir.join("driver.c"))
        .arg(dir.join("gapsim_newton_test.c"))
        .arg(dir.join("gapsim_runtime.c"))
        .arg("-o")
        .arg(&exe)
        .arg("-lm")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{cc} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // Slave along a random direction, master facing it within +-40 degrees.
    let mut rng = Rng(0x6a95_00c1);
    let mut configs = Vec::new();
    for _ in 0..300 {
        let (a, ls, lm) = (
            rng.uniform(-3.1, 3.1),
            rng.uniform(0.2, 5.0),
            rng.uniform(0.2, 5.0),
        );
        let b = a + std::f64::consts::PI + rng.uniform(-0.7, 0.7);
        let o = [rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0)];
        let c = [
            o[0] + rng.uniform(-2.0, 2.0) * ls,
            o[1] + rng.uniform(-2.0, 2.0) * ls,
        ];
        let q = [
            o[0],
            o[1],
            o[0] + ls * a.cos(),
            o[1] + ls * a.sin(),
            c[0] - 0.5 * lm * b.cos(),
            c[1] - 0.5 * lm * b.sin(),
            c[0] + 0.5 * lm * b.cos(),
            c[1] + 0.5 * lm * b.sin(),
        ];
        configs.push((q, rng.uniform(-1.0, 1.0)));
    }
    let mut input = String::new();
    for (q, xi_s) in &configs {
        input.push_str(&format!("{:016x}", xi_s.to_bits()));
        for v in q {
            input.push_str(&format!(" {:016x}", v.to_bits()));
        }
        input.push('\n');
    }
    let mut child = Command::new(&exe)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let output = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), configs.len() * 7);

    let (mut compared, mut values) = (0, 0);
    for (k, (q, xi_s)) in configs.iter().enumerate() {
        let c_side: Vec<(i32, Vec<u64>)> = lines[k * 7..k * 7 + 7]
            .iter()
            .map(|l| {
                let mut w = l.split_whitespace();
                let status = w.next().unwrap().parse().unwrap();
                (
                    status,
                    w.map(|x| u64::from_str_radix(x, 16).unwrap()).collect(),
                )
            })
            .collect();
        match reference(set, q, *xi_s) {
            None => assert!(
                c_side.iter().all(|(s, _)| *s != 0),
                "#{k}: the Newton projection fails in Rust but not in C"
            ),
            Some(r) => {
                for (j, ((status, bits), r)) in c_side.iter().zip(&r).enumerate() {
                    // Non-finite outputs are refused in C; compare the rest.
                    if r.iter().all(|b| f64::from_bits(*b).is_finite()) {
                        assert_eq!(*status, 0, "#{k} function {j}: C status {status}");
                        assert_eq!(bits, r, "#{k} function {j}: C and Rust bits differ");
                        values += bits.len();
                    }
                }
                compared += 1;
            }
        }
    }
    eprintln!(
        "Newton formulation: {compared} of {} configurations projected, {values} values equal bit for bit",
        configs.len()
    );
    assert!(compared >= 200, "only {compared} configurations projected");
}
