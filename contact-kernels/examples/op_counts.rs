//! Prints the operation count of every generated kernel.
//!
//! ```text
//! cargo run -p contact-kernels --example op_counts
//! ```
use contact_kernels::{ApproxType, compiled_formulations, op_count};

fn main() {
    println!("| formulation | kernel | add | mul | div | sqrt | neg | total |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for f in compiled_formulations() {
        let rows = std::iter::once(("projection".to_owned(), op_count(f, None)))
            .chain(ApproxType::ALL.map(|t| (format!("type {t}"), op_count(f, Some(t)))));
        for (kernel, ops) in rows {
            let o = ops.expect("compiled formulations have op counts");
            println!(
                "| {f} | {kernel} | {} | {} | {} | {} | {} | {} |",
                o.add,
                o.mul,
                o.div,
                o.sqrt,
                o.neg,
                o.total()
            );
        }
    }
}
