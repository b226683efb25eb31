//! The SCORM package and its grade for the pages: conversion only. The package, the files it
//! takes and the scoring rule are `crate::package::scorm`'s.

use super::{refusal, to_json, unreadable};
use crate::model::activity::Activity;
use crate::package::scorm::{grade, is_page_file, packaged_scene, scorm_package};
use crate::sim::activity_check::Status;
use wasm_bindgen::prelude::*;

/// Of the page files `paths_json` (a JSON array of paths relative to the page folder, such as
/// the service worker's precache list), those a SCORM package takes, as a JSON array.
#[wasm_bindgen]
pub fn scorm_page_files(paths_json: &str) -> Result<String, JsValue> {
    let paths: Vec<String> = serde_json::from_str(paths_json).map_err(|e| unreadable("files", e))?;
    let wanted: Vec<&String> = paths.iter().filter(|p| is_page_file(p)).collect();
    to_json(&wanted).map_err(JsValue::from)
}

/// Checks that `link` can be packaged (an activity with a check one scene decides) before the
/// page fetches its files; throws the same coded refusal as [`scorm_package_zip`] would.
#[wasm_bindgen]
pub fn scorm_check_link(link: &str) -> Result<(), JsValue> {
    packaged_scene(link).map(|_| ()).map_err(refusal)
}

/// The SCORM 1.2 zip of the activity in `link`, with the page files whose names and byte
/// lengths `files_json` lists (`[[path, length], …]`) laid end to end in `bytes`. Throws the
/// core's coded refusal (no activity, no check, a missing file, …).
#[wasm_bindgen]
pub fn scorm_package_zip(link: &str, files_json: &str, bytes: &[u8]) -> Result<Vec<u8>, JsValue> {
    let listed: Vec<(String, usize)> =
        serde_json::from_str(files_json).map_err(|e| unreadable("files", e))?;
    let mut files = Vec::with_capacity(listed.len());
    let mut at = 0usize;
    for (name, length) in listed {
        let end = at.checked_add(length).filter(|&end| end <= bytes.len());
        let Some(end) = end else {
            return Err(unreadable("files", format!("{name}: {length} bytes past the end of the data")));
        };
        files.push((name, bytes[at..end].to_vec()));
        at = end;
    }
    let package = scorm_package(link, &files).map_err(refusal)?;
    Ok(package.zip)
}

/// The grade of a run (`{lesson_status, score_raw}` as JSON): the activity (its JSON), the
/// check's status as the report names it (`running`, `met`, `missed`, `unavailable`) and the
/// chosen prediction (index from 0, or none).
#[wasm_bindgen]
pub fn scorm_grade(activity_json: &str, status: &str, answer: Option<u32>) -> Result<String, JsValue> {
    let activity: Activity = serde_json::from_str(activity_json).map_err(|e| unreadable("activity", e))?;
    let status = match status {
        "running" => Status::Running,
        "met" => Status::Met,
        "missed" => Status::Missed,
        "unavailable" => Status::Unavailable,
        other => return Err(unreadable("activity", format!("unknown check status {other:?}"))),
    };
    to_json(&grade(&activity, status, answer)).map_err(JsValue::from)
}
