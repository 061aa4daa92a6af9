//! Prints `project` and `evaluate` (every formulation and type) on 4000
//! deterministic configurations — scaled, shifted, with degenerate segments,
//! perpendicular masters and non-finite input — one line per call, floats
//! in their shortest round-trip form, errors by `Debug`.
//!
//! Diffing its output between two builds proves the kernels' results
//! identical bit for bit (the file only uses API that predates the kernel
//! handles, so it can be copied into an older checkout):
//!
//! ```text
//! cargo run -q --release -p contact-kernels --example result_dump > new.txt
//! ```

use contact_kernels::{ApproxType, evaluate, pair_formulations, project};

/// A tiny deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}
fn main() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let mut cases: Vec<([f64; 8], f64)> = Vec::new();
    let base = [0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0];
    for k in 0..4000 {
        let scale = [1.0, 1e-6, 1e6, 1e-300, 1e300][k % 5];
        let shift = [0.0, 1e8, -3.0, 1e15][k % 4];
        let mut q = base;
        for v in q.iter_mut() {
            *v = (*v + 0.3 * rng.next()) * scale + shift;
        }
        if k % 7 == 0 {
            q[4] = q[6];
            q[5] = q[7];
        }
        if k % 11 == 0 {
            q[2] = q[0];
            q[3] = q[1];
        }
        if k % 13 == 0 {
            q[6] = 1.5;
            q[4] = 1.5;
            q[5] = 0.5;
            q[7] = -0.5;
            q[0] = 0.0;
            q[1] = 1.0;
            q[2] = 2.0;
            q[3] = 1.0;
        }
        if k % 17 == 0 {
            q[k % 8] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][k % 3];
        }
        let xi_s = if k % 19 == 0 {
            f64::NAN
        } else {
            rng.next() * 1.2
        };
        cases.push((q, xi_s));
    }
    for (q, xi_s) in &cases {
        for f in pair_formulations() {
            println!("{f} P {:?}", project(f, q, *xi_s));
            for ty in ApproxType::ALL {
                match evaluate(f, ty, q, *xi_s) {
                    Ok(o) => println!(
                        "{f} {ty} {:?} {:?} {:?} {:?}",
                        o.gap,
                        o.xi_m,
                        o.grad.as_slice(),
                        o.hess.map(|h| h.as_slice().to_vec())
                    ),
                    Err(e) => println!("{f} {ty} ERR {e:?}"),
                }
            }
        }
    }
}
