//! The stress measures of a solid element at a point or averaged over it,
//! in 2D and 3D alike.

/// Stress and strain measures in Voigt order (`V = 3` components
/// `[xx, yy, xy]` in 2D, the default; `V = 6` components
/// `[xx, yy, zz, yz, xz, xy]` in 3D, see docs/conventions.md "Solid
/// element").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stress<const V: usize = 3> {
    /// Second Piola–Kirchhoff stress (reference frame; with small
    /// kinematics the Cauchy stress of linear elasticity).
    pub pk2: [f64; V],
    /// Cauchy stress `sigma = F S F^T / det F` (current frame; in 2D the
    /// in-plane components).
    pub cauchy: [f64; V],
    /// Green–Lagrange strain (tensor shear: `E12`, not `2 E12`; the
    /// infinitesimal strain with small kinematics).
    pub green: [f64; V],
}

impl<const V: usize> Stress<V> {
    /// The mean of `points` with equal weights: the point itself when
    /// there is one, else the sum of each point's `1/n` share in point
    /// order.
    pub fn mean(points: &[Stress<V>]) -> Stress<V> {
        if let [one] = points {
            return *one;
        }
        let n = points.len() as f64;
        let mut m = Stress {
            pk2: [0.0; V],
            cauchy: [0.0; V],
            green: [0.0; V],
        };
        for p in points {
            for c in 0..V {
                m.pk2[c] += p.pk2[c] / n;
                m.cauchy[c] += p.cauchy[c] / n;
                m.green[c] += p.green[c] / n;
            }
        }
        m
    }
}
