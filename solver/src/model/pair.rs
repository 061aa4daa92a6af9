//! A contact pair of either dimension, [`ContactPair<D>`]: a slave and a
//! master surface made of *facets*, the surface elements of the dimension
//! ([`SurfaceDim::Facet`]): 2-node segments in 2D, tri3 and quad4 faces in
//! 3D (as fenris serves segments and faces through one surface-element
//! trait).
//!
//! Sign conventions (docs/conventions.md): a segment's nodes run
//! counter-clockwise around its body, so that the outward normal of a
//! segment with tangent `t` is `(t.y, -t.x)/|t|`; a face's nodes run
//! counter-clockwise seen from outside its body (outward normal
//! `t_1 x t_2`).

use contact_kernels::Formulation;
use serde::{Deserialize, Serialize};

use crate::ids::NodeId;
use crate::mesh::Mesh;
use crate::mesh::volume::Face;

/// The spatial dimension `D` as a type (defined with the mesh, whose
/// blocks are the first thing that differs by it): what differs between
/// the dimensions beyond the sizes `D` fixes is a trait implemented for
/// `Dim<2>` and `Dim<3>` ([`SurfaceDim`] here, `crate::dim::SpaceDim`
/// above the contact element).
pub use crate::mesh::Dim;

/// The surface element of dimension `D` (module docs).
pub trait SurfaceDim<const D: usize> {
    /// A facet: `[NodeId; 2]` in 2D, [`Face<NodeId>`] in 3D.
    type Facet: Facet;

    /// Why `facet` of `mesh` cannot carry contact (its reference size is
    /// zero), `None` if it can. The pair's check in [`crate::model::Model::check`]
    /// asks it of every facet; in 3D the slave faces are checked when
    /// the pair is laid out (`crate::contact::FaceLayout`), so here none.
    fn degenerate(mesh: &Mesh<D>, facet: &Self::Facet) -> Option<String>;
}

/// One facet of a contact surface (module docs).
pub trait Facet: Copy + PartialEq + std::fmt::Debug + Send + Sync + 'static {
    /// What one facet is called in messages: `segment`, `face`.
    const NAME: &'static str;
    /// What a surface of facets is called in messages: `face` (of
    /// segments), `surface` (of faces).
    const SURFACE: &'static str;

    /// Its nodes, in order.
    fn nodes(&self) -> &[NodeId];
}

/// The facet of dimension `D`.
pub type FacetOf<const D: usize> = <Dim<D> as SurfaceDim<D>>::Facet;

impl Facet for [NodeId; 2] {
    const NAME: &'static str = "segment";
    const SURFACE: &'static str = "face";

    fn nodes(&self) -> &[NodeId] {
        self
    }
}

impl Facet for Face<NodeId> {
    const NAME: &'static str = "face";
    const SURFACE: &'static str = "surface";

    fn nodes(&self) -> &[NodeId] {
        Face::nodes(self)
    }
}

impl SurfaceDim<2> for Dim<2> {
    type Facet = [NodeId; 2];

    fn degenerate(mesh: &Mesh<2>, seg: &[NodeId; 2]) -> Option<String> {
        let (a, b) = (mesh.node_ref(seg[0]), mesh.node_ref(seg[1]));
        let d = [a[0] - b[0], a[1] - b[1]];
        // printed as the plain `[a, b]` it always was
        (!(crate::mesh::length(&d) > mesh.coordinate_tolerance()))
            .then(|| format!("segment {:?} has zero length", seg.map(NodeId::index)))
    }
}

impl SurfaceDim<3> for Dim<3> {
    type Facet = Face<NodeId>;

    fn degenerate(_: &Mesh<3>, _: &Face<NodeId>) -> Option<String> {
        None
    }
}

/// How a contact pair integrates over its slave facets
/// (`[[contact]] integration`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integration {
    /// `gauss_points` Gauss points on every slave facet (the default).
    #[default]
    Gauss,
    /// Each slave facet split where the master surface's edges cross it,
    /// `gauss_points` points on every piece: in 2D each slave segment at
    /// the projections of the master nodes
    /// ([`crate::contact::segmented_rule`]), in 3D each slave face clipped
    /// against the master faces projected onto it
    /// ([`crate::contact::FaceLayout`]).
    Segmented,
}

impl Integration {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Integration::Gauss => "gauss",
            Integration::Segmented => "segmented",
        }
    }
}

/// The multiplier basis of a contact pair's slave facets
/// (`[[contact]] multipliers`; docs/conventions.md, "3D faces").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Multipliers {
    /// `lambda(xi_s) = sum_a N_a(xi_s) l_a`, the slave facet's shape
    /// functions (the default; the paper's discretisation).
    #[default]
    Standard,
    /// 3D faces only: the dual (biorthogonal) basis
    /// `psi_a = sum_b A_ab N_b` of each slave face, `A = D M^-1` with
    /// `D = diag(int N_a)` and `M = int N_a N_b` over the face in the
    /// reference configuration, so that `int psi_a N_b = delta_ab int N_b`:
    /// each node's weighted gap couples to its own multiplier only, and
    /// `l_a` is the node's pressure in the mortar sense.
    Dual,
}

/// How a contact pair's constraint is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactMode {
    /// Equality `g = 0` at every paired integration point (frictionless
    /// sliding; the paper's contact).
    #[default]
    Persistent,
    /// Inequality `g >= 0` with compressive pressure `p = -lambda >= 0`
    /// and an active set of multiplier nodes (see [`crate::contact`]).
    Unilateral,
}

impl ContactMode {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            ContactMode::Persistent => "persistent",
            ContactMode::Unilateral => "unilateral",
        }
    }
}

/// One contact pair: a slave and a master surface, each a list of facets
/// (global node indices) in the order of module docs. In 2D the kernel of
/// a pair is its `formulation`; in 3D the solver picks the kernel of each
/// (slave face, master face) pair from the pair's `formulation` (the
/// reading, `slave-normal` or `closest-point`) and the two faces' kinds
/// ([`crate::contact::face_formulation`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair<const D: usize = 2>
where
    Dim<D>: SurfaceDim<D>,
{
    /// A name for reports.
    pub name: String,
    /// Slave facets.
    pub slave: Vec<FacetOf<D>>,
    /// Master facets.
    pub master: Vec<FacetOf<D>>,
    /// The gap formulation (in 3D its reading of the faces).
    pub formulation: Formulation,
    /// Persistent or unilateral.
    pub mode: ContactMode,
    /// Coulomb's coefficient `mu` (0: frictionless; finite, `>= 0`).
    pub friction: f64,
    /// `gauss_points`: on a segment `n` points (1..=8), on a quad4 `n x n`,
    /// on a tri3 `n` (1, 3, 4, 6 or 7); with segmented integration the
    /// rule on each piece (3D: each clipped triangle, 1, 3 or 7). `None`:
    /// the facet kind's default
    /// ([`crate::contact::face_rules::default_points`]: 2 on a segment,
    /// 2 x 2 on a quad4, 3 on a tri3, 7 on a clipped triangle).
    pub gauss_points: Option<usize>,
    /// The rule on the slave facets (see [`Integration`]).
    pub integration: Integration,
    /// The multiplier basis on the slave facets (see [`Multipliers`]).
    pub multipliers: Multipliers,
}
