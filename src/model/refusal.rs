//! Refusals in a form the pages can word in the reader's language: beside its English message
//! (the `Display` text every front-end shows), each refusal has a stable `code` and named `args`
//! (strings: a field path, the refused value, what is allowed, a limit, known names). The web
//! layer puts them on the JS `Error` (`error.code`, `error.args`), and the page formats them with
//! its strings tables (`www/js/core/errors.js`, keys `error.<code>`). Codes and argument names
//! are a contract with those tables: add freely, never rename.
//!
//! Layer: model (plain data about the model's own errors).

use crate::model::params::{ParamError, SetParamError, UnknownPlanner};
use crate::model::scene::SceneError;

/// A refusal with a stable code and named string arguments beside its English message.
pub trait Refusal: std::fmt::Display {
    /// The stable name of this kind of refusal (`field`, `unknown_preset`, …).
    fn code(&self) -> &'static str;
    /// The refusal's parts by name, as text.
    fn args(&self) -> Vec<(&'static str, String)>;
}

impl Refusal for SceneError {
    fn code(&self) -> &'static str {
        match self {
            SceneError::Parse(_) => "parse",
            SceneError::NotFinite(_) => "not_finite",
            SceneError::OutOfRange(_) => "out_of_range",
            SceneError::BadReference(_) => "bad_reference",
            SceneError::Blocked(_) => "blocked",
            SceneError::TooCostly(_) => "too_costly",
            SceneError::Field(_) => "field",
            SceneError::TooLarge { .. } => "too_large",
            SceneError::FlowFieldMemory { .. } => "flow_field_memory",
            SceneError::UnknownPreset { .. } => "unknown_preset",
        }
    }

    fn args(&self) -> Vec<(&'static str, String)> {
        match self {
            // Worded by the core only: the page matches the few it words itself (unknown
            // version, the planning and density limits) by their text and shows the rest as given.
            SceneError::Parse(m)
            | SceneError::OutOfRange(m)
            | SceneError::BadReference(m)
            | SceneError::Blocked(m)
            | SceneError::TooCostly(m) => vec![("message", m.clone())],
            SceneError::NotFinite(what) => vec![("what", what.clone())],
            SceneError::Field(f) => {
                vec![("path", f.path.clone()), ("value", f.value.clone()), ("allowed", f.allowed.clone())]
            }
            SceneError::TooLarge { what, bytes, limit } => {
                let mut args = vec![("what", (*what).to_string()), ("limit", limit.to_string())];
                if let Some(bytes) = bytes {
                    args.push(("bytes", bytes.to_string()));
                }
                args
            }
            SceneError::FlowFieldMemory { path, fields, cells, bytes, limit } => vec![
                ("path", path.clone()),
                ("fields", fields.to_string()),
                ("cells", cells.to_string()),
                ("mb", bytes.div_ceil(1 << 20).to_string()),
                ("limit_mb", (limit / (1 << 20)).to_string()),
            ],
            SceneError::UnknownPreset { name, known } => {
                vec![("name", name.clone()), ("known", known.join(", "))]
            }
        }
    }
}

impl Refusal for UnknownPlanner {
    fn code(&self) -> &'static str {
        "unknown_planner"
    }

    fn args(&self) -> Vec<(&'static str, String)> {
        vec![("name", self.name.clone()), ("known", self.known().join(", "))]
    }
}

impl Refusal for ParamError {
    fn code(&self) -> &'static str {
        "param_range"
    }

    fn args(&self) -> Vec<(&'static str, String)> {
        vec![
            ("key", self.key.clone()),
            ("label", self.label.to_string()),
            ("value", self.value.clone()),
            ("allowed", self.allowed.clone()),
        ]
    }
}

impl Refusal for SetParamError {
    fn code(&self) -> &'static str {
        match self {
            SetParamError::UnknownKey { .. } => "unknown_param",
            SetParamError::WrongType { .. } => "param_type",
            SetParamError::Refused(e) => e.code(),
        }
    }

    fn args(&self) -> Vec<(&'static str, String)> {
        match self {
            SetParamError::UnknownKey { planner, key } => {
                vec![("planner", planner.to_string()), ("key", key.clone())]
            }
            SetParamError::WrongType { label, problem } => {
                vec![("label", label.to_string()), ("problem", problem.clone())]
            }
            SetParamError::Refused(e) => e.args(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::codec;
    use crate::model::params::PlannerKind;
    use crate::model::presets;

    fn arg<'a>(args: &'a [(&'static str, String)], name: &str) -> &'a str {
        args.iter().find(|(k, _)| *k == name).map(|(_, v)| v.as_str()).unwrap_or("<absent>")
    }

    #[test]
    fn a_field_refusal_names_path_value_and_allowed() {
        let mut scene = (presets::ALL[0].build)();
        scene.groups[0].agent_radius = 500.0;
        let text = codec::scene_to_json(&scene);
        let e = codec::scene_from_any(&text).expect_err("radius 500 is refused");
        assert_eq!(e.code(), "field");
        let args = e.args();
        assert_eq!(arg(&args, "path"), "groups[0].agent_radius");
        assert_eq!(arg(&args, "value"), "500");
        assert!(arg(&args, "allowed").contains("0.5…100"), "{args:?}");
        // The message is the same words, so English pages lose nothing.
        assert!(e.to_string().starts_with("groups[0].agent_radius is 500"), "{e}");
    }

    #[test]
    fn unknown_names_list_the_known_ones() {
        let e = presets::lookup("no-such-preset").expect_err("unknown");
        assert_eq!(e.code(), "unknown_preset");
        assert_eq!(arg(&e.args(), "name"), "no-such-preset");
        assert!(arg(&e.args(), "known").starts_with(presets::ALL[0].name));
        let p = PlannerKind::parse("teleport").expect_err("unknown");
        assert_eq!(p.code(), "unknown_planner");
        assert_eq!(arg(&p.args(), "name"), "teleport");
        assert!(arg(&p.args(), "known").contains("boids"));
    }

    #[test]
    fn a_parameter_out_of_range_has_its_key_and_range() {
        let mut config = PlannerKind::Boids.default_config();
        let e = config.set_param("max_speed", serde_json::json!(1e6)).expect_err("too fast");
        assert_eq!(e.code(), "param_range");
        assert_eq!(arg(&e.args(), "key"), "max_speed");
        assert_eq!(arg(&e.args(), "label"), "Max speed");
        let unknown = config.set_param("warp", serde_json::json!(1)).expect_err("no such key");
        assert_eq!(unknown.code(), "unknown_param");
        assert_eq!(arg(&unknown.args(), "key"), "warp");
    }

    #[test]
    fn an_unknown_version_is_a_parse_refusal_with_its_message() {
        let e = codec::scene_from_any("9.abc").expect_err("version 9");
        assert_eq!(e.code(), "parse");
        assert!(
            arg(&e.args(), "message").starts_with("unknown scene format version \"9\""),
            "{:?}",
            e.args()
        );
    }
}
