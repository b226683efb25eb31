//! A deterministic run of a scene: the world (struct-of-arrays agent state, spawn, the
//! two-phase fixed step that calls the planners), its cost limits, metrics and the fitness
//! measures, diagnosis of one agent, and the run's timeline (recording, metric history, replay,
//! lockstep comparison).
//!
//! Layer: sim. Uses `model`, `spatial`, `planners` and `rng`.

pub mod compare;
pub mod cost;
pub mod diagnose;
pub mod fitness;
pub mod history;
pub mod metrics;
pub mod recording;
pub mod replay;
pub mod spawn;
pub mod world;
