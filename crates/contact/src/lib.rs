//! stiction-contact: the contact mechanics of a rough MEMS sidewall.
//!
//! * [`single`]: single-asperity laws (Hertz eq. 3, DMT eq. 4, JKR, Maugis-Dugdale) and the Tabor parameter.
//! * [`gw`]: Greenwood-Williamson statistics (eq. 5-9), with and without DMT adhesion.
//! * [`limits`]: elastic limits (section 3.3, eq. 11).
//! * [`capillary`]: capillary condensation (Kelvin radius, meniscus force of a wetted summit).
//! * [`discrete`]: the discrete N-contact model (eq. 12).
//! * [`error`]: the error type [`ContactError`] of the analytic models.
//! * [`explicit`]: the explicit asperity-by-asperity solver with a rigid, tilting shoe.

pub mod capillary;
pub mod discrete;
pub mod error;
pub mod explicit;
pub mod gw;
pub mod limits;
pub mod single;

pub use error::ContactError;
