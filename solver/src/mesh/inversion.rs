//! Elements inverted by a displacement field: the check of every Newton
//! iterate (an iterate that inverts an element is rejected and the step
//! cut back, so no converged state has one; see [`crate::newton`]).
//!
//! An element is inverted at the displacements `u` when its smallest
//! volume ratio over the integration points,
//! `det F = det(I + du/dX)` ([`crate::element::SolidElement::min_det_f`];
//! in 2D the in-plane `2 x 2`), is at most zero: the current element has
//! turned inside out or been flattened there. A material law may still
//! give such a state a finite energy (St Venant–Kirchhoff does), so the
//! residual alone does not reveal it.
//!
//! Invariant: the result does not depend on the number of threads (the
//! determinants are computed by [`crate::par::map`], the worst chosen
//! sequentially, the lowest index on a tie).

use super::{Geometries, Mesh, MeshError};

/// Elements per parallel chunk.
const PAR_MIN_LEN: usize = 256;

/// An element inverted at some displacements, as [`Mesh::most_inverted`]
/// finds it.
#[derive(Debug, Clone, PartialEq)]
pub struct InvertedElement {
    /// Global element index.
    pub element: usize,
    /// Its smallest `det F` over the integration points (`<= 0`).
    pub det_f: f64,
    /// The element as a user finds it ([`Mesh::element_label`]).
    pub label: String,
}

impl std::fmt::Display for InvertedElement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} is inverted (det F = {:.3e} at an integration point)",
            self.label, self.det_f
        )
    }
}

impl Geometries {
    /// The element of the set of smallest `det F <= 0` at the displacements
    /// `u` (module docs), or `None` when every element of the set keeps a
    /// positive volume (or a `det F` is NaN: a non-finite `u` is the
    /// residual's failure, not an inversion). Across MPI ranks each rank
    /// checks its own elements and the ranks' worst is taken
    /// (`crate::newton`).
    pub fn most_inverted<const D: usize>(
        &self,
        mesh: &Mesh<D>,
        u: &[f64],
    ) -> Option<InvertedElement> {
        let dets = crate::par::map(self.len(), PAR_MIN_LEN, |k| {
            let (e, g) = self.at(k);
            g.min_det_f(&mesh.element_displacements(e, u))
        });
        let (k, det_f) = dets
            .into_iter()
            .enumerate()
            .filter(|(_, d)| *d <= 0.0)
            .fold(None, |worst: Option<(usize, f64)>, (k, d)| match worst {
                Some((_, w)) if w <= d => worst,
                _ => Some((k, d)),
            })?;
        let element = self.at(k).0.index();
        Some(InvertedElement {
            element,
            det_f,
            label: mesh.element_label(element),
        })
    }
}

impl<const D: usize> Mesh<D> {
    /// The element of smallest `det F <= 0` at the displacements `u` over
    /// the whole mesh ([`Geometries::most_inverted`] of every element's
    /// geometry, computed here).
    pub fn most_inverted(&self, u: &[f64]) -> Result<Option<InvertedElement>, MeshError> {
        Ok(Geometries::of(self, None)?.most_inverted(self, u))
    }

    /// Element `element` as a user finds it: its global index, kind, body,
    /// nodes (by [`Mesh::node_number`]: mesh file tags or internal indices,
    /// and which) and reference centroid, e.g.
    /// ``element 3 (8-node hexahedron) of body `block`, nodes 4, 5, 8, 7,
    /// 13, 14, 17, 16 (internal), centroid (0.25, 0.25, 0.125)``.
    pub fn element_label(&self, element: usize) -> String {
        let el = &self.elements[element];
        let body = &self.bodies[self.element_body[element]].name;
        let mut numbering = None;
        let nodes: Vec<String> = el
            .iter()
            .map(|n| {
                let (number, kind) = self.node_number(n.index());
                numbering = Some(kind);
                number.to_string()
            })
            .collect();
        let mut centroid = [0.0; D];
        for n in el.iter() {
            for (c, x) in centroid.iter_mut().zip(self.node_ref(*n)) {
                *c += x / el.len() as f64;
            }
        }
        let centroid: Vec<String> = centroid.iter().map(|c| format!("{c}")).collect();
        format!(
            "element {element} ({}) of body `{body}`, nodes {} ({}), centroid ({})",
            el.kind(),
            nodes.join(", "),
            numbering.map_or("internal", |k| match k {
                super::NodeNumbering::MeshFile => "mesh file tags",
                super::NodeNumbering::Internal => "internal",
            }),
            centroid.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::element::Element;
    use crate::mesh::Mesh;
    use crate::mesh::tests::MAT;

    /// Two unit squares side by side; `u` pushes the shared edge's nodes
    /// by `dx` along x.
    fn two_squares(dx: f64) -> (Mesh, Vec<f64>) {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [2.0, 1.0],
        ];
        let elements = [Element::Quad4([0, 1, 4, 3]), Element::Quad4([1, 2, 5, 4])];
        let mut mesh = Mesh::new();
        mesh.push_body("pair", MAT, &nodes, &elements, None)
            .unwrap();
        let mut u = vec![0.0; 12];
        u[2] = dx;
        u[8] = dx;
        (mesh, u)
    }

    /// `det F` of the stretched element is `1 + dx`, of the squeezed one
    /// `1 - dx`: inverted exactly from `dx = 1` on, the squeezed one named.
    #[test]
    fn the_squeezed_element_inverts_when_its_edges_cross() {
        let (mesh, u) = two_squares(0.5);
        assert_eq!(mesh.most_inverted(&u).unwrap(), None);
        let (mesh, u) = two_squares(1.5);
        let inv = mesh.most_inverted(&u).unwrap().unwrap();
        assert_eq!(inv.element, 1);
        assert!((inv.det_f + 0.5).abs() < 1e-12, "{inv:?}");
        assert_eq!(
            inv.to_string(),
            "element 1 (4-node quadrilateral) of body `pair`, nodes 1, 2, 5, 4 (internal), \
             centroid (1.5, 0.5) is inverted (det F = -5.000e-1 at an integration point)"
        );
        // the reverse push inverts the other one
        let (mesh, u) = two_squares(-1.25);
        assert_eq!(mesh.most_inverted(&u).unwrap().unwrap().element, 0);
        // a non-finite field is not an inversion
        let (mesh, mut u) = two_squares(0.0);
        u[0] = f64::NAN;
        assert_eq!(mesh.most_inverted(&u).unwrap(), None);
    }
}
