//! The 3D pairs' slave nodes in the reference configuration
//! ([`crate::contact::reference`]): each node at its corner of the first
//! slave face that has it, paired with the master face it projects into
//! with the smallest `|g|`, whether the two face each other or not.

use crate::contact::KernelCounts;
use crate::contact::reference::ReferencePairing;
use crate::mesh::Mesh;
use crate::mesh::volume::dot;

use super::FaceLayout;
use super::nodal::FaceNodalError;

/// `v / |v|` (zero for a zero vector).
fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    if l > 0.0 { v.map(|c| c / l) } else { [0.0; 3] }
}

impl FaceLayout {
    /// Every slave node of pair `pair` (its index in the layout) that
    /// projects into a master face in the reference configuration (module
    /// docs), in the order the nodes first appear on its slave faces.
    pub fn reference_pairings(
        &self,
        mesh: &Mesh<3>,
        pair: usize,
    ) -> Result<Vec<ReferencePairing<3>>, FaceNodalError> {
        let u = vec![0.0; 3 * mesh.node_count()];
        let indexes = self.master_indexes(mesh, &u);
        let mut counts = KernelCounts::default();
        let mut out = Vec::new();
        for dof in self.multipliers.iter().filter(|m| m.pair.index() == pair) {
            let Some(probe) = self.corner_probe(dof) else {
                continue;
            };
            let found = self
                .find_master(mesh, &u, &probe, &indexes, &mut counts, false)
                .map_err(|(_, error)| FaceNodalError {
                    pair,
                    node: dof.node.index(),
                    error,
                })?;
            let Some((master, gap, xi_m)) = found else {
                continue;
            };
            let slave = Self::current_face(mesh, &u, &probe.slave);
            let master = Self::current_face(mesh, &u, &self.masters_of(dof.pair)[master.index()]);
            let n_s = unit(slave.normal_at(probe.xi_s));
            let n_m = unit(master.normal_at(xi_m));
            out.push(ReferencePairing {
                node: dof.node,
                gap,
                size: slave.size(),
                cos: dot(n_s, n_m),
                normals: [n_s, n_m],
            });
        }
        Ok(out)
    }
}
