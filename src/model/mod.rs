//! What users draw and share, with no running simulation: the scene (bounds, obstacles, goals,
//! groups, seed, the time step), geometry, each group's planner choice and parameter tables as
//! plain data, the codec (JSON and the versioned URL fragment), edit operations, presets, and the
//! classroom options a link carries beside the scene (controls shown, parts locked, panels hidden).
//!
//! Layer: model. Uses `rng` only (presets scatter obstacles); every layer above uses it.

pub mod activity;
pub mod classroom;
pub mod codec;
pub mod edit;
pub mod forces_cases;
pub mod geometry;
pub mod link;
pub mod palette;
pub mod params;
pub mod presets;
pub mod refusal;
pub mod scene;
pub mod shape;
