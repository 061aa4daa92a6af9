//! The checks of a scene's values that need no mesh: refinement factors,
//! body names and materials, prescribed values, load vectors, contact
//! settings, the load schedule and the Newton settings.
//!
//! Each check names the field it rejects (`body[1].name`,
//! `contact[0].gauss_points`, ...) in a [`SceneError::Invalid`].
//! [`Scene::build_model`] calls each where the value is first needed, so a
//! scene with several faults reports the first in this order: `[refine]`;
//! each body (its name and material here, then its source's own checks,
//! such as a block's `nx`, `size` and `origin`); supports; prescribed
//! displacements; loads; tractions; contacts; `[loading]`; `[newton]`.
//! A load curve (`amplitude`) is checked with its item, after the item's
//! values: its first bad point is named (`load[1].amplitude[2]: load
//! factors must increase`). Checks that
//! depend on how a body was made belong to its mesh source, and checks that
//! need the mesh (a selection that finds no node) to `select.rs`.

use super::dimension::Dimension;
use super::{ContactSpec, LoadSpec, PrescribeSpec, Scene, SceneError, TractionSpec};
use crate::amplitude::Amplitude;
use crate::material::Material;
use crate::model::ContactMode;

impl Scene {
    /// An [`SceneError::Invalid`] for `field` of this scene.
    pub(super) fn invalid(
        &self,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            origin: self.origin.clone(),
            field: field.into(),
            message: message.into(),
        }
    }

    /// `[refine]`: every factor at least 1.
    pub(super) fn check_refine(&self) -> Result<(), SceneError> {
        if self.refine.x == 0 || self.refine.y == 0 || self.refine.z == Some(0) {
            return Err(self.invalid("refine", "factors must be at least 1"));
        }
        Ok(())
    }

    /// `body[i]`: a name no earlier body has, and a valid material (its own
    /// or the scene's default) for a body of dimension `dim` (in 3D,
    /// Poisson's ratio below 1/2), which it returns.
    pub(super) fn check_body(&self, i: usize, dim: Dimension) -> Result<Material, SceneError> {
        let b = &self.bodies[i];
        let f = format!("body[{i}]");
        if self.bodies[..i].iter().any(|o| o.name == b.name) {
            return Err(self.invalid(
                format!("{f}.name"),
                format!("duplicate body name `{}`", b.name),
            ));
        }
        let material = b.material.or(self.material).ok_or_else(|| {
            self.invalid(
                format!("{f}.material"),
                "no material (and no default [material])",
            )
        })?;
        let material = material.material();
        let checked = match dim {
            Dimension::Two => material.check(),
            Dimension::Three => material.check_3d().map_err(|e| e.to_string()),
        };
        checked.map_err(|m| {
            let field = if b.material.is_some() {
                format!("{f}.material")
            } else {
                "material".into()
            };
            self.invalid(field, m)
        })?;
        Ok(material)
    }

    /// `prescribe[i]` (named `f`) of a scene of dimension `dim`: at least
    /// one component, each finite.
    pub(super) fn check_prescribe(
        &self,
        f: &str,
        p: &PrescribeSpec,
        dim: Dimension,
    ) -> Result<(), SceneError> {
        if p.ux.is_none() && p.uy.is_none() && p.uz.is_none() {
            let which = match dim {
                Dimension::Two => "give `ux` and/or `uy`",
                Dimension::Three => "give `ux`, `uy` and/or `uz`",
            };
            return Err(self.invalid(f, which));
        }
        for (c, v) in [(0, p.ux), (1, p.uy), (2, p.uz)] {
            if v.is_some_and(|v| !v.is_finite()) {
                return Err(
                    self.invalid(format!("{f}.{}", ["ux", "uy", "uz"][c]), "must be finite")
                );
            }
        }
        Ok(())
    }

    /// The load curve `amplitude` of item `f` (`load[1]`, ...), if any:
    /// at least two points, finite, load factors strictly increasing
    /// ([`Amplitude::new`]); an error names the point
    /// (`{f}.amplitude[k]`) or, for too few points, the key.
    pub(super) fn check_amplitude(
        &self,
        f: &str,
        amplitude: &Option<Vec<[f64; 2]>>,
    ) -> Result<Option<Amplitude>, SceneError> {
        let Some(points) = amplitude else {
            return Ok(None);
        };
        Amplitude::new(points.clone()).map(Some).map_err(|e| {
            let field = match e.point() {
                Some(k) => format!("{f}.amplitude[{k}]"),
                None => format!("{f}.amplitude"),
            };
            let message = match e {
                crate::amplitude::AmplitudeError::TooFewPoints { count } => {
                    format!("{} (got {count})", e.reason())
                }
                _ => e.reason().to_owned(),
            };
            self.invalid(field, message)
        })
    }

    /// `load[i]` (named `f`): a finite force.
    pub(super) fn check_load(&self, f: &str, l: &LoadSpec) -> Result<(), SceneError> {
        if !l.force.as_slice().iter().all(|v| v.is_finite()) {
            return Err(self.invalid(format!("{f}.force"), "must be finite"));
        }
        Ok(())
    }

    /// `contact[i]` (named `f`) of a 2D scene: 1..=8 Gauss points if
    /// given (that its faces are on two different bodies is checked where
    /// they are resolved; a 3D pair's count is checked against its faces'
    /// kinds by `solid.rs`).
    pub(super) fn check_contact(&self, f: &str, c: &ContactSpec) -> Result<(), SceneError> {
        if c.gauss_points.is_some_and(|n| !(1..=8).contains(&n)) {
            return Err(self.invalid(format!("{f}.gauss_points"), "must be in 1..=8"));
        }
        Ok(())
    }

    /// `contact[i].friction` (named `f`) in either dimension: a finite
    /// number `>= 0`; above 0 only on a unilateral pair (a persistent pair
    /// holds its faces together, and Coulomb's bound `mu p` of a pair that
    /// may pull has no meaning). That the dimension solves friction is
    /// checked by `solid.rs` (3D refuses it).
    pub(super) fn check_friction(&self, f: &str, c: &ContactSpec) -> Result<(), SceneError> {
        let mu = c.friction;
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(self.invalid(
                format!("{f}.friction"),
                format!("must be a finite number >= 0 (Coulomb's coefficient), got {mu}"),
            ));
        }
        if mu > 0.0 && c.mode != ContactMode::Unilateral {
            return Err(self.invalid(
                format!("{f}.friction"),
                "friction needs `mode = \"unilateral\"`: a persistent pair holds its faces together, so Coulomb's bound `mu p` has no meaning where the pair pulls",
            ));
        }
        Ok(())
    }

    /// `traction[i]` (named `f`): a finite force per length (2D) or per
    /// area (3D); that the scene's dimension has the key is checked by
    /// `check_dimension`.
    pub(super) fn check_traction(&self, f: &str, t: &TractionSpec) -> Result<(), SceneError> {
        if t.force_per_length
            .is_some_and(|v| !v.iter().all(|v| v.is_finite()))
        {
            return Err(self.invalid(format!("{f}.force_per_length"), "must be finite"));
        }
        if t.force_per_area
            .is_some_and(|v| !v.iter().all(|v| v.is_finite()))
        {
            return Err(self.invalid(format!("{f}.force_per_area"), "must be finite"));
        }
        Ok(())
    }

    /// `[loading]`: a finite final load factor and positive step counts.
    pub(super) fn check_loading(&self) -> Result<(), SceneError> {
        let l = &self.loading;
        if !l.load_factor_end.is_finite() {
            return Err(self.invalid("loading.load_factor_end", "must be finite"));
        }
        if l.steps.is_empty() || l.steps.contains(&0) {
            return Err(self.invalid(
                "loading.steps",
                "needs at least one step count, each at least 1",
            ));
        }
        if l.default_steps == Some(0) {
            return Err(self.invalid("loading.default_steps", "must be at least 1"));
        }
        Ok(())
    }

    /// `[newton]`: a positive tolerance, at least one iteration and a
    /// positive `taylor_tolerance` if given.
    pub(super) fn check_newton(&self) -> Result<(), SceneError> {
        let n = &self.newton;
        if !(n.tolerance.is_finite() && n.tolerance > 0.0) {
            return Err(self.invalid("newton.tolerance", "must be positive"));
        }
        if n.max_iterations == 0 {
            return Err(self.invalid("newton.max_iterations", "must be at least 1"));
        }
        if n.taylor_tolerance
            .is_some_and(|t| !(t.is_finite() && t > 0.0))
        {
            return Err(self.invalid("newton.taylor_tolerance", "must be positive"));
        }
        Ok(())
    }
}
