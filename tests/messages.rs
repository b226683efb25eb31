//! Every message code the core can produce ([`Code::ALL`], generated from the code list itself)
//! has a template in every language the page ships (`www/js/core/messages/<lang>.js`), with the
//! same argument names; the English templates are the core's own words, so an English page says
//! what the CLI says.

use flockpath::model::codec;
use flockpath::model::params::PlannerKind;
use flockpath::model::presets;
use flockpath::model::refusal::{Arg, Code, Refusal};
use std::collections::BTreeSet;

/// The languages the page ships message templates for.
const LANGUAGES: [&str; 2] = ["en", "zh"];

/// The templates of `lang`: the file's body after `export default` is a JSON object.
fn templates(lang: &str) -> serde_json::Map<String, serde_json::Value> {
    let path = format!("{}/www/js/core/messages/{lang}.js", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let body = text
        .split_once("export default")
        .map(|(_, b)| b.trim().trim_end_matches(';'))
        .expect("export default");
    serde_json::from_str(body)
        .unwrap_or_else(|e| panic!("{path} is not a JSON object after `export default`: {e}"))
}

/// The argument names of a template (`{name}` or `{name:spec}`), as the core reads them.
fn arg_names(template: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        rest = &rest[open + 1..];
        let len = rest.find(|c: char| !(c.is_ascii_lowercase() || c == '_')).unwrap_or(rest.len());
        if len > 0 && (rest[len..].starts_with('}') || rest[len..].starts_with(':')) {
            names.insert(rest[..len].to_string());
        }
    }
    names
}

#[test]
fn every_code_has_a_template_in_every_language_with_the_same_arguments() {
    assert!(Code::ALL.len() > 90, "{} codes", Code::ALL.len());
    for lang in LANGUAGES {
        let table = templates(lang);
        for code in Code::ALL {
            let template = table.get(code.as_str()).and_then(|t| t.as_str());
            let template =
                template.unwrap_or_else(|| panic!("{lang}.js has no template for {}", code.as_str()));
            let core: BTreeSet<String> = code.arg_names().into_iter().map(str::to_string).collect();
            assert_eq!(arg_names(template), core, "{lang} {}: {template}", code.as_str());
            if lang == "en" {
                assert_eq!(template, code.english(), "en.js {} is the core's own words", code.as_str());
            }
        }
        let known: BTreeSet<&str> = Code::ALL.iter().map(|c| c.as_str()).collect();
        let unused: Vec<&String> = table.keys().filter(|k| !known.contains(k.as_str())).collect();
        assert!(unused.is_empty(), "{lang}.js has templates for codes the core does not have: {unused:?}");
    }
}

#[test]
fn a_field_refusal_names_path_value_and_allowed() {
    let mut scene = (presets::ALL[0].build)();
    scene.groups[0].agent_radius = 500.0;
    let text = codec::scene_to_json(&scene);
    let e = codec::scene_from_any(&text).expect_err("radius 500 is refused");
    let m = e.message();
    assert_eq!(m.code, Code::SceneField);
    assert_eq!(m.arg_text("path").as_deref(), Some("groups[0].agent_radius"));
    assert_eq!(m.arg_text("value").as_deref(), Some("500"));
    assert!(m.arg_text("allowed").is_some_and(|a| a.contains("0.5…100")), "{m:?}");
    assert_eq!(m.to_string(), e.to_string());
    assert!(e.to_string().starts_with("groups[0].agent_radius is 500"), "{e}");
}

#[test]
fn unknown_names_list_the_known_ones() {
    let e = presets::lookup("no-such-preset").expect_err("unknown");
    assert_eq!(e.code(), "scene.unknown_preset");
    assert_eq!(e.message().arg_text("name").as_deref(), Some("no-such-preset"));
    assert!(e.message().arg_text("known").is_some_and(|k| k.starts_with(presets::ALL[0].name)));
    let p = PlannerKind::parse("teleport").expect_err("unknown");
    assert_eq!(p.code(), "planner.unknown");
    assert_eq!(p.message().arg_text("name").as_deref(), Some("teleport"));
    assert!(p.message().arg_text("known").is_some_and(|k| k.contains("boids")));
}

#[test]
fn a_parameter_out_of_range_has_its_key_and_range() {
    let mut config = PlannerKind::Boids.default_config();
    let e = config.set_param("max_speed", serde_json::json!(1e6)).expect_err("too fast");
    assert_eq!(e.code(), "param.range");
    assert_eq!(e.message().arg_text("key").as_deref(), Some("max_speed"));
    assert_eq!(e.message().arg_text("label").as_deref(), Some("Max speed"));
    assert_eq!(e.message().to_string(), e.to_string());
    let unknown = config.set_param("warp", serde_json::json!(1)).expect_err("no such key");
    assert_eq!(unknown.code(), "param.unknown");
    assert_eq!(unknown.message().arg_text("key").as_deref(), Some("warp"));
}

#[test]
fn an_unknown_version_is_a_parse_refusal_with_its_reason() {
    let e = codec::scene_from_any("9.abc").expect_err("version 9");
    let m = e.message();
    assert_eq!(m.code, Code::SceneParse);
    let Some(Arg::Message(reason)) = m.arg("reason") else { panic!("a reason: {m:?}") };
    assert_eq!(reason.code, Code::SceneUnknownVersion);
    assert_eq!(reason.arg_text("version").as_deref(), Some("9"));
    assert!(e.to_string().starts_with("cannot read the scene: unknown scene format version \"9\""), "{e}");
}
