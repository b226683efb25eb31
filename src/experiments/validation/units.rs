//! Metres and seconds for the suite: the scale it draws its scenes at, the body size and free
//! speed it gives its walkers, and setting a planner's desired speed in m/s.

use crate::model::params::{PlannerConfig, PlannerKind, SetParamError};
use crate::model::scene::{SceneError, DEFAULT_PX_PER_METRE, DT};

/// Why a test's run could not be set up (before anything was measured).
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The planner has neither a desired speed nor a speed limit to set.
    #[error("{0} has no speed parameter to set")]
    NoSpeedParameter(&'static str),
    /// The walking speed is out of the parameter's range.
    #[error(transparent)]
    Param(#[from] SetParamError),
    /// The world refused the test's scene.
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// Pixels per metre of the suite's scenes: the scenes' default scale (20 px = 1 m), which
/// every scene of the suite states as its `px_per_metre`.
pub const PX_PER_METRE: f32 = DEFAULT_PX_PER_METRE;

/// A walker's body radius (m): a 0.4 m wide body, as in the RiMEA tests.
pub const BODY_RADIUS_M: f32 = 0.2;

/// Free walking speed (m/s), Weidmann (1993).
pub const FREE_SPEED: f32 = 1.34;

/// Metres → px.
pub fn px(metres: f32) -> f32 {
    metres * PX_PER_METRE
}

/// A speed in m/s as px/step (the planners' unit).
pub fn px_per_step(mps: f32) -> f32 {
    mps * PX_PER_METRE * DT
}

/// A velocity in px/step as m/s.
pub fn mps(px_per_step: f32) -> f32 {
    px_per_step / (PX_PER_METRE * DT)
}

/// Keys a planner may use for the speed it wants to walk at (a model with a desired speed
/// below its limit) and for its speed limit.
const DESIRED_KEYS: &[&str] = &["desired_speed", "preferred_speed"];
const LIMIT_KEYS: &[&str] = &["max_speed", "max_velocity"];

/// How much faster than desired a planner with both a desired speed and a limit may go (the
/// social force model's 1.3, Helbing & Molnár 1995).
const LIMIT_OVER_DESIRED: f32 = 1.3;

/// `kind`'s default configuration walking at `speed` m/s: its desired-speed parameter set to
/// `speed` (and its limit to 1.3 × that), or, for the swarm planners that only have a speed
/// limit, the limit set to `speed`. Refuses a planner with neither, or a speed out of range.
pub fn config_at_speed(kind: PlannerKind, speed: f32) -> Result<PlannerConfig, SetupError> {
    let mut config = kind.default_config();
    let keys: Vec<&str> = kind.param_specs().iter().map(|s| s.key).collect();
    let v = px_per_step(speed);
    let desired = DESIRED_KEYS.iter().find(|k| keys.contains(k));
    let limit = LIMIT_KEYS.iter().find(|k| keys.contains(k));
    let round = |x: f32| serde_json::json!((f64::from(x) * 1e6).round() / 1e6);
    match (desired, limit) {
        (Some(d), l) => {
            if let Some(l) = l {
                config.set_param(l, round(v * LIMIT_OVER_DESIRED))?;
            }
            config.set_param(d, round(v))?;
        }
        (None, Some(l)) => config.set_param(l, round(v))?,
        (None, None) => return Err(SetupError::NoSpeedParameter(kind.name())),
    }
    Ok(config)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_convert_both_ways() {
        // 1.34 m/s at 20 px/m and 60 steps/s is 0.4467 px/step.
        assert!((px_per_step(1.34) - 1.34 * 20.0 / 60.0).abs() < 1e-6);
        assert!((mps(px_per_step(0.9)) - 0.9).abs() < 1e-6);
        assert_eq!(px(2.0), 40.0);
    }

    #[test]
    fn every_planner_can_be_given_a_walking_speed() {
        for &kind in PlannerKind::ALL {
            let config = config_at_speed(kind, 1.34).expect("a speed parameter");
            let planner = crate::planners::build(&config, 1, &[]);
            let limit = planner.max_speed();
            assert!(
                limit >= px_per_step(1.34) - 1e-5 && limit <= px_per_step(1.34) * 1.31,
                "{kind:?} {limit}"
            );
        }
    }
}
