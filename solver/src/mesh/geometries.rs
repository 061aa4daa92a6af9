//! The reference geometry ([`ElementGeometry`]) of a set of a mesh's
//! elements: those a solve assembles, computed once per solve (every element
//! on one rank; across MPI ranks the rank's own, `crate::partition`), and
//! any other element's computed when it is asked for.
//!
//! The mesh keeps no geometry ([`Mesh::add_body`] checks each element's and
//! drops it): a hexahedron's is 1.6 kB (eight points of `G_a` and weight),
//! 48 MB for 30000 hexahedra, which every rank held in full before; now a
//! rank holds its own elements' only.
//!
//! Invariant ([`Geometries::check_invariants`]): the elements are in
//! strictly increasing order, one geometry each, equal to
//! [`Mesh::geometry`] of that element.

use std::borrow::Cow;

use super::{Mesh, MeshError};
use crate::element::ElementGeometry;
use crate::ids::ElementId;
use crate::par;

/// Elements per parallel chunk.
const PAR_MIN_LEN: usize = 256;

/// The geometry of a set of elements (module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Geometries {
    /// The elements, increasing; `None`: every element of the mesh.
    elements: Option<Vec<ElementId>>,
    /// `of[k]`: the geometry of the `k`-th element.
    of: Vec<ElementGeometry>,
}

impl Geometries {
    /// The geometry of `mesh`'s `elements` (increasing; `None`: every
    /// element), computed in parallel (`crate::par`); the first failing
    /// element's error.
    pub fn of<const D: usize>(
        mesh: &Mesh<D>,
        elements: Option<&[ElementId]>,
    ) -> Result<Geometries, MeshError> {
        let count = elements.map_or(mesh.element_count(), <[ElementId]>::len);
        let element = |k: usize| elements.map_or(ElementId::new(k), |list| list[k]);
        let of = par::map(count, PAR_MIN_LEN, |k| mesh.geometry(element(k)))
            .into_iter()
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Geometries {
            elements: elements.map(<[ElementId]>::to_vec),
            of,
        })
    }

    /// The number of elements.
    pub fn len(&self) -> usize {
        self.of.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.of.is_empty()
    }

    /// The `k`-th element and its geometry.
    pub fn at(&self, k: usize) -> (ElementId, &ElementGeometry) {
        let e = self
            .elements
            .as_ref()
            .map_or(ElementId::new(k), |list| list[k]);
        (e, &self.of[k])
    }

    /// The elements, increasing (`None`: every element of the mesh).
    pub fn elements(&self) -> Option<&[ElementId]> {
        self.elements.as_deref()
    }

    /// Element `e`'s geometry, when it is one of the set.
    pub fn get(&self, e: ElementId) -> Option<&ElementGeometry> {
        match &self.elements {
            None => self.of.get(e.index()),
            Some(list) => list.binary_search(&e).ok().map(|k| &self.of[k]),
        }
    }

    /// Element `e`'s geometry: the set's, or computed from `mesh` for an
    /// element outside it ([`Mesh::geometry`]).
    pub fn or_compute<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        e: ElementId,
    ) -> Result<Cow<'_, ElementGeometry>, MeshError> {
        match self.get(e) {
            Some(g) => Ok(Cow::Borrowed(g)),
            None => mesh.geometry(e).map(Cow::Owned),
        }
    }

    /// Whether the invariant of the module docs holds for `mesh`.
    pub fn check_invariants<const D: usize>(&self, mesh: &Mesh<D>) -> bool {
        let count = self
            .elements
            .as_ref()
            .map_or(mesh.element_count(), Vec::len);
        let increasing = self
            .elements
            .as_ref()
            .is_none_or(|list| list.windows(2).all(|w| w[0] < w[1]));
        increasing
            && count == self.of.len()
            && (0..count).all(|k| {
                let (e, g) = self.at(k);
                e.index() < mesh.element_count() && mesh.geometry(e).as_ref() == Ok(g)
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::Element;
    use crate::mesh::tests::MAT;

    /// Three quadrilaterals and a triangle: the set of two of them holds
    /// exactly their geometry, computes the others', and every element's
    /// equals the whole set's.
    #[test]
    fn a_set_holds_its_elements_and_computes_the_others() {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.2],
            [2.0, 1.0],
            [3.0, 0.5],
        ];
        let elements = [
            Element::Quad4([0, 1, 4, 3]),
            Element::Quad4([1, 2, 5, 4]),
            Element::Tri3([2, 6, 5]),
        ];
        let mut mesh = Mesh::new();
        mesh.add_body("b", MAT, &nodes, &elements).unwrap();
        let all = Geometries::of(&mesh, None).unwrap();
        assert!(all.check_invariants(&mesh));
        assert_eq!(all.len(), 3);
        let some = [ElementId::new(0), ElementId::new(2)];
        let part = Geometries::of(&mesh, Some(&some)).unwrap();
        assert!(part.check_invariants(&mesh));
        assert_eq!(part.len(), 2);
        assert_eq!(part.at(1).0, ElementId::new(2));
        assert!(part.get(ElementId::new(1)).is_none());
        for e in mesh.element_ids() {
            let g = part.or_compute(&mesh, e).unwrap();
            assert_eq!(Some(g.as_ref()), all.get(e));
            assert_eq!(matches!(g, Cow::Borrowed(_)), e.index() != 1);
        }
        // a node moved so that an element crosses itself: its error
        mesh.nodes_ref[4] = [-2.0, 1.0];
        assert!(matches!(
            mesh.geometry(ElementId::new(0)),
            Err(MeshError::InvalidElement { element: 0, .. })
        ));
        assert!(Geometries::of(&mesh, None).is_err());
        assert!(!part.check_invariants(&mesh));
    }
}
