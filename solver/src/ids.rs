//! Typed indices for the index spaces that meet in the solver.
//!
//! Each is a `usize` in a newtype, so that a value of one space cannot be
//! used where another is meant without saying so (`index()` gives the raw
//! value for indexing a slice of that space; `new` wraps one):
//!
//! | type | space | slices it indexes |
//! |---|---|---|
//! | [`NodeId`] | mesh nodes, body after body | `Mesh::nodes_ref`, `u` by `DofId::of` |
//! | [`ElementId`] | mesh elements, body after body | `Mesh::elements`, `Mesh::geometry` |
//! | [`DofId`] | displacement dofs, `D node + component` in `D` dimensions | `u`, `Model::prescribed[].dof` |
//! | [`EquationIndex`] | rows/columns of the Newton system | `System::residual`, `dx` |
//! | [`MultiplierIndex`] | multiplier dofs, pair by pair | `lambda`, `ContactLayout::multipliers` |
//! | [`ContactPointIndex`] | slave integration points | `ContactLayout::points`, pairings, evaluations |
//! | [`PairId`] | contact pairs | `Model::contacts`, per-pair tables of the layout |
//! | [`MasterSegmentIndex`] | master segments of one pair, along its chain | `ContactPair::master`, pairings |
//! | [`MasterFaceIndex`] | master faces of one 3D pair | `ContactPair::master`, 3D pairings |
//! | [`AmplitudeId`] | load curves of a model | `Model::amplitudes` |
//!
//! The equation numbering is owned by [`crate::system::DofMap`]: free dofs
//! first (in dof order), then the multipliers, then one equation per node tie
//! of the complete formulation. The node and element numbering is owned by
//! [`crate::mesh::Mesh`] (bodies in the order they were appended). Body
//! indices, body-local node numbers of a generator's connectivity and slave
//! segments (which only reports name) stay plain `usize`; reports in
//! [`crate::solution`] and error variants keep plain `usize` fields too,
//! converted where they are written.

macro_rules! index_type {
    ($(#[$meta:meta])* $name:ident) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name(usize);

        impl $name {
            /// Wraps a raw index.
            #[inline]
            pub const fn new(index: usize) -> $name {
                $name(index)
            }

            /// The raw index.
            #[inline]
            pub const fn index(self) -> usize {
                self.0
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.0.fmt(f)
            }
        }
    };
}

index_type!(
    /// A mesh node (index into [`Mesh::nodes_ref`](crate::mesh::Mesh::nodes_ref));
    /// its dofs are [`DofId::in_dim`]`::<D>(node, 0..D)`.
    NodeId
);

index_type!(
    /// A mesh element (index into [`Mesh::elements`](crate::mesh::Mesh::elements)
    /// and [`Mesh::geometry`](crate::mesh::Mesh::geometry)).
    ElementId
);

index_type!(
    /// A displacement degree of freedom: `D node + component` in a mesh of
    /// `D` dimensions (component 0 is `x`, 1 is `y`, 2 is `z`).
    DofId
);

impl DofId {
    /// The dof of `component` (0: `x`, 1: `y`, 2: `z`) of `node` in `D`
    /// dimensions: `D node + component`, the one dof formula.
    #[inline]
    pub const fn in_dim<const D: usize>(node: NodeId, component: usize) -> DofId {
        DofId(D * node.0 + component)
    }

    /// The node this dof belongs to in `D` dimensions.
    #[inline]
    pub const fn node_in<const D: usize>(self) -> NodeId {
        NodeId(self.0 / D)
    }

    /// Its component in `D` dimensions (0: `x`, 1: `y`, 2: `z`).
    #[inline]
    pub const fn component_in<const D: usize>(self) -> usize {
        self.0 % D
    }

    /// The dof of `component` (0: `x`, 1: `y`) of `node` in 2D
    /// ([`DofId::in_dim`] with `D = 2`).
    #[inline]
    pub const fn of(node: NodeId, component: usize) -> DofId {
        DofId::in_dim::<2>(node, component)
    }

    /// The node this dof belongs to in 2D.
    #[inline]
    pub const fn node(self) -> NodeId {
        self.node_in::<2>()
    }

    /// Its component in 2D (0: `x`, 1: `y`).
    #[inline]
    pub const fn component(self) -> usize {
        self.component_in::<2>()
    }
}

index_type!(
    /// A row (and column) of the Newton system (see
    /// [`crate::system::DofMap`]).
    EquationIndex
);

index_type!(
    /// A multiplier dof (index into
    /// [`ContactLayout::multipliers`](crate::contact::ContactLayout::multipliers)
    /// and the multiplier vector).
    MultiplierIndex
);

index_type!(
    /// A slave integration point (index into
    /// [`ContactLayout::points`](crate::contact::ContactLayout::points)).
    ContactPointIndex
);

index_type!(
    /// A contact pair (index into [`Model::contacts`](crate::Model::contacts)).
    PairId
);

index_type!(
    /// A master segment of one contact pair (index into its
    /// [`ContactPair::master`](crate::model::ContactPair::master) list).
    MasterSegmentIndex
);

index_type!(
    /// A master face of one 3D contact pair (index into its
    /// [`ContactPair::master`](crate::model::ContactPair::master) list).
    MasterFaceIndex
);

index_type!(
    /// A load curve of a model (index into
    /// [`Model::amplitudes`](crate::Model::amplitudes)).
    AmplitudeId
);
