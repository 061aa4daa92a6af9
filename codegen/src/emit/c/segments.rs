//! The C99 files of a formulation of 2D segments (two-node or 3-node): the
//! header with the public prototypes (`xi_s` and `xi_m` as single doubles),
//! and the wrappers that do what contact-kernels' `validate.rs`,
//! `projection.rs` and `Kernel::eval` do around the generated functions,
//! in the same order: validation (finite input, relative coordinates,
//! degenerate segments, and for 3-node segments folded ones), the
//! projection (closed form inside the kernels, or Newton on the residual),
//! the kernel, the projection check and finite outputs.

use std::fmt::Write as _;

use super::{comment, generated_line, k_implicit};
use crate::plan::{FormulationPlan, FunctionPlan, KernelSetPlan, Role};

/// The scalar parameters of the public functions (`double xi_s`).
fn param_args(set: &KernelSetPlan) -> String {
    set.signature
        .params()
        .iter()
        .map(|p| format!(", double {p}"))
        .collect()
}

/// The public prototype of the projection function.
fn project_prototype(set: &KernelSetPlan) -> String {
    let n = set.signature.coords();
    format!(
        "int gapsim_{}_project(const double q[{n}]{}, double *gap, double *{})",
        set.ident,
        param_args(set),
        set.signature.implicit()
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
        "int gapsim_{}_type{ty}(const double q[{n}]{}, double *gap, double *{}, double grad[{n}], {hess})",
        set.ident,
        param_args(set),
        k_implicit(set, k),
    )
}

/// The header of one formulation.
pub(super) fn header(f: &FormulationPlan, set: &KernelSetPlan) -> String {
    let sig = &set.signature;
    let (n, upper) = (sig.coords(), set.ident.to_uppercase());
    let guard = format!("GAPSIM_{upper}_H");
    let mut out = generated_line(f);
    let mut about = String::new();
    if !f.doc.is_empty() {
        let _ = writeln!(about, "{}\n", f.doc);
    }
    let points = sig.points().join(", ");
    let params = sig.params().join(", ");
    let implicit = sig.implicit();
    let _ = write!(
        about,
        "gapsim_{ident}.h: the `{name}` kernels for C and C++ (C99; link \
gapsim_{ident}.c and -lm; compile with -ffp-contract=off for the same bits \
as the Rust kernels).\n\n\
Every function takes q, the {n} coordinates of the points {points} (x, y \
of each, point by point: the slave segment's nodes, then the master \
segment's), and {params}; it returns a gapsim_status code (gapsim.h) and on \
GAPSIM_OK writes the gap g (negative when penetrating) and {implicit}, the \
master coordinate of the projection. The Hessians are full symmetric \
{n} x {n} matrices, row-major (equal to column-major).",
        ident = set.ident,
        name = f.name,
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
        "Projects the slave point onto the master segment: the gap and {implicit} only \
(no derivatives), as a solver does to re-project and re-pair. Cost: {}.",
        set.projection_ops
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
    let _ = write!(
        out,
        "#ifdef __cplusplus\n}} /* extern \"C\" */\n#endif\n\n#endif /* {guard} */\n"
    );
    out
}

/// The fold checks of 3-node segments (contact-kernels' `validate::check_fold`,
/// same operations in the same order): `t(+-1) . (b - a)` must stay positive
/// with margin, `a`, `b` the end nodes and `m` the mid node of each segment.
fn fold_checks(out: &mut String, dim: usize) {
    for (code, first) in [("GAPSIM_FOLDED_SLAVE", 0), ("GAPSIM_FOLDED_MASTER", 3)] {
        let (a, b, m) = (first * dim, (first + 1) * dim, (first + 2) * dim);
        let _ = writeln!(
            out,
            "    {{\n        /* 3-node segment: its mid node must not fold it. */\n        double chord2 = 0.0;\n        double along = 0.0;\n        double half_chord2;"
        );
        for k in 0..dim {
            let _ = writeln!(
                out,
                "        {{\n            const double c = d[{bk}] - d[{ak}];\n            chord2 += c * c;\n            along += (d[{ak}] + d[{bk}] - 2.0 * d[{mk}]) * c;\n        }}",
                ak = a + k,
                bk = b + k,
                mk = m + k
            );
        }
        let _ = writeln!(
            out,
            "        half_chord2 = 0.5 * chord2;\n        /* Written so that a NaN is also rejected. */\n        if (!(half_chord2 - fabs(along) > GAPSIM_DEGENERATE_LENGTH * half_chord2)) {{\n            return {code};\n        }}\n    }}"
        );
    }
}

/// The wrapper logic and the public functions of one formulation: what
/// contact-kernels' `validate.rs`, `projection.rs` and `Kernel::eval` do,
/// in the same order.
pub(super) fn wrappers(set: &KernelSetPlan) -> String {
    let sig = &set.signature;
    let (n, dim, points) = (sig.coords(), sig.dim(), sig.points().len());
    let half = points / 2;
    let id = &set.ident;
    let params = sig.params();
    let param_decl = param_args(set);
    let param_names: String = params.iter().map(|p| format!(", {p}")).collect();
    let mut out = String::new();

    // Validation: contact-kernels' validate::relative_coordinates.
    let mut finite_params = String::new();
    for p in params {
        let _ = write!(
            finite_params,
            "\n    if (!isfinite({p})) {{\n        return GAPSIM_NON_FINITE_INPUT;\n    }}"
        );
    }
    let _ = write!(
        out,
        "/* Whether all len values are finite. */
static int {id}_all_finite(const double *v, int len)
{{
    int i;
    for (i = 0; i < len; ++i) {{
        if (!isfinite(v[i])) {{
            return 0;
        }}
    }}
    return 1;
}}

/*
 * Validates q and the parameters and writes the coordinates relative to the
 * first point into d (contact-kernels' validate.rs): every value finite,
 * then neither segment (slave: points 1..{half}, master: {m1}..{points}; the chord
 * between a segment's first and {ends} point) shorter than
 * GAPSIM_DEGENERATE_LENGTH times the largest |d[i]|.{folds}
 */
static int {id}_validate(const double *q{param_decl}, double *d)
{{
    double size = 0.0;
    double threshold;
    int i;
    if (!{id}_all_finite(q, {n})) {{
        return GAPSIM_NON_FINITE_INPUT;
    }}{finite_params}
    for (i = 0; i < {n}; ++i) {{
        d[i] = q[i] - q[i % {dim}];
    }}
    for (i = 0; i < {n}; ++i) {{
        if (fabs(d[i]) > size) {{
            size = fabs(d[i]);
        }}
    }}
    threshold = GAPSIM_DEGENERATE_LENGTH * size;
",
        m1 = half + 1,
        ends = if half == 2 { "last" } else { "second" },
        folds = if half == 3 {
            "\n * Then neither 3-node segment folded (GAPSIM_FOLDED_SLAVE, _MASTER): its\n * tangent's component along the chord must stay positive at both ends,\n * chord^2 / 2 - |(a + b - 2 m) . (b - a)| > GAPSIM_DEGENERATE_LENGTH *\n * chord^2 / 2 (a, b the end nodes, m the mid node)."
        } else {
            ""
        },
    );
    // The end nodes: the first two of each segment (for two-node segments
    // the first and last).
    for (code, first, last) in [
        ("GAPSIM_DEGENERATE_SLAVE", 0, 1),
        ("GAPSIM_DEGENERATE_MASTER", half, half + 1),
    ] {
        let (a, b) = (first * dim, last * dim);
        let _ = writeln!(out, "    {{\n        double length2 = 0.0;");
        for k in 0..dim {
            let _ = writeln!(
                out,
                "        const double c{k} = d[{}] - d[{}];\n        length2 += c{k} * c{k};",
                b + k,
                a + k
            );
        }
        let _ = writeln!(
            out,
            "        /* Written so that a NaN length is also rejected. */\n        if (!(length2 > threshold * threshold)) {{\n            return {code};\n        }}\n    }}"
        );
    }
    if half == 3 {
        fold_checks(&mut out, dim);
    }
    out.push_str("    return GAPSIM_OK;\n}\n\n");

    // The projection start: closed form (the kernels solve it) or Newton.
    if set.closed_form_projection {
        let _ = write!(
            out,
            "/* The projection is solved in closed form inside the kernels (the residual
 * is affine in xi): they ignore the start value. */
static int {id}_start(const double *d{param_decl}, double *xi)
{{
    (void)d;{voids}
    *xi = 0.0;
    return GAPSIM_OK;
}}

",
            voids = params
                .iter()
                .map(|p| format!("\n    (void){p};"))
                .collect::<String>()
        );
    } else {
        let _ = write!(
            out,
            "/* Newton's method on the projection residual from xi = 0
 * (contact-kernels' projection::solve). */
static int {id}_start(const double *d{param_decl}, double *xi)
{{
    double x = 0.0;
    int it;
    for (it = 0; it < GAPSIM_PROJECTION_ITERATIONS; ++it) {{
        double r_xi;
        const double r = {res}(d{param_names}, x, &r_xi);
        const double step = r / r_xi;
        if (!isfinite(step)) {{
            return GAPSIM_NO_PROJECTION;
        }}
        x -= step;
        if (fabs(x) > GAPSIM_XI_M_LIMIT) {{
            return GAPSIM_PROJECTION_OUT_OF_REACH;
        }}
        if (fabs(step) <= GAPSIM_PROJECTION_TOLERANCE * (1.0 + fabs(x))) {{
            *xi = x;
            return GAPSIM_OK;
        }}
    }}
    return GAPSIM_PROJECTION_DIVERGED;
}}

",
            res = set.residual.name
        );
    }
    let _ = write!(
        out,
        "/* Rejects a projection the kernel could not find or that lies out of reach
 * (contact-kernels' projection::check). */
static int {id}_check(double xi)
{{
    if (!isfinite(xi)) {{
        return GAPSIM_NO_PROJECTION;
    }}
    if (fabs(xi) > GAPSIM_XI_M_LIMIT) {{
        return GAPSIM_PROJECTION_OUT_OF_REACH;
    }}
    return GAPSIM_OK;
}}

"
    );

    // The public functions.
    let implicit = sig.implicit();
    let _ = write!(
        out,
        "{proto}
{{
    double d[{n}];
    double xi;
    double g;
    int status = {id}_validate(q{param_names}, d);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    status = {id}_start(d{param_names}, &xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    g = {gap_fn}(d{param_names}, &xi);
    status = {id}_check(xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!isfinite(g)) {{
        return GAPSIM_NON_FINITE_GAP;
    }}
    *gap = g;
    *{implicit} = xi;
    return GAPSIM_OK;
}}
",
        proto = project_prototype(set),
        gap_fn = set.gap.name,
    );
    for k in &set.kernels {
        let Role::Kernel { ty, hessian } = k.role else {
            continue;
        };
        let (call_hess, check_hess, void_hess) = if hessian {
            (
                ", hess",
                format!(
                    "    if (!{id}_all_finite(hess, {})) {{\n        return GAPSIM_NON_FINITE_HESSIAN;\n    }}\n",
                    n * n
                ),
                "",
            )
        } else {
            ("", String::new(), "    (void)hess;\n")
        };
        let _ = write!(
            out,
            "
{proto}
{{
    double d[{n}];
    double xi;
    double g;
    int status;
{void_hess}    status = {id}_validate(q{param_names}, d);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    status = {id}_start(d{param_names}, &xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    g = {kfn}(d{param_names}, &xi, grad{call_hess});
    status = {id}_check(xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!isfinite(g)) {{
        return GAPSIM_NON_FINITE_GAP;
    }}
    if (!{id}_all_finite(grad, {n})) {{
        return GAPSIM_NON_FINITE_GRADIENT;
    }}
{check_hess}    *gap = g;
    *{imp} = xi;
    return GAPSIM_OK;
}}
",
            proto = kernel_prototype(set, k, ty, hessian),
            kfn = k.name,
            imp = k_implicit(set, k),
        );
    }
    out
}
