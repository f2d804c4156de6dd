//! Whirl: rotordynamics with hysteretic damping treated properly.
//!
//! The layers, lowest first; each module imports only from those before it:
//!
//! 1. `linalg`: the thin layer over faer, the only module that imports it.
//! 2. `model`: the request as it arrives (`api`: serde + OpenAPI types; `json`: bodies read
//!    strictly) and its validation into domain types and tasks (`task`).
//! 3. `system`: the assembled rotor in complex coordinates, the currency of what follows.
//! 4. `fem`: Timoshenko elements, assembly into a system, Guyan reduction, undamped modes.
//! 5. `damping`: the damping models (viscous, hysteretic, equivalent, nonviscous) on a system.
//! 6. `analysis`: poles, Campbell, stability, time and unbalance responses, the audit; a task
//!    run to its outcome (`run`).
//! 7. `answer`: an outcome in the wire types its endpoint returns (`Output`), or why there is
//!    none (`ApiError`, with its problem).
//! 8. `render`: an answer as a document: a table, an SVG plot, the HTML report.
//! 9. `studies`: a job request over many values of its parameters: designs (grid, Monte
//!    Carlo, Latin hypercube), JSON pointers, the statistics of the outputs.
//! 10. `jobs`: where analyses run off the request: the worker pool, the job store (SQLite or
//!     PostgreSQL), this replica's runner, the counters of `/metrics`; a study's samples as jobs.
//! 11. `service`: HTTP: routes, configuration, errors as problems, OpenAPI, middleware; the
//!     only layer that knows HTTP.
//!
//! Data flows one way: api types -> validated model -> assembled system -> damping model ->
//! analysis -> answer -> rendering, served (synchronously or as a job) by `service`.

pub mod analysis;
pub mod answer;
pub mod damping;
pub mod fem;
pub mod jobs;
pub mod linalg;
pub mod model;
pub mod render;
pub mod service;
pub mod studies;
pub mod system;
