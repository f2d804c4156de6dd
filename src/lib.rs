//! Whirl: rotordynamics with hysteretic damping treated properly.
//!
//! Data flows one way: `model` (request types and their validation) -> `system` (the assembled
//! rotor in complex coordinates) -> `damping` (hysteretic, equivalent, nonviscous) ->
//! `analysis` (modal, Campbell, stability) -> results, served over HTTP by `service`.
//! `linalg` is the only module that touches faer; only `service` knows HTTP.

pub mod analysis;
pub mod damping;
pub mod fem;
pub mod linalg;
pub mod model;
pub mod service;
pub mod system;
