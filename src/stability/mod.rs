//! Where the kernels' accuracy ends: the stability sweep.
//!
//! The Type 6 kernels (the exact gap, gradient and Hessian) of both
//! formulations, evaluated in f64 by [`contact_kernels::Kernel`], against a
//! reference computed from the same f64 inputs in double-double precision
//! with exact hyper-dual differentiation ([`reference`]), over the hard
//! families:
//!
//! | family | parameter | values |
//! |---|---|---|
//! | `offset` | distance of the pair from the origin | 1 .. 1e8 |
//! | `scale` | size of the pair (segments and gap scaled together) | 1e-8 .. 1e8 |
//! | `angle` | `90° - angle` between master and slave | 90° .. 0.01° |
//! | `end` | distance `1 - xi_m` of the projection from the master end | 0.1 .. 0 |
//! | `gap` | the gap, with unit segments | 1 .. 1e-14 |
//!
//! Each value is 32 seeded configurations (segments of length about 1 at
//! random orientation, `xi_s` and `xi_m` in (-0.8, 0.8), master tilted by
//! up to 10° unless the family sets it); the errors are the worst over
//! them: `|g - g_ref| / |g_ref|`, and for the gradient and the Hessian the
//! largest entry error over the largest reference entry. A configuration
//! the kernel refuses (an error such as `NoProjection`) is counted, not
//! compared.
//!
//! [`faces`] does the same for the 3D face kernels (tri3 and quad4, both
//! readings) against [`face_reference`], over [`Family::FACES`].

use std::fmt::Write as _;

use contact_kernels::{ApproxType, Formulation, GapOut, Kernel, pair_formulations};

pub mod dd;
pub mod face_reference;
pub mod faces;
pub mod hyper;
pub mod plot;
pub mod reference;

use reference::reference;

/// A family of hard configurations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Far from the origin.
    Offset,
    /// Tiny or huge.
    Scale,
    /// Master nearly perpendicular to slave.
    Angle,
    /// Projection near or at the master segment's end.
    End,
    /// Small gaps.
    Gap,
    /// Projection near or on a master face's edge (3D).
    Edge,
    /// Projection near or at a master face's corner (3D).
    Corner,
}

impl Family {
    /// Every family, in table order.
    pub const ALL: [Family; 5] = [
        Family::Offset,
        Family::Scale,
        Family::Angle,
        Family::End,
        Family::Gap,
    ];

    /// The families of the face sweep ([`faces`]), in table order.
    pub const FACES: [Family; 6] = [
        Family::Offset,
        Family::Scale,
        Family::Angle,
        Family::Edge,
        Family::Corner,
        Family::Gap,
    ];

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Family::Offset => "offset",
            Family::Scale => "scale",
            Family::Angle => "angle",
            Family::End => "end",
            Family::Gap => "gap",
            Family::Edge => "edge",
            Family::Corner => "corner",
        }
    }

    /// What its parameter is.
    pub fn parameter(self) -> &'static str {
        match self {
            Family::Offset => "distance from the origin",
            Family::Scale => "scale",
            Family::Angle => "90° - angle (degrees)",
            Family::End => "1 - xi_m",
            Family::Gap => "gap",
            Family::Edge => "distance of xi_m from a master edge",
            Family::Corner => "distance of xi_m from a master corner",
        }
    }

    /// The parameter values.
    pub fn values(self) -> &'static [f64] {
        match self {
            Family::Offset => &[1.0, 1e2, 1e4, 1e6, 1e8],
            Family::Scale => &[1e-8, 1e-4, 1.0, 1e4, 1e8],
            Family::Angle => &[90.0, 30.0, 10.0, 1.0, 0.1, 0.01],
            Family::End => &[0.1, 1e-4, 1e-8, 0.0],
            Family::Gap => &[1.0, 1e-2, 1e-4, 1e-8, 1e-14],
            Family::Edge | Family::Corner => &[0.1, 1e-4, 1e-8, 0.0],
        }
    }

    /// The parameter values of the face sweep: those of [`Family::values`],
    /// with a master tilted 85° (`90° - tilt = 5`) among the angles.
    pub fn face_values(self) -> &'static [f64] {
        match self {
            Family::Angle => &[90.0, 30.0, 10.0, 5.0, 1.0, 0.1, 0.01],
            _ => self.values(),
        }
    }
}

/// One configuration's geometry before the family's transformation.
struct Geometry {
    gap: f64,
    /// Master tilt against anti-parallel, degrees.
    tilt: f64,
    xi_m: f64,
    scale: f64,
    offset: f64,
}

/// A small deterministic generator.
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// A configuration: slave of length about 1 at a random orientation, the
/// master through the point at distance `gap` along the slave normal,
/// tilted by `tilt`, with that point at `xi_m`; scaled, then moved
/// `offset` away from the origin.
fn configuration(g: &Geometry, rng: &mut Lcg) -> ([f64; 8], f64) {
    let theta = rng.uniform(0.0, std::f64::consts::TAU);
    let len_s = rng.uniform(0.8, 1.2);
    let len_m = rng.uniform(0.8, 1.2);
    let xi_s = rng.uniform(-0.8, 0.8);
    let ts = [theta.cos(), theta.sin()];
    let xs1 = [rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)];
    let xs2 = [xs1[0] + len_s * ts[0], xs1[1] + len_s * ts[1]];
    let x_s = [
        xs1[0] + (1.0 + xi_s) / 2.0 * len_s * ts[0],
        xs1[1] + (1.0 + xi_s) / 2.0 * len_s * ts[1],
    ];
    let n = [ts[1], -ts[0]];
    let p = [x_s[0] + g.gap * n[0], x_s[1] + g.gap * n[1]];
    let a = g.tilt.to_radians();
    // anti-parallel to the slave, tilted
    let tm = [
        -(ts[0] * a.cos() - ts[1] * a.sin()),
        -(ts[0] * a.sin() + ts[1] * a.cos()),
    ];
    let before = (1.0 + g.xi_m) / 2.0 * len_m;
    let after = (1.0 - g.xi_m) / 2.0 * len_m;
    let xm1 = [p[0] - before * tm[0], p[1] - before * tm[1]];
    let xm2 = [p[0] + after * tm[0], p[1] + after * tm[1]];
    let phi = rng.uniform(0.0, std::f64::consts::TAU);
    let shift = [g.offset * phi.cos(), g.offset * phi.sin()];
    let mut q = [
        xs1[0], xs1[1], xs2[0], xs2[1], xm1[0], xm1[1], xm2[0], xm2[1],
    ];
    for (i, v) in q.iter_mut().enumerate() {
        *v = *v * g.scale + shift[i % 2];
    }
    (q, xi_s)
}

/// Configurations per parameter value.
pub const CONFIGURATIONS: usize = 32;

/// The worst errors of one (family, value, formulation).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    /// The family.
    pub family: Family,
    /// Its parameter value.
    pub value: f64,
    /// The formulation.
    pub formulation: Formulation,
    /// Worst relative error of the gap (`None` if every configuration was
    /// refused).
    pub gap: Option<f64>,
    /// Worst relative error of the gradient.
    pub grad: Option<f64>,
    /// Worst relative error of the Hessian.
    pub hess: Option<f64>,
    /// Configurations the kernel refused, and the first refusal.
    pub refused: usize,
    /// The first refusal's message.
    pub refusal: Option<String>,
}

fn geometry(family: Family, value: f64, rng: &mut Lcg) -> Geometry {
    let mut g = Geometry {
        gap: 0.1,
        tilt: rng.uniform(-10.0, 10.0),
        xi_m: rng.uniform(-0.8, 0.8),
        scale: 1.0,
        offset: 0.0,
    };
    match family {
        Family::Offset => g.offset = value,
        Family::Scale => g.scale = value,
        Family::Angle => g.tilt = 90.0 - value,
        Family::End => g.xi_m = 1.0 - value,
        Family::Gap => g.gap = value,
        // Face families (the face sweep's).
        Family::Edge | Family::Corner => {}
    }
    g
}

/// Runs the sweep over every family, value and compiled formulation.
pub fn sweep() -> Vec<SweepRow> {
    let mut rows = Vec::new();
    for family in Family::ALL {
        for &value in family.values() {
            for formulation in pair_formulations() {
                rows.push(sweep_one(family, value, formulation));
            }
        }
    }
    rows
}

/// `max |a - b| / max |b|` over the entries.
fn normwise(a: &[f64], b: &[dd::Dd]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.to_f64().abs()));
    let err = a.iter().zip(b).fold(0.0_f64, |m, (x, r)| {
        m.max((dd::Dd::from_f64(*x) - *r).abs().to_f64())
    });
    err / scale
}

fn sweep_one(family: Family, value: f64, formulation: Formulation) -> SweepRow {
    sweep_row(
        family,
        value,
        formulation,
        0x5eed ^ value.to_bits(),
        |rng| configuration(&geometry(family, value, rng), rng),
        |q, xi_s, _| {
            let r = reference(formulation, q, xi_s);
            (r.gap, r.grad.to_vec(), r.hess.to_vec())
        },
    )
}

/// One row of a sweep (2D or faces): [`CONFIGURATIONS`] configurations
/// `(q, xi_s)` drawn by `sample` from the generator seeded `seed`, each
/// evaluated by the Type 6 kernel of `formulation` and compared with the
/// double-double `reference` (gap, gradient, Hessian) of the
/// configuration and the kernel's output; a configuration the kernel
/// refuses is counted, not compared.
fn sweep_row<Q: AsRef<[f64]>, X: contact_kernels::XiArg + Copy>(
    family: Family,
    value: f64,
    formulation: Formulation,
    seed: u64,
    mut sample: impl FnMut(&mut Lcg) -> (Q, X),
    reference: impl Fn(&Q, X, &GapOut) -> (dd::Dd, Vec<dd::Dd>, Vec<dd::Dd>),
) -> SweepRow {
    let kernel = Kernel::new(formulation, ApproxType::Type6).expect("compiled formulation");
    let mut out = GapOut::new(&kernel);
    let mut rng = Lcg(seed);
    let mut row = SweepRow {
        family,
        value,
        formulation,
        gap: None,
        grad: None,
        hess: None,
        refused: 0,
        refusal: None,
    };
    let worse = |slot: &mut Option<f64>, e: f64| *slot = Some(slot.map_or(e, |m| m.max(e)));
    for _ in 0..CONFIGURATIONS {
        let (q, xi_s) = sample(&mut rng);
        if let Err(e) = kernel.eval(q.as_ref(), xi_s, &mut out) {
            row.refused += 1;
            row.refusal.get_or_insert_with(|| e.to_string());
            continue;
        }
        let (gap, grad, hess) = reference(&q, xi_s, &out);
        let gap_err = (dd::Dd::from_f64(out.gap()) - gap).abs().to_f64() / gap.abs().to_f64();
        worse(&mut row.gap, gap_err);
        worse(&mut row.grad, normwise(out.grad(), &grad));
        worse(&mut row.hess, normwise(out.hess().expect("Type 6"), &hess));
    }
    row
}

fn sci(v: Option<f64>) -> String {
    v.map_or_else(|| "–".to_string(), |v| format!("{v:.1e}"))
}

/// The sweep as CSV.
pub fn csv(rows: &[SweepRow]) -> String {
    let mut out =
        String::from("family,value,formulation,gap_error,grad_error,hess_error,refused\n");
    let opt = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:e}"));
    for r in rows {
        let _ = writeln!(
            out,
            "{},{:e},{},{},{},{},{}",
            r.family.name(),
            r.value,
            r.formulation.name(),
            opt(r.gap),
            opt(r.grad),
            opt(r.hess),
            r.refused
        );
    }
    out
}

/// The sweep as a Markdown table (one row per family value, both
/// formulations side by side).
pub fn markdown(rows: &[SweepRow]) -> String {
    table(rows, &Family::ALL, Family::values, &pair_formulations())
}

/// The face sweep ([`faces::sweep_faces`]) as a Markdown table (one row
/// per family value, the four face formulations side by side).
pub fn markdown_faces(rows: &[SweepRow]) -> String {
    table(
        rows,
        &Family::FACES,
        Family::face_values,
        &faces::face_formulations(),
    )
}

fn table(
    rows: &[SweepRow],
    families: &[Family],
    values: fn(Family) -> &'static [f64],
    formulations: &[Formulation],
) -> String {
    let mut out = String::from("| family | parameter |");
    for f in formulations {
        let _ = write!(out, " {f}: g | g' | g'' | refused |");
    }
    out.push('\n');
    out.push_str("|---|---:|");
    for _ in formulations {
        out.push_str("---:|---:|---:|---:|");
    }
    out.push('\n');
    for &family in families {
        for &value in values(family) {
            let _ = write!(
                out,
                "| {} | {} = {value:e} |",
                family.name(),
                family.parameter()
            );
            for f in formulations {
                if let Some(r) = rows
                    .iter()
                    .find(|r| r.family == family && r.value == value && r.formulation == *f)
                {
                    let _ = write!(
                        out,
                        " {} | {} | {} | {}/{CONFIGURATIONS} |",
                        sci(r.gap),
                        sci(r.grad),
                        sci(r.hess),
                        r.refused
                    );
                }
            }
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On benign configurations the f64 kernels agree with the
    /// double-double reference to roundoff, so the reference is the same
    /// function; and the families are seeded (the same numbers every run).
    #[test]
    fn benign_configurations_agree_to_roundoff() {
        for f in pair_formulations() {
            let row = sweep_one(Family::Offset, 1.0, f);
            assert_eq!(row.refused, 0);
            assert!(row.gap.unwrap() < 1e-12, "{row:?}");
            assert!(row.grad.unwrap() < 1e-12, "{row:?}");
            assert!(row.hess.unwrap() < 1e-12, "{row:?}");
            assert_eq!(row, sweep_one(Family::Offset, 1.0, f));
        }
    }

    /// Far from the origin the relative coordinates keep the derivatives
    /// exact to roundoff of the (rounded) inputs; the gap loses what the
    /// input rounding loses (the sweep's first finding).
    #[test]
    fn offset_keeps_the_derivatives() {
        for f in pair_formulations() {
            let row = sweep_one(Family::Offset, 1e8, f);
            assert_eq!(row.refused, 0);
            assert!(row.hess.unwrap() < 1e-8, "{row:?}");
        }
    }
}
