//! The solver's output: everything a solved [`crate::Solution`] is written
//! as, and how files are written.
//!
//! * [`contact_table`](mod@contact_table): the nodal contact table of a
//!   state in either dimension ([`ContactTable`]: pressure, gap and
//!   projection at every slave node), behind `contact.csv` and the `.vtu`
//!   contact fields; each dimension's table is its contact element's
//!   (`crate::contact::nodal_contact` for segments,
//!   `crate::contact::FaceLayout::nodal_table` for faces);
//! * [`vtu`]: the ASCII VTK unstructured grid of a state (`.vtu`);
//! * [`contact_csv`](mod@contact_csv): `contact.csv`, the nodal contact table as CSV;
//! * [`reactions_csv`](mod@reactions_csv): `reactions.csv`, the support groups' reactions at
//!   every converged step;
//! * [`pvd`]: the ParaView collection of a solve's step files (`.pvd`);
//! * [`csv`]: CSV fields (the one quoting rule of both CSV files);
//! * [`atomic`]: atomic file output (every file `gapsim run --out` and
//!   `gapsim study --out` write goes through [`write_atomic`] or
//!   [`replace_with`]).
//!
//! This is the top layer of the solver: it reads the solution (and
//! contact's nodal tables), and nothing below imports from it.

pub mod atomic;
pub mod contact_csv;
pub mod contact_table;
pub mod csv;
pub mod pvd;
pub mod reactions_csv;
pub mod vtu;

pub use atomic::{replace_with, write_atomic};
pub use contact_csv::contact_csv;
pub use contact_table::{ContactTable, ContactTableError, FrictionTable, RowFriction};
pub use pvd::pvd_string;
pub use reactions_csv::reactions_csv;
pub use vtu::{vtu_string, write_vtu, write_vtu_state};
