//! flockpath: swarm-intelligence crowd planners you can draw scenes for, run, measure and render.
//!
//! The core is plain Rust with no web types: a [`Scene`] is validated and turned into a [`World`]
//! (agent state as struct-of-arrays, a fixed step, one seeded generator), planners steer groups,
//! [`sim::metrics`] measures the run and [`render`] rasterises it. A [`sim::run::Run`] keeps a
//! world with its recording, timeline and metric series in step: `web` (wasm32 only) wraps one
//! with a renderer for the page, and `src/bin/flockpath/` (the command line) drives one too.
//!
//! Layers, bottom up; each uses only those before it (`tests/hygiene.rs` holds the table):
//!
//! | layer | what it is |
//! |---|---|
//! | [`rng`], [`digest`], [`csv`] | the one seeded, portable generator; the one fingerprint of bit patterns; CSV fields (leaves) |
//! | [`model`] | what users draw and share: scene, geometry, planner parameters, codec, edits, presets |
//! | [`spatial`] | neighbour queries: the agents' grid, the obstacle index, the flow field |
//! | [`optim`] | optimizers on R^d and benchmark functions (a leaf beside the crowd) |
//! | [`planners`] | the Planner trait and one file per planner |
//! | [`sim`] | a run: the world's step, spawn, cost limits, metrics, one bounded series, recording, replay, comparison, and [`sim::run::Run`] (what the page and the CLI drive), budgets in [`sim::limits`] |
//! | [`experiments`], [`tune`], [`render`], [`export`] | tables, GA tuning, pixels, files |
//! | [`package`] | a store-only zip and the SCORM 1.2 package of an activity (what an LMS grades) |
//! | `web` | wasm32 only: conversion and errors for the pages |
//!
//! ```
//! use flockpath::{presets, World};
//!
//! let scene = (presets::find("open-field").expect("preset").build)();
//! let mut world = World::new(scene).expect("valid scene");
//! world.step_n(600);
//! let m = world.metrics();
//! assert_eq!(m.steps, 600);
//! assert!(m.overall.arrived_share > 0.5);
//! ```

pub mod csv;
pub mod digest;
pub mod experiments;
pub mod export;
pub mod model;
pub mod optim;
pub mod package;
pub mod planners;
pub mod render;
pub mod rng;
pub mod sim;
pub mod spatial;
pub mod tune;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use model::codec::{
    scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment, scene_to_json,
};
pub use model::geometry::Obstacle;
pub use model::params::{PlannerConfig, PlannerKind};
pub use model::presets;
pub use model::scene::{Goal, Group, Region, Scene, SceneError, ViewOptions, DT};
pub use planners::Planner;
pub use sim::metrics::{GroupMetrics, Metrics};
pub use sim::world::World;
