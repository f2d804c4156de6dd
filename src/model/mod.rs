//! The request as it arrives (`api`, serde + OpenAPI schemas) and its validation into domain
//! types that cannot be physically invalid (`rotor`, `damping`, `speeds`).
//!
//! Validation collects every bad field with its JSON path and a reason, instead of stopping at
//! the first, so that a client fixes its request in one round trip.

pub mod api;
pub mod beam;
pub mod coupling;
pub mod damping;
pub mod error;
pub mod gear;
pub mod jeffcott;
pub mod json;
pub mod limits;
pub mod loads;
pub mod objects;
pub mod pchip;
pub mod point_masses;
pub mod pwl;
pub mod ross;
pub mod rotor;
pub mod shaft;
pub mod speeds;
pub mod spline;
pub mod supports;
pub mod tagged;
pub mod task;
pub mod torque;
pub mod train;

pub use error::{FieldError, Invalid};
pub use limits::{Cost, Limits};
pub use task::{Model, Task, TaskKind};
