//! The stability sweep over 3D face pairs: the Type 6 kernels of
//! tri3-on-tri3 and quad4-on-quad4 contact, both readings, in f64 against
//! the double-double hyper-dual reference of [`face_reference`], over the
//! hard families of 3D ([`Family::FACES`]):
//!
//! | family | parameter | values |
//! |---|---|---|
//! | `offset` | distance of the pair from the origin | 1 .. 1e8 |
//! | `scale` | size of the pair (faces and gap scaled together) | 1e-8 .. 1e8 |
//! | `angle` | `90° - tilt` of the master against the slave's plane | 90° .. 0.01° (85° at 5) |
//! | `edge` | distance of `xi_m` from a master edge (parameter units) | 0.1 .. 0 |
//! | `corner` | distance of `xi_m` from a master corner in both coordinates | 0.1 .. 0 |
//! | `gap` | the gap, with faces of unit size | 1 .. 1e-14 |
//!
//! A configuration, built in a local frame: the slave face of size about
//! 1 in the plane `z = 0`, facing `+z` (nodes jittered by up to 0.1 of its
//! size in the plane; a quad4's also by 0.03 out of it: a warped face),
//! its point `xi_s` drawn inside (tri3: `u, v >= 0.1`, `u + v <= 0.9`;
//! quad4: `[-0.8, 0.8]^2`); the master face, jittered and warped alike,
//! facing `-z`, turned about `z` at random and tilted about `x` by up to
//! 10° (unless the family sets the tilt), then moved so that its point at
//! the family's `xi_m` is the foot of the projection at distance `gap`:
//! `x_s + gap n_s` for slave-normal, `x_s - gap n_m(xi_m)` for
//! closest-point (`n_s`, `n_m` the faces' outward unit normals there).
//! The pair is then rotated at random, scaled and moved `offset` along a
//! random direction. 32 seeded configurations per value; the errors are
//! the worst over them (as in 2D, [`super`]); a configuration the kernel
//! refuses is counted, not compared.

use contact_kernels::Formulation;

#[cfg(test)]
use super::face_reference::face_gap;
use super::face_reference::face_reference;
use super::{Family, Lcg, SweepRow, sweep_row};

/// The face formulations the sweep covers, those compiled in.
pub fn face_formulations() -> Vec<Formulation> {
    [
        Formulation::Tri3SlaveNormal,
        Formulation::Tri3ClosestPoint,
        Formulation::Quad4SlaveNormal,
        Formulation::Quad4ClosestPoint,
    ]
    .into_iter()
    .filter(|f| f.face_nodes().is_some())
    .collect()
}

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: P3) -> P3 {
    let len = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|c| c / len)
}

/// The reference corners `(u, v)` of a face of `nodes` nodes,
/// counter-clockwise.
fn corners(nodes: usize) -> &'static [[f64; 2]] {
    if nodes == 3 {
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    } else {
        &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
    }
}

/// A face's point and tangents `dx/du`, `dx/dv` at `(u, v)`.
fn face_at(nodes: &[P3], [u, v]: [f64; 2]) -> (P3, P3, P3) {
    let mut out = ([0.0; 3], [0.0; 3], [0.0; 3]);
    let weights: Vec<[f64; 3]> = if nodes.len() == 3 {
        vec![[1.0 - u - v, -1.0, -1.0], [u, 1.0, 0.0], [v, 0.0, 1.0]]
    } else {
        corners(4)
            .iter()
            .map(|&[ua, va]| {
                let (fu, fv) = (1.0 + u * ua, 1.0 + v * va);
                [0.25 * fu * fv, 0.25 * ua * fv, 0.25 * fu * va]
            })
            .collect()
    };
    for (p, w) in nodes.iter().zip(&weights) {
        for (k, &pk) in p.iter().enumerate() {
            out.0[k] += w[0] * pk;
            out.1[k] += w[1] * pk;
            out.2[k] += w[2] * pk;
        }
    }
    out
}

/// A point drawn inside a face of `nodes` nodes (module docs).
fn inside(nodes: usize, rng: &mut Lcg) -> [f64; 2] {
    if nodes == 3 {
        loop {
            let (u, v) = (rng.uniform(0.1, 0.8), rng.uniform(0.1, 0.8));
            if u + v <= 0.9 {
                return [u, v];
            }
        }
    } else {
        [rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8)]
    }
}

/// A face of `nodes` nodes and size about `size` centred on the origin in
/// the plane `z = 0`, jittered and (quad4) warped (module docs), facing
/// `+z`, or `-z` when `facing_down`.
fn local_face(nodes: usize, size: f64, facing_down: bool, rng: &mut Lcg) -> Vec<P3> {
    let (centre, half) = if nodes == 3 {
        ([1.0 / 3.0, 1.0 / 3.0], size)
    } else {
        ([0.0, 0.0], 0.5 * size)
    };
    let warp = if nodes == 4 { 0.03 } else { 0.0 };
    corners(nodes)
        .iter()
        .map(|&[u, v]| {
            let x = (u - centre[0]) * half + rng.uniform(-0.1, 0.1) * size;
            let y = (v - centre[1]) * half + rng.uniform(-0.1, 0.1) * size;
            let z = rng.uniform(-warp, warp) * size;
            [x, if facing_down { -y } else { y }, z]
        })
        .collect()
}

type M3 = [[f64; 3]; 3];

fn apply(r: &M3, p: P3) -> P3 {
    std::array::from_fn(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2])
}

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn rot_z(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn rot_y(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn rot_x(t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

/// A random rotation (z-y-z Euler angles, uniform on the sphere).
fn random_rotation(rng: &mut Lcg) -> M3 {
    let tau = std::f64::consts::TAU;
    let (a, b, c) = (
        rng.uniform(0.0, tau),
        rng.uniform(-1.0, 1.0).acos(),
        rng.uniform(0.0, tau),
    );
    mul(&mul(&rot_z(a), &rot_y(b)), &rot_z(c))
}

/// The family's target `xi_m` on a master of `nodes` nodes.
fn target_xi_m(family: Family, value: f64, nodes: usize, rng: &mut Lcg) -> [f64; 2] {
    match (family, nodes) {
        (Family::Edge, 3) => [rng.uniform(0.2, 0.7), value],
        (Family::Edge, _) => [rng.uniform(-0.7, 0.7), 1.0 - value],
        (Family::Corner, 3) => [value, value],
        (Family::Corner, _) => [1.0 - value, 1.0 - value],
        _ => inside(nodes, rng),
    }
}

/// One configuration of `f` for the family's value (module docs): `q`
/// and `xi_s`.
fn configuration(
    f: Formulation,
    family: Family,
    value: f64,
    rng: &mut Lcg,
) -> (Vec<f64>, [f64; 2]) {
    let (ns, nm) = f.face_nodes().expect("a compiled face formulation");
    let closest = f.name().ends_with("closest-point");
    let mut gap = 0.1;
    let mut tilt = rng.uniform(-10.0, 10.0);
    let (mut scale, mut offset) = (1.0, 0.0);
    match family {
        Family::Offset => offset = value,
        Family::Scale => scale = value,
        Family::Angle => tilt = 90.0 - value,
        Family::Gap => gap = value,
        Family::End | Family::Edge | Family::Corner => {}
    }
    let xi_m = target_xi_m(family, value, nm, rng);
    let slave = local_face(ns, rng.uniform(0.8, 1.2), false, rng);
    let xi_s = inside(ns, rng);
    let (x_s, ts1, ts2) = face_at(&slave, xi_s);
    let n_s = unit(cross(ts1, ts2));
    let r = mul(
        &rot_x(tilt.to_radians()),
        &rot_z(rng.uniform(0.0, std::f64::consts::TAU)),
    );
    let master: Vec<P3> = local_face(nm, rng.uniform(0.8, 1.2), true, rng)
        .into_iter()
        .map(|p| apply(&r, p))
        .collect();
    let (p0, tm1, tm2) = face_at(&master, xi_m);
    let n_m = unit(cross(tm1, tm2));
    let foot: P3 = std::array::from_fn(|k| {
        if closest {
            x_s[k] - gap * n_m[k]
        } else {
            x_s[k] + gap * n_s[k]
        }
    });
    let shift = sub(foot, p0);
    let master = master
        .into_iter()
        .map(|p| std::array::from_fn(|k| p[k] + shift[k]));
    let turn = random_rotation(rng);
    let dir = apply(&random_rotation(rng), [0.0, 0.0, 1.0]);
    let q = slave
        .into_iter()
        .chain(master)
        .flat_map(|p: P3| {
            let p = apply(&turn, p);
            [0, 1, 2].map(|k| p[k] * scale + offset * dir[k])
        })
        .collect();
    (q, xi_s)
}

/// Runs the face sweep over every family of [`Family::FACES`], value and
/// formulation of [`face_formulations`], in that order.
pub fn sweep_faces() -> Vec<SweepRow> {
    let mut rows = Vec::new();
    for family in Family::FACES {
        for &value in family.face_values() {
            for formulation in face_formulations() {
                rows.push(sweep_one_face(family, value, formulation));
            }
        }
    }
    rows
}

/// One row of the face sweep.
pub(super) fn sweep_one_face(family: Family, value: f64, formulation: Formulation) -> SweepRow {
    let family_bits = (Family::FACES.iter().position(|&f| f == family).unwrap_or(0) as u64) << 56;
    sweep_row(
        family,
        value,
        formulation,
        0x3d_5eed ^ family_bits ^ value.to_bits(),
        |rng| configuration(formulation, family, value, rng),
        |q, xi_s, out| {
            let xi_m = out.xi_m_all();
            let r = face_reference(formulation, q, xi_s, [xi_m[0], xi_m[1]]);
            (r.gap, r.grad, r.hess)
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The configurations put the projection where the family says: the
    /// reference's `xi_m` is the target, and its gap the family's gap
    /// (unit scale, no offset).
    #[test]
    fn configurations_land_on_their_targets() {
        for f in face_formulations() {
            let (_, nm) = f.face_nodes().unwrap();
            for (family, value) in [
                (Family::Corner, 0.0),
                (Family::Edge, 1e-4),
                (Family::Gap, 1e-2),
            ] {
                let mut rng = Lcg(7);
                let mut probe = Lcg(7);
                // `configuration` draws the tilt first, then the target.
                probe.uniform(-10.0, 10.0);
                let target = target_xi_m(family, value, nm, &mut probe);
                let (q, xi_s) = configuration(f, family, value, &mut rng);
                let r = face_reference(f, &q, xi_s, [0.0, 0.0]);
                let xi = r.xi_m.map(|x| x.to_f64());
                assert!(
                    (xi[0] - target[0]).abs() < 1e-12,
                    "{f} {family:?}: {xi:?} {target:?}"
                );
                assert!(
                    (xi[1] - target[1]).abs() < 1e-12,
                    "{f} {family:?}: {xi:?} {target:?}"
                );
                let gap = if family == Family::Gap { value } else { 0.1 };
                assert!(
                    (r.gap.to_f64() - gap).abs() < 1e-12 * (1.0 + gap),
                    "{f}: {}",
                    r.gap.to_f64()
                );
            }
        }
    }

    /// On benign configurations the f64 face kernels agree with the
    /// double-double reference to roundoff (so the reference is the same
    /// function), and the rows are seeded.
    #[test]
    fn benign_face_configurations_agree_to_roundoff() {
        for f in face_formulations() {
            let row = sweep_one_face(Family::Offset, 1.0, f);
            assert_eq!(row.refused, 0, "{row:?}");
            assert!(row.gap.unwrap() < 1e-12, "{row:?}");
            assert!(row.grad.unwrap() < 1e-12, "{row:?}");
            assert!(row.hess.unwrap() < 1e-12, "{row:?}");
            assert_eq!(row, sweep_one_face(Family::Offset, 1.0, f));
        }
    }

    /// The reference's derivatives are those of its gap: central
    /// differences of the double-double gap agree with its gradient.
    #[test]
    fn reference_gradient_matches_differences_of_its_gap() {
        for f in face_formulations() {
            let mut rng = Lcg(11);
            let (q, xi_s) = configuration(f, Family::Offset, 1.0, &mut rng);
            let r = face_reference(f, &q, xi_s, [0.0, 0.0]);
            let h = 1e-6;
            for j in 0..q.len() {
                let at = |d: f64| {
                    let mut qq = q.clone();
                    qq[j] += d;
                    let g = face_gap(f, &qq, xi_s, r.xi_m.map(|x| x.to_f64())).0;
                    (qq[j], g)
                };
                let ((xp, gp), (xm, gm)) = (at(h), at(-h));
                // the steps the f64 coordinates actually took
                let fd = (gp - gm).to_f64() / (xp - xm);
                assert!(
                    (fd - r.grad[j].to_f64()).abs() < 1e-7,
                    "{f} [{j}]: {fd} {:?}",
                    r.grad[j]
                );
            }
        }
    }
}
