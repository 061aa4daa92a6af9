//! Prints the operation count of every generated kernel: the projection,
//! every type's gap kernel and every type's slip kernel.
//!
//! ```text
//! cargo run -p contact-kernels --example op_counts
//! ```
use contact_kernels::{ApproxType, Kernel, compiled_formulations, op_count};

fn main() {
    println!("| formulation | kernel | add | mul | div | sqrt | neg | total |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    for f in compiled_formulations() {
        let rows = std::iter::once(("projection".to_owned(), op_count(f, None)))
            .chain(ApproxType::ALL.map(|t| (format!("type {t}"), op_count(f, Some(t)))))
            .chain(ApproxType::ALL.map(|t| {
                let slip = Kernel::new(f, t).ok().and_then(|k| k.slip());
                (format!("slip type {t}"), slip.map(|s| s.op_count()))
            }));
        for (kernel, ops) in rows {
            let Some(o) = ops else { continue };
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
