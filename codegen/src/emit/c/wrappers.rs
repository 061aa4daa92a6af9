//! The C99 header and wrappers of one formulation, over its parametric
//! dimension `P` (1 for 2D segments, two-node or 3-node; 2 for 3D tri3
//! and quad4 faces): the header with the public prototypes, and the public
//! functions, which do what contact-kernels' `Kernel::eval` does around the
//! generated functions, in the same order, through the shared runtime
//! (`gapsim_runtime.c`, [`super::runtime`]):
//!
//! * validation: `gapsim_validate_segments` (finite input, relative
//!   coordinates, degenerate segments, and for 3-node segments folded ones:
//!   `validate.rs`) or `gapsim_validate_faces` (finite input, the slave
//!   point on its face, relative coordinates, degenerate and folded faces,
//!   slave first: `faces.rs`);
//! * the projection: in closed form inside the kernels
//!   (`gapsim_start_closed_form`), or Newton on the residual
//!   (`gapsim_newton_segment`, `gapsim_newton_face`);
//! * the kernel, the projection check (`gapsim_check_projection`: every
//!   component finite and within `GAPSIM_XI_M_LIMIT`) and finite outputs
//!   (gap, gradient, Hessian).
//!
//! The public functions take the slave point as `P` doubles and write the
//! projection through `P` pointers: `gapsim_{ident}_type6(q, xi_s, &gap,
//! &xi_m, grad, hess)` for segments,
//! `gapsim_{ident}_type6(q, xi_s_u, xi_s_v, &gap, &xi_m_u, &xi_m_v, grad, hess)`
//! for faces.

use std::fmt::Write as _;

use super::{comment, generated_line, k_implicit};
use crate::plan::{FormulationPlan, FunctionPlan, KernelSetPlan, Role};

/// The parametric dimension `P` of a formulation: the component count of
/// its implicit unknown and of its one parameter (1 for segments, 2 for
/// faces).
fn param_dim(set: &KernelSetPlan) -> usize {
    set.signature.implicit_len()
}

/// The suffixes of the `P` scalar arguments a parametric point is passed
/// as (`xi_s`; `xi_s_u`, `xi_s_v`).
fn suffixes(set: &KernelSetPlan) -> &'static [&'static str] {
    if param_dim(set) == 2 {
        &["_u", "_v"]
    } else {
        &[""]
    }
}

/// `name` as the `P` scalars of a point (`xi_m`, or `(xi_m_u, xi_m_v)`).
fn point_text(set: &KernelSetPlan, name: &str) -> String {
    let parts: Vec<String> = suffixes(set).iter().map(|s| format!("{name}{s}")).collect();
    match parts.as_slice() {
        [one] => one.clone(),
        _ => format!("({})", parts.join(", ")),
    }
}

/// The slave point's scalar arguments (`, double xi_s` or `, double
/// xi_s_u, double xi_s_v`), from the signature's parameter name.
fn param_args(set: &KernelSetPlan) -> String {
    let p = &set.signature.params()[0];
    suffixes(set)
        .iter()
        .map(|s| format!(", double {p}{s}"))
        .collect()
}

/// The projection's out arguments (`double *xi_m` or `double *xi_m_u,
/// double *xi_m_v`).
fn out_args(set: &KernelSetPlan, m: &str) -> String {
    suffixes(set)
        .iter()
        .map(|s| format!("double *{m}{s}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The public prototype of the projection function.
fn project_prototype(set: &KernelSetPlan) -> String {
    let n = set.signature.coords();
    format!(
        "int gapsim_{}_project(const double q[{n}]{}, double *gap, {})",
        set.ident,
        param_args(set),
        out_args(set, set.signature.implicit()),
    )
}

/// The public prototype of a type's function.
fn kernel_prototype(set: &KernelSetPlan, k: &FunctionPlan, ty: usize, hessian: bool) -> String {
    let n = set.signature.coords();
    let hess = if hessian {
        format!("double hess[{}]", n * n)
    } else {
        "double *hess".into()
    };
    format!(
        "int gapsim_{}_type{ty}(const double q[{n}]{}, double *gap, {}, double grad[{n}], {hess})",
        set.ident,
        param_args(set),
        out_args(set, &k_implicit(set, k)),
    )
}

/// The public prototype of a type's slip function.
fn slip_prototype(set: &KernelSetPlan, k: &FunctionPlan, ty: usize, hessian: bool) -> String {
    let n = set.signature.coords();
    let c = set.slip_components;
    let hess = if hessian {
        format!("double hess[{}]", c * n * n)
    } else {
        "double *hess".into()
    };
    let previous: String = suffixes(set)
        .iter()
        .map(|s| format!(", double {}0{s}", set.signature.implicit()))
        .collect();
    format!(
        "int gapsim_{}_slip_type{ty}(const double q[{n}]{}{previous}, double slip[{c}], {}, \
         double grad[{}], {hess})",
        set.ident,
        param_args(set),
        out_args(set, &k_implicit(set, k)),
        c * n,
    )
}

/// A face kind's name from its node count.
fn kind(nodes: usize) -> &'static str {
    if nodes == 3 { "tri3" } else { "quad4" }
}

/// The domain of a face kind's parametric coordinates.
fn domain(nodes: usize) -> &'static str {
    if nodes == 3 {
        "u, v >= 0 and u + v <= 1"
    } else {
        "[-1, 1]^2"
    }
}

/// What every function of the header takes and writes (the header's
/// second paragraph).
fn inputs_text(set: &KernelSetPlan) -> String {
    let sig = &set.signature;
    let n = sig.coords();
    let points = sig.points().join(", ");
    let m = point_text(set, sig.implicit());
    if param_dim(set) == 1 {
        format!(
            "Every function takes q, the {n} coordinates of the points {points} (x, y \
of each, point by point: the slave segment's nodes, then the master \
segment's), and {params}; it returns a gapsim_status code (gapsim.h) and on \
GAPSIM_OK writes the gap g (negative when penetrating) and {m}, the \
master coordinate of the projection. The Hessians are full symmetric \
{n} x {n} matrices, row-major (equal to column-major).",
            params = sig.params().join(", "),
        )
    } else {
        let (ns, nm) = (sig.slave_points(), sig.points().len() - sig.slave_points());
        format!(
            "Every function takes q, the {n} coordinates of the points {points} (x, y, \
z of each, point by point: the slave face's {ns} nodes ({sk}), then the \
master face's {nm} ({mk}), each face counter-clockwise seen from outside \
its body), and the slave point {p} on its face ({sdomain}); it \
returns a gapsim_status code (gapsim.h) and on GAPSIM_OK writes the gap g \
(negative when penetrating) and {m}, the master face's \
parametric coordinates of the projection. The Hessians are full symmetric \
{n} x {n} matrices, row-major (equal to column-major).",
            p = point_text(set, &sig.params()[0]),
            sk = kind(ns),
            mk = kind(nm),
            sdomain = domain(ns),
        )
    }
}

/// The header of one formulation.
pub(super) fn header(f: &FormulationPlan, set: &KernelSetPlan) -> String {
    let (n, upper) = (set.signature.coords(), set.ident.to_uppercase());
    let guard = format!("GAPSIM_{upper}_H");
    let mut out = generated_line(f);
    let mut about = String::new();
    if !f.doc.is_empty() {
        let _ = writeln!(about, "{}\n", f.doc);
    }
    let _ = write!(
        about,
        "gapsim_{ident}.h: the `{name}` kernels for C and C++ (C99; link \
gapsim_{ident}.c, gapsim_runtime.c and -lm; compile with -ffp-contract=off \
for the same bits as the Rust kernels).\n\n{inputs}",
        ident = set.ident,
        name = f.name,
        inputs = inputs_text(set),
    );
    out.push_str(&comment(&about, ""));
    let _ = write!(
        out,
        "#ifndef {guard}\n#define {guard}\n\n#include \"gapsim.h\"\n\n\
#ifdef __cplusplus\nextern \"C\" {{\n#endif\n\n\
/* The coordinate count n: the length of q and grad (hess: n * n). */\n\
#define GAPSIM_{upper}_COORDS {n}\n\n"
    );
    let proj = format!(
        "Projects the slave point onto the master {facet}: the gap and {m} only \
(no derivatives), as a solver does to re-project and re-pair. Cost: {}.",
        set.projection_ops,
        facet = if param_dim(set) == 1 {
            "segment"
        } else {
            "face"
        },
        m = point_text(set, set.signature.implicit()),
    );
    out.push_str(&comment(&proj, ""));
    let _ = writeln!(out, "{};\n", project_prototype(set));
    for k in &set.kernels {
        let Role::Kernel { ty, hessian } = k.role else {
            continue;
        };
        let mut doc = k.doc.clone();
        if hessian {
            doc.push_str(" grad: n values; hess: n * n values.");
        } else {
            doc.push_str(" grad: n values; hess is not used and may be NULL.");
        }
        out.push_str(&comment(&doc, ""));
        let _ = writeln!(out, "{};\n", kernel_prototype(set, k, ty, hessian));
    }
    if !set.slips.is_empty() {
        let c = set.slip_components;
        let _ = write!(
            out,
            "/* The slip's component count c: 1 (along the tangent) for segments, 3\n \
             * (global x, y, z) for faces (docs/conventions.md, \"The slip\"). */\n\
             #define GAPSIM_{upper}_SLIP_COMPONENTS {c}\n\n"
        );
    }
    for k in &set.slips {
        let Role::Slip { ty, hessian } = k.role else {
            continue;
        };
        let mut doc = k.doc.clone();
        doc.push_str(&format!(
            " {m0} is the last converged projection. slip: c values; grad: c * n values \
             (component after component); {}",
            if hessian {
                "hess: c * n * n values."
            } else {
                "hess is not used and may be NULL."
            },
            m0 = point_text(set, &format!("{}0", set.signature.implicit())),
        ));
        out.push_str(&comment(&doc, ""));
        let _ = writeln!(out, "{};\n", slip_prototype(set, k, ty, hessian));
    }
    let _ = write!(
        out,
        "#ifdef __cplusplus\n}} /* extern \"C\" */\n#endif\n\n#endif /* {guard} */\n"
    );
    out
}

/// The steps of the public functions that depend on the formulation: the
/// validation and projection-start calls, and how a generated function
/// takes the slave point `s` (`s[0]` by value, or the array).
struct Steps {
    validate: String,
    start: String,
    slave: &'static str,
}

/// The [`Steps`] of one formulation (module docs).
fn steps(set: &KernelSetPlan) -> Steps {
    let sig = &set.signature;
    let p = param_dim(set);
    let validate = if p == 1 {
        format!(
            "gapsim_validate_segments(q, s, {}, {}, d)",
            sig.points().len(),
            sig.dim()
        )
    } else {
        let ns = sig.slave_points();
        format!(
            "gapsim_validate_faces(q, s, {ns}, {}, d)",
            sig.points().len() - ns
        )
    };
    let slave = if p == 1 { "s[0]" } else { "s" };
    let start = if set.closed_form_projection {
        format!("gapsim_start_closed_form(xi, {p})")
    } else {
        let newton = if p == 1 { "segment" } else { "face" };
        format!(
            "gapsim_newton_{newton}({}, d, {slave}, xi)",
            set.residual.name
        )
    };
    Steps {
        validate,
        start,
        slave,
    }
}

/// One public function: `proto`, calling the generated function `call`
/// with the gradient (and the Hessian) when `derivatives` is
/// `Some(hessian)`, writing the projection into `m`'s `P` pointers.
fn public_function(
    set: &KernelSetPlan,
    proto: &str,
    call: &str,
    m: &str,
    derivatives: Option<bool>,
) -> String {
    let n = set.signature.coords();
    let p = &set.signature.params()[0];
    let steps = steps(set);
    let sfx = suffixes(set);
    let k = sfx.len();
    let mut out = format!(
        "{proto}\n{{\n    double d[{n}];\n    double s[{k}];\n    double xi[{k}];\n    double g;\n    int status;\n"
    );
    if derivatives == Some(false) {
        out.push_str("    (void)hess;\n");
    }
    for (c, suffix) in sfx.iter().enumerate() {
        let _ = writeln!(out, "    s[{c}] = {p}{suffix};");
    }
    let args = match derivatives {
        None => String::new(),
        Some(false) => ", grad".into(),
        Some(true) => ", grad, hess".into(),
    };
    let _ = write!(
        out,
        "    status = {validate};
    if (status != GAPSIM_OK) {{
        return status;
    }}
    status = {start};
    if (status != GAPSIM_OK) {{
        return status;
    }}
    g = {call}(d, {slave}, xi{args});
    status = gapsim_check_projection(xi, {k});
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!isfinite(g)) {{
        return GAPSIM_NON_FINITE_GAP;
    }}
",
        validate = steps.validate,
        start = steps.start,
        slave = steps.slave,
    );
    if let Some(hessian) = derivatives {
        let _ = write!(
            out,
            "    if (!gapsim_all_finite(grad, {n})) {{\n        return GAPSIM_NON_FINITE_GRADIENT;\n    }}\n"
        );
        if hessian {
            let _ = write!(
                out,
                "    if (!gapsim_all_finite(hess, {})) {{\n        return GAPSIM_NON_FINITE_HESSIAN;\n    }}\n",
                n * n
            );
        }
    }
    out.push_str("    *gap = g;\n");
    for (c, suffix) in sfx.iter().enumerate() {
        let _ = writeln!(out, "    *{m}{suffix} = xi[{c}];");
    }
    out.push_str("    return GAPSIM_OK;\n}\n");
    out
}

/// One public slip function (type `ty`): the steps of
/// [`public_function`] with the last converged projection checked finite
/// after the validation (`GAPSIM_NON_FINITE_INPUT`), the slip's `c`
/// components into `slip` (the generated function returns the first and
/// writes the others through pointers), `c` gradients into `grad` and `c`
/// Hessians into `hess`, component after component.
fn public_slip(set: &KernelSetPlan, k: &FunctionPlan, ty: usize, hessian: bool) -> String {
    let sig = &set.signature;
    let n = sig.coords();
    let c = set.slip_components;
    let p = &sig.params()[0];
    let m0 = format!("{}0", sig.implicit());
    let m = k_implicit(set, k);
    let steps = steps(set);
    let sfx = suffixes(set);
    let kk = sfx.len();
    let mut out = format!(
        "{}\n{{\n    double d[{n}];\n    double s[{kk}];\n    double m0[{kk}];\n    double xi[{kk}];\n    double sl[{c}];\n    int status;\n    int i;\n",
        slip_prototype(set, k, ty, hessian)
    );
    if !hessian {
        out.push_str("    (void)hess;\n");
    }
    for (i, suffix) in sfx.iter().enumerate() {
        let _ = writeln!(out, "    s[{i}] = {p}{suffix};");
        let _ = writeln!(out, "    m0[{i}] = {m0}{suffix};");
    }
    // The generated function's arguments after the projection.
    let mut args: Vec<String> = (1..c).map(|i| format!("&sl[{i}]")).collect();
    for i in 0..c {
        args.push(if i == 0 {
            "grad".to_owned()
        } else {
            format!("grad + {}", i * n)
        });
    }
    if hessian {
        for i in 0..c {
            args.push(if i == 0 {
                "hess".to_owned()
            } else {
                format!("hess + {}", i * n * n)
            });
        }
    }
    let previous = if kk == 1 { "m0[0]" } else { "m0" };
    let _ = write!(
        out,
        "    status = {validate};
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!gapsim_all_finite(m0, {kk})) {{
        return GAPSIM_NON_FINITE_INPUT;
    }}
    status = {start};
    if (status != GAPSIM_OK) {{
        return status;
    }}
    sl[0] = {call}(d, {slave}, {previous}, xi, {args});
    status = gapsim_check_projection(xi, {kk});
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!gapsim_all_finite(sl, {c})) {{
        return GAPSIM_NON_FINITE_SLIP;
    }}
    if (!gapsim_all_finite(grad, {cn})) {{
        return GAPSIM_NON_FINITE_GRADIENT;
    }}
",
        validate = steps.validate,
        start = steps.start,
        slave = steps.slave,
        call = k.name,
        args = args.join(", "),
        cn = c * n,
    );
    if hessian {
        let _ = write!(
            out,
            "    if (!gapsim_all_finite(hess, {})) {{\n        return GAPSIM_NON_FINITE_HESSIAN;\n    }}\n",
            c * n * n
        );
    }
    let _ = write!(
        out,
        "    for (i = 0; i < {c}; ++i) {{\n        slip[i] = sl[i];\n    }}\n"
    );
    for (i, suffix) in sfx.iter().enumerate() {
        let _ = writeln!(out, "    *{m}{suffix} = xi[{i}];");
    }
    out.push_str("    return GAPSIM_OK;\n}\n");
    out
}

/// The public functions of one formulation (module docs).
pub(super) fn wrappers(set: &KernelSetPlan) -> String {
    let mut out = public_function(
        set,
        &project_prototype(set),
        &set.gap.name,
        set.signature.implicit(),
        None,
    );
    for k in &set.kernels {
        let Role::Kernel { ty, hessian } = k.role else {
            continue;
        };
        out.push('\n');
        out.push_str(&public_function(
            set,
            &kernel_prototype(set, k, ty, hessian),
            &k.name,
            &k_implicit(set, k),
            Some(hessian),
        ));
    }
    for k in &set.slips {
        let Role::Slip { ty, hessian } = k.role else {
            continue;
        };
        out.push('\n');
        out.push_str(&public_slip(set, k, ty, hessian));
    }
    out
}
