//! The nodal contact table of a 2D state: contact results at the slave
//! **nodes** (the nodal contact pressure, the nodal gap and where the node
//! projects), what the 2D `contact.csv` and the contact point data of the
//! `.vtu` files are written from (`crate::report::ContactTable` for
//! `Dim<2>`; the 3D table is `crate::contact::face`'s `nodal.rs`).
//!
//! # Pressure
//!
//! The multipliers are nodal values of the linear field
//! `lambda(xi_s) = N1 l1 + N2 l2` on each slave segment, so the nodal
//! pressure is `p_a = -lambda_a` (positive in compression; the same formula
//! for persistent and unilateral pairs; an inactive unilateral node has
//! `p = 0`). With the reference tributary length `T_a` of a node (half the
//! reference length of each slave segment of the pair it belongs to),
//! `sum_a p_a T_a` is the integral of the pressure over the slave face in
//! the reference configuration, `integral N_a dGamma0 = T_a` exactly for
//! every Gauss rule: the resultant the contact pair transmits along its
//! normal when the face is straight.
//!
//! # Gap
//!
//! The node itself (not an integration point) is projected onto the
//! master face in the current configuration with the pair's formulation,
//! the complete projection of [`crate::contact::ContactLayout::project_all`]: every
//! master segment of the pair is tried, those the node projects into
//! (`|xi_m| <= 1 +` [`crate::contact::XI_INSIDE_TOL`]) are kept, and the one with
//! the smallest `|g|` wins (the first on a tie, in master order). Where the
//! node projects into none, the segment its projection misses by the least
//! is taken if that is within [`crate::contact::XI_STUCK_BAND`] (`1 < |xi_m| <= 1 +`
//! band): a node at the very end of the master face, such as a node on a
//! symmetry line where both faces end, whose slave-normal projection lands
//! a hair beyond the master's last node, or a node in the shadow of a
//! convex master corner. A master segment the kernel rejects for a reason
//! of its own (degenerate or folded master, no projection, projection out
//! of reach or diverged: what pairing, `search.rs`, also treats as
//! "not this segment") is skipped; a node with no projection has no gap,
//! `xi_m` or master segment (`None`; empty fields in `contact.csv`), never
//! NaN. A failure no master segment can cure (contact's `slave_side`
//! errors: a degenerate or folded slave segment, non-finite coordinates, a
//! formulation whose coordinate count is not the two-node pair's, one not
//! compiled in) is a [`NodalContactError`], never a missing projection.
//!
//! The kernels take a slave **segment** and `xi_s`. A slave node belongs to
//! one or two slave segments of the pair; its gap is evaluated on the
//! segment that **starts** at the node (`xi_s = -1`) and, for the last node
//! of an open slave face, on the segment that ends there (`xi_s = +1`).
//! The point `x_s` is the node in both cases, so a `closest-point` gap does
//! not depend on the choice; a `slave-normal` gap uses that segment's
//! normal (the normal the slave face has just after the node, walking
//! counter-clockwise around the slave body). At a node between two slave
//! segments that meet at an angle the two readings differ to first order
//! in the angle times the gap, so the gap of a closed node (`g = 0`) is the
//! same either way.
//!
//! Cost: on a master face of [`crate::contact::INDEX_MIN_SEGMENTS`]
//! segments or more (and a formulation whose gap is a distance), the
//! smallest `|g|` is found through the spatial index of the master face in
//! the state's configuration (`master_search.rs`, which proves the
//! same choice, ties included): `O(log n_master)` projections per node
//! that projects into a segment. A node the index cannot decide (one that
//! projects into no candidate, which includes every node of the band's
//! fallback) is projected onto every master segment as on a short face,
//! `O(n_master)`.
//!
//! Invariants: rows come pair by pair in model order and, within a pair,
//! in slave-face order (the multiplier order of
//! [`crate::contact::ContactLayout`]); every value is finite.

use std::cell::OnceCell;
use std::collections::HashMap;

use contact_kernels::{Formulation, KernelError, PAIR_COORDS};

use crate::contact::face_index::QueryStats;
use crate::contact::report::MultiplierDofInfo;
use crate::contact::{XI_INSIDE_TOL, XI_STUCK_BAND, slave_side};
use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::model::ContactPair;

use super::master_search::{INDEX_MIN_SEGMENTS, MasterIndex, Tried, gap_is_distance};

/// A slave node the kernels cannot project for a reason no master segment
/// avoids (see the module docs): the nodal table of that state does not
/// exist.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "contact pair `{pair}`: slave node {node} (on slave segment {slave_segment}, xi_s = {xi_s}) \
     cannot be projected onto master segment {master_segment}: {error}"
)]
pub struct NodalContactError {
    /// The contact pair's name.
    pub pair: String,
    /// The global node.
    pub node: usize,
    /// The slave segment the node was evaluated on (index within the
    /// pair's slave face).
    pub slave_segment: usize,
    /// The node's parametric coordinate on it (`-1` or `1`).
    pub xi_s: f64,
    /// The master segment tried (index within the pair's master face).
    pub master_segment: usize,
    /// The kernel's error.
    pub error: KernelError,
}

/// Where a slave node projects on the master face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodalProjection {
    /// The gap `g = n . (x_m(xi_m) - x_s)` (negative when penetrating).
    pub gap: f64,
    /// The projection coordinate on the master segment.
    pub xi_m: f64,
    /// The master segment (index within the pair's master face).
    pub master_segment: usize,
    /// That segment's global nodes.
    pub master_nodes: [usize; 2],
}

/// One slave node of one contact pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodalContactRow {
    /// The contact pair (index into the solved pairs,
    /// `crate::solution::Solution::contact_pairs`).
    pub pair: usize,
    /// The global node.
    pub node: usize,
    /// Its current coordinates (reference plus displacement).
    pub position: [f64; 2],
    /// The contact pressure `p = -lambda` (positive in compression).
    pub pressure: f64,
    /// Half the reference length of each slave segment of the pair the
    /// node belongs to (so that `sum p T` integrates the pressure).
    pub tributary_length: f64,
    /// The slave segment the gap is evaluated on (index within the pair's
    /// slave face; see the module docs).
    pub slave_segment: usize,
    /// The node's parametric coordinate on that segment (`-1` or `1`).
    pub xi_s: f64,
    /// The projection, `None` when the node projects into no master
    /// segment.
    pub projection: Option<NodalProjection>,
}

/// A solved 2D state as the nodal table reads it: the mesh, the pairs
/// with the formulation each was solved with, the multiplier dofs, and the
/// state's displacements and multipliers (in multiplier-dof order).
#[derive(Debug, Clone, Copy)]
pub struct NodalState<'a> {
    /// The mesh.
    pub mesh: &'a Mesh<2>,
    /// The contact pairs.
    pub pairs: &'a [ContactPair<2>],
    /// Each pair's formulation.
    pub formulations: &'a [Formulation],
    /// The pair and slave node of every multiplier.
    pub multiplier_dofs: &'a [MultiplierDofInfo],
    /// Nodal displacements.
    pub displacements: &'a [[f64; 2]],
    /// The multipliers.
    pub multipliers: &'a [f64],
}

/// The nodal contact table of `state`: one row per slave node and pair
/// (see the module docs); an error for the first node the kernels cannot
/// project onto any master segment.
pub fn nodal_contact(state: &NodalState) -> Result<Vec<NodalContactRow>, NodalContactError> {
    nodal_contact_with(state, INDEX_MIN_SEGMENTS)
}

/// [`nodal_contact`], searching master faces of at least
/// `index_min_segments` segments through the spatial index (the rows are
/// the same for every value; the tests compare them).
fn nodal_contact_with(
    state: &NodalState,
    index_min_segments: usize,
) -> Result<Vec<NodalContactRow>, NodalContactError> {
    let mesh = state.mesh;
    let current = |n: usize| {
        let (x, d) = (mesh.nodes_ref[n], state.displacements[n]);
        [x[0] + d[0], x[1] + d[1]]
    };
    // one multiplier per (pair, slave node)
    let lambdas: HashMap<(usize, usize), f64> = state
        .multiplier_dofs
        .iter()
        .zip(state.multipliers)
        .map(|(m, &l)| ((m.pair, m.node), l))
        .collect();
    let mut rows = Vec::new();
    for (p, pair) in state.pairs.iter().enumerate() {
        // the segments as plain node indices
        let raw = |f: &[[NodeId; 2]]| -> Vec<[usize; 2]> {
            f.iter().map(|s| s.map(NodeId::index)).collect()
        };
        let (slave_segs, master_segs) = (raw(&pair.slave), raw(&pair.master));
        let formulation = state.formulations[p];
        // the master face's index in this state, built for the first node
        // that needs it (`None`: every node scans)
        let index: OnceCell<Option<MasterIndex>> = OnceCell::new();
        let build_index = || {
            if master_segs.len() < index_min_segments || !gap_is_distance(formulation) {
                return None;
            }
            let segments: Vec<[[f64; 2]; 2]> =
                master_segs.iter().map(|seg| seg.map(current)).collect();
            MasterIndex::build(&segments)
        };
        // slave nodes in first-seen order, as the multipliers are laid out
        let mut nodes: Vec<usize> = Vec::new();
        for seg in &slave_segs {
            for &n in seg {
                if !nodes.contains(&n) {
                    nodes.push(n);
                }
            }
        }
        for node in nodes {
            let (slave_segment, xi_s) = slave_segs
                .iter()
                .position(|s| s[0] == node)
                .map(|s| (s, -1.0))
                .or_else(|| {
                    slave_segs
                        .iter()
                        .position(|s| s[1] == node)
                        .map(|s| (s, 1.0))
                })
                .expect("the node was taken from the pair's slave segments");
            let tributary_length = slave_segs
                .iter()
                .filter(|s| s.contains(&node))
                .map(|s| {
                    let (a, b) = (mesh.nodes_ref[s[0]], mesh.nodes_ref[s[1]]);
                    (b[0] - a[0]).hypot(b[1] - a[1]) / 2.0
                })
                .sum();
            let lambda = lambdas.get(&(p, node)).copied().unwrap_or(0.0);
            let slave = slave_segs[slave_segment];
            let project = |m: usize| {
                let master = master_segs[m];
                let nodes = [slave[0], slave[1], master[0], master[1]];
                let q: [f64; PAIR_COORDS] = std::array::from_fn(|k| current(nodes[k / 2])[k % 2]);
                contact_kernels::project(formulation, &q, xi_s)
            };
            if let Some(index) = index.get_or_init(build_index) {
                let chosen = index.nearest_inside(
                    slave.map(current),
                    xi_s,
                    &mut QueryStats::default(),
                    |m| match project(m) {
                        Ok(pr) if pr.xi_m.abs() - 1.0 <= XI_INSIDE_TOL => Tried::Inside {
                            abs_gap: pr.gap.abs(),
                            value: NodalProjection {
                                gap: pr.gap,
                                xi_m: pr.xi_m,
                                master_segment: m,
                                master_nodes: master_segs[m],
                            },
                        },
                        Ok(_) => Tried::Elsewhere,
                        Err(error) if slave_side(&error) => Tried::Unsure,
                        Err(_) => Tried::Elsewhere,
                    },
                );
                if let Some((_, projection)) = chosen {
                    rows.push(NodalContactRow {
                        pair: p,
                        node,
                        position: current(node),
                        pressure: -lambda,
                        tributary_length,
                        slave_segment,
                        xi_s,
                        projection: Some(projection),
                    });
                    continue;
                }
            }
            // (projection, how far it misses the segment) on every master
            // segment the kernel accepts
            let mut candidates: Vec<(NodalProjection, f64)> = Vec::new();
            for (m, master) in master_segs.iter().enumerate() {
                let pr = match project(m) {
                    Ok(pr) => pr,
                    Err(error) if slave_side(&error) => {
                        return Err(NodalContactError {
                            pair: pair.name.clone(),
                            node,
                            slave_segment,
                            xi_s,
                            master_segment: m,
                            error,
                        });
                    }
                    // this master segment's own problem: not a candidate
                    Err(_) => continue,
                };
                let projection = NodalProjection {
                    gap: pr.gap,
                    xi_m: pr.xi_m,
                    master_segment: m,
                    master_nodes: *master,
                };
                candidates.push((projection, pr.xi_m.abs() - 1.0));
            }
            let mut best: Option<NodalProjection> = None;
            for (pr, _) in candidates.iter().filter(|(_, miss)| *miss <= XI_INSIDE_TOL) {
                if best.is_none_or(|b| pr.gap.abs() < b.gap.abs()) {
                    best = Some(*pr);
                }
            }
            if best.is_none() {
                let mut nearest: Option<(NodalProjection, f64)> = None;
                for &(pr, miss) in candidates.iter().filter(|(_, miss)| *miss <= XI_STUCK_BAND) {
                    if nearest.is_none_or(|(_, m)| miss < m) {
                        nearest = Some((pr, miss));
                    }
                }
                best = nearest.map(|(pr, _)| pr);
            }
            rows.push(NodalContactRow {
                pair: p,
                node,
                position: current(node),
                pressure: -lambda,
                tributary_length,
                slave_segment,
                xi_s,
                projection: best,
            });
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solution::{Solution, State};
    use crate::{Scene, SolveOptions, solve};

    /// `state` of `sol` as the table reads it.
    fn read<'a>(sol: &'a Solution, state: &'a State) -> NodalState<'a> {
        NodalState {
            mesh: &sol.mesh,
            pairs: &sol.contact_pairs,
            formulations: &sol.formulations,
            multiplier_dofs: &sol.multiplier_dofs,
            displacements: &state.displacements,
            multipliers: &state.multipliers,
        }
    }

    const PRESSED_BLOCKS: &str = include_str!("../../../../scenes/pressed-blocks.toml");

    /// The total load on the block of `scenes/pressed-blocks.toml`.
    const LOAD: f64 = 1.0;

    fn pressed_blocks(formulation: Formulation) -> Solution {
        let scene = Scene::from_toml_str(PRESSED_BLOCKS, "pressed-blocks.toml").unwrap();
        let options = SolveOptions {
            formulation: Some(formulation),
            ..SolveOptions::from_scene(&scene)
        };
        solve(&scene, &options).unwrap()
    }

    /// The block's five bottom nodes, in slave-face order (left to right:
    /// the bottom side runs counter-clockwise around the block); their
    /// pressure integrates to the load; they are closed (gap 0) and
    /// project into the base's two top segments.
    ///
    /// Tolerances: the scene's solution is homogeneous (see the scene
    /// file), so the only error is Newton's. Converged means
    /// `|r| <= 1e-10 max(1, |f_ext|)` (here `|f_ext| < 1`); the block's
    /// y-equilibrium is one combination of at most 5 residual components
    /// of unit weight, so `|sum p T - F| <= sqrt(5) 1e-10 < 1e-9`. The
    /// weighted gaps are residual components too (`<= 1e-10`), and a nodal
    /// gap is at most the inverse of the smallest eigenvalue of the
    /// segments' mass matrix (`T/6 >= 1/48` for these segments) times
    /// that, `< 1e-8`.
    #[test]
    fn pressure_balances_the_load_and_closed_gaps_vanish() {
        for formulation in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
            let sol = pressed_blocks(formulation);
            let rows = nodal_contact(&read(&sol, &sol.final_state)).unwrap();
            assert_eq!(rows.len(), 5);
            assert_eq!(sol.contact_pairs[0].name, "interface");
            let total: f64 = rows.iter().map(|r| r.pressure * r.tributary_length).sum();
            assert!((total - LOAD).abs() < 1e-9, "{formulation}: {total}");
            let lengths: Vec<f64> = rows.iter().map(|r| r.tributary_length).collect();
            assert_eq!(lengths, [0.125, 0.25, 0.25, 0.25, 0.125]);
            let mut last_x = f64::NEG_INFINITY;
            for (k, r) in rows.iter().enumerate() {
                assert_eq!(r.pair, 0);
                // uniform pressure F / width (the patch test passes exactly)
                assert!((r.pressure - LOAD).abs() < 1e-8, "{r:?}");
                let pr = r.projection.expect("every node projects");
                assert!(pr.gap.abs() < 1e-8, "{r:?}");
                assert!(pr.xi_m.abs() <= 1.0 + XI_INSIDE_TOL);
                assert_eq!(
                    pr.master_nodes,
                    sol.contact_pairs[0].master[pr.master_segment].map(NodeId::index)
                );
                // the nodes' current positions: left to right on y < 0.5
                let reference = sol.mesh.nodes_ref[r.node];
                let d = sol.final_state.displacements[r.node];
                assert_eq!(r.position, [reference[0] + d[0], reference[1] + d[1]]);
                assert!(r.position[0] > last_x && r.position[1] < 0.5, "{r:?}");
                last_x = r.position[0];
                // the segment starting at the node, the last ending there
                let expected = if k < 4 { (k, -1.0) } else { (3, 1.0) };
                assert_eq!((r.slave_segment, r.xi_s), expected);
                // the base's top runs right to left: the left half is its
                // second segment
                let left = reference[0] < 0.5;
                if k != 2 {
                    assert_eq!(pr.master_segment, usize::from(left), "{r:?}");
                }
            }
        }
    }

    /// Moves `node` of `sol`'s final state onto `onto`'s current position.
    fn collapse(sol: &mut Solution, node: usize, onto: usize) {
        let (x, d) = (&sol.mesh.nodes_ref, &mut sol.final_state.displacements);
        let target = [x[onto][0] + d[onto][0], x[onto][1] + d[onto][1]];
        d[node] = [target[0] - x[node][0], target[1] - x[node][1]];
    }

    /// A slave segment collapsed to a point: no master segment can cure
    /// it, so the table is an error naming the pair, node and segments
    /// (before, the node silently had no projection).
    #[test]
    fn a_collapsed_slave_segment_is_an_error() {
        let mut sol = pressed_blocks(Formulation::SlaveNormal);
        let [a, b] = sol.contact_pairs[0].slave[1].map(NodeId::index);
        collapse(&mut sol, a, b);
        let e = nodal_contact(&read(&sol, &sol.final_state)).unwrap_err();
        assert_eq!(
            (e.pair.as_str(), e.node, e.slave_segment, e.master_segment),
            ("interface", a, 1, 0)
        );
        assert!(matches!(
            e.error,
            contact_kernels::KernelError::DegenerateSegment {
                segment: contact_kernels::Segment::Slave,
                ..
            }
        ));
        let msg = e.to_string();
        assert!(
            msg.contains("contact pair `interface`") && msg.contains("degenerate slave segment"),
            "{msg}"
        );
        let vtu = crate::report::vtu_string(&sol, &sol.final_state).unwrap_err();
        assert_eq!(vtu, e.into());
    }

    /// A master segment collapsed to a point is that segment's problem
    /// only: the table exists, and no node projects onto it.
    #[test]
    fn a_collapsed_master_segment_is_skipped() {
        let mut sol = pressed_blocks(Formulation::SlaveNormal);
        let [a, b] = sol.contact_pairs[0].master[0].map(NodeId::index);
        collapse(&mut sol, a, b);
        let rows = nodal_contact(&read(&sol, &sol.final_state)).unwrap();
        assert_eq!(rows.len(), 5);
        assert!(
            rows.iter()
                .filter_map(|r| r.projection)
                .all(|p| p.master_segment == 1)
        );
        assert!(rows.iter().any(|r| r.projection.is_some()));
    }

    #[test]
    fn a_node_beyond_the_master_face_has_no_projection() {
        let mut sol = pressed_blocks(Formulation::SlaveNormal);
        // keep the base's right half only (its first top segment)
        sol.contact_pairs[0].master.truncate(1);
        let rows = nodal_contact(&read(&sol, &sol.final_state)).unwrap();
        let paired: Vec<bool> = rows.iter().map(|r| r.projection.is_some()).collect();
        assert_eq!(paired, [false, false, true, true, true]);
        // the pressure is the solution's, whatever the projection
        assert!(rows.iter().all(|r| (r.pressure - LOAD).abs() < 1e-8));
    }

    /// The coarse Hertz scene (a curved slave face): the pressure's
    /// integral over the reference face is the normal force, whose vertical
    /// components carry the load `P/2`, so `P/2 <= sum p T <= P/2 / cos
    /// theta` with `theta` the largest angle of a pressed slave segment to
    /// the horizontal (here `a / R`, about 0.1, so the bound is 0.5 %); the
    /// node on the symmetry line, where both faces end, has a projection
    /// (within the band); the nodes off the contact zone have no pressure.
    #[test]
    fn hertz_pressure_carries_the_load() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/hertz-coarse.toml");
        let scene = Scene::from_file(path).unwrap();
        let model = scene.build_model::<2>().unwrap();
        let load: f64 = -model
            .loads
            .iter()
            .filter(|l| l.dof.component() == 1)
            .map(|l| l.value)
            .sum::<f64>();
        assert!((load - 4.315).abs() < 1e-9, "{load}");
        let sol = solve(&scene, &SolveOptions::from_scene(&scene)).unwrap();
        let rows = nodal_contact(&read(&sol, &sol.final_state)).unwrap();
        let total: f64 = rows.iter().map(|r| r.pressure * r.tributary_length).sum();
        let mut cos_min: f64 = 1.0;
        for r in rows.iter().filter(|r| r.pressure > 0.0) {
            let s = sol.contact_pairs[0].slave[r.slave_segment].map(NodeId::index);
            let [a, b] = s.map(|n| {
                let (x, d) = (sol.mesh.nodes_ref[n], sol.final_state.displacements[n]);
                [x[0] + d[0], x[1] + d[1]]
            });
            cos_min = cos_min.min((b[0] - a[0]).abs() / (b[0] - a[0]).hypot(b[1] - a[1]));
        }
        assert!(cos_min > 0.99, "{cos_min}");
        assert!(
            total >= load * (1.0 - 1e-9) && total <= load / cos_min * (1.0 + 1e-9),
            "{total} against {load} (cos {cos_min})"
        );
        let symmetry = rows
            .iter()
            .find(|r| r.position[0] == 0.0)
            .expect("a node at x = 0");
        let pr = symmetry.projection.expect("the symmetry node projects");
        assert!(pr.xi_m.abs() <= 1.0 + XI_STUCK_BAND, "{pr:?}");
        assert!(symmetry.pressure > 0.0);
        assert!(
            rows.iter()
                .any(|r| r.pressure == 0.0 && r.projection.is_none())
        );
    }

    /// The index-driven table against the table that projects every node
    /// onto every master segment, on the sliding and ironing scenes'
    /// solutions (32 and 100 master segments) and on many seeded random
    /// states around them: the block or punch shifted along the strip
    /// and lifted or pressed in, every node jittered. Rows (and errors)
    /// are equal, and the comparison covers nodes in and out of contact.
    #[test]
    fn the_index_gives_the_scanned_table() {
        let mut rng = crate::testutil::Lcg::new(31);
        let (mut paired, mut unpaired) = (0, 0);
        for (scene, steps) in [("sliding.toml", 10), ("ironing.toml", 20)] {
            let path = format!("{}/../scenes/{scene}", env!("CARGO_MANIFEST_DIR"));
            let scene = Scene::from_file(&path).unwrap();
            for formulation in [Formulation::SlaveNormal, Formulation::ClosestPoint] {
                let options = SolveOptions {
                    formulation: Some(formulation),
                    steps,
                    ..SolveOptions::from_scene(&scene)
                };
                let sol = solve::<2>(&scene, &options).unwrap();
                let pair = &sol.contact_pairs[0];
                let slave: Vec<usize> = pair.slave.iter().flatten().map(|n| n.index()).collect();
                for trial in 0..40 {
                    let mut state = sol.final_state.clone();
                    if trial > 0 {
                        let shift = [rng.uniform(-4.0, 4.0), rng.uniform(-0.3, 0.15)];
                        for (n, d) in state.displacements.iter_mut().enumerate() {
                            let jitter = [rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01)];
                            let s = if slave.contains(&n) { shift } else { [0.0; 2] };
                            d[0] += s[0] + jitter[0];
                            d[1] += s[1] + jitter[1];
                        }
                    }
                    let scanned = nodal_contact_with(&read(&sol, &state), usize::MAX);
                    let indexed = nodal_contact_with(&read(&sol, &state), 0);
                    assert_eq!(indexed, scanned, "{path} {formulation} trial {trial}");
                    for r in scanned.unwrap() {
                        if r.projection.is_some() {
                            paired += 1;
                        } else {
                            unpaired += 1;
                        }
                    }
                }
            }
        }
        assert!(
            paired > 1000 && unpaired > 100,
            "{paired} paired, {unpaired} not"
        );
    }

    #[test]
    fn the_vtu_file_carries_the_table() {
        let sol = pressed_blocks(Formulation::SlaveNormal);
        let vtu = crate::report::vtu_string(&sol, &sol.final_state).unwrap();
        let field = |name: &str| -> Vec<f64> {
            let start = vtu
                .find(&format!("Name=\"{name}\""))
                .unwrap_or_else(|| panic!("no {name}"));
            let body = &vtu[start..];
            let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
            body.split_whitespace()
                .map(|v| v.parse().unwrap())
                .collect()
        };
        let n = sol.mesh.node_count();
        let (slave, paired, gap, pressure) = (
            field("contact_slave"),
            field("contact_paired"),
            field("contact_gap"),
            field("contact_pressure"),
        );
        assert_eq!([slave.len(), paired.len(), gap.len()], [n, n, n]);
        let rows = nodal_contact(&read(&sol, &sol.final_state)).unwrap();
        for node in 0..n {
            let row = rows.iter().find(|r| r.node == node);
            assert_eq!(slave[node], f64::from(u8::from(row.is_some())));
            assert_eq!(paired[node], slave[node]);
            match row {
                Some(r) => {
                    assert_eq!(gap[node], r.projection.unwrap().gap);
                    assert_eq!(pressure[node], r.pressure);
                }
                None => assert_eq!([gap[node], pressure[node]], [0.0, 0.0]),
            }
        }
    }
}
