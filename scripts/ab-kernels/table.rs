//! Prints the A/B kernel benchmark (`bench.rs`) as a Markdown table: median
//! ns per evaluation of the earlier revision's `evaluate`, this tree's
//! `evaluate` and its `Kernel::eval`, and their ratios to the earlier one.
//! Reads criterion's `estimates.json` files under `CRITERION_DIR`.

use std::path::{Path, PathBuf};

fn median_ns(dir: &Path, group: &str, id: &str) -> Option<f64> {
    let path = dir.join(group).join(id).join("new/estimates.json");
    let text = std::fs::read_to_string(&path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    json["median"]["point_estimate"].as_f64()
}

fn main() {
    let dir = PathBuf::from(std::env::var_os("CRITERION_DIR").expect("CRITERION_DIR is set"));
    let rev = std::env::var("AB_REV").unwrap_or_else(|_| "the earlier revision".into());
    println!(
        "Median ns per evaluation, one criterion run, the worked example of docs/conventions.md; \
         old: `evaluate` at {rev}; new: `evaluate` and `Kernel::eval` of this tree.\n"
    );
    println!("| formulation | kernel | old `evaluate` | new `evaluate` | new `Kernel::eval` | new `evaluate` / old | new `Kernel::eval` / old |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    let mut ratios = Vec::new();
    for name in ["closest-point", "slave-normal"] {
        let group = format!("ab-{name}");
        let mut rows: Vec<(String, String, String, String)> = (1..=6)
            .map(|t| {
                (
                    format!("type {t}"),
                    format!("type{t}-old-evaluate"),
                    format!("type{t}-new-evaluate"),
                    format!("type{t}-new-handle"),
                )
            })
            .collect();
        rows.push(("projection".into(), "project-old".into(), "project-new".into(), String::new()));
        for (label, old, new_eval, new_handle) in rows {
            let (Some(o), Some(n)) = (median_ns(&dir, &group, &old), median_ns(&dir, &group, &new_eval)) else {
                continue;
            };
            let h = median_ns(&dir, &group, &new_handle);
            ratios.push(n / o);
            println!(
                "| {name} | {label} | {o:.1} | {n:.1} | {} | {:.2} | {} |",
                h.map_or("–".into(), |h| format!("{h:.1}")),
                n / o,
                h.map_or("–".into(), |h| format!("{:.2}", h / o)),
            );
        }
    }
    if !ratios.is_empty() {
        let geo = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
        println!("\nGeometric mean of new `evaluate` / old `evaluate`: {geo:.3} ({} kernels).", ratios.len());
    }
}
