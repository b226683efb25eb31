//! Browser tests of the classroom options' wasm API in headless Chromium (`bash
//! scripts/test-wasm.sh`): a locked link read by the `Classroom` handle gives the same view as the
//! native reading, refusals are JS `Error`s carrying the option, the unknown name and the allowed
//! names (the page translates them), and a locked edit is refused with its part.
#![cfg(target_arch = "wasm32")]

use flockpath::model::codec::classroom_from_link;
use flockpath::web::classroom::{classroom_from_ticks, Classroom};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::{wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

/// A string property of a JS value.
fn property(value: &JsValue, key: &str) -> Option<String> {
    js_sys::Reflect::get(value, &JsValue::from_str(key)).ok().and_then(|v| v.as_string())
}

/// The message of a JS `Error`.
fn message(value: &JsValue) -> String {
    let error: &js_sys::Error = value.dyn_ref().expect("a JS Error");
    String::from(error.message())
}

#[wasm_bindgen_test]
fn a_locked_link_reads_as_it_does_natively() {
    let link = include_str!("data/classroom/pillars-locked.txt").trim();
    let handle = Classroom::from_link(link);
    assert!(handle.errors().is_empty());
    let view: serde_json::Value = serde_json::from_str(&handle.view_json().expect("view")).expect("JSON");
    let native = serde_json::to_value(classroom_from_link(link).expect("valid").view()).expect("JSON");
    assert_eq!(view, native);
    assert_eq!(view["lock"], serde_json::json!(["obstacles", "goals"]));
    assert_eq!(view["can_load"], serde_json::json!(false));
}

#[wasm_bindgen_test]
fn a_refused_option_is_an_error_with_its_field_name_and_allowed_names() {
    let handle = Classroom::new(Some("play".into()), Some("obstacles,walls".into()), None);
    let errors = handle.errors();
    assert_eq!(errors.len(), 1);
    assert_eq!(property(&errors[0], "field").as_deref(), Some("lock"));
    assert_eq!(property(&errors[0], "name").as_deref(), Some("walls"));
    assert_eq!(property(&errors[0], "allowed").as_deref(), Some("obstacles, goals, groups, paths"));
    assert!(message(&errors[0]).starts_with("lock: unknown name \"walls\""));
    let view: serde_json::Value = serde_json::from_str(&handle.view_json().expect("view")).expect("JSON");
    assert_eq!(view["lock"], serde_json::json!([]), "the refused option locks nothing");
    assert_eq!(view["controls"], serde_json::json!(["play"]), "the other option applies");

    let ticks = classroom_from_ticks(vec!["play".into()], vec!["roofs".into()], vec![]);
    let Err(error) = ticks else { panic!("an unknown tick is refused") };
    assert_eq!(property(&error, "field").as_deref(), Some("lock"));
}

#[wasm_bindgen_test]
fn a_locked_edit_is_refused_with_its_part_and_a_group_link_is_dropped() {
    let handle = Classroom::new(None, Some("goals,groups".into()), None);
    let refused = handle
        .check_edit(r#"{"op":"move","item":{"kind":"goal","index":0},"dx":5,"dy":0}"#)
        .expect_err("goals are locked");
    assert_eq!(property(&refused, "part").as_deref(), Some("goals"));
    let path = handle
        .check_edit(r#"{"op":"add_path","points":[[0,0],[10,10]],"radius":null,"group":0}"#)
        .expect("paths are not locked");
    let path: serde_json::Value = serde_json::from_str(&path).expect("JSON");
    assert_eq!(path["group"], serde_json::Value::Null, "groups are locked: the path is not linked to one");
}
