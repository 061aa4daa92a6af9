//! St Venant–Kirchhoff material in two and three dimensions.
//!
//! The second Piola–Kirchhoff stress is linear in the Green–Lagrange strain,
//! `S_v = D E_v`, in Voigt notation with engineering shear:
//!
//! ```text
//! 2D:  E_v = [E11, E22, 2 E12],                          S_v = [S11, S22, S12]
//! 3D:  E_v = [E11, E22, E33, 2 E23, 2 E13, 2 E12],       S_v = [S11, S22, S33, S23, S13, S12]
//! ```
//!
//! * plane stress: `D = E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]]`
//! * plane strain: `D = E/((1+nu)(1-2nu)) [[1-nu, nu, 0], [nu, 1-nu, 0], [0, 0, (1-2nu)/2]]`
//! * 3D ([`Material::d_matrix_3d`]): `D = E/((1+nu)(1-2nu))` times `1-nu` on
//!   the normal diagonal, `nu` between normal components, `(1-2nu)/2` on
//!   the shear diagonal, zero elsewhere (`lambda + 2 mu`, `lambda`, `mu`);
//!   its normal-shear block in the plane is the plane-strain `D`, to the
//!   bit. The plane model is not used in 3D, and Poisson's ratio must be
//!   below 1/2 ([`Material::check_3d`]).
//!
//! The strain energy density is `W = 1/2 E_v . S_v` (per unit reference
//! area in 2D, the thickness being one; per unit reference volume in 3D).
//!
//! [`Kinematics::Small`] replaces the Green–Lagrange strain by the
//! infinitesimal strain `eps = (H + H^T)/2` and the stress measure by the
//! Cauchy stress `sigma = D eps` of linear elasticity (no geometric
//! stiffness): the assumptions of the classical solutions such as Hertz's.
//! Contact stays in the current configuration either way.

use serde::{Deserialize, Serialize};

/// Why the constants of a [`Material`] are not admissible.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum MaterialError {
    /// `E` is not positive and finite.
    #[error("Young's modulus must be positive and finite, got {young}")]
    Young {
        /// The offending value.
        young: f64,
    },
    /// `nu` is outside `(-1, upper)` for a plane model.
    #[error("Poisson's ratio must lie in (-1, {upper}) for {model:?}, got {poisson}")]
    PlanePoisson {
        /// The offending value.
        poisson: f64,
        /// The plane model.
        model: PlaneModel,
        /// Its upper bound (1 in plane stress, 1/2 in plane strain).
        upper: f64,
    },
    /// `nu` is outside `(-1, 1/2)` for a 3D solid.
    #[error(
        "Poisson's ratio must lie in (-1, 0.5) for a 3D solid, got {poisson} (at 0.5 the material is incompressible and its elasticity matrix is singular)"
    )]
    SolidPoisson {
        /// The offending value.
        poisson: f64,
    },
}

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
/// `kinematics = "finite" | "small"`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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

    /// The 6x6 Voigt elasticity matrix `D` of a 3D solid (row-major,
    /// order `[11, 22, 33, 23, 13, 12]`), see the module docs.
    pub fn d_matrix_3d(&self) -> [[f64; 6]; 6] {
        let (e, nu) = (self.young, self.poisson);
        let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mut d = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                d[i][j] = if i == j { c * (1.0 - nu) } else { c * nu };
            }
            d[3 + i][3 + i] = c * (1.0 - 2.0 * nu) / 2.0;
        }
        d
    }

    /// The elasticity matrix of `V` Voigt components: [`Material::d_matrix`]
    /// for `V = 3` (2D), [`Material::d_matrix_3d`] for `V = 6` (3D).
    pub fn elasticity<const V: usize>(&self) -> [[f64; V]; V] {
        const { assert!(V == 3 || V == 6, "V is 3 (2D) or 6 (3D)") };
        let mut out = [[0.0; V]; V];
        if V == 3 {
            let d = self.d_matrix();
            for r in 0..V {
                out[r].copy_from_slice(&d[r]);
            }
        } else {
            let d = self.d_matrix_3d();
            for r in 0..V {
                out[r].copy_from_slice(&d[r]);
            }
        }
        out
    }

    /// Why the constants are not admissible for a 2D (plane) solid, if they
    /// are not (the message of [`Material::check_plane`]).
    pub fn check(&self) -> Result<(), String> {
        self.check_plane().map_err(|e| e.to_string())
    }

    /// Whether the constants are admissible for a 2D solid: `E > 0`
    /// finite, `nu` in `(-1, 1)` in plane stress and `(-1, 1/2)` in plane
    /// strain.
    pub fn check_plane(&self) -> Result<(), MaterialError> {
        self.check_young()?;
        let upper = match self.model {
            PlaneModel::PlaneStress => 1.0,
            PlaneModel::PlaneStrain => 0.5,
        };
        if !(self.poisson > -1.0 && self.poisson < upper) {
            return Err(MaterialError::PlanePoisson {
                poisson: self.poisson,
                model: self.model,
                upper,
            });
        }
        Ok(())
    }

    /// Whether the constants are admissible for a 3D solid: `E > 0`
    /// finite and `nu` in `(-1, 1/2)` (the plane model is not read).
    pub fn check_3d(&self) -> Result<(), MaterialError> {
        self.check_young()?;
        if !(self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(MaterialError::SolidPoisson {
                poisson: self.poisson,
            });
        }
        Ok(())
    }

    fn check_young(&self) -> Result<(), MaterialError> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(MaterialError::Young { young: self.young });
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

    /// The 2D messages are what they were; the 3D check refuses
    /// `nu >= 1/2` (and `nu <= -1`, `E <= 0`) whatever the plane model,
    /// with its own message.
    #[test]
    fn plane_and_solid_checks() {
        let m = |poisson: f64, model: PlaneModel| Material {
            young: 10.0,
            poisson,
            model,
            kinematics: Kinematics::Finite,
        };
        assert_eq!(
            m(0.5, PlaneModel::PlaneStrain).check().unwrap_err(),
            "Poisson's ratio must lie in (-1, 0.5) for PlaneStrain, got 0.5"
        );
        assert_eq!(
            m(1.0, PlaneModel::PlaneStress).check().unwrap_err(),
            "Poisson's ratio must lie in (-1, 1) for PlaneStress, got 1"
        );
        let young = Material {
            young: f64::NAN,
            ..m(0.3, PlaneModel::PlaneStress)
        };
        assert_eq!(
            young.check().unwrap_err(),
            "Young's modulus must be positive and finite, got NaN"
        );
        assert!(matches!(young.check_3d(), Err(MaterialError::Young { young }) if young.is_nan()));
        // plane stress admits 0.6, a 3D solid does not
        assert!(m(0.6, PlaneModel::PlaneStress).check().is_ok());
        for (nu, ok) in [
            (0.49, true),
            (-0.99, true),
            (0.5, false),
            (0.6, false),
            (-1.0, false),
        ] {
            for model in [PlaneModel::PlaneStress, PlaneModel::PlaneStrain] {
                let r = m(nu, model).check_3d();
                assert_eq!(r.is_ok(), ok, "nu = {nu}, {model:?}");
                if !ok {
                    assert_eq!(r, Err(MaterialError::SolidPoisson { poisson: nu }));
                }
            }
        }
        let msg = m(0.5, PlaneModel::PlaneStress)
            .check_3d()
            .unwrap_err()
            .to_string();
        assert!(
            msg.starts_with("Poisson's ratio must lie in (-1, 0.5) for a 3D solid, got 0.5"),
            "{msg}"
        );
    }

    /// The 3D matrix: `lambda + 2 mu`, `lambda`, `mu` of the constants;
    /// its in-plane normal and shear entries are the plane-strain matrix's
    /// bits; `elasticity` gives the 2D or 3D matrix by size.
    #[test]
    fn solid_matrix_is_isotropic_elasticity() {
        let m = Material {
            young: 210.0,
            poisson: 0.3,
            model: PlaneModel::PlaneStrain,
            kinematics: Kinematics::Finite,
        };
        let d = m.d_matrix_3d();
        let lambda = 210.0 * 0.3 / (1.3 * 0.4);
        let mu = 210.0 / 2.6;
        for i in 0..6 {
            for j in 0..6 {
                let want = match (i < 3, j < 3) {
                    (true, true) if i == j => lambda + 2.0 * mu,
                    (true, true) => lambda,
                    (false, false) if i == j => mu,
                    _ => 0.0,
                };
                assert!((d[i][j] - want).abs() < 1e-12 * mu, "D[{i}][{j}]");
                assert_eq!(d[i][j], d[j][i]);
            }
        }
        let p = m.d_matrix();
        for (i3, i2) in [(0, 0), (1, 1), (5, 2)] {
            for (j3, j2) in [(0, 0), (1, 1), (5, 2)] {
                assert_eq!(d[i3][j3], p[i2][j2]);
            }
        }
        assert_eq!(m.elasticity::<3>(), p);
        assert_eq!(m.elasticity::<6>(), d);
    }
}
