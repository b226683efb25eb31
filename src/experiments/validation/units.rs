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

impl crate::model::refusal::Refusal for SetupError {
    fn message(&self) -> crate::model::refusal::Message {
        use crate::model::refusal::{Code, Message};
        match self {
            SetupError::NoSpeedParameter(planner) => {
                Message::new(Code::ValidationNoSpeed).with("planner", *planner)
            }
            SetupError::Param(e) => e.message(),
            SetupError::Scene(e) => e.message(),
        }
    }
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
const DESIRED_KEYS: &[&str] = &["desired_speed", "preferred_speed", "pref_speed"];
const LIMIT_KEYS: &[&str] = &["max_speed", "max_velocity"];

/// `kind`'s default configuration walking at `speed` m/s, each baseline with the speed limit
/// its own paper gives, in its parameter's own unit (m/s for the baseline models, px/step for
/// the swarm planners):
/// - a desired speed and a limit as a factor of it (social force): the desired speed set to
///   `speed`, the factor left at its default (Helbing & Molnár 1995: `v_max = 1.3 v⁰`);
/// - a desired speed and a limit of its own (ORCA's `pref_speed` and `max_speed`): both set to
///   `speed`, as in RVO2, where the preferred velocity is the velocity an agent walks at and
///   the disc of allowed velocities no larger (the suite gave ORCA social force's 1.3 × until
///   issue 25: RVO2's fallback then walked on the edge of the larger disc, 1.72 m/s in a jam);
/// - only a limit (the swarm planners): the limit set to `speed`.
///
/// Refuses a planner with neither, or a speed out of range.
pub fn config_at_speed(kind: PlannerKind, speed: f32) -> Result<PlannerConfig, SetupError> {
    let mut config = kind.default_config();
    let specs = kind.param_specs();
    let find = |keys: &[&'static str]| {
        keys.iter().find_map(|k| specs.iter().find(|s| s.key == *k)).map(|s| (s.key, s.unit == "m/s"))
    };
    let value = |m_s: f32, in_m_s: bool| {
        let v = if in_m_s { m_s } else { px_per_step(m_s) };
        serde_json::json!((f64::from(v) * 1e6).round() / 1e6)
    };
    match (find(DESIRED_KEYS), find(LIMIT_KEYS)) {
        (Some((d, d_m_s)), l) => {
            if let Some((l, l_m_s)) = l {
                config.set_param(l, value(speed, l_m_s))?;
            }
            config.set_param(d, value(speed, d_m_s))?;
        }
        (None, Some((l, l_m_s))) => config.set_param(l, value(speed, l_m_s))?,
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

    /// Regression: ORCA had social force's limit, 1.3 × its preferred speed (1.74 m/s at 1.34),
    /// and walked up to it in a jam; its limit is its preferred speed. Social force keeps
    /// Helbing & Molnár's 1.3 × desired.
    #[test]
    fn each_baseline_gets_its_own_papers_speed_limit() {
        let limit = |kind: PlannerKind| {
            let config = config_at_speed(kind, 1.34).expect("a speed parameter");
            crate::planners::build(&config, 1, &[]).max_speed()
        };
        let orca = limit(PlannerKind::Orca);
        assert!((orca - px_per_step(1.34)).abs() < 1e-5, "ORCA's limit {} m/s", mps(orca));
        let social = limit(PlannerKind::SocialForce);
        assert!((social - px_per_step(1.3 * 1.34)).abs() < 1e-5, "social force's limit {} m/s", mps(social));
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
