//! Closest-point projection: the gap vector is perpendicular to the master
//! segment, `(x_m(xi) - x_s) . t_m = 0`, and the normal is the master
//! segment's inward unit normal (pointing towards the slave body).
inputs!(xs1, xs2, xm1, xm2; xi_s);

// Slave point and master tangent.
let x_s = lerp(xs1, xs2, xi_s);
let t_m = xm2 - xm1;

// Projection coordinate on the master segment.
let xi_m = implicit!(xi => dot(lerp(xm1, xm2, xi) - x_s, t_m));

// Gap vector from the slave point to its projection, and the unit normal.
let x_ms = entity!(lerp(xm1, xm2, xi_m) - x_s);
let n = entity!(-perp(t_m) / norm(t_m));

gap!(dot(n, x_ms));

// The slip: the motion of the master point the slave point faces, since the
// last converged state (where it faced `xi_m0`), along the unit tangent
// `(-n.y, n.x)` (n turned a quarter counter-clockwise: along `-t_m`).
let xi_m0 = previous!(xi_m);
let s_m = entity!(lerp(xm1, xm2, xi_m) - lerp(xm1, xm2, xi_m0));
slip!(dot(vec2(-n.y, n.x), s_m));
