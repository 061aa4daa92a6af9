//! Configurations of 3D face pairs (tri3 and quad4 faces, 3 coordinates a
//! node, `xi_s = (u, v)`), for formulations declared
//! `inputs!(dim 3; slave nodes; master nodes; xi_s: 2)`.
//!
//! A configuration is built in a local frame: the slave face near the
//! plane `z = 0` with its outward normal `+z` (nodes counter-clockwise seen
//! from above), the master face facing it (its nodes clockwise seen from
//! above: outward normal `-z`) at height `gap` (negative: penetration),
//! shifted and turned about `z`; then the whole configuration is rotated
//! and translated. Node jitter keeps every face well shaped (no face
//! degenerates or folds). [`faces`] gives, per pair of kinds:
//!
//! | family | configurations |
//! |---|---|
//! | `worked` | the worked example of docs/conventions.md for the pair (its slave and master faces) |
//! | `random` | 60: sizes 0.5–2, jitter 0.15, gap -0.3..0.6, master shifted ±0.3 and turned about `z`, any rotation, offset in [-10, 10]³ |
//! | `rotated` | 20: one configuration under 20 random rotations |
//! | `warped` | 20 with quad4 nodes out of plane by up to 0.3 face sizes (non-planar faces) |
//! | `edges` | 20: the slave point on its face's edges and corners, the master shifted so that the projection lands near its edges and corners |
//! | `far` | 20 offset by ~1e6 from the origin |
//! | `scale` | 20 scaled by 1e-6 and by 1e6 |
//! | `steep` | 20 with the master tilted 60–85° about an in-plane axis |
//! | `penetration` | 10 with the master below the slave (gap -0.5..-1e-3) |

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::{Config, seeded};

/// A face kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceKind {
    /// The linear triangle: 3 nodes, `N = (1 - u - v, u, v)`.
    Tri3,
    /// The bilinear quadrilateral: 4 nodes on `[-1, 1]^2`.
    Quad4,
}

impl FaceKind {
    /// The node count.
    pub fn nodes(self) -> usize {
        match self {
            FaceKind::Tri3 => 3,
            FaceKind::Quad4 => 4,
        }
    }

    /// The kind of `nodes` nodes (3 or 4).
    pub fn of_nodes(nodes: usize) -> Option<FaceKind> {
        match nodes {
            3 => Some(FaceKind::Tri3),
            4 => Some(FaceKind::Quad4),
            _ => None,
        }
    }

    /// The reference nodes `(u, v)` of the face, counter-clockwise.
    fn corners(self) -> &'static [[f64; 2]] {
        match self {
            FaceKind::Tri3 => &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
            FaceKind::Quad4 => &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
        }
    }

    /// The centre of the parameter domain.
    fn centre(self) -> [f64; 2] {
        match self {
            FaceKind::Tri3 => [1.0 / 3.0, 1.0 / 3.0],
            FaceKind::Quad4 => [0.0, 0.0],
        }
    }

    /// A point `(u, v)` drawn inside the face, `margin` away from its edges
    /// in parameter units.
    fn inside(self, rng: &mut ChaCha8Rng, margin: f64) -> [f64; 2] {
        match self {
            FaceKind::Tri3 => loop {
                let (u, v) = (rng.random::<f64>(), rng.random::<f64>());
                if u >= margin && v >= margin && u + v <= 1.0 - margin {
                    return [u, v];
                }
            },
            FaceKind::Quad4 => {
                let m = 1.0 - margin;
                [rng.random_range(-m..=m), rng.random_range(-m..=m)]
            }
        }
    }

    /// The face's corners and edge midpoints in parameters (exactly on its
    /// boundary).
    fn boundary(self) -> Vec<[f64; 2]> {
        match self {
            FaceKind::Tri3 => vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [0.5, 0.0],
                [0.5, 0.5],
                [0.0, 0.5],
            ],
            FaceKind::Quad4 => vec![
                [-1.0, -1.0],
                [1.0, -1.0],
                [1.0, 1.0],
                [-1.0, 1.0],
                [0.0, -1.0],
                [1.0, 0.0],
                [0.0, 1.0],
                [-1.0, 0.0],
            ],
        }
    }
}

/// The shape functions of `kind` at `(u, v)`.
pub fn shape(kind: FaceKind, [u, v]: [f64; 2]) -> Vec<f64> {
    match kind {
        FaceKind::Tri3 => vec![1.0 - u - v, u, v],
        FaceKind::Quad4 => vec![
            0.25 * (1.0 - u) * (1.0 - v),
            0.25 * (1.0 + u) * (1.0 - v),
            0.25 * (1.0 + u) * (1.0 + v),
            0.25 * (1.0 - u) * (1.0 + v),
        ],
    }
}

/// The point of a face (`nodes`, 3 coordinates each) at `(u, v)`.
pub fn point(kind: FaceKind, nodes: &[[f64; 3]], xi: [f64; 2]) -> [f64; 3] {
    let n = shape(kind, xi);
    std::array::from_fn(|k| nodes.iter().zip(&n).map(|(p, w)| w * p[k]).sum())
}

/// A face in the local frame: `size` across, its nodes jittered by up to
/// `jitter` (in face sizes) in the plane and `warp` out of it, centred on
/// the origin, counter-clockwise seen from `+z` (`facing_down`: clockwise,
/// the master's orientation).
fn local_face(
    rng: &mut ChaCha8Rng,
    kind: FaceKind,
    size: f64,
    jitter: f64,
    warp: f64,
    facing_down: bool,
) -> Vec<[f64; 3]> {
    let c = kind.centre();
    let scale = match kind {
        FaceKind::Tri3 => size,
        FaceKind::Quad4 => 0.5 * size,
    };
    let mut nodes: Vec<[f64; 3]> = kind
        .corners()
        .iter()
        .map(|&[u, v]| {
            let mut p = [(u - c[0]) * scale, (v - c[1]) * scale, 0.0];
            p[0] += rng.random_range(-jitter..=jitter) * size;
            p[1] += rng.random_range(-jitter..=jitter) * size;
            p[2] += rng.random_range(-warp..=warp) * size;
            p
        })
        .collect();
    if facing_down {
        // Mirror y: clockwise seen from above, outward normal -z.
        for p in &mut nodes {
            p[1] = -p[1];
        }
    }
    nodes
}

/// A rotation matrix from three angles (z, y, z Euler angles).
fn rotation(a: f64, b: f64, c: f64) -> [[f64; 3]; 3] {
    let rz = |t: f64| {
        let (s, co) = t.sin_cos();
        [[co, -s, 0.0], [s, co, 0.0], [0.0, 0.0, 1.0]]
    };
    let ry = |t: f64| {
        let (s, co) = t.sin_cos();
        [[co, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, co]]
    };
    mul(mul(rz(a), ry(b)), rz(c))
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn apply(r: [[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| r[i][k] * p[k]).sum())
}

/// A random rotation.
fn random_rotation(rng: &mut ChaCha8Rng) -> [[f64; 3]; 3] {
    let tau = std::f64::consts::TAU;
    rotation(
        rng.random_range(0.0..tau),
        rng.random::<f64>().mul_add(2.0, -1.0).acos(),
        rng.random_range(0.0..tau),
    )
}

/// One configuration in the local frame: slave and master nodes.
struct Pair {
    slave: Vec<[f64; 3]>,
    master: Vec<[f64; 3]>,
}

impl Pair {
    /// A pair of kinds `(s, m)`: sizes drawn in `0.5..2`, the master at
    /// height `gap`, shifted by `shift` and turned by `turn` about `z`,
    /// tilted by `tilt` about the x axis.
    #[allow(clippy::too_many_arguments)]
    fn build(
        rng: &mut ChaCha8Rng,
        s: FaceKind,
        m: FaceKind,
        gap: f64,
        shift: [f64; 2],
        turn: f64,
        tilt: f64,
        warp: f64,
    ) -> Pair {
        let (ss, ms) = (rng.random_range(0.5..2.0), rng.random_range(0.5..2.0));
        let slave = local_face(
            rng,
            s,
            ss,
            0.15,
            if s == FaceKind::Quad4 { warp } else { 0.0 },
            false,
        );
        let master = local_face(
            rng,
            m,
            ms,
            0.15,
            if m == FaceKind::Quad4 { warp } else { 0.0 },
            true,
        );
        let r = mul(
            rotation(turn, 0.0, 0.0),
            rotation(
                0.5 * std::f64::consts::PI,
                tilt,
                -0.5 * std::f64::consts::PI,
            ),
        );
        let master = master
            .into_iter()
            .map(|p| {
                let p = apply(r, p);
                [p[0] + shift[0], p[1] + shift[1], p[2] + gap]
            })
            .collect();
        Pair { slave, master }
    }

    /// `q` after the rotation `r`, scaled by `scale` and moved by `offset`.
    fn q(&self, r: [[f64; 3]; 3], scale: f64, offset: [f64; 3]) -> Vec<f64> {
        self.slave
            .iter()
            .chain(&self.master)
            .flat_map(|&p| {
                let p = apply(r, p);
                [0, 1, 2].map(|k| p[k] * scale + offset[k])
            })
            .collect()
    }
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn config(label: String, q: Vec<f64>, xi_s: [f64; 2]) -> Config {
    Config {
        label,
        q,
        params: xi_s.to_vec(),
    }
}

/// The worked examples' faces (docs/conventions.md, "3D faces").
fn worked_face(kind: FaceKind, master: bool) -> Vec<f64> {
    match (kind, master) {
        (FaceKind::Quad4, false) => {
            vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.1, 1.0, 1.0, 1.0, 1.0, 0.0, 0.9]
        }
        (FaceKind::Quad4, true) => vec![
            -0.2, -0.1, 0.8, 1.2, 0.0, 0.85, 1.1, 1.3, 0.75, -0.1, 1.2, 0.8,
        ],
        (FaceKind::Tri3, false) => vec![0.0, 0.0, 1.0, 0.1, 1.0, 1.05, 1.0, 0.1, 0.95],
        (FaceKind::Tri3, true) => vec![-0.3, -0.2, 0.8, 1.4, 0.1, 0.85, 0.2, 1.5, 0.75],
    }
}

/// The worked example's slave point on a face of `kind`.
fn worked_xi(kind: FaceKind) -> [f64; 2] {
    match kind {
        FaceKind::Quad4 => [0.2, -0.1],
        FaceKind::Tri3 => [0.3, 0.25],
    }
}

/// Every family for a slave face of kind `s` on a master face of kind `m`
/// (module docs), in a fixed order.
pub fn faces(s: FaceKind, m: FaceKind) -> Vec<Config> {
    let mut out = Vec::new();
    let mut q = worked_face(s, false);
    q.extend(worked_face(m, true));
    out.push(config("worked".into(), q, worked_xi(s)));
    let seed = 0x3d00_0000 + 16 * s.nodes() as u64 + m.nodes() as u64;
    let mut rng = seeded(seed);
    let tau = std::f64::consts::TAU;
    let random_pair = |rng: &mut ChaCha8Rng, gap: f64, tilt: f64, warp: f64| {
        let shift = [rng.random_range(-0.3..0.3), rng.random_range(-0.3..0.3)];
        let turn = rng.random_range(0.0..tau);
        Pair::build(rng, s, m, gap, shift, turn, tilt, warp)
    };
    for k in 0..60 {
        let gap = rng.random_range(-0.3..0.6);
        let p = random_pair(&mut rng, gap, 0.0, 0.05);
        let r = random_rotation(&mut rng);
        let offset = [0, 1, 2].map(|_| rng.random_range(-10.0..10.0));
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(format!("random #{k}"), p.q(r, 1.0, offset), xi));
    }
    let p = random_pair(&mut rng, 0.2, 0.0, 0.05);
    for k in 0..20 {
        let r = random_rotation(&mut rng);
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(format!("rotated #{k}"), p.q(r, 1.0, [0.0; 3]), xi));
    }
    for k in 0..20 {
        let p = random_pair(&mut rng, 0.3, 0.0, 0.3);
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(
            format!("warped #{k}"),
            p.q(IDENTITY, 1.0, [0.0; 3]),
            xi,
        ));
    }
    let boundary = s.boundary();
    for k in 0..20 {
        // The master shifted by most of its size: projections near its
        // edges and corners.
        let gap = rng.random_range(0.05..0.4);
        let shift = [
            0.45 * (k % 3) as f64 - 0.45,
            0.45 * (k / 3 % 3) as f64 - 0.45,
        ];
        let turn = rng.random_range(0.0..tau);
        let p = Pair::build(&mut rng, s, m, gap, shift, turn, 0.0, 0.05);
        let xi = boundary[k % boundary.len()];
        out.push(config(
            format!("edges #{k}"),
            p.q(IDENTITY, 1.0, [0.0; 3]),
            xi,
        ));
    }
    for k in 0..20 {
        let p = random_pair(&mut rng, 0.2, 0.0, 0.05);
        let r = random_rotation(&mut rng);
        let dir = apply(random_rotation(&mut rng), [0.0, 0.0, 1.0]);
        let offset = dir.map(|c| 1e6 * c);
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(format!("far #{k}"), p.q(r, 1.0, offset), xi));
    }
    for k in 0..20 {
        let p = random_pair(&mut rng, 0.2, 0.0, 0.05);
        let r = random_rotation(&mut rng);
        let scale = if k % 2 == 0 { 1e-6 } else { 1e6 };
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(format!("scale #{k}"), p.q(r, scale, [0.0; 3]), xi));
    }
    for k in 0..20 {
        let tilt =
            rng.random_range(60.0_f64..85.0).to_radians() * if k % 2 == 0 { 1.0 } else { -1.0 };
        // No shift and the slave point near its centre: the slave normal
        // meets the steep master within a few of its sizes.
        let turn = rng.random_range(0.0..tau);
        let p = Pair::build(&mut rng, s, m, 0.3, [0.0; 2], turn, tilt, 0.05);
        let r = random_rotation(&mut rng);
        let margin = match s {
            FaceKind::Tri3 => 0.3,
            FaceKind::Quad4 => 0.9,
        };
        let xi = s.inside(&mut rng, margin);
        out.push(config(format!("steep #{k}"), p.q(r, 1.0, [0.0; 3]), xi));
    }
    for k in 0..10 {
        let gap = -rng.random_range(1e-3..0.5);
        let p = random_pair(&mut rng, gap, 0.0, 0.05);
        let r = random_rotation(&mut rng);
        let xi = s.inside(&mut rng, 0.05);
        out.push(config(
            format!("penetration #{k}"),
            p.q(r, 1.0, [0.0; 3]),
            xi,
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pair_has_its_families_with_faces_that_face_each_other() {
        for s in [FaceKind::Tri3, FaceKind::Quad4] {
            for m in [FaceKind::Tri3, FaceKind::Quad4] {
                let configs = faces(s, m);
                assert_eq!(configs.len(), 191);
                let n = 3 * (s.nodes() + m.nodes());
                for c in &configs {
                    assert_eq!(c.q.len(), n, "{}", c.label);
                    assert_eq!(c.params.len(), 2);
                    assert!(c.q.iter().all(|v| v.is_finite()));
                }
                // Seeded: the same configurations every time.
                assert_eq!(configs, faces(s, m));
                // Every slave point lies on its face.
                for c in &configs {
                    let [u, v] = [c.params[0], c.params[1]];
                    let inside = match s {
                        FaceKind::Tri3 => u >= 0.0 && v >= 0.0 && u + v <= 1.0,
                        FaceKind::Quad4 => u.abs() <= 1.0 && v.abs() <= 1.0,
                    };
                    assert!(inside, "{}: ({u}, {v})", c.label);
                }
            }
        }
    }
}
