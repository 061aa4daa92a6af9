//! A scene's dimension, and the keys that only one dimension has.
//!
//! A scene is 2D or 3D, and its bodies say which: a block body is 3D when
//! its `origin` and `size` have three numbers (then it needs `nz`), 2D
//! when they have two; a body of the `[mesh]` file has the file's
//! dimension (3D when the file holds tetrahedra or hexahedra). Bodies of
//! both dimensions in one scene are an error naming the first body that
//! differs from `body[0]`.
//!
//! The dimension then decides which keys make sense, and
//! [`Scene::check_dimension`] refuses, naming the key, what cannot mean what
//! it says:
//!
//! * in 2D: `nz`, `[refine] z`, a `z` selector, `z` in `dofs`, `uz`, three
//!   numbers in `at` or `force`, `force_per_area`, the sides `front` and
//!   `back`;
//! * in 3D: two numbers in `at` or `force`, `force_per_length`, a plane
//!   `model` in a material (a 3D solid has none); Poisson's ratio must be
//!   below 1/2 ([`crate::material::Material::check_3d`], checked with each
//!   body's material).
//!
//! The checks run in the order of the scene's tables (`[material]`,
//! bodies, `[refine]`, fixes, prescribed displacements, loads, tractions,
//! contacts), so the first error reported is stable.

use super::source::is_block;
use super::{Coords, FaceSpec, Scene, SceneError};
use crate::mesh::Side;
use crate::mesh::gmsh::{AnyMsh, read_any};

/// A scene's dimension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// Plane bodies: quadrilaterals and triangles, `[x, y]`.
    Two,
    /// Solid bodies: hexahedra and tetrahedra, `[x, y, z]`.
    Three,
}

impl Dimension {
    /// 2 or 3.
    pub fn count(self) -> usize {
        match self {
            Dimension::Two => 2,
            Dimension::Three => 3,
        }
    }

    fn of(n: usize) -> Dimension {
        if n == 3 {
            Dimension::Three
        } else {
            Dimension::Two
        }
    }

    /// `2D` or `3D`, for messages.
    pub(super) fn name(self) -> &'static str {
        match self {
            Dimension::Two => "2D",
            Dimension::Three => "3D",
        }
    }
}

impl Scene {
    /// The scene's dimension (module docs): reads the `[mesh] file`, if
    /// any, to see whether it is a 3D mesh. Errors name the key (a block
    /// whose `origin` and `size` disagree, bodies of both dimensions, a
    /// mesh file of the other dimension or unreadable, as `mesh.file`).
    pub fn dimension(&self) -> Result<Dimension, SceneError> {
        let file = self.read_mesh_file()?;
        self.dimension_with(file.as_ref())
    }

    /// The `[mesh] file`, read as what it holds (a 3D mesh when it has
    /// tetrahedra or hexahedra), if the scene has one; errors name
    /// `mesh.file`.
    pub(super) fn read_mesh_file(&self) -> Result<Option<AnyMsh>, SceneError> {
        let Some(spec) = &self.mesh else {
            return Ok(None);
        };
        read_any(super::source::resolve(&self.origin, &spec.file))
            .map(Some)
            .map_err(|e| self.invalid("mesh.file", e.to_string()))
    }

    /// The scene's dimension with its mesh file `file` (read): that of its
    /// bodies, which the file's must be.
    pub(super) fn dimension_with(&self, file: Option<&AnyMsh>) -> Result<Dimension, SceneError> {
        let of_file = file.map(|f| match f {
            AnyMsh::Planar(_) => Dimension::Two,
            AnyMsh::Volume(_) => Dimension::Three,
        });
        let dim = self.bodies_dimension(of_file)?;
        match of_file {
            Some(f) if f != dim => Err(self.invalid(
                "mesh.file",
                format!(
                    "is a {} mesh{}, but the scene's bodies are {} blocks: the bodies of a scene are all 2D or all 3D",
                    f.name(),
                    if f == Dimension::Three {
                        " (it holds tetrahedra or hexahedra)"
                    } else {
                        " (it holds no tetrahedra or hexahedra)"
                    },
                    dim.name()
                ),
            )),
            _ => Ok(dim),
        }
    }

    /// The dimension of `body[i]`, given that of the mesh file (if read):
    /// `None` for a mesh body without a file (an error the mesh source
    /// reports).
    fn body_dimension(
        &self,
        i: usize,
        file: Option<Dimension>,
    ) -> Result<Option<Dimension>, SceneError> {
        let b = &self.bodies[i];
        if !is_block(b) {
            return Ok(file);
        }
        let f = format!("body[{i}]");
        let dim = match (b.origin, b.size) {
            (Some(o), Some(s)) if o.len() != s.len() => {
                return Err(self.invalid(
                    format!("{f}.size"),
                    format!(
                        "has {} numbers but `origin` has {}: a 2D block takes [x, y] in both, a 3D block [x, y, z]",
                        s.len(),
                        o.len()
                    ),
                ));
            }
            (Some(c), _) | (None, Some(c)) => Dimension::of(c.len()),
            (None, None) if b.nz.is_some() => Dimension::Three,
            (None, None) => Dimension::Two,
        };
        if dim == Dimension::Two && b.nz.is_some() {
            return Err(self.invalid(
                format!("{f}.nz"),
                "`nz` is for a 3D block: give `origin` and `size` three numbers [x, y, z]",
            ));
        }
        Ok(Some(dim))
    }

    /// The dimension of the bodies, `file` being the mesh file's (if
    /// read): every body the same, 2D when there are none.
    fn bodies_dimension(&self, file: Option<Dimension>) -> Result<Dimension, SceneError> {
        let mut first: Option<(usize, Dimension)> = None;
        for i in 0..self.bodies.len() {
            let Some(dim) = self.body_dimension(i, file)? else {
                continue;
            };
            match first {
                None => first = Some((i, dim)),
                Some((k, d)) if d != dim => {
                    let why = |dim: Dimension, j: usize| {
                        if is_block(&self.bodies[j]) {
                            format!("a {} block", dim.name())
                        } else {
                            format!("a body of the {} mesh file", dim.name())
                        }
                    };
                    return Err(self.invalid(
                        format!("body[{i}]"),
                        format!(
                            "is {}, but body[{k}] `{}` is {}: the bodies of a scene are all 2D or all 3D",
                            why(dim, i),
                            self.bodies[k].name,
                            why(d, k)
                        ),
                    ));
                }
                Some(_) => {}
            }
        }
        Ok(first.map_or(Dimension::Two, |(_, d)| d))
    }

    /// Refuses the keys that the scene's dimension `dim` does not have
    /// (module docs), naming the first.
    pub(super) fn check_dimension(&self, dim: Dimension) -> Result<(), SceneError> {
        let three = dim == Dimension::Three;
        let only_3d = |field: String, what: &str| {
            self.invalid(
                field,
                format!("{what} is for 3D scenes; this scene is 2D (its bodies are plane)"),
            )
        };
        let coords = |field: String, c: &Option<Coords>| match c {
            Some(c) if c.len() != dim.count() => Err(self.invalid(
                field,
                format!(
                    "needs {} in a {} scene, got {} numbers",
                    if three {
                        "three numbers [x, y, z]"
                    } else {
                        "two numbers [x, y]"
                    },
                    dim.name(),
                    c.len()
                ),
            )),
            _ => Ok(()),
        };
        let side = |field: String, face: &FaceSpec| self.check_side(field, face.side, dim);
        // materials
        if three {
            let no_model = |field: String| {
                self.invalid(
                    field,
                    "a 3D solid has no plane model (`plane-stress` and `plane-strain` are 2D idealisations): leave `model` out",
                )
            };
            if self.material.is_some_and(|m| m.model.is_some()) {
                return Err(no_model("material.model".into()));
            }
            for (i, b) in self.bodies.iter().enumerate() {
                if b.material.is_some_and(|m| m.model.is_some()) {
                    return Err(no_model(format!("body[{i}].material.model")));
                }
            }
        }
        // bodies: `nz` is checked with the body's dimension
        if !three && self.refine.z.is_some() {
            return Err(only_3d("refine.z".into(), "`z`"));
        }
        let selection = |f: &str, z: Option<f64>, at: &Option<Coords>| {
            if !three && z.is_some() {
                return Err(only_3d(format!("{f}.z"), "the `z` selector"));
            }
            coords(format!("{f}.at"), at)
        };
        for (i, fx) in self.fixes.iter().enumerate() {
            let f = format!("fix[{i}]");
            selection(&f, fx.z, &fx.at)?;
            if !three && fx.dofs.is_some_and(|d| d.has_z()) {
                return Err(only_3d(format!("{f}.dofs"), "the component z"));
            }
        }
        for (i, p) in self.prescribes.iter().enumerate() {
            let f = format!("prescribe[{i}]");
            selection(&f, p.z, &p.at)?;
            if !three && p.uz.is_some() {
                return Err(only_3d(format!("{f}.uz"), "`uz`"));
            }
        }
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}]");
            coords(format!("{f}.at"), &l.at)?;
            coords(format!("{f}.force"), &Some(l.force))?;
        }
        for (i, t) in self.tractions.iter().enumerate() {
            let f = format!("traction[{i}]");
            self.check_side(format!("{f}.side"), t.side, dim)?;
            match (
                three,
                t.force_per_length.is_some(),
                t.force_per_area.is_some(),
            ) {
                (true, true, _) => {
                    return Err(self.invalid(
                        format!("{f}.force_per_length"),
                        "is for 2D scenes; a 3D traction is `force_per_area = [tx, ty, tz]` (force per unit reference area)",
                    ));
                }
                (false, _, true) => {
                    return Err(self.invalid(
                        format!("{f}.force_per_area"),
                        "is for 3D scenes; a 2D traction is `force_per_length = [tx, ty]` (force per unit reference length)",
                    ));
                }
                (true, false, false) => {
                    return Err(self.invalid(&f, "give `force_per_area = [tx, ty, tz]`"));
                }
                (false, false, false) => {
                    return Err(self.invalid(&f, "give `force_per_length = [tx, ty]`"));
                }
                _ => {}
            }
        }
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            side(format!("{f}.slave.side"), &c.slave)?;
            side(format!("{f}.master.side"), &c.master)?;
        }
        Ok(())
    }

    /// A `side` (of the item `field`) that a block of dimension `dim` has:
    /// `front` and `back` are 3D only.
    fn check_side(
        &self,
        field: String,
        side: Option<Side>,
        dim: Dimension,
    ) -> Result<(), SceneError> {
        match side {
            Some(s) if dim == Dimension::Two && s.axis::<2>().is_none() => Err(self.invalid(
                field,
                format!(
                    "`{}` is a side of a 3D block; a 2D block has the sides bottom, right, top and left",
                    s.name()
                ),
            )),
            _ => Ok(()),
        }
    }
}
