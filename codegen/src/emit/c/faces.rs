//! The C99 files of a formulation of 3D faces (tri3 and quad4, `inputs!(dim
//! 3; ..; xi_s: 2)`): the header with the public prototypes, and the
//! wrappers that do what contact-kernels' face path does around the
//! generated functions, in the same order and with the same operations:
//!
//! * validation (`faces::relative_coordinates`): every coordinate and both
//!   components of `xi_s` finite, the slave point on its face, the
//!   coordinates relative to the first point, then per face (slave first)
//!   the degenerate corners (`|t_1 x t_2|` against
//!   `GAPSIM_DEGENERATE_LENGTH` times the face's size squared) and, for a
//!   quad4, the folded ones (a corner's `t_1 x t_2` against the mean normal
//!   `(x_3 - x_1) x (x_4 - x_2)`);
//! * the projection: in closed form inside the kernels (a tri3 master), or
//!   Newton from `(0, 0)` on the residual `[r_0, r_1, A_00, A_01, A_10,
//!   A_11]` (`faces::solve`: the step by Cramer's rule, at most
//!   `GAPSIM_PROJECTION_ITERATIONS` iterations, `max|dxi| <=
//!   GAPSIM_PROJECTION_TOLERANCE (1 + max|xi|)`);
//! * the projection check (both components finite, each within
//!   `GAPSIM_XI_M_LIMIT`) and finite outputs (gap, gradient, Hessian).
//!
//! The public functions take the slave point as two doubles and write the
//! projection through two pointers:
//! `gapsim_{ident}_type6(q, xi_s_u, xi_s_v, &gap, &xi_m_u, &xi_m_v, grad, hess)`.

use std::fmt::Write as _;

use super::{comment, generated_line, k_implicit};
use crate::plan::{FormulationPlan, FunctionPlan, KernelSetPlan, Role};

/// The slave point's two scalar arguments (`double xi_s_u, double
/// xi_s_v`), from the signature's parameter name.
fn param_args(set: &KernelSetPlan) -> String {
    let p = &set.signature.params()[0];
    format!(", double {p}_u, double {p}_v")
}

/// The public prototype of the projection function.
fn project_prototype(set: &KernelSetPlan) -> String {
    let n = set.signature.coords();
    let m = set.signature.implicit();
    format!(
        "int gapsim_{}_project(const double q[{n}]{}, double *gap, double *{m}_u, double *{m}_v)",
        set.ident,
        param_args(set),
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
    let m = k_implicit(set, k);
    format!(
        "int gapsim_{}_type{ty}(const double q[{n}]{}, double *gap, double *{m}_u, double *{m}_v, double grad[{n}], {hess})",
        set.ident,
        param_args(set),
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

/// The header of one formulation of faces.
pub(super) fn header(f: &FormulationPlan, set: &KernelSetPlan) -> String {
    let sig = &set.signature;
    let (n, upper) = (sig.coords(), set.ident.to_uppercase());
    let (ns, nm) = (sig.slave_points(), sig.points().len() - sig.slave_points());
    let guard = format!("GAPSIM_{upper}_H");
    let mut out = generated_line(f);
    let mut about = String::new();
    if !f.doc.is_empty() {
        let _ = writeln!(about, "{}\n", f.doc);
    }
    let points = sig.points().join(", ");
    let p = &sig.params()[0];
    let m = sig.implicit();
    let _ = write!(
        about,
        "gapsim_{ident}.h: the `{name}` kernels for C and C++ (C99; link \
gapsim_{ident}.c and -lm; compile with -ffp-contract=off for the same bits \
as the Rust kernels).\n\n\
Every function takes q, the {n} coordinates of the points {points} (x, y, \
z of each, point by point: the slave face's {ns} nodes ({sk}), then the \
master face's {nm} ({mk}), each face counter-clockwise seen from outside \
its body), and the slave point ({p}_u, {p}_v) on its face ({sdomain}); it \
returns a gapsim_status code (gapsim.h) and on GAPSIM_OK writes the gap g \
(negative when penetrating) and ({m}_u, {m}_v), the master face's \
parametric coordinates of the projection. The Hessians are full symmetric \
{n} x {n} matrices, row-major (equal to column-major).",
        ident = set.ident,
        name = f.name,
        sk = kind(ns),
        mk = kind(nm),
        sdomain = domain(ns),
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
        "Projects the slave point onto the master face: the gap and ({m}_u, {m}_v) \
only (no derivatives), as a solver does to re-project and re-pair. Cost: {}.",
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

/// The vector helpers and the check of one face (contact-kernels'
/// `faces::check_face`, same operations in the same order).
fn face_check(id: &str) -> String {
    format!(
        "/* a - b (3 components). */
static void {id}_sub(const double *a, const double *b, double *c)
{{
    c[0] = a[0] - b[0];
    c[1] = a[1] - b[1];
    c[2] = a[2] - b[2];
}}

/* a x b. */
static void {id}_cross(const double *a, const double *b, double *c)
{{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}}

/* a . b. */
static double {id}_dot(const double *a, const double *b)
{{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}}

/* The (sub(a, b)) / 2 of a quad4's tangents. */
static void {id}_half_edge(const double *a, const double *b, double *c)
{{
    {id}_sub(a, b, c);
    c[0] = 0.5 * c[0];
    c[1] = 0.5 * c[1];
    c[2] = 0.5 * c[2];
}}

/*
 * The degenerate and fold checks of one face (p: its nodes, 3 or 4 points of
 * three coordinates, relative to the configuration's first point): at each
 * corner t1 x t2 (a tri3: one value; a quad4: the tangents dx/du, dx/dv at
 * its corners), whose squared length must be above the square of
 * GAPSIM_DEGENERATE_LENGTH times the face's size squared (the size: the
 * largest coordinate difference between its first node and the others);
 * then, for a quad4, each corner's t1 x t2 must point the way of the mean
 * normal (x3 - x1) x (x4 - x2).
 */
static int {id}_check_face(const double *p, int nodes, int degenerate, int folded)
{{
    double size = 0.0;
    double threshold;
    double corners[4][3];
    int count;
    int a;
    int k;
    for (a = 1; a < nodes; ++a) {{
        for (k = 0; k < 3; ++k) {{
            const double c = fabs(p[3 * a + k] - p[k]);
            /* A NaN difference leaves the size as it is (Rust's f64::max). */
            if (c > size) {{
                size = c;
            }}
        }}
    }}
    threshold = GAPSIM_DEGENERATE_LENGTH * size * size;
    if (nodes == 3) {{
        double e1[3];
        double e2[3];
        {id}_sub(p + 3, p, e1);
        {id}_sub(p + 6, p, e2);
        {id}_cross(e1, e2, corners[0]);
        count = 1;
    }} else {{
        double e12[3];
        double e43[3];
        double e14[3];
        double e23[3];
        {id}_half_edge(p + 3, p, e12);
        {id}_half_edge(p + 6, p + 9, e43);
        {id}_half_edge(p + 9, p, e14);
        {id}_half_edge(p + 6, p + 3, e23);
        {id}_cross(e12, e14, corners[0]);
        {id}_cross(e12, e23, corners[1]);
        {id}_cross(e43, e23, corners[2]);
        {id}_cross(e43, e14, corners[3]);
        count = 4;
    }}
    for (a = 0; a < count; ++a) {{
        const double area2 = {id}_dot(corners[a], corners[a]);
        /* Written so that a NaN is also rejected. */
        if (!(area2 > threshold * threshold)) {{
            return degenerate;
        }}
    }}
    if (nodes == 4) {{
        double d13[3];
        double d24[3];
        double mean[3];
        {id}_sub(p + 6, p, d13);
        {id}_sub(p + 9, p + 3, d24);
        {id}_cross(d13, d24, mean);
        for (a = 0; a < count; ++a) {{
            if (!({id}_dot(corners[a], mean) > 0.0)) {{
                return folded;
            }}
        }}
    }}
    return GAPSIM_OK;
}}

"
    )
}

/// The wrapper logic and the public functions of one formulation of faces
/// (module docs).
pub(super) fn wrappers(set: &KernelSetPlan) -> String {
    let sig = &set.signature;
    let n = sig.coords();
    let (ns, nm) = (sig.slave_points(), sig.points().len() - sig.slave_points());
    let id = &set.ident;
    let mut out = String::new();
    let inside = if ns == 3 {
        "xi_s[0] >= 0.0 && xi_s[1] >= 0.0 && xi_s[0] + xi_s[1] <= 1.0"
    } else {
        "fabs(xi_s[0]) <= 1.0 && fabs(xi_s[1]) <= 1.0"
    };
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

{checks}/*
 * Validates q and xi_s and writes the coordinates relative to the first
 * point into d (contact-kernels' faces.rs): every value finite, the slave
 * point on its {sk} face ({sdomain}), then the slave face (points 1..{ns}, a
 * {sk}) and the master face (points {m1}..{points}, a {mk}) neither degenerate nor
 * folded.
 */
static int {id}_validate(const double *q, const double *xi_s, double *d)
{{
    int i;
    int status;
    if (!{id}_all_finite(q, {n}) || !{id}_all_finite(xi_s, 2)) {{
        return GAPSIM_NON_FINITE_INPUT;
    }}
    if (!({inside})) {{
        return GAPSIM_SLAVE_POINT_OUTSIDE;
    }}
    for (i = 0; i < {n}; ++i) {{
        d[i] = q[i] - q[i % 3];
    }}
    status = {id}_check_face(d, {ns}, GAPSIM_DEGENERATE_SLAVE_FACE, GAPSIM_FOLDED_SLAVE_FACE);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    return {id}_check_face(d + {moff}, {nm}, GAPSIM_DEGENERATE_MASTER_FACE, GAPSIM_FOLDED_MASTER_FACE);
}}

",
        checks = face_check(id),
        sk = kind(ns),
        mk = kind(nm),
        sdomain = domain(ns),
        m1 = ns + 1,
        points = ns + nm,
        moff = 3 * ns,
    );

    if set.closed_form_projection {
        let _ = write!(
            out,
            "/* The projection is solved in closed form inside the kernels (the residual
 * is affine in xi): they ignore the start value. */
static int {id}_start(const double *d, const double *xi_s, double *xi)
{{
    (void)d;
    (void)xi_s;
    xi[0] = 0.0;
    xi[1] = 0.0;
    return GAPSIM_OK;
}}

"
        );
    } else {
        let _ = write!(
            out,
            "/* Newton's method on the projection residual from xi = (0, 0), the step by
 * Cramer's rule (contact-kernels' faces::solve). */
static int {id}_start(const double *d, const double *xi_s, double *xi)
{{
    double x[2];
    int it;
    x[0] = 0.0;
    x[1] = 0.0;
    for (it = 0; it < GAPSIM_PROJECTION_ITERATIONS; ++it) {{
        double r1;
        double a00;
        double a01;
        double a10;
        double a11;
        const double r0 = {res}(d, xi_s, x, &r1, &a00, &a01, &a10, &a11);
        const double det = a00 * a11 - a01 * a10;
        const double du = (a11 * r0 - a01 * r1) / det;
        const double dv = (a00 * r1 - a10 * r0) / det;
        double reach;
        double step;
        if (det == 0.0 || !(isfinite(du) && isfinite(dv))) {{
            return GAPSIM_NO_PROJECTION;
        }}
        x[0] = x[0] - du;
        x[1] = x[1] - dv;
        reach = fabs(x[0]) >= fabs(x[1]) ? fabs(x[0]) : fabs(x[1]);
        if (reach > GAPSIM_XI_M_LIMIT) {{
            return GAPSIM_PROJECTION_OUT_OF_REACH;
        }}
        step = fabs(du) >= fabs(dv) ? fabs(du) : fabs(dv);
        if (step <= GAPSIM_PROJECTION_TOLERANCE * (1.0 + reach)) {{
            xi[0] = x[0];
            xi[1] = x[1];
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
 * (contact-kernels' faces::check). */
static int {id}_check(const double *xi)
{{
    if (!(isfinite(xi[0]) && isfinite(xi[1]))) {{
        return GAPSIM_NO_PROJECTION;
    }}
    if (fabs(xi[0]) > GAPSIM_XI_M_LIMIT || fabs(xi[1]) > GAPSIM_XI_M_LIMIT) {{
        return GAPSIM_PROJECTION_OUT_OF_REACH;
    }}
    return GAPSIM_OK;
}}

"
    );

    let p = &sig.params()[0];
    let m = sig.implicit();
    let _ = write!(
        out,
        "{proto}
{{
    double d[{n}];
    double xi_s[2];
    double xi[2];
    double g;
    int status;
    xi_s[0] = {p}_u;
    xi_s[1] = {p}_v;
    status = {id}_validate(q, xi_s, d);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    status = {id}_start(d, xi_s, xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    g = {gap_fn}(d, xi_s, xi);
    status = {id}_check(xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    if (!isfinite(g)) {{
        return GAPSIM_NON_FINITE_GAP;
    }}
    *gap = g;
    *{m}_u = xi[0];
    *{m}_v = xi[1];
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
        let m = k_implicit(set, k);
        let _ = write!(
            out,
            "
{proto}
{{
    double d[{n}];
    double xi_s[2];
    double xi[2];
    double g;
    int status;
{void_hess}    xi_s[0] = {p}_u;
    xi_s[1] = {p}_v;
    status = {id}_validate(q, xi_s, d);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    status = {id}_start(d, xi_s, xi);
    if (status != GAPSIM_OK) {{
        return status;
    }}
    g = {kfn}(d, xi_s, xi, grad{call_hess});
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
    *{m}_u = xi[0];
    *{m}_v = xi[1];
    return GAPSIM_OK;
}}
",
            proto = kernel_prototype(set, k, ty, hessian),
            kfn = k.name,
        );
    }
    out
}
