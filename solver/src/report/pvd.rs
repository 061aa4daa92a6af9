//! The ParaView collection (`.pvd`) of a solve's step files: one
//! `DataSet` per `.vtu` file, its `timestep` the state's load factor, so
//! that ParaView opens the steps as one time series (`gapsim run --out DIR
//! --every-step` writes `DIR/steps.pvd` beside `step-NNNN.vtu`).
//!
//! ```text
//! <?xml version="1.0"?>
//! <VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
//!   <Collection>
//!     <DataSet timestep="0.5" group="" part="0" file="step-0001.vtu"/>
//!   </Collection>
//! </VTKFile>
//! ```
//!
//! Invariant: the data sets are in the order given (the steps' order);
//! timesteps in shortest round-trip form ([`super::csv::num`]); file names
//! XML-escaped.

use super::csv::num;

/// The `.pvd` text of `files`: each a load factor and a file name
/// relative to the `.pvd`'s directory.
pub fn pvd_string(files: &[(f64, &str)]) -> String {
    let mut out = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (load_factor, file) in files {
        out.push_str(&format!(
            "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
            num(*load_factor),
            escape(file)
        ));
    }
    out.push_str("  </Collection>\n</VTKFile>\n");
    out
}

/// `s` with XML's five special characters escaped (an attribute value).
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_data_set_per_file_in_order_with_its_load_factor() {
        let text = pvd_string(&[
            (0.0, "step-0000.vtu"),
            (0.25, "step-0001.vtu"),
            (1.0, "a&\"b<.vtu"),
        ]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 8, "{text}");
        assert_eq!(lines[0], "<?xml version=\"1.0\"?>");
        assert_eq!(
            lines[4],
            "    <DataSet timestep=\"0.25\" group=\"\" part=\"0\" file=\"step-0001.vtu\"/>"
        );
        assert_eq!(
            lines[5],
            "    <DataSet timestep=\"1\" group=\"\" part=\"0\" file=\"a&amp;&quot;b&lt;.vtu\"/>"
        );
        assert_eq!(lines[7], "</VTKFile>");
        assert!(pvd_string(&[]).contains("<Collection>\n  </Collection>"));
    }
}
