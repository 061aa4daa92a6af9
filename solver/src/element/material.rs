//! St Venant–Kirchhoff material in two dimensions.
//!
//! The second Piola–Kirchhoff stress is linear in the Green–Lagrange strain,
//! `S_v = D E_v`, in Voigt notation with engineering shear:
//!
//! ```text
//! E_v = [E11, E22, 2 E12],   S_v = [S11, S22, S12]
//! ```
//!
//! * plane stress: `D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]`
//! * plane strain: `D = E/((1+nu)(1-2nu)) [[1-nu, nu, 0], [nu, 1-nu, 0], [0, 0, (1-2nu)/2]]`
//!
//! The strain energy density is `W = 1/2 E_v . S_v` (per unit reference
//! area; the thickness is one).
//!
//! [`Kinematics::Small`] replaces the Green–Lagrange strain by the
//! infinitesimal strain `eps = (H + H^T)/2` and the stress measure by the
//! Cauchy stress `sigma = D eps` of linear elasticity (no geometric
//! stiffness): the assumptions of the classical solutions such as Hertz's.
//! Contact stays in the current configuration either way.

use serde::{Deserialize, Serialize};

/// The two-dimensional idealisation of the third direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlaneModel {
    /// `S33 = 0` (thin plates; the paper's choice).
    #[default]
    PlaneStress,
    /// `E33 = 0` (long prismatic bodies).
    PlaneStrain,
}

/// How a solid measures strain (in scene files: `kinematics = "finite" |
/// "small"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kinematics {
    /// Total-Lagrangian St Venant–Kirchhoff: Green–Lagrange strain, second
    /// Piola–Kirchhoff stress, exact for large rotations (the default).
    #[default]
    Finite,
    /// Linear elasticity: infinitesimal strain, no geometric stiffness;
    /// valid for small strains and rotations only (a rigid rotation
    /// strains it).
    Small,
}

impl Kinematics {
    /// Whether the tangent has the geometric (initial-stress) term.
    pub fn geometric_stiffness(self) -> bool {
        self == Kinematics::Finite
    }

    /// Whether this is the default (for serialisation).
    fn is_finite(&self) -> bool {
        *self == Kinematics::Finite
    }
}

/// An isotropic St Venant–Kirchhoff material (in scene files: `young`,
/// `poisson`, optionally `model = "plane-stress" | "plane-strain"` and
/// `kinematics = "finite" | "small"`). Its `Debug` text leaves out the
/// default kinematics, so fingerprints of existing models are unchanged.
#[derive(Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus `E` (> 0).
    pub young: f64,
    /// Poisson's ratio `nu` (in (-1, 1/2), and below 1/2 for plane strain).
    pub poisson: f64,
    /// Plane stress (the default) or plane strain.
    #[serde(default)]
    pub model: PlaneModel,
    /// Finite strain (the default) or linear elasticity.
    #[serde(default, skip_serializing_if = "Kinematics::is_finite")]
    pub kinematics: Kinematics,
}

impl std::fmt::Debug for Material {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("Material");
        d.field("young", &self.young)
            .field("poisson", &self.poisson)
            .field("model", &self.model);
        if self.kinematics != Kinematics::Finite {
            d.field("kinematics", &self.kinematics);
        }
        d.finish()
    }
}

impl Material {
    /// The 3x3 Voigt elasticity matrix `D` (row-major), see the module docs.
    pub fn d_matrix(&self) -> [[f64; 3]; 3] {
        let (e, nu) = (self.young, self.poisson);
        match self.model {
            PlaneModel::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                [
                    [c, c * nu, 0.0],
                    [c * nu, c, 0.0],
                    [0.0, 0.0, c * (1.0 - nu) / 2.0],
                ]
            }
            PlaneModel::PlaneStrain => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                [
                    [c * (1.0 - nu), c * nu, 0.0],
                    [c * nu, c * (1.0 - nu), 0.0],
                    [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
                ]
            }
        }
    }

    /// Why the constants are not admissible, if they are not.
    pub fn check(&self) -> Result<(), String> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(format!(
                "Young's modulus must be positive and finite, got {}",
                self.young
            ));
        }
        let upper = match self.model {
            PlaneModel::PlaneStress => 1.0,
            PlaneModel::PlaneStrain => 0.5,
        };
        if !(self.poisson > -1.0 && self.poisson < upper) {
            return Err(format!(
                "Poisson's ratio must lie in (-1, {upper}) for {:?}, got {}",
                self.model, self.poisson
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_stress_matrix_matches_design() {
        let m = Material {
            young: 1000.0,
            poisson: 0.3,
            model: PlaneModel::PlaneStress,
            kinematics: Kinematics::Finite,
        };
        let d = m.d_matrix();
        let c = 1000.0 / 0.91;
        assert!((d[0][0] - c).abs() < 1e-12);
        assert!((d[0][1] - 0.3 * c).abs() < 1e-12);
        assert!((d[2][2] - 0.35 * c).abs() < 1e-12);
        assert!(m.check().is_ok());
    }

    #[test]
    fn inadmissible_constants_are_rejected() {
        let m = Material {
            young: 1.0,
            poisson: 0.5,
            model: PlaneModel::PlaneStrain,
            kinematics: Kinematics::Finite,
        };
        assert!(m.check().is_err());
        let m = Material {
            young: -1.0,
            poisson: 0.3,
            model: PlaneModel::PlaneStress,
            kinematics: Kinematics::Finite,
        };
        assert!(m.check().is_err());
    }
}
