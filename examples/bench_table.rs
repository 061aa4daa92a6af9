//! Prints the kernel benchmark as a Markdown table.
//!
//! ```text
//! cargo bench --bench kernels && cargo run --release --example bench_table
//! cargo bench --bench kernels -- faces && cargo run --release --example bench_table -- --faces
//! ```
//!
//! With `--slip` (after `cargo bench --bench kernels -- slip`) it prints
//! only the slip tables: the slip kernels against the gap kernels of the
//! same type, num-dual's Hessian of the 2D slip, and the slip's batch
//! against one point at a time (docs/kernels.md, "The slip kernels").
//!
//! With `--faces` it prints only the 3D face table (group
//! `faces-tri3-slave-normal`, docs/kernels.md's `bench-faces` section),
//! with the CPU model of `/proc/cpuinfo` and the load average of
//! `/proc/loadavg`; `scripts/splice-docs.sh bench-faces FILE docs/kernels.md`
//! puts it into docs/kernels.md (as `scripts/refresh-docs.sh` does).
//!
//! Reads criterion's results (`<criterion dir>/<formulation>/<id>/new/estimates.json`,
//! the median's point estimate in ns) written by `benches/kernels.rs` (the
//! value API `type1`..`type6`, `project`, `num-dual-hessian`; the handles
//! `<id>-handle`, shown as `–` when absent), and
//! the generated kernels' operation counts from `contact_kernels::op_count`.
//! The criterion directory is, in order: the first argument, `$CRITERION_HOME`,
//! `$CARGO_TARGET_DIR/criterion`, or the `criterion` folder of the target
//! directory this example was built into.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use contact_kernels::{ApproxType, OpCount, op_count, pair_formulations};

/// Where criterion wrote its results.
fn criterion_dir() -> PathBuf {
    if let Some(arg) = std::env::args_os()
        .skip(1)
        .find(|a| a != "--faces" && a != "--slip")
    {
        return PathBuf::from(arg);
    }
    if let Some(home) = std::env::var_os("CRITERION_HOME") {
        return PathBuf::from(home);
    }
    if let Some(target) = std::env::var_os("CARGO_TARGET_DIR") {
        return PathBuf::from(target).join("criterion");
    }
    // target/<profile>/examples/bench_table -> target
    std::env::current_exe()
        .ok()
        .and_then(|exe| exe.ancestors().nth(3).map(Path::to_path_buf))
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"))
        .join("criterion")
}

/// The median time per iteration (ns) of benchmark `group/id`.
fn median_ns(dir: &Path, group: &str, id: &str) -> Result<f64, String> {
    let path = dir.join(group).join(id).join("new").join("estimates.json");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        format!(
            "cannot read {}: {e}\n(run `cargo bench --bench kernels` first)",
            path.display()
        )
    })?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("cannot parse {}: {e}", path.display()))?;
    json["median"]["point_estimate"]
        .as_f64()
        .ok_or_else(|| format!("{}: no median.point_estimate", path.display()))
}

fn ops_columns(ops: Option<OpCount>) -> String {
    match ops {
        Some(o) => format!(
            "{} | {} | {} | {} | {} | {}",
            o.add,
            o.mul,
            o.div,
            o.sqrt,
            o.neg,
            o.total()
        ),
        None => "– | – | – | – | – | –".to_owned(),
    }
}

/// The handle's columns: its median and its ratio to the value API's
/// median `value_ns` (`–` when the handle was not benchmarked).
fn handle_columns(dir: &Path, group: &str, id: &str, value_ns: f64) -> String {
    match median_ns(dir, group, &format!("{id}-handle")) {
        Ok(t) => format!("{t:.1} | {:.2}", t / value_ns),
        Err(_) => "– | –".to_owned(),
    }
}

fn table(dir: &Path) -> Result<String, String> {
    let mut out = String::new();
    out.push_str(
        "| formulation | type | ns/eval | speed-up vs num-dual hessian | handle ns/eval | handle / value | add | mul | div | sqrt | neg | total ops |\n",
    );
    out.push_str("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for f in pair_formulations() {
        let name = f.name();
        let reference = median_ns(dir, name, "num-dual-hessian")?;
        for ty in ApproxType::ALL {
            let id = format!("type{}", ty.index());
            let t = median_ns(dir, name, &id)?;
            out.push_str(&format!(
                "| {name} | {} | {t:.1} | {:.1}× | {} | {} |\n",
                ty.index(),
                reference / t,
                handle_columns(dir, name, &id, t),
                ops_columns(op_count(f, Some(ty)))
            ));
        }
        let t = median_ns(dir, name, "project")?;
        out.push_str(&format!(
            "| {name} | projection (g, xi_m) | {t:.1} | {:.1}× | {} | {} |\n",
            reference / t,
            handle_columns(dir, name, "project", t),
            ops_columns(op_count(f, None))
        ));
        out.push_str(&format!(
            "| {name} | num-dual `hessian` (Type 6) | {reference:.1} | 1.0× | – | – | {} |\n",
            ops_columns(None)
        ));
    }
    Ok(out)
}

/// The issue's targets for Type 6 per point (issue #9, section 5): at least
/// this many times faster than the sympy-cse peer and than num-dual's
/// `hessian`.
const PEER_TARGET: f64 = 4.0;
const DUAL_TARGET: f64 = 40.0;

/// "met" or "missed by ...": `ratio` against `target`.
fn verdict(ratio: f64, target: f64) -> String {
    if ratio >= target {
        format!("met ({ratio:.2}× ≥ {target}×)")
    } else {
        format!(
            "missed ({ratio:.2}× < {target}×: {:.0} % short)",
            100.0 * (1.0 - ratio / target)
        )
    }
}

/// The `points64` table: 64 configurations per iteration (slave-normal),
/// every row per point and against the sympy-cse peer and num-dual, all
/// from the same run; then the targets for Type 6's fastest path.
fn points_table(dir: &Path) -> Result<String, String> {
    const GROUP: &str = "points64";
    const POINTS: f64 = 64.0;
    let per_point = |id: &str| median_ns(dir, GROUP, id).map(|t| t / POINTS);
    let peer = per_point("sympy-cse")?;
    let dual = per_point("num-dual-hessian")?;
    let mut out = String::from(
        "| kernel (slave-normal) | ns/point | peer / this | num-dual / this |\n|---|---:|---:|---:|\n",
    );
    let mut row = |name: String, t: f64| {
        out.push_str(&format!(
            "| {name} | {t:.1} | {:.2}× | {:.1}× |\n",
            peer / t,
            dual / t
        ));
    };
    row(
        "value only (`Projector::project`: g, xi_m)".into(),
        per_point("value-only")?,
    );
    for ty in [1, 3, 6] {
        row(
            format!("Type {ty}, `evaluate`"),
            per_point(&format!("type{ty}"))?,
        );
        row(
            format!("Type {ty}, `Kernel::eval`"),
            per_point(&format!("type{ty}-handle"))?,
        );
        row(
            format!("Type {ty}, `Kernel::eval_batch` (64 points per call, SIMD lanes)"),
            per_point(&format!("type{ty}-batch"))?,
        );
    }
    // Absent in results of an older bench run: then the row is left out.
    if let Ok(t) = per_point("type6-batch-portable") {
        row(
            "Type 6, `Kernel::eval_batch`, portable lane build (no AVX2)".into(),
            t,
        );
    }
    row(
        "sympy-cse peer (g, xi_m, gradient, full Hessian)".into(),
        peer,
    );
    row("num-dual `hessian`".into(), dual);
    let best = ["type6-handle", "type6-batch"]
        .into_iter()
        .filter_map(|id| per_point(id).ok().map(|t| (id, t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .ok_or("no Type 6 handle or batch result")?;
    out.push_str(&format!(
        "\nType 6, fastest path (`{}`, {:.1} ns/point): against the peer {}; against num-dual {}.\n",
        best.0,
        best.1,
        verdict(peer / best.1, PEER_TARGET),
        verdict(dual / best.1, DUAL_TARGET)
    ));
    Ok(out)
}

/// The 3D face targets for Type 6 through `eval_batch` per point: at
/// least this many times faster than the sympy-cse 3D peer and than
/// num-dual's `hessian`.
const FACE_PEER_TARGET: f64 = 5.0;
const FACE_DUAL_TARGET: f64 = 100.0;

/// The CPU's model name and whether it has AVX2 and AVX-512F (from
/// `/proc/cpuinfo`; "unknown CPU" elsewhere).
fn cpu() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")?
                .split_once(':')
                .map(|(_, m)| m.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".to_owned());
    let flags = info
        .lines()
        .find_map(|l| {
            l.strip_prefix("flags")?
                .split_once(':')
                .map(|(_, f)| f.to_owned())
        })
        .unwrap_or_default();
    let has = |f: &str| flags.split_whitespace().any(|x| x == f);
    let cores = info.lines().filter(|l| l.starts_with("processor")).count();
    format!(
        "{model}, {cores} cores, AVX2 {}, AVX-512F {}",
        if has("avx2") { "yes" } else { "no" },
        if has("avx512f") { "yes" } else { "no" }
    )
}

/// The load averages over 1, 5 and 15 minutes (`/proc/loadavg`), as
/// "a / b / c"; "unknown" elsewhere. Printed with the table, which is made
/// right after the benchmark run, so the 5-minute figure covers the run.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| {
            let v: Vec<&str> = s.split_whitespace().take(3).collect();
            (v.len() == 3).then(|| v.join(" / "))
        })
        .unwrap_or_else(|| "unknown".to_owned())
}

/// The `faces-tri3-slave-normal` table: 64 tri3-on-tri3 configurations
/// per iteration, every row per point and against the sympy-cse 3D peer
/// and num-dual, all from the same run; then the targets for Type 6
/// through `eval_batch`.
fn faces_table(dir: &Path) -> Result<String, String> {
    const GROUP: &str = "faces-tri3-slave-normal";
    const POINTS: f64 = 64.0;
    let per_point = |id: &str| median_ns(dir, GROUP, id).map(|t| t / POINTS);
    let peer = per_point("sympy-cse")?;
    let dual = per_point("num-dual-hessian")?;
    let mut out = format!(
        "Per point over 64 tri3-on-tri3 configurations near the worked example (group `{GROUP}`, \
         one criterion run, median; CPU: {}; load average over 1 / 5 / 15 minutes when the table \
         was made: {}): gapsim's `tri3-slave-normal` kernels, the sympy-cse 3D \
         peer of `benches/peer/sympy_kernel_3d.rs` and num-dual's `hessian` of the same gap \
         (18 coordinates).\n\n\
         | kernel (tri3-slave-normal) | ns/point | peer / this | num-dual / this |\n|---|---:|---:|---:|\n",
        cpu(),
        load_average()
    );
    let mut row = |name: &str, t: f64| {
        out.push_str(&format!(
            "| {name} | {t:.1} | {:.2}× | {:.1}× |\n",
            peer / t,
            dual / t
        ));
    };
    let batch = "(64 points per call, SIMD lanes)";
    for ty in [1, 6] {
        row(
            &format!("Type {ty}, `Kernel::eval` (one point at a time)"),
            per_point(&format!("type{ty}-handle"))?,
        );
        row(
            &format!("Type {ty}, `Kernel::eval_batch` {batch}"),
            per_point(&format!("type{ty}-batch"))?,
        );
    }
    if let Ok(t) = per_point("type6-batch-portable") {
        row(
            &format!("Type 6, `Kernel::eval_batch` {batch}, portable lane build (no AVX2)"),
            t,
        );
    }
    row("sympy-cse 3D peer (g, xi_m, gradient, full Hessian)", peer);
    row("num-dual `hessian`", dual);
    let t = per_point("type6-batch")?;
    out.push_str(&format!(
        "\nType 6 through `eval_batch` ({t:.1} ns/point): against the peer {}; against num-dual {}.\n",
        verdict(peer / t, FACE_PEER_TARGET),
        verdict(dual / t, FACE_DUAL_TARGET)
    ));
    Ok(out)
}

/// The slip table (groups `slip-slave-normal`, `slip-quad4-slave-normal`).
fn slip_table(dir: &Path) -> Result<String, String> {
    let mut out = format!(
        "Median time per point (criterion, one run; CPU: {}; load average over 1 / 5 / 15 \
         minutes: {}): the slip kernel (`Slip::eval`) against the gap kernel of the same \
         type (`Kernel::eval`), both with validation and projection, at the slip's worked \
         examples of docs/conventions.md.\n\n\
         | formulation | type | gap (ns) | slip (ns) | slip / gap | ops gap | ops slip |\n\
         |---|---|---:|---:|---:|---:|---:|\n",
        cpu(),
        load_average()
    );
    for name in ["slave-normal", "quad4-slave-normal"] {
        let group = format!("slip-{name}");
        let f: contact_kernels::Formulation = name.parse().map_err(|e| format!("{e}"))?;
        for ty in [ApproxType::Type1, ApproxType::Type3, ApproxType::Type6] {
            let t = ty.index();
            let gap = median_ns(dir, &group, &format!("gap-type{t}"))?;
            let slip = median_ns(dir, &group, &format!("slip-type{t}"))?;
            let kernel = contact_kernels::Kernel::new(f, ty).map_err(|e| e.to_string())?;
            let slip_ops = kernel.slip().map_or(0, |s| s.op_count().total());
            out.push_str(&format!(
                "| {name} | {t} | {gap:.1} | {slip:.1} | {:.2} | {} | {slip_ops} |\n",
                slip / gap,
                kernel.op_count().total()
            ));
        }
    }
    let dual = median_ns(dir, "slip-slave-normal", "num-dual-slip-hessian")?;
    let six = median_ns(dir, "slip-slave-normal", "slip-type6")?;
    out.push_str(&format!(
        "\nnum-dual's `hessian` of the same 2D slip: {dual:.1} ns, {:.1} times Type 6's slip \
         kernel.\n",
        dual / six
    ));
    out.push_str(
        "\nThe slip of Type 6 at 64 points (group `slip-batch64`, time per point): one point \
         at a time (`Slip::eval`) against one `Slip::eval_batch` call (the slip's lane \
         kernels, 4 points per call, AVX2 where the CPU has it, and the portable lane build; \
         a face slip's three components are three lane functions, built for AVX2 only: \
         its portable build goes point by point).\n\n\
         | formulation | `Slip::eval` (ns) | `eval_batch` (ns) | speed-up | portable lanes (ns) | speed-up |\n\
         |---|---:|---:|---:|---:|---:|\n",
    );
    for name in ["slave-normal", "tri3-slave-normal"] {
        let per =
            |id: &str| median_ns(dir, "slip-batch64", &format!("{name}-{id}")).map(|t| t / 64.0);
        let (points, batch, portable) = (per("points")?, per("batch")?, per("batch-portable")?);
        out.push_str(&format!(
            "| {name} | {points:.1} | {batch:.1} | {:.2}x | {portable:.1} | {:.2}x |\n",
            points / batch,
            points / portable
        ));
    }
    Ok(out)
}

fn main() -> ExitCode {
    let dir = criterion_dir();
    // One table alone: printed, or its error.
    let alone = |table: Result<String, String>| match table {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bench_table: {e}");
            ExitCode::FAILURE
        }
    };
    if std::env::args().any(|a| a == "--slip") {
        return alone(slip_table(&dir));
    }
    if std::env::args().any(|a| a == "--faces") {
        return alone(faces_table(&dir));
    }
    // Each table is printed when its group's results exist (`cargo bench
    // --bench kernels -- points64` runs only the second group).
    let mut printed = false;
    match table(&dir) {
        Ok(t) => {
            println!(
                "Median time per evaluation (criterion, the worked example of docs/conventions.md; kernels via \
                 `contact_kernels::evaluate`, including input validation and the projection solve; \
                 handle: `Kernel::eval` into a reused `GapOut` / `Projector::project`, and its \
                 time relative to the value API in the same run).\n"
            );
            print!("{t}");
            printed = true;
        }
        Err(e) => eprintln!("bench_table: per-formulation table skipped: {e}"),
    }
    match points_table(&dir) {
        Ok(p) => {
            if printed {
                println!();
            }
            println!(
                "Per point over 64 configurations near the worked example (group `points64`, \
                 one run; CPU: {}; load average over 1 / 5 / 15 minutes when the table was \
                 made: {}): gapsim's kernels, the sympy-cse peer of `benches/peer/` (what \
                 Kratos and IPC Toolkit generate) and num-dual.\n",
                cpu(),
                load_average()
            );
            print!("{p}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bench_table: {e}");
            ExitCode::FAILURE
        }
    }
}
