//! The service and process tests, one binary (one link of the crate) with a module per area.

#[path = "../cluster/mod.rs"]
mod cluster;
#[path = "../common/mod.rs"]
mod common;

mod build_features;
mod flood;
mod guard;
mod jobs;
mod outage;
mod process;
mod readme_client;
mod readme_settings;
mod server;
mod slow_memory;
mod slow_reader;
mod store_memory;
mod store_postgres;
mod store_sqlite;
mod studies;
mod studies_cluster;
