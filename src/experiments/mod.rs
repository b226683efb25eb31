//! The papers' experiments as data, with no printing: optimizer runs and the Table-3-style
//! summaries, the force-step timing and the paper's Table 4 (`flockpath optimize` prints them).
//!
//! Layer: experiments. Uses `optim`, `model`, `spatial`, `planners`, `sim` and `rng`.

pub mod tables;
pub mod validation;
