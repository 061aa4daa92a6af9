//! Closest-point projection between 3D faces: the slave face is
//! a quad4 (bilinear quadrilateral on [-1, 1]^2, nodes at (-1,-1), (1,-1), (1,1), (-1,1): Gmsh order),
//! the master face a quad4 (bilinear quadrilateral on [-1, 1]^2, nodes at (-1,-1), (1,-1), (1,1), (-1,1): Gmsh order).
//! The gap vector is perpendicular to both master tangents at the projection,
//! `(x_m(xi) - x_s) . t_m1(xi) = 0` and `(x_m(xi) - x_s) . t_m2(xi) = 0`, and
//! the normal is minus the master's outward unit normal there.
//! On the quad4 master the residual is not affine in xi: Newton from (0, 0).
inputs!(dim 3; xs1, xs2, xs3, xs4; xm1, xm2, xm3, xm4; xi_s: 2);

// Slave point at xi_s.
let x_s = quad4_point(xs1, xs2, xs3, xs4, xi_s);

// Projection (u, v) on the master face.
let xi_m = implicit!(xi: 2 => [
    dot(quad4_point(xm1, xm2, xm3, xm4, xi) - x_s, quad4_du(xm1, xm2, xm3, xm4, xi)),
    dot(quad4_point(xm1, xm2, xm3, xm4, xi) - x_s, quad4_dv(xm1, xm2, xm3, xm4, xi))
]);

// Gap vector from the slave point to its projection, and the unit normal
// (minus the master's outward normal at the projection).
let x_ms = entity!(quad4_point(xm1, xm2, xm3, xm4, xi_m) - x_s);
let n = entity!(
    -cross(quad4_du(xm1, xm2, xm3, xm4, xi_m), quad4_dv(xm1, xm2, xm3, xm4, xi_m))
        / norm(cross(quad4_du(xm1, xm2, xm3, xm4, xi_m), quad4_dv(xm1, xm2, xm3, xm4, xi_m)))
);

gap!(dot(n, x_ms));

// The slip: the motion of the master point the slave point faces, since the
// last converged state (where it faced `xi_m0`), in the tangent plane of n
// (global components).
let xi_m0 = previous!(xi_m);
let s_m = entity!(quad4_point(xm1, xm2, xm3, xm4, xi_m) - quad4_point(xm1, xm2, xm3, xm4, xi_m0));
slip!(s_m - dot(n, s_m) * n);
