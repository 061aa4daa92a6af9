//! Projection along the slave normal between 3D faces: the slave face is
//! a quad4 (bilinear quadrilateral on [-1, 1]^2, nodes at (-1,-1), (1,-1), (1,1), (-1,1): Gmsh order),
//! the master face a tri3 (linear triangle, `N = (1 - u - v, u, v)` on the unit triangle).
//! The gap vector stays perpendicular to both slave tangents at the slave
//! point, `(x_m(xi) - x_s) . t_s1 = 0` and `(x_m(xi) - x_s) . t_s2 = 0`, and
//! the normal is the slave's outward unit normal `t_s1 x t_s2 / |t_s1 x t_s2|`.
//! The residual is affine in xi (a tri3 master): solved in closed form.
inputs!(dim 3; xs1, xs2, xs3, xs4; xm1, xm2, xm3; xi_s: 2);

// Slave point and slave tangents dx_s/du, dx_s/dv at xi_s.
let x_s = quad4_point(xs1, xs2, xs3, xs4, xi_s);
let ts1 = quad4_du(xs1, xs2, xs3, xs4, xi_s);
let ts2 = quad4_dv(xs1, xs2, xs3, xs4, xi_s);

// Projection (u, v) on the master face.
let xi_m = implicit!(xi: 2 => [
    dot(tri3_point(xm1, xm2, xm3, xi) - x_s, ts1),
    dot(tri3_point(xm1, xm2, xm3, xi) - x_s, ts2)
]);

// Gap vector from the slave point to its projection, and the unit normal.
let x_ms = entity!(tri3_point(xm1, xm2, xm3, xi_m) - x_s);
let n = entity!(cross(ts1, ts2) / norm(cross(ts1, ts2)));

gap!(dot(n, x_ms));

// The slip: the motion of the master point the slave point faces, since the
// last converged state (where it faced `xi_m0`), in the tangent plane of n
// (global components).
let xi_m0 = previous!(xi_m);
let s_m = entity!(tri3_point(xm1, xm2, xm3, xi_m) - tri3_point(xm1, xm2, xm3, xi_m0));
slip!(s_m - dot(n, s_m) * n);
