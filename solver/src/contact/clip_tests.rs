//! Tests of `clip.rs` (its child module, private items included): the
//! pieces of master faces tiling a slave face sum to its area, the rules
//! integrate polynomials up to their degree exactly, the parametric
//! coordinates invert the slave map, degenerate overlaps give no piece or
//! the whole face, and bad faces are typed errors.

use super::*;

/// A frame in space: origin, two in-plane axes, normal.
struct Frame {
    o: V3,
    a: V3,
    b: V3,
    n: V3,
}

impl Frame {
    fn tilted() -> Frame {
        let a = [0.6, 0.8, 0.0];
        let b0 = [-0.48, 0.36, 0.8];
        let n = cross3(&a, &b0);
        Frame {
            o: [0.3, -1.2, 2.5],
            a,
            b: b0,
            n,
        }
    }

    /// The point `x a + y b + z n` from the origin.
    fn at(&self, x: f64, y: f64, z: f64) -> V3 {
        let mut p = self.o;
        for k in 0..3 {
            p[k] += x * self.a[k] + y * self.b[k] + z * self.n[k];
        }
        p
    }
}

/// A tiling of master faces covering `[-1, 3]^2` of the frame's plane:
/// a grid of spacing `h` rotated by `angle`, shifted by `offset`, at
/// height `gap + tilt x`, each face clockwise seen from the slave side
/// (its outward normal against the slave's); quads, or each quad cut
/// into two triangles.
fn tiling(f: &Frame, h: f64, angle: f64, offset: V2, tilt: f64, tri: bool) -> Vec<Vec<V3>> {
    let (c, s) = (angle.cos(), angle.sin());
    let m = (6.0 / h).ceil() as i64;
    let node = |i: i64, j: i64| {
        let (x, y) = (i as f64 * h + offset[0], j as f64 * h + offset[1]);
        let (x, y) = (c * x - s * y + 1.0, s * x + c * y + 1.0);
        f.at(x, y, 0.01 + tilt * x)
    };
    let mut faces = Vec::new();
    for j in -m..m {
        for i in -m..m {
            let q = [
                node(i, j),
                node(i, j + 1),
                node(i + 1, j + 1),
                node(i + 1, j),
            ];
            if tri {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    faces
}

fn slaves(f: &Frame) -> Vec<(&'static str, Vec<V3>)> {
    vec![
        (
            "square",
            vec![
                f.at(0.0, 0.0, 0.0),
                f.at(1.0, 0.0, 0.0),
                f.at(1.0, 1.0, 0.0),
                f.at(0.0, 1.0, 0.0),
            ],
        ),
        (
            "parallelogram",
            vec![
                f.at(0.0, 0.0, 0.0),
                f.at(1.3, 0.2, 0.0),
                f.at(1.8, 1.1, 0.0),
                f.at(0.5, 0.9, 0.0),
            ],
        ),
        (
            "general quad",
            vec![
                f.at(0.1, 0.0, 0.0),
                f.at(1.4, 0.3, 0.0),
                f.at(1.1, 1.6, 0.0),
                f.at(-0.2, 0.8, 0.0),
            ],
        ),
        (
            "triangle",
            vec![
                f.at(0.0, 0.1, 0.0),
                f.at(1.7, 0.4, 0.0),
                f.at(0.6, 1.5, 0.0),
            ],
        ),
    ]
}

#[test]
fn pieces_over_a_tiling_sum_to_the_slave_area() {
    let f = Frame::tilted();
    let cases = [
        (0.37, 0.3, [0.05, -0.11], 0.0),
        (0.25, 0.0, [0.0, 0.0], 0.0),
        (0.21, -1.1, [0.013, 0.17], 0.2),
        (0.9, 0.7, [0.3, 0.1], -0.1),
    ];
    for (name, slave) in slaves(&f) {
        let face = SlaveFace::new(&slave).unwrap();
        // The plane area of the face, from the frame's coordinates.
        let exact = {
            let p: Vec<V2> = slave
                .iter()
                .map(|x| {
                    let d = sub3(x, &f.o);
                    [dot3(&d, &f.a), dot3(&d, &f.b)]
                })
                .collect();
            signed_area(&p)
        };
        assert!((face.area() - exact).abs() <= 1e-14 * exact, "{name}");
        for &(h, angle, offset, tilt) in &cases {
            for tri in [false, true] {
                let mut area = 0.0;
                let mut weights = 0.0;
                let mut touched = 0;
                for master in tiling(&f, h, angle, offset, tilt, tri) {
                    let pieces = face.clip(&master).unwrap();
                    touched += usize::from(!pieces.is_empty());
                    area += pieces.iter().map(|p| p.area).sum::<f64>();
                    weights += face
                        .integration_points(&master, TriangleRule::Three)
                        .unwrap()
                        .iter()
                        .map(|p| p.weight)
                        .sum::<f64>();
                }
                let what = format!("{name}, h {h}, angle {angle}, tri {tri}");
                assert!(touched > 1, "{what}: {touched} masters");
                assert!(
                    (area - exact).abs() <= 1e-12 * exact,
                    "{what}: {area} vs {exact}"
                );
                assert!(
                    (weights - exact).abs() <= 1e-12 * exact,
                    "{what}: {weights}"
                );
            }
        }
    }
}

/// `int u^a v^b du dv` over the unit triangle and over `[-1, 1]^2`.
fn monomial_tri(a: i32, b: i32) -> f64 {
    let fact = |k: i32| (1..=k).map(f64::from).product::<f64>();
    fact(a) * fact(b) / fact(a + b + 2)
}
fn monomial_square(a: i32, b: i32) -> f64 {
    let one = |k: i32| {
        if k % 2 == 0 {
            2.0 / f64::from(k + 1)
        } else {
            0.0
        }
    };
    one(a) * one(b)
}

#[test]
fn polynomials_up_to_the_rule_degree_integrate_exactly() {
    let f = Frame::tilted();
    for (name, slave) in slaves(&f) {
        if name == "general quad" {
            continue; // not affine: (u, v) monomials are not polynomials in x
        }
        let face = SlaveFace::new(&slave).unwrap();
        // The affine map's Jacobian: area over the reference area.
        let (jac, reference): (f64, fn(i32, i32) -> f64) = if slave.len() == 3 {
            (face.area() / 0.5, monomial_tri)
        } else {
            (face.area() / 4.0, monomial_square)
        };
        let masters = tiling(&f, 0.31, 0.4, [0.02, 0.07], 0.1, true);
        for rule in [
            TriangleRule::Centroid,
            TriangleRule::Three,
            TriangleRule::Seven,
        ] {
            let points: Vec<ClipPoint> = masters
                .iter()
                .flat_map(|m| face.integration_points(m, rule).unwrap())
                .collect();
            let d = rule.degree() as i32;
            let mut worst_above: f64 = 0.0;
            for total in 0..=d + 1 {
                for a in 0..=total {
                    let b = total - a;
                    let got: f64 = points
                        .iter()
                        .map(|p| p.weight * p.uv[0].powi(a) * p.uv[1].powi(b))
                        .sum();
                    let exact = jac * reference(a, b);
                    let err = (got - exact).abs();
                    if total <= d {
                        assert!(
                            err <= 1e-12 * face.area(),
                            "{name} {rule:?} u^{a} v^{b}: {got} vs {exact}"
                        );
                    } else {
                        worst_above = worst_above.max(err);
                    }
                }
            }
            // One degree more is not exact: the check above can fail.
            assert!(
                worst_above > 1e-9 * face.area(),
                "{name} {rule:?}: {worst_above}"
            );
        }
    }
}

#[test]
fn parametric_coordinates_invert_the_slave_map() {
    let f = Frame::tilted();
    for (name, slave) in slaves(&f) {
        let face = SlaveFace::new(&slave).unwrap();
        for (k, x) in slave.iter().enumerate() {
            let uv = face.parametric(face.to_plane(x)).unwrap();
            let reference = if slave.len() == 3 {
                [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]][k]
            } else {
                [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]][k]
            };
            assert!(
                norm2(&sub2(&uv, &reference)) < 1e-12,
                "{name} node {k}: {uv:?}"
            );
        }
        for uv in [[0.2, 0.3], [0.05, 0.9], [-0.0, 0.0]] {
            let back = face.parametric(face.plane_point(uv)).unwrap();
            assert!(norm2(&sub2(&back, &uv)) < 1e-12, "{name} {uv:?}: {back:?}");
        }
    }
}

#[test]
fn degenerate_overlaps_give_no_piece_or_the_whole_face() {
    let f = Frame::tilted();
    let square = |x0: f64, y0: f64, s: f64| {
        vec![
            f.at(x0, y0, 0.0),
            f.at(x0, y0 + s, 0.0),
            f.at(x0 + s, y0 + s, 0.0),
            f.at(x0 + s, y0, 0.0),
        ]
    };
    let slave: Vec<V3> = square(0.0, 0.0, 1.0).into_iter().rev().collect();
    let face = SlaveFace::new(&slave).unwrap();
    // No overlap, a shared edge, a touching corner.
    for master in [
        square(2.0, 0.0, 1.0),
        square(1.0, 0.0, 1.0),
        square(1.0, 1.0, 0.5),
    ] {
        assert_eq!(face.clip(&master).unwrap(), vec![]);
    }
    // A sliver 1e-14 wide: below the tolerance.
    assert_eq!(face.clip(&square(1.0 - 1e-14, 0.0, 1.0)).unwrap(), vec![]);
    // Edge-on (perpendicular to the slave plane).
    let edge_on = vec![
        f.at(0.5, 0.0, -1.0),
        f.at(0.5, 1.0, -1.0),
        f.at(0.5, 1.0, 1.0),
        f.at(0.5, 0.0, 1.0),
    ];
    assert_eq!(face.clip(&edge_on).unwrap(), vec![]);
    // Identical (either orientation): the whole face.
    for master in [slave.clone(), square(0.0, 0.0, 1.0)] {
        let pieces = face.clip(&master).unwrap();
        let area: f64 = pieces.iter().map(|p| p.area).sum();
        assert!((area - face.area()).abs() <= 1e-14, "{area}");
    }
    // A master with collinear corners (a triangle drawn as a quad).
    let collinear = vec![
        f.at(0.0, 0.0, 0.0),
        f.at(0.0, 0.5, 0.0),
        f.at(0.0, 1.0, 0.0),
        f.at(1.0, 0.0, 0.0),
    ];
    let area: f64 = face.clip(&collinear).unwrap().iter().map(|p| p.area).sum();
    assert!((area - 0.5).abs() <= 1e-14, "{area}");
}

#[test]
fn bad_faces_are_typed_errors() {
    let f = Frame::tilted();
    let slave = vec![
        f.at(0.0, 0.0, 0.0),
        f.at(1.0, 0.0, 0.0),
        f.at(1.0, 1.0, 0.0),
        f.at(0.0, 1.0, 0.0),
    ];
    let face = SlaveFace::new(&slave).unwrap();
    let folded = vec![
        f.at(0.0, 0.0, 0.0),
        f.at(1.0, 0.0, 0.0),
        f.at(0.2, 0.2, 0.0),
        f.at(0.0, 1.0, 0.0),
    ];
    let bow_tie = vec![
        f.at(0.0, 0.0, 0.0),
        f.at(1.0, 1.0, 0.0),
        f.at(1.0, 0.0, 0.0),
        f.at(0.0, 1.0, 0.0),
    ];
    for bad in [&folded, &bow_tie] {
        let err = face.clip(bad).unwrap_err();
        assert!(
            matches!(
                err,
                ClipError::NotConvex {
                    role: Role::Master,
                    ..
                }
            ),
            "{err}"
        );
        let err = SlaveFace::new(bad).unwrap_err();
        assert!(
            matches!(
                err,
                ClipError::NotConvex {
                    role: Role::Slave,
                    ..
                } | ClipError::DegenerateSlave { .. }
            ),
            "{err}"
        );
    }
    let err = SlaveFace::new(&folded).unwrap_err();
    assert!(
        matches!(
            err,
            ClipError::NotConvex {
                role: Role::Slave,
                ..
            }
        ),
        "{err}"
    );
    let mut nan = slave.clone();
    nan[2][1] = f64::NAN;
    assert_eq!(
        face.clip(&nan).unwrap_err(),
        ClipError::NonFinite {
            role: Role::Master,
            node: 2
        }
    );
    assert_eq!(
        SlaveFace::new(&nan).unwrap_err(),
        ClipError::NonFinite {
            role: Role::Slave,
            node: 2
        }
    );
    assert_eq!(
        face.clip(&slave[..2]).unwrap_err(),
        ClipError::NodeCount {
            role: Role::Master,
            count: 2
        }
    );
    let collapsed = vec![
        f.at(0.0, 0.0, 0.0),
        f.at(1.0, 0.0, 0.0),
        f.at(2.0, 0.0, 0.0),
    ];
    assert!(matches!(
        SlaveFace::new(&collapsed).unwrap_err(),
        ClipError::DegenerateSlave { .. }
    ));
}
