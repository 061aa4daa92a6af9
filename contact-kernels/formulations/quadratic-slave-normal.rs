//! Projection along the slave normal for 3-node quadratic segments (the
//! faces of Q8/Q9 elements). Each segment's nodes are in Gmsh line3 order:
//! the two end nodes, then the mid node; the Lagrange shape functions on
//! [-1, 1] are N1 = xi (xi - 1) / 2, N2 = xi (xi + 1) / 2, N3 = 1 - xi^2.
//! The gap vector stays perpendicular to the slave tangent at the slave
//! point, `(x_m(xi) - x_s) . t_s = 0` (quadratic in xi: solved by Newton
//! from xi = 0), and the normal is the slave's outward unit normal there.
inputs!(xs1, xs2, xs3, xm1, xm2, xm3; xi_s);

// Slave point and slave tangent dx_s/dxi_s at xi_s.
let x_s = xs1 * (0.5 * xi_s * (xi_s - 1.0)) + xs2 * (0.5 * xi_s * (xi_s + 1.0))
    + xs3 * (1.0 - xi_s * xi_s);
let t_s = xs1 * (xi_s - 0.5) + xs2 * (xi_s + 0.5) - xs3 * (2.0 * xi_s);

// Projection coordinate on the master segment.
let xi_m = implicit!(xi => dot(
    xm1 * (0.5 * xi * (xi - 1.0)) + xm2 * (0.5 * xi * (xi + 1.0)) + xm3 * (1.0 - xi * xi) - x_s,
    t_s
));

// Gap vector from the slave point to its projection, and the unit normal.
let x_ms = entity!(
    xm1 * (0.5 * xi_m * (xi_m - 1.0)) + xm2 * (0.5 * xi_m * (xi_m + 1.0))
        + xm3 * (1.0 - xi_m * xi_m) - x_s
);
let n = entity!(perp(t_s) / norm(t_s));

gap!(dot(n, x_ms));

// The slip: the motion of the master point the slave point faces, since the
// last converged state (where it faced `xi_m0`), along the unit tangent
// `(-n.y, n.x)` (n turned a quarter counter-clockwise: along `t_s`).
let xi_m0 = previous!(xi_m);
let s_m = entity!(
    xm1 * (0.5 * xi_m * (xi_m - 1.0)) + xm2 * (0.5 * xi_m * (xi_m + 1.0))
        + xm3 * (1.0 - xi_m * xi_m)
        - (xm1 * (0.5 * xi_m0 * (xi_m0 - 1.0)) + xm2 * (0.5 * xi_m0 * (xi_m0 + 1.0))
            + xm3 * (1.0 - xi_m0 * xi_m0))
);
slip!(dot(vec2(-n.y, n.x), s_m));
