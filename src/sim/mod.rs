//! A deterministic run of a scene: the world (struct-of-arrays agent state, spawn, the
//! two-phase fixed step that calls the planners, and in `sweep` the move of one agent, which
//! never passes through an obstacle), its cost limits, metrics and the fitness
//! measures, diagnosis of one agent, and the run's timeline (one bounded series that halves
//! when full, the recording, the metric series, the replay, lockstep comparison), a `Run` that keeps
//! a world and its recording, replay and metric series in step for the page and the command
//! line, the budgets and limits of the front-ends in `limits`, and the check of a scene's
//! activity goal on the metrics (`activity_check`), and the notice that a goal is too small for
//! its crowd (`capacity_notice`).
//!
//! Layer: sim. Uses `model`, `spatial`, `planners` and `rng`.

pub mod activity_check;
pub mod capacity_notice;
pub mod compare;
pub mod cost;
pub mod diagnose;
pub mod fitness;
pub mod gather;
pub mod limits;
pub mod metric_series;
pub mod metrics;
pub mod recording;
pub mod replay;
pub mod run;
pub mod series;
pub mod spawn;
pub mod sweep;
pub mod world;
