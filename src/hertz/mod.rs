//! The Hertz benchmarks: an elastic body of revolution pressed onto a
//! flat one of the same material, held only by contact, against Hertz's
//! solution, in both dimensions; two benchmarks that share what Hertz's
//! theory shares:
//!
//! * `cylinder.rs`: 2D, plane strain, a cylinder on a flat body (line
//!   contact: the half-width `a = sqrt(4 P R / (pi E*))`), the problem
//!   given (load per unit thickness), the pressure read as `-lambda` at the
//!   slave multiplier nodes, the profile's L2 error; its items are
//!   re-exported here (`gapsim::hertz::measure`);
//! * `sphere.rs`: 3D, a quarter model of a sphere on a block (point
//!   contact: the radius `a = (3 P R / (4 E*))^(1/3)`), the load read from
//!   the support's reaction, the pressure from the nodal contact table,
//!   the contact radius, the picture of the pressure;
//! * `refinement.rs`: the 2D benchmark on meshes refined at the contact;
//! * `mindlin.rs`: Cattaneo–Mindlin partial slip in 2D (friction), the
//!   stick zone and the shear against Mindlin's solution.
//!
//! What both use, written once here: the contact modulus `E*` of two
//! bodies of one material ([`contact_modulus`]), Hertz's pressure, a half
//! ellipse (2D) or half ellipsoid (3D) over the distance from the axis
//! ([`half_ellipse`]), and the least-squares fit of that shape to nodal
//! pressures ([`fit_half_ellipse`]).

pub mod cylinder;
pub mod mindlin;
pub mod mindlin3d;
pub mod refinement;
pub mod sphere;

pub use cylinder::{HertzMeasured, HertzProblem, NodalPressure, SCENES, measure, pressure_profile};

/// The contact modulus `E*` of two bodies of Young's modulus `young` and
/// Poisson's ratio `poisson`: `1/E* = 2 (1 - nu^2) / E`.
pub fn contact_modulus(young: f64, poisson: f64) -> f64 {
    young / (2.0 * (1.0 - poisson * poisson))
}

/// Hertz's pressure `p0 sqrt(1 - r^2 / a^2)` at the distance `r` from the
/// axis (the centre line in 2D) of a contact of peak `p0` and half-width
/// or radius `a`; zero outside the contact.
pub fn half_ellipse(p0: f64, a: f64, r: f64) -> f64 {
    p0 * (1.0 - (r / a).powi(2)).max(0.0).sqrt()
}

/// The least-squares fit of `p^2 = A + B r^2` over the points `(r, p)`
/// (the nodes in contact): `(p0, a) = (sqrt(A), sqrt(-A / B))`, the peak
/// and the radius of the half ellipse (2D) or half ellipsoid (3D) that
/// Hertz's pressure is. `None` with fewer than three points or when the
/// fit is no such curve (`A <= 0` or `B >= 0`).
pub fn fit_half_ellipse(points: impl Iterator<Item = (f64, f64)>) -> Option<(f64, f64)> {
    let (count, sx, sy, sxx, sxy) = points.fold((0usize, 0.0, 0.0, 0.0, 0.0), |s, (r, p)| {
        let (u, v) = (r * r, p * p);
        (s.0 + 1, s.1 + u, s.2 + v, s.3 + u * u, s.4 + u * v)
    });
    let n = count as f64;
    let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    let a0 = (sy - b * sx) / n;
    (count >= 3 && a0 > 0.0 && b < 0.0).then(|| (a0.sqrt(), (-a0 / b).sqrt()))
}
