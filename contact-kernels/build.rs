fn main() {
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("kernels.rs");
    std::fs::write(out, r#"
/// A contact formulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Formulation {
    /// slave normal
    SlaveNormal,
    /// closest point
    ClosestPoint,
}
impl Formulation {
    /// All formulations.
    pub const ALL: [Formulation; 2] = [Formulation::SlaveNormal, Formulation::ClosestPoint];
    /// The name.
    pub fn name(self) -> &'static str { match self { Formulation::SlaveNormal => "slave-normal", Formulation::ClosestPoint => "closest-point" } }
}
use EntityOrder::*;
pub(crate) const TRUNCATION: [[EntityOrder; 3]; 6] = [[Constant, Linear, Constant],[Linear, Linear, Linear],[Linear, Quadratic, Linear],[Quadratic, Quadratic, Linear],[Linear, Quadratic, Quadratic],[Quadratic, Quadratic, Quadratic]];
pub(crate) fn kernel_set(_f: Formulation) -> Option<&'static KernelSet> { None }
"#).unwrap();
}
