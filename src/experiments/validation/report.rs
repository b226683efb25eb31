//! What the suite returns: a table row per test and planner, and curves (a fundamental diagram,
//! a lane-order series, a sweep) as columns of numbers.

use crate::model::refusal::Message;
use serde::Serialize;

/// One line of the table: a test run with one planner.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Row {
    /// Test id (`t1-free-walking`, …).
    pub test: String,
    /// Planner name (`boids`, …).
    pub planner: String,
    /// The measured value in `unit`, `null` when there is none (the run failed to produce it).
    pub value: Option<f64>,
    /// Unit of `value`.
    pub unit: String,
    /// The measurement in words, with the figures behind the value: the English of `words`,
    /// kept as text for `flockpath validate`'s tables and JSON and the scripts that read them.
    pub measured: String,
    /// The measurement as a message (code and figures), which the page words in its language.
    #[serde(skip)]
    pub words: Message,
    /// The criterion, in words.
    pub criterion: String,
    /// Whether the criterion holds.
    pub pass: bool,
    /// The test's scene with this planner as a link fragment (`index.html#s=…`).
    pub scene: String,
}

/// A curve: named columns and rows of numbers (NaN where a value is missing, `null` in JSON).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Curve {
    /// File-friendly name (`t4-fundamental-diagram-boids`).
    pub name: String,
    /// Test id.
    pub test: String,
    /// Planner name.
    pub planner: String,
    /// Column names with units (`density_per_m2`, …).
    pub columns: Vec<String>,
    /// Rows, each as long as `columns`.
    pub rows: Vec<Vec<f64>>,
}

/// What one test gives for one planner.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Outcome {
    /// Table rows (usually one).
    pub rows: Vec<Row>,
    /// Curves.
    pub curves: Vec<Curve>,
}

/// The whole suite's result.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Report {
    /// Scale of every scene (px per metre).
    pub px_per_metre: f32,
    /// Every row, test by test, planner by planner.
    pub rows: Vec<Row>,
    /// Every curve.
    pub curves: Vec<Curve>,
}
