//! What the contact element reports of its integration points and
//! multipliers: a point's identity ([`ContactPointId`], in errors and
//! cut-back reasons), a 2D point's projection at the final state
//! ([`ContactPointReport`]) and a multiplier's pair and slave node
//! ([`MultiplierDofInfo`]). [`crate::solution`] re-exports them.

/// Identifies one slave integration point: of a slave segment and a
/// master segment in 2D, of a slave face and a master face in 3D
/// (`on_faces`; the fields keep their 2D names).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ContactPointId {
    /// Contact pair index.
    pub pair: usize,
    /// Slave segment (face) index within the pair.
    pub slave_segment: usize,
    /// Gauss point (rule point) index within the segment (face).
    pub gauss: usize,
    /// The master segment (face) involved, if any.
    pub master_segment: Option<usize>,
    /// A point of a 3D face pair.
    pub on_faces: bool,
}

impl std::fmt::Display for ContactPointId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (element, point) = if self.on_faces {
            ("face", "point")
        } else {
            ("segment", "Gauss point")
        };
        write!(
            f,
            "pair {}, slave {element} {}, {point} {}",
            self.pair, self.slave_segment, self.gauss
        )?;
        if let Some(m) = self.master_segment {
            write!(f, ", master {element} {m}")?;
        }
        Ok(())
    }
}

/// One multiplier dof.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MultiplierDofInfo {
    /// Contact pair.
    pub pair: usize,
    /// The slave node it lives at.
    pub node: usize,
}

/// One slave integration point at the final state, re-projected exactly
/// (projection kernel) after the last step, whatever the method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPointReport {
    /// Contact pair.
    pub pair: usize,
    /// Slave segment index within the pair.
    pub slave_segment: usize,
    /// Gauss point index.
    pub gauss: usize,
    /// Parametric coordinate on the slave segment.
    pub xi_s: f64,
    /// The slave segment's nodes.
    pub slave_nodes: [usize; 2],
    /// The master segment it projects into (`None`: unpaired).
    pub master_segment: Option<usize>,
    /// That segment's nodes.
    pub master_nodes: Option<[usize; 2]>,
    /// The projection coordinate.
    pub xi_m: Option<f64>,
    /// The exact gap.
    pub gap: Option<f64>,
}
