//! Tests of every element through [`SolidElement`], written once over the
//! dimension: the 3D hexahedron and tetrahedron (and the 2D quadrilateral
//! and triangle through the same functions): tangents and forces against
//! finite differences with both kinematics, rigid motions, homogeneous
//! deformations (the analytic St Venant–Kirchhoff stress on each element
//! and the element patch test), the reference-Jacobian checks and the
//! element kinds.

use super::hex::{CORNERS, HexGeometry, KUHN_TETS};
use super::kinematics::{VOIGT_2D, VOIGT_3D};
use super::material::{Kinematics, Material, PlaneModel};
use super::quad::QuadGeometry;
use super::tet::TetGeometry;
use super::tri::TriGeometry;
use super::{ElementKind, SolidElement, Stress};
use crate::testutil::Lcg;

const FINITE: Material = Material {
    young: 1000.0,
    poisson: 0.3,
    model: PlaneModel::PlaneStrain,
    kinematics: Kinematics::Finite,
};

const SMALL: Material = Material {
    kinematics: Kinematics::Small,
    ..FINITE
};

/// A distorted hexahedron in Gmsh's order: the unit cube with every corner
/// moved by up to 0.15 (seeded), then scaled to 1.3 x 0.9 x 1.1.
fn distorted_hex(rng: &mut Lcg) -> [[f64; 3]; 8] {
    CORNERS.map(|c| {
        let p: [f64; 3] = std::array::from_fn(|i| (c[i] + 1.0) / 2.0 + rng.uniform(-0.15, 0.15));
        [1.3 * p[0], 0.9 * p[1], 1.1 * p[2]]
    })
}

/// A random positive tetrahedron that is not too flat (`detJ0 > 0.2`).
fn random_tet(rng: &mut Lcg) -> [[f64; 3]; 4] {
    loop {
        let x: [[f64; 3]; 4] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.uniform(-1.0, 1.0)));
        if let Ok(g) = TetGeometry::new(&x)
            && g.measure_ref() * 6.0 > 0.2
        {
            return x;
        }
    }
}

/// A random counter-clockwise triangle that is not too flat.
fn random_tri(rng: &mut Lcg) -> [[f64; 2]; 3] {
    loop {
        let x: [[f64; 2]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.uniform(-1.0, 1.0)));
        if let Ok(g) = TriGeometry::new(&x)
            && g.measure_ref() * 2.0 > 0.2
        {
            return x;
        }
    }
}

const QUAD: [[f64; 2]; 4] = [[0.1, -0.05], [1.2, 0.1], [1.0, 0.7], [-0.1, 0.55]];

fn max_abs<'a>(v: impl IntoIterator<Item = &'a f64>) -> f64 {
    v.into_iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The nodal displacements of `x -> R (I + H) X + c` (`r` row-major).
fn mapped<const D: usize, const N: usize, const M: usize>(
    x: &[[f64; D]; N],
    h: &[[f64; D]; D],
    r: &[[f64; D]; D],
    c: &[f64; D],
) -> [f64; M] {
    let mut u = [0.0; M];
    for a in 0..N {
        let y: [f64; D] =
            std::array::from_fn(|i| x[a][i] + (0..D).map(|j| h[i][j] * x[a][j]).sum::<f64>());
        for i in 0..D {
            u[D * a + i] = (0..D).map(|j| r[i][j] * y[j]).sum::<f64>() + c[i] - x[a][i];
        }
    }
    u
}

/// The rotation by `angle` about the unit `axis` (Rodrigues), or in 2D
/// about z.
fn rotation<const D: usize>(axis: [f64; 3], angle: f64) -> [[f64; D]; D] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let k = axis.map(|v| v / n);
    let (s, c) = angle.sin_cos();
    let full: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let kk = k[i] * k[j] * (1.0 - c);
            let cross = match (i, j) {
                (0, 1) => -k[2],
                (1, 0) => k[2],
                (0, 2) => k[1],
                (2, 0) => -k[1],
                (1, 2) => -k[0],
                (2, 1) => k[0],
                _ => 0.0,
            };
            kk + if i == j { c } else { 0.0 } + s * cross
        })
    });
    if D == 2 {
        let r2 = [[c, -s], [s, c]];
        std::array::from_fn(|i| std::array::from_fn(|j| r2[i][j]))
    } else {
        std::array::from_fn(|i| std::array::from_fn(|j| full[i][j]))
    }
}

/// Central differences (h = 1e-6) of `f_int` against the tangent and of
/// the energy against `f_int`, at `u`: the largest errors relative to the
/// largest tangent entry. Also checks that the tangent is symmetric and
/// the response's energy is `energy`'s, to the bit.
fn fd_errors<E, const D: usize, const N: usize, const M: usize, const V: usize>(
    g: &E,
    u: [f64; M],
    material: &Material,
) -> (f64, f64)
where
    E: SolidElement<D, N, M, V>,
{
    let r = g.response(&u, material);
    assert_eq!(r.energy, g.energy(&u, material));
    let scale = max_abs(r.k.iter().flatten());
    assert!(scale > 0.0);
    let h = 1e-6;
    let (mut worst_k, mut worst_f) = (0.0_f64, 0.0_f64);
    for p in 0..M {
        let (mut up, mut um) = (u, u);
        up[p] += h;
        um[p] -= h;
        let fd_e = (g.energy(&up, material) - g.energy(&um, material)) / (2.0 * h);
        worst_f = worst_f.max((fd_e - r.f_int[p]).abs() / scale);
        let (rp, rm) = (g.response(&up, material), g.response(&um, material));
        for q in 0..M {
            let fd = (rp.f_int[q] - rm.f_int[q]) / (2.0 * h);
            worst_k = worst_k.max((fd - r.k[q][p]).abs() / scale);
            assert_eq!(r.k[p][q], r.k[q][p], "K[{p}][{q}] not symmetric");
        }
    }
    (worst_k, worst_f)
}

/// Seeded random deformations of size `amp` (both kinematics) on the
/// element: the tangent is the derivative of the force and the force the
/// gradient of the energy, to 1e-8 of the largest tangent entry (measured:
/// below 1e-10 on every element).
fn check_fd<E, const D: usize, const N: usize, const M: usize, const V: usize>(
    g: &E,
    rng: &mut Lcg,
    amp: f64,
) where
    E: SolidElement<D, N, M, V>,
{
    for material in [FINITE, SMALL] {
        for _ in 0..3 {
            let u: [f64; M] = std::array::from_fn(|_| rng.uniform(-amp, amp));
            let (k, f) = fd_errors(g, u, &material);
            assert!(
                k < 1e-8 && f < 1e-8,
                "{:?} {:?}: tangent {k:e}, force {f:e}",
                E::KIND,
                material.kinematics
            );
        }
    }
}

#[test]
fn tangent_and_force_match_finite_differences_3d() {
    let mut rng = Lcg::new(31);
    for _ in 0..3 {
        let hex = HexGeometry::new(&distorted_hex(&mut rng)).unwrap();
        check_fd(&hex, &mut rng, 0.15);
        let tet = TetGeometry::new(&random_tet(&mut rng)).unwrap();
        check_fd(&tet, &mut rng, 0.15);
    }
    // the 2D elements through the same interface
    check_fd(&QuadGeometry::new(&QUAD).unwrap(), &mut rng, 0.15);
    let tri = TriGeometry::new(&random_tri(&mut rng)).unwrap();
    check_fd(&tri, &mut rng, 0.15);
}

/// With small kinematics the tangent does not depend on the displacement,
/// equals the finite-strain tangent at the reference state to the bit, and
/// `f = K u`.
#[test]
fn small_kinematics_is_linear_3d() {
    fn check<E, const D: usize, const N: usize, const M: usize, const V: usize>(
        g: &E,
        rng: &mut Lcg,
    ) where
        E: SolidElement<D, N, M, V>,
    {
        let k0 = g.response(&[0.0; M], &SMALL).k;
        assert_eq!(k0, g.response(&[0.0; M], &FINITE).k);
        let u: [f64; M] = std::array::from_fn(|_| rng.uniform(-0.2, 0.2));
        let r = g.response(&u, &SMALL);
        assert_eq!(
            r.k,
            k0,
            "{:?}: the small-strain tangent depends on u",
            E::KIND
        );
        let scale = max_abs(r.f_int.iter());
        for p in 0..M {
            let ku: f64 = (0..M).map(|q| k0[p][q] * u[q]).sum();
            assert!(
                (ku - r.f_int[p]).abs() < 1e-12 * scale,
                "{:?} f[{p}]",
                E::KIND
            );
        }
    }
    let mut rng = Lcg::new(5);
    check(
        &HexGeometry::new(&distorted_hex(&mut rng)).unwrap(),
        &mut rng,
    );
    check(&TetGeometry::new(&random_tet(&mut rng)).unwrap(), &mut rng);
}

/// Rigid motions carry no strain, no energy and no force: translations
/// with both kinematics, a large rotation (1.1 rad about a random axis)
/// plus translation with finite kinematics. Small kinematics strains under
/// the rotation (the documented limit of linear elasticity).
#[test]
fn rigid_motion_is_force_free() {
    fn check<E, const D: usize, const N: usize, const M: usize, const V: usize>(
        x: &[[f64; D]; N],
        rng: &mut Lcg,
    ) where
        E: SolidElement<D, N, M, V>,
    {
        let g = E::from_reference(x).unwrap();
        let zero = [[0.0; D]; D];
        let id: [[f64; D]; D] =
            std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }));
        let c: [f64; D] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let axis = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 1.0];
        let rot = rotation::<D>(axis, 1.1);
        // the force scale of a unit strain
        let unit = max_abs(g.response(&[0.0; M], &FINITE).k.iter().flatten());
        for (r, materials) in [(id, &[FINITE, SMALL][..]), (rot, &[FINITE][..])] {
            let u: [f64; M] = mapped(x, &zero, &r, &c);
            for m in materials {
                let resp = g.response(&u, m);
                assert!(
                    resp.energy.abs() < 1e-12 * unit,
                    "{:?}: U = {}",
                    E::KIND,
                    resp.energy
                );
                assert!(
                    max_abs(resp.f_int.iter()) < 1e-12 * unit,
                    "{:?}: {:?}",
                    E::KIND,
                    resp.f_int
                );
                let s = g.mean_stress(&u, m);
                assert!(max_abs(s.pk2.iter().chain(&s.cauchy)) < 1e-12 * m.young);
            }
        }
        let u: [f64; M] = mapped(x, &zero, &rot, &c);
        assert!(g.energy(&u, &SMALL) > 1e-3 * unit, "{:?}", E::KIND);
    }
    let mut rng = Lcg::new(17);
    for _ in 0..3 {
        let xh = distorted_hex(&mut rng);
        check::<HexGeometry, 3, 8, 24, 6>(&xh, &mut rng);
        let xt = random_tet(&mut rng);
        check::<TetGeometry, 3, 4, 12, 6>(&xt, &mut rng);
    }
    check::<QuadGeometry, 2, 4, 8, 3>(&QUAD, &mut rng);
}

/// The analytic St Venant–Kirchhoff stress of the homogeneous deformation
/// `F = I + H`: `S = D E` with `E = (F^T F - I)/2` (or `D eps` and
/// `sigma = S` with small kinematics), `sigma = F S F^T / det F`, and the
/// strain with tensor shear.
fn analytic<const D: usize, const V: usize>(
    h: &[[f64; D]; D],
    material: &Material,
    pairs: &[(usize, usize); V],
) -> Stress<V> {
    let small = material.kinematics == Kinematics::Small;
    let f: [[f64; D]; D] =
        std::array::from_fn(|i| std::array::from_fn(|j| h[i][j] + if i == j { 1.0 } else { 0.0 }));
    let e = |i: usize, j: usize| {
        if small {
            (h[i][j] + h[j][i]) / 2.0
        } else {
            let ftf: f64 = (0..D).map(|k| f[k][i] * f[k][j]).sum();
            (ftf - if i == j { 1.0 } else { 0.0 }) / 2.0
        }
    };
    let green: [f64; V] = pairs.map(|(i, j)| e(i, j));
    let e_v: [f64; V] = std::array::from_fn(|r| {
        let (i, j) = pairs[r];
        if i == j { green[r] } else { 2.0 * green[r] }
    });
    let d = material.elasticity::<V>();
    let s_v: [f64; V] = std::array::from_fn(|r| (0..V).map(|t| d[r][t] * e_v[t]).sum());
    let mut s = [[0.0; D]; D];
    for (r, &(i, j)) in pairs.iter().enumerate() {
        s[i][j] = s_v[r];
        s[j][i] = s_v[r];
    }
    let fm = if small {
        std::array::from_fn(|i| std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }))
    } else {
        f
    };
    let det_f = if D == 2 {
        fm[0][0] * fm[1][1] - fm[0][1] * fm[1][0]
    } else {
        let m = |i: usize, j: usize| fm[i % D][j % D];
        (0..3)
            .map(|k| m(0, k) * (m(1, k + 1) * m(2, k + 2) - m(1, k + 2) * m(2, k + 1)))
            .sum()
    };
    let sigma = |i: usize, j: usize| -> f64 {
        let mut v = 0.0;
        for k in 0..D {
            for l in 0..D {
                v += fm[i][k] * s[k][l] * fm[j][l];
            }
        }
        v / det_f
    };
    Stress {
        pk2: s_v,
        cauchy: pairs.map(|(i, j)| sigma(i, j)),
        green,
    }
}

/// The largest difference of two stresses relative to `scale`.
fn stress_error<const V: usize>(a: &Stress<V>, b: &Stress<V>, scale: f64) -> f64 {
    let d = |x: &[f64; V], y: &[f64; V]| {
        x.iter()
            .zip(y)
            .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()))
    };
    (d(&a.pk2, &b.pk2).max(d(&a.cauchy, &b.cauchy)) / scale).max(d(&a.green, &b.green))
}

/// The gradient of a homogeneous deformation used below (strains of
/// about 10 %, all components).
const H3: [[f64; 3]; 3] = [[0.08, 0.03, -0.02], [-0.04, 0.05, 0.06], [0.01, -0.03, 0.1]];

/// The energy density `1/2 E_v . S_v` of a stress and its strain.
fn density<const V: usize>(s: &Stress<V>, pairs: &[(usize, usize); V]) -> f64 {
    let mut w = 0.0;
    for (r, &(i, j)) in pairs.iter().enumerate() {
        w += if i == j { 1.0 } else { 2.0 } * s.green[r] * s.pk2[r] / 2.0;
    }
    w
}

/// A homogeneous deformation gives every integration point of distorted
/// hexahedra and of random tetrahedra the analytic stress (PK2, Cauchy and
/// strain to 1e-12 of the stress scale), with both kinematics, and the
/// energy `V0 W`; a superposed rigid rotation (finite kinematics) leaves
/// PK2, the strain and the energy as they were.
#[test]
fn homogeneous_deformation_gives_analytic_stress_3d() {
    fn check<E, const N: usize, const M: usize>(x: &[[f64; 3]; N], material: &Material)
    where
        E: SolidElement<3, N, M, 6>,
    {
        let g = E::from_reference(x).unwrap();
        let want = analytic(&H3, material, &VOIGT_3D);
        let scale = max_abs(want.pk2.iter());
        let id = rotation::<3>([0.0, 0.0, 1.0], 0.0);
        let c = [0.2, -0.1, 0.3];
        let u: [f64; M] = mapped(x, &H3, &id, &c);
        let points = g.point_stresses(&u, material);
        for p in points.iter().chain([&g.mean_stress(&u, material)]) {
            let err = stress_error(p, &want, scale);
            assert!(
                err < 1e-12,
                "{:?} {:?}: {err:e}",
                E::KIND,
                material.kinematics
            );
        }
        let energy = g.energy(&u, material);
        let exact = g.measure_ref() * density(&want, &VOIGT_3D);
        assert!(
            (energy - exact).abs() < 1e-12 * exact,
            "{energy} vs {exact}"
        );
        if material.kinematics == Kinematics::Finite {
            let rot = rotation::<3>([0.3, -0.5, 1.0], 0.9);
            let u: [f64; M] = mapped(x, &H3, &rot, &c);
            for p in g.point_stresses(&u, material) {
                let unrotated = Stress {
                    cauchy: want.cauchy,
                    ..p
                };
                assert!(stress_error(&unrotated, &want, scale) < 1e-12);
            }
            assert!((g.energy(&u, material) - exact).abs() < 1e-12 * exact);
        }
    }
    let mut rng = Lcg::new(41);
    for material in [FINITE, SMALL] {
        for _ in 0..3 {
            check::<HexGeometry, 8, 24>(&distorted_hex(&mut rng), &material);
            check::<TetGeometry, 4, 12>(&random_tet(&mut rng), &material);
        }
    }
}

/// The 2x2x2 patch of distorted hexahedra around one interior node, node
/// `i + 3 j + 9 k` at `(i, j, k) / 2` moved by up to 0.08 (seeded), the
/// interior node 13 by more.
fn patch_nodes(rng: &mut Lcg) -> [[f64; 3]; 27] {
    std::array::from_fn(|n| {
        let ijk = [n % 3, (n / 3) % 3, n / 9];
        let amp = if n == 13 { 0.12 } else { 0.08 };
        std::array::from_fn(|i| ijk[i] as f64 / 2.0 + rng.uniform(-amp, amp))
    })
}

/// The patch's eight hexahedra (Gmsh order).
fn patch_hexes() -> Vec<[usize; 8]> {
    let mut out = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                let n = |di: usize, dj: usize, dk: usize| (i + di) + 3 * (j + dj) + 9 * (k + dk);
                out.push([
                    n(0, 0, 0),
                    n(1, 0, 0),
                    n(1, 1, 0),
                    n(0, 1, 0),
                    n(0, 0, 1),
                    n(1, 0, 1),
                    n(1, 1, 1),
                    n(0, 1, 1),
                ]);
            }
        }
    }
    out
}

/// Each hexahedron of the patch split into six tetrahedra around its
/// diagonal from local node 0 to local node 6 (positive for these mildly
/// distorted cells).
fn patch_tets() -> Vec<[usize; 4]> {
    patch_hexes()
        .iter()
        .flat_map(|h| KUHN_TETS.map(|t| t.map(|a| h[a])))
        .collect()
}

/// The element patch test in 3D: under a homogeneous deformation (with a
/// rotation, finite kinematics; without, small) prescribed at every node,
/// the assembled internal force of the 2x2x2 patch of distorted
/// hexahedra, and of the same patch in 48 tetrahedra, vanishes at the
/// interior node (1e-12 of the largest nodal force), every element has
/// the analytic stress, and each mesh's energy is its volume times the
/// energy density (1e-12; the two volumes differ where the hexahedra's
/// faces are warped).
#[test]
fn patch_test_3d() {
    fn assemble<E, const N: usize, const M: usize>(
        x: &[[f64; 3]; 27],
        elements: &[[usize; N]],
        u: &[f64; 81],
        material: &Material,
        want: &Stress<6>,
    ) -> ([f64; 81], f64)
    where
        E: SolidElement<3, N, M, 6>,
    {
        let mut f = [0.0; 81];
        let mut energy = 0.0;
        let scale = max_abs(want.pk2.iter());
        for el in elements {
            let g = E::from_reference(&el.map(|n| x[n])).unwrap();
            let ue: [f64; M] = std::array::from_fn(|p| u[3 * el[p / 3] + p % 3]);
            let r = g.response(&ue, material);
            for p in 0..M {
                f[3 * el[p / 3] + p % 3] += r.f_int[p];
            }
            energy += r.energy;
            // the Cauchy stress is rotated with finite kinematics: the
            // frame-indifferent PK2 stress and strain are compared
            let mut st = g.mean_stress(&ue, material);
            if material.kinematics == Kinematics::Finite {
                st.cauchy = want.cauchy;
            }
            assert!(stress_error(&st, want, scale) < 1e-12, "{:?}", E::KIND);
        }
        (f, energy)
    }
    let mut rng = Lcg::new(53);
    let x = patch_nodes(&mut rng);
    for material in [FINITE, SMALL] {
        let r = if material.kinematics == Kinematics::Small {
            rotation::<3>([0.0, 0.0, 1.0], 0.0)
        } else {
            rotation::<3>([1.0, 0.4, -0.2], 0.7)
        };
        let u: [f64; 81] = mapped(&x, &H3, &r, &[0.05, 0.1, -0.2]);
        let want = analytic(&H3, &material, &VOIGT_3D);
        let (fh, eh) = assemble::<HexGeometry, 8, 24>(&x, &patch_hexes(), &u, &material, &want);
        let (ft, et) = assemble::<TetGeometry, 4, 12>(&x, &patch_tets(), &u, &material, &want);
        let scale = max_abs(fh.iter());
        assert!(scale > 1.0);
        for i in 0..3 {
            assert!(
                fh[39 + i].abs() < 1e-12 * scale,
                "hex interior f[{i}] = {}",
                fh[39 + i]
            );
            assert!(
                ft[39 + i].abs() < 1e-12 * scale,
                "tet interior f[{i}] = {}",
                ft[39 + i]
            );
        }
        let w = density(&want, &VOIGT_3D);
        let vh: f64 = patch_hexes()
            .iter()
            .map(|h| HexGeometry::new(&h.map(|n| x[n])).unwrap().measure_ref())
            .sum();
        let vt: f64 = patch_tets()
            .iter()
            .map(|t| TetGeometry::new(&t.map(|n| x[n])).unwrap().measure_ref())
            .sum();
        assert!((eh - vh * w).abs() < 1e-12 * eh, "{eh} vs {}", vh * w);
        assert!((et - vt * w).abs() < 1e-12 * et, "{et} vs {}", vt * w);
    }
}

/// On an axis-aligned brick with dyadic coordinates and a dyadic
/// displacement gradient, the six tetrahedra of its split have exact
/// gradients, so they give the same stress bits; the hexahedron's Gauss
/// points carry the rounding of `1/sqrt 3` in their gradients, so they
/// agree with the tetrahedra to 1e-15 of the stress scale (not to the
/// bit), and all match the analytic stress to 1e-14.
#[test]
fn brick_tets_give_the_same_bits_and_the_hex_agrees() {
    let l = [2.0, 1.0, 0.5];
    let x: [[f64; 3]; 8] = CORNERS.map(|c| std::array::from_fn(|i| (c[i] + 1.0) / 2.0 * l[i]));
    let h = [
        [0.125, 0.0625, -0.03125],
        [-0.0625, 0.09375, 0.046875],
        [0.015625, -0.03125, 0.0625],
    ];
    let id = rotation::<3>([0.0, 0.0, 1.0], 0.0);
    for material in [FINITE, SMALL] {
        let u: [f64; 24] = mapped(&x, &h, &id, &[0.0; 3]);
        let hex = HexGeometry::new(&x).unwrap();
        let mut stresses = hex.point_stresses(&u, &material);
        for t in KUHN_TETS {
            let g = TetGeometry::new(&t.map(|a| x[a])).unwrap();
            let ut: [f64; 12] = std::array::from_fn(|p| u[3 * t[p / 3] + p % 3]);
            stresses.push(g.mean_stress(&ut, &material));
        }
        let want = analytic(&h, &material, &VOIGT_3D);
        let scale = max_abs(want.pk2.iter());
        for (k, s) in stresses.iter().enumerate() {
            if k > 8 {
                assert_eq!(s, &stresses[8], "{:?}: tet {}", material.kinematics, k - 8);
            }
            let err = stress_error(s, &stresses[8], scale);
            assert!(err < 1e-15, "{:?}: point {k}: {err:e}", material.kinematics);
            assert!(stress_error(s, &want, scale) < 1e-14);
        }
    }
}

/// Inverted, flat, collapsed and non-finite elements are refused with
/// [`super::InvalidElement`] (its `det_j0` and message); honest thin or
/// distorted ones pass.
#[test]
fn invalid_3d_elements_are_refused() {
    let mut rng = Lcg::new(3);
    let x = distorted_hex(&mut rng);
    assert!(HexGeometry::new(&x).is_ok());
    // top and bottom faces swapped: inverted
    let inverted: [[f64; 3]; 8] = std::array::from_fn(|a| x[(a + 4) % 8]);
    let err = HexGeometry::new(&inverted).unwrap_err();
    assert!(err.det_j0 < 0.0, "{err:?}");
    assert!(err.to_string().contains("not positive"), "{err}");
    // the top face collapsed onto the bottom one: flat
    let flat: [[f64; 3]; 8] = std::array::from_fn(|a| [x[a % 4][0], x[a % 4][1], x[a % 4][2]]);
    assert!(!(HexGeometry::new(&flat).unwrap_err().det_j0 > 0.0));
    // a node pulled through the opposite face: negative at a Gauss point
    let mut folded = x;
    folded[6] = [-0.5, -0.5, -0.5];
    assert!(HexGeometry::new(&folded).is_err());
    for bad in [f64::NAN, f64::INFINITY] {
        let mut y = x;
        y[5][1] = bad;
        assert!(HexGeometry::new(&y).unwrap_err().det_j0.is_nan());
        let mut t = random_tet(&mut rng);
        t[2][0] = bad;
        assert!(TetGeometry::new(&t).unwrap_err().det_j0.is_nan());
    }

    // coordinates whose Jacobian overflows
    assert!(HexGeometry::new(&x.map(|p| p.map(|v| v * 1e200))).is_err());
    let t = random_tet(&mut rng);
    assert!(TetGeometry::new(&t.map(|p| p.map(|v| v * 1e200))).is_err());
    let swapped = [t[0], t[2], t[1], t[3]];
    assert!(TetGeometry::new(&swapped).unwrap_err().det_j0 < 0.0);
    let coplanar = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    assert_eq!(TetGeometry::new(&coplanar).unwrap_err().det_j0, 0.0);
    assert!(TetGeometry::new(&[[0.3, 0.1, 0.2]; 4]).is_err());
    // coplanar in exact arithmetic, with coordinates that are not
    // representable: refused whatever the sign of the computed detJ0
    for _ in 0..200 {
        let p: [[f64; 3]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.uniform(-1.0, 1.0)));
        let (s, q) = (rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9));
        let inside =
            std::array::from_fn(|i| p[0][i] + s * (p[1][i] - p[0][i]) + q * (p[2][i] - p[0][i]));
        let near = [p[0], p[1], p[2], inside];
        assert!(TetGeometry::new(&near).is_err(), "{near:?}");
        assert!(TetGeometry::new(&[p[0], p[2], p[1], inside]).is_err());
    }
    // a thin but honest tetrahedron passes, with its volume
    let thin = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.2, 0.3, 1e-6],
    ];
    let g = TetGeometry::new(&thin).unwrap();
    assert!((g.measure_ref() - 1e-6 / 6.0).abs() < 1e-20);
    let unit = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.5],
    ];
    assert_eq!(TetGeometry::new(&unit).unwrap().measure_ref(), 0.5);
}

/// Reference gradients: a partition of unity's (they sum to zero) and
/// reproducing the identity (`sum_a X_a G_a^T = I`), at every Gauss point;
/// the brick's volume is exact.
#[test]
fn reference_gradients_3d() {
    fn check<E, const N: usize, const M: usize>(x: &[[f64; 3]; N], grads: &[[[f64; 3]; N]])
    where
        E: SolidElement<3, N, M, 6>,
    {
        for g in grads {
            for j in 0..3 {
                let s: f64 = (0..N).map(|a| g[a][j]).sum();
                assert!(s.abs() < 1e-13, "{:?}", E::KIND);
                for i in 0..3 {
                    let v: f64 = (0..N).map(|a| x[a][i] * g[a][j]).sum();
                    let id = if i == j { 1.0 } else { 0.0 };
                    assert!((v - id).abs() < 1e-13, "{:?} [{i}][{j}] = {v}", E::KIND);
                }
            }
        }
    }
    let mut rng = Lcg::new(9);
    let x = distorted_hex(&mut rng);
    check::<HexGeometry, 8, 24>(&x, &HexGeometry::new(&x).unwrap().grads_ref);
    let t = random_tet(&mut rng);
    check::<TetGeometry, 4, 12>(&t, &TetGeometry::new(&t).unwrap().grads_ref);
    let brick: [[f64; 3]; 8] =
        CORNERS.map(|c| [c[0] + 1.0, (c[1] + 1.0) * 1.5, (c[2] + 1.0) / 4.0]);
    assert!((HexGeometry::new(&brick).unwrap().measure_ref() - 3.0).abs() < 1e-14);
}

/// The kinds: node counts, dimensions, VTK cell types and names, and each
/// element type's `KIND` matching its const parameters.
#[test]
fn element_kinds() {
    fn kind<E, const D: usize, const N: usize, const M: usize, const V: usize>() -> ElementKind
    where
        E: SolidElement<D, N, M, V>,
    {
        assert_eq!((E::KIND.dim(), E::KIND.node_count()), (D, N));
        E::KIND
    }
    let kinds = [
        kind::<QuadGeometry, 2, 4, 8, 3>(),
        kind::<TriGeometry, 2, 3, 6, 3>(),
        kind::<HexGeometry, 3, 8, 24, 6>(),
        kind::<TetGeometry, 3, 4, 12, 6>(),
    ];
    assert_eq!(kinds.map(|k| k.vtk_cell_type()), [9, 5, 12, 10]);
    assert_eq!(
        kinds.map(|k| k.to_string()),
        [
            "4-node quadrilateral",
            "3-node triangle",
            "8-node hexahedron",
            "4-node tetrahedron"
        ]
    );
    assert_eq!(VOIGT_2D, [(0, 0), (1, 1), (0, 1)]);
}
