//! The Validation page's bindings (`www/validation.html`, `www/js/validation/*.js`): the list of
//! tests and planners, one (test, planner) run of the suite as JSON for the page's worker, and
//! the reference curves for the fundamental-diagram plot. Conversion only; the suite is
//! `crate::experiments::validation`.

use super::{refused, to_json};
use crate::experiments::validation::measure::{seyfried_speed, weidmann_specific_flow, weidmann_speed};
use crate::experiments::validation::{find_test, Curve, Row, TESTS};
use crate::model::params::PlannerKind;
use crate::model::refusal::{Code, Message};
use serde::Serialize;
use wasm_bindgen::prelude::*;

#[derive(Serialize)]
struct TestInfo {
    id: &'static str,
    title: &'static str,
    setup: &'static str,
    measurement: &'static str,
    criterion: &'static str,
}

#[derive(Serialize)]
struct PlannerInfo {
    name: &'static str,
    label: &'static str,
}

#[derive(Serialize)]
struct Options {
    tests: Vec<TestInfo>,
    planners: Vec<PlannerInfo>,
}

/// `{tests: [{id, title, setup, measurement, criterion}], planners: [{name, label}]}`, in table
/// order; `setup` and `measurement` are docs/validation.md's words for the page's "how it is
/// measured" paragraphs.
#[wasm_bindgen]
pub fn validation_options_json() -> Result<String, JsError> {
    to_json(&Options {
        tests: TESTS
            .iter()
            .map(|t| TestInfo {
                id: t.id,
                title: t.title,
                setup: t.setup,
                measurement: t.measurement,
                criterion: t.criterion,
            })
            .collect(),
        planners: PlannerKind::ALL.iter().map(|k| PlannerInfo { name: k.name(), label: k.label() }).collect(),
    })
}

/// A table row as the page reads it: the row as `flockpath validate --json` writes it, and its
/// measurement as a message (`words: {code, args, message}`) for the page to word.
#[derive(Serialize)]
struct PageRow<'a> {
    #[serde(flatten)]
    row: &'a Row,
    words: &'a Message,
}

/// The suite's `Outcome` with [`PageRow`]s.
#[derive(Serialize)]
struct PageOutcome<'a> {
    rows: Vec<PageRow<'a>>,
    curves: &'a [Curve],
}

/// Runs test `test_id` with planner `planner` (by name): `{rows: [...], curves: [...]}` as
/// `flockpath validate --json` writes them, each row with its measurement as a message too
/// (`words`).
#[wasm_bindgen]
pub fn validation_run_json(test_id: &str, planner: &str) -> Result<String, JsValue> {
    console_error_panic_hook::set_once();
    let test = find_test(test_id)
        .ok_or_else(|| refused(Message::new(Code::ValidationUnknownTest).with("name", test_id)))?;
    let kind = PlannerKind::from_name(planner)
        .ok_or_else(|| refused(Message::new(Code::ValidationUnknownPlanner).with("name", planner)))?;
    let outcome = test.run(kind);
    let rows = outcome.rows.iter().map(|row| PageRow { row, words: &row.words }).collect();
    Ok(to_json(&PageOutcome { rows, curves: &outcome.curves })?)
}

/// The reference speed (m/s) at each density of `densities`: Weidmann (1993) for `"weidmann"`
/// (persons/m²), Seyfried et al. (2005) for `"seyfried"` (persons/m, single file).
#[wasm_bindgen]
pub fn validation_reference_speeds(curve: &str, densities: &[f64]) -> Result<Vec<f64>, JsValue> {
    let f: fn(f64) -> f64 = match curve {
        "weidmann" => weidmann_speed,
        "seyfried" => seyfried_speed,
        _ => {
            return Err(refused(
                Message::new(Code::ValidationUnknownCurve)
                    .with("name", curve)
                    .with("known", vec!["weidmann", "seyfried"]),
            ))
        }
    };
    Ok(densities.iter().map(|&d| f(d)).collect())
}

/// Weidmann's (1993) specific flow `J_s = ρ·v(ρ)` (persons/(m·s)) at each density of
/// `densities` (persons/m²): the reference line of the page's flow–density plot.
#[wasm_bindgen]
pub fn validation_reference_specific_flows(densities: &[f64]) -> Vec<f64> {
    densities.iter().map(|&d| weidmann_specific_flow(d)).collect()
}
