//! Closest-point projection between 3D faces: the slave face is
//! a quad4 (bilinear quadrilateral on [-1, 1]^2, nodes at (-1,-1), (1,-1), (1,1), (-1,1): Gmsh order),
//! the master face a tri3 (linear triangle, `N = (1 - u - v, u, v)` on the unit triangle).
//! The gap vector is perpendicular to both master tangents at the projection,
//! `(x_m(xi) - x_s) . t_m1(xi) = 0` and `(x_m(xi) - x_s) . t_m2(xi) = 0`, and
//! the normal is minus the master's outward unit normal there.
//! The residual is affine in xi (a tri3 master): solved in closed form.
inputs!(dim 3; xs1, xs2, xs3, xs4; xm1, xm2, xm3; xi_s: 2);

// Slave point at xi_s.
let x_s = quad4_point(xs1, xs2, xs3, xs4, xi_s);

// Projection (u, v) on the master face.
let xi_m = implicit!(xi: 2 => [
    dot(tri3_point(xm1, xm2, xm3, xi) - x_s, tri3_du(xm1, xm2, xm3)),
    dot(tri3_point(xm1, xm2, xm3, xi) - x_s, tri3_dv(xm1, xm2, xm3))
]);

// Gap vector from the slave point to its projection, and the unit normal
// (minus the master's outward normal at the projection).
let x_ms = entity!(tri3_point(xm1, xm2, xm3, xi_m) - x_s);
let n = entity!(
    -cross(tri3_du(xm1, xm2, xm3), tri3_dv(xm1, xm2, xm3))
        / norm(cross(tri3_du(xm1, xm2, xm3), tri3_dv(xm1, xm2, xm3)))
);

gap!(dot(n, x_ms));

// The slip: the motion of the master point the slave point faces, since the
// last converged state (where it faced `xi_m0`), in the tangent plane of n
// (global components).
let xi_m0 = previous!(xi_m);
let s_m = entity!(tri3_point(xm1, xm2, xm3, xi_m) - tri3_point(xm1, xm2, xm3, xi_m0));
slip!(s_m - dot(n, s_m) * n);
