//! Load curves (amplitudes): a scale factor as a piecewise linear function of
//! the load factor, as the tabular amplitudes of Abaqus and CalculiX.
//!
//! An amplitude is a table of points `(L_0, a_0), ..., (L_n, a_n)` with at
//! least two points, strictly increasing load factors `L_0 < L_1 < ... < L_n`
//! and finite values ([`Amplitude::new`] checks this). A load, traction or
//! prescribed displacement that carries one has the value
//! `value * a(L)` at load factor `L` instead of the proportional
//! `L * value`, where
//!
//! ```text
//! a(L) = a_0                                          L <  L_0
//! a(L) = a_i + (L - L_i) / (L_{i+1} - L_i) (a_{i+1} - a_i)   L_i <= L < L_{i+1}
//! a(L) = a_n                                          L >= L_n
//! ```
//!
//! Outside the table the end values are held (constant extrapolation, as
//! Abaqus does). The segments are half-open, so at a table point the value
//! is that point's `a_i` exactly, and on a plateau (`a_i = a_{i+1}`) every
//! load factor gives `a_i` exactly: a step across a plateau changes nothing,
//! to the bit.

/// Why a table is not an amplitude.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum AmplitudeError {
    /// Fewer than two points.
    #[error("needs at least two points [load_factor, value], got {count}")]
    TooFewPoints {
        /// The number of points given.
        count: usize,
    },
    /// A load factor or value that is NaN or infinite.
    #[error("point {index}: load factor and value must be finite")]
    NonFinite {
        /// The point (0-based).
        index: usize,
    },
    /// A load factor not above the previous point's.
    #[error("point {index}: load factors must increase")]
    NotIncreasing {
        /// The point (0-based) whose load factor is not above its
        /// predecessor's.
        index: usize,
    },
}

impl AmplitudeError {
    /// What is wrong, without the point (for messages that name the point
    /// themselves, e.g. `load[1].amplitude[2]: load factors must
    /// increase`).
    pub fn reason(&self) -> &'static str {
        match self {
            AmplitudeError::TooFewPoints { .. } => "needs at least two points [load_factor, value]",
            AmplitudeError::NonFinite { .. } => "load factor and value must be finite",
            AmplitudeError::NotIncreasing { .. } => "load factors must increase",
        }
    }

    /// The point the error is about, if one.
    pub fn point(&self) -> Option<usize> {
        match *self {
            AmplitudeError::TooFewPoints { .. } => None,
            AmplitudeError::NonFinite { index } | AmplitudeError::NotIncreasing { index } => {
                Some(index)
            }
        }
    }
}

/// A checked load curve (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Amplitude {
    /// `(load factor, value)` points, load factors strictly increasing.
    points: Vec<[f64; 2]>,
}

impl Amplitude {
    /// The amplitude of `points` (`[load factor, value]`), checked: at
    /// least two points, all finite, load factors strictly increasing.
    pub fn new(points: Vec<[f64; 2]>) -> Result<Amplitude, AmplitudeError> {
        if points.len() < 2 {
            return Err(AmplitudeError::TooFewPoints {
                count: points.len(),
            });
        }
        for (index, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(AmplitudeError::NonFinite { index });
            }
            if index > 0 && !(p[0] > points[index - 1][0]) {
                return Err(AmplitudeError::NotIncreasing { index });
            }
        }
        Ok(Amplitude { points })
    }

    /// The table's points.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The amplitude at load factor `load_factor` (module docs; a NaN load
    /// factor gives NaN).
    pub fn at(&self, load_factor: f64) -> f64 {
        let p = &self.points;
        let last = p.len() - 1;
        if load_factor.is_nan() {
            return f64::NAN;
        }
        if load_factor < p[0][0] {
            return p[0][1];
        }
        if load_factor >= p[last][0] {
            return p[last][1];
        }
        // the segment [L_i, L_{i+1}) holding the load factor
        let i = p.partition_point(|q| q[0] <= load_factor) - 1;
        let [l0, a0] = p[i];
        let [l1, a1] = p[i + 1];
        a0 + (load_factor - l0) / (l1 - l0) * (a1 - a0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn press_slide() -> Amplitude {
        Amplitude::new(vec![[0.0, 0.0], [0.2, 1.0], [1.0, 1.0]]).unwrap()
    }

    #[test]
    fn interpolates_linearly_between_points() {
        let a = Amplitude::new(vec![[0.0, 0.0], [0.5, 1.0], [1.0, -1.0]]).unwrap();
        assert_eq!(a.at(0.25), 0.5);
        assert_eq!(a.at(0.75), 0.0);
        assert!((a.at(0.6) - 0.6).abs() < 1e-15);
    }

    #[test]
    fn table_points_and_plateaus_are_exact() {
        let a = Amplitude::new(vec![[0.0, 0.1], [0.3, 0.7], [0.7, 0.3], [1.0, 0.3]]).unwrap();
        for [l, v] in [[0.0, 0.1], [0.3, 0.7], [0.7, 0.3], [1.0, 0.3]] {
            assert_eq!(a.at(l), v, "at {l}");
        }
        for l in [0.7000001, 0.75, 0.8, 0.9, 0.99999] {
            assert_eq!(a.at(l), 0.3, "plateau at {l}");
        }
        let s = press_slide();
        for k in 2..=10 {
            assert_eq!(s.at(k as f64 / 10.0), 1.0);
        }
    }

    #[test]
    fn holds_the_end_values_outside_the_table() {
        let a = Amplitude::new(vec![[0.1, 2.0], [0.4, 3.0]]).unwrap();
        assert_eq!(a.at(0.0), 2.0);
        assert_eq!(a.at(-5.0), 2.0);
        assert_eq!(a.at(0.4), 3.0);
        assert_eq!(a.at(7.0), 3.0);
        assert!(a.at(f64::NAN).is_nan());
    }

    #[test]
    fn rejects_bad_tables_naming_the_point() {
        assert_eq!(
            Amplitude::new(vec![[0.0, 1.0]]),
            Err(AmplitudeError::TooFewPoints { count: 1 })
        );
        assert_eq!(
            Amplitude::new(vec![]),
            Err(AmplitudeError::TooFewPoints { count: 0 })
        );
        let e = Amplitude::new(vec![[0.0, 0.0], [0.5, 1.0], [0.5, 2.0]]).unwrap_err();
        assert_eq!(e, AmplitudeError::NotIncreasing { index: 2 });
        assert_eq!(e.point(), Some(2));
        assert_eq!(e.to_string(), "point 2: load factors must increase");
        assert_eq!(
            Amplitude::new(vec![[0.0, 0.0], [0.5, 1.0], [0.4, 2.0]]),
            Err(AmplitudeError::NotIncreasing { index: 2 })
        );
        assert_eq!(
            Amplitude::new(vec![[0.0, 0.0], [f64::NAN, 1.0]]),
            Err(AmplitudeError::NonFinite { index: 1 })
        );
        assert_eq!(
            Amplitude::new(vec![[0.0, f64::INFINITY], [1.0, 1.0]]),
            Err(AmplitudeError::NonFinite { index: 0 })
        );
    }
}
