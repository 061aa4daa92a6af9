//! The plane-strain Hertz benchmark (2D, line contact): a cylinder pressed
//! on a flat body, held only by contact, against Hertz's solution.
//!
//! Two elastic bodies of moduli `E_i` and Poisson ratios `nu_i`, a cylinder
//! of radius `R` on a half-space, under the load `P` per unit thickness:
//!
//! ```text
//! 1/E* = sum_i (1 - nu_i^2) / E_i       (super::contact_modulus)
//! a    = sqrt(4 P R / (pi E*))          contact half-width
//! p0   = 2 P / (pi a)                   peak pressure
//! p(x) = p0 sqrt(1 - x^2 / a^2)         |x| <= a (super::half_ellipse)
//! ```
//!
//! Hertz's theory is linear elasticity with small strains and `a << R`;
//! here the strain scale is `p0 / E* = a / (2 R)`.
//!
//! The scenes `scenes/hertz*.toml` model the quarter (x >= 0) of the
//! issue's problem (`R = 10`, both bodies `E = 200`, `nu = 0.3`,
//! `P = 8.63`, so `a = 1.000` and `p0 = 5.494`). The measured pressure is
//! `p = -lambda` at the slave nodes (the multiplier is a force per unit
//! reference length, interpolated linearly along the slave segments),
//! plotted over the slave nodes' current x. [`measure`] reports the peak
//! nodal pressure, `a` and `p0` of the least-squares fit of
//! `p^2 = A + B x^2` over the nodes in contact
//! ([`super::fit_half_ellipse`]: `p0 = sqrt(A)`, `a = sqrt(-A/B)`), and
//! the relative L2 error of the nodal pressures against the profile over
//! the nodes with `x < 1.5 a`.

use solver::Solution;

use super::{contact_modulus, fit_half_ellipse, half_ellipse};

/// A plane-strain Hertz problem of two bodies of the same material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzProblem {
    /// Young's modulus of both bodies.
    pub young: f64,
    /// Poisson's ratio of both bodies.
    pub poisson: f64,
    /// The cylinder's radius.
    pub radius: f64,
    /// The load per unit thickness on the full cylinder.
    pub load: f64,
}

/// The problem of `scenes/hertz*.toml`.
pub const SCENES: HertzProblem = HertzProblem {
    young: 200.0,
    poisson: 0.3,
    radius: 10.0,
    load: 8.63,
};

impl HertzProblem {
    /// The same problem under the load times `scale`.
    pub fn scaled(self, scale: f64) -> HertzProblem {
        HertzProblem {
            load: self.load * scale,
            ..self
        }
    }

    /// The contact modulus `E*` (`1/E* = 2 (1 - nu^2) / E`,
    /// [`contact_modulus`]).
    pub fn contact_modulus(&self) -> f64 {
        contact_modulus(self.young, self.poisson)
    }

    /// The contact half-width `a`.
    pub fn half_width(&self) -> f64 {
        (4.0 * self.load * self.radius / (std::f64::consts::PI * self.contact_modulus())).sqrt()
    }

    /// The peak pressure `p0`.
    pub fn peak_pressure(&self) -> f64 {
        2.0 * self.load / (std::f64::consts::PI * self.half_width())
    }

    /// Hertz's pressure at `x` (zero outside the contact;
    /// [`half_ellipse`]).
    pub fn pressure(&self, x: f64) -> f64 {
        half_ellipse(self.peak_pressure(), self.half_width(), x)
    }
}

/// One slave node's contact pressure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodalPressure {
    /// Reference x.
    pub x_ref: f64,
    /// Current x.
    pub x: f64,
    /// `p = -lambda` (positive in compression).
    pub pressure: f64,
}

/// The slave nodes' pressures of a solution, by current x.
pub fn pressure_profile(sol: &Solution) -> Vec<NodalPressure> {
    let mut out: Vec<NodalPressure> = sol
        .multiplier_dofs
        .iter()
        .zip(&sol.final_state.multipliers)
        .map(|(m, &lambda)| {
            let x_ref = sol.mesh.nodes_ref[m.node][0];
            NodalPressure {
                x_ref,
                x: x_ref + sol.final_state.displacements[m.node][0],
                pressure: -lambda,
            }
        })
        .collect();
    out.sort_by(|a, b| a.x.total_cmp(&b.x));
    out
}

/// What a solution gives against Hertz (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzMeasured {
    /// Peak nodal pressure.
    pub peak: f64,
    /// `p0` of the fit (NaN-free: `None` with fewer than three nodes in
    /// contact or a fit without a peak).
    pub p0_fit: Option<f64>,
    /// `a` of the fit (`None` as `p0_fit`).
    pub a_fit: Option<f64>,
    /// Relative L2 error of the nodal pressures against Hertz's profile
    /// (over the nodes with x < 1.5 a).
    pub profile: f64,
    /// Slave nodes with positive pressure.
    pub in_contact: usize,
    /// The mean reference length of the slave segments within the exact
    /// contact width (the element size at the contact; `None` with fewer
    /// than two slave nodes there).
    pub element_size: Option<f64>,
}

impl HertzMeasured {
    /// Relative error of the peak pressure against `problem`.
    pub fn peak_error(&self, problem: &HertzProblem) -> f64 {
        self.peak / problem.peak_pressure() - 1.0
    }

    /// Relative error of the fitted `p0` against `problem`.
    pub fn p0_fit_error(&self, problem: &HertzProblem) -> Option<f64> {
        self.p0_fit.map(|p0| p0 / problem.peak_pressure() - 1.0)
    }

    /// Relative error of the fitted half-width against `problem`.
    pub fn a_fit_error(&self, problem: &HertzProblem) -> Option<f64> {
        self.a_fit.map(|a| a / problem.half_width() - 1.0)
    }
}

/// Measures a solution of a Hertz scene against `problem`.
pub fn measure(sol: &Solution, problem: &HertzProblem) -> HertzMeasured {
    let a = problem.half_width();
    let nodes = pressure_profile(sol);
    let contact: Vec<&NodalPressure> = nodes.iter().filter(|n| n.pressure > 0.0).collect();
    let fit = fit_half_ellipse(contact.iter().map(|node| (node.x, node.pressure)));
    let (num, den) = nodes
        .iter()
        .filter(|node| node.x < 1.5 * a)
        .fold((0.0, 0.0), |s, node| {
            let exact = problem.pressure(node.x);
            (s.0 + (node.pressure - exact).powi(2), s.1 + exact * exact)
        });
    let mut within: Vec<f64> = nodes
        .iter()
        .map(|node| node.x_ref)
        .filter(|&x| x <= a)
        .collect();
    within.sort_by(f64::total_cmp);
    let element_size = match (within.first(), within.last()) {
        (Some(first), Some(last)) if within.len() > 1 => {
            Some((last - first) / (within.len() - 1) as f64)
        }
        _ => None,
    };
    HertzMeasured {
        peak: contact
            .iter()
            .fold(0.0, |m, node| f64::max(m, node.pressure)),
        p0_fit: fit.map(|f| f.0),
        a_fit: fit.map(|f| f.1),
        profile: (num / den).sqrt(),
        in_contact: contact.len(),
        element_size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The issue's numbers: a = 1.000, p0 = 5.494.
    #[test]
    fn reference_values() {
        assert!((SCENES.half_width() - 1.000).abs() < 5e-4);
        assert!((SCENES.peak_pressure() - 5.494).abs() < 5e-4);
        // the pressure integrates to the load: int p dx = pi a p0 / 2 = P
        let integral = std::f64::consts::PI * SCENES.half_width() * SCENES.peak_pressure() / 2.0;
        assert!((integral - SCENES.load).abs() < 1e-12);
        assert_eq!(SCENES.pressure(2.0), 0.0);
    }
}
