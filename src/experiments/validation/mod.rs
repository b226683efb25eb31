//! The validation suite (issue 14 §3): the field's standard crowd tests (RiMEA's, the Jülich
//! checks, counter-flow lanes) as data. Each test builds a scene for it, runs it with a
//! planner, measures in metres and seconds and states its criterion; the result is a table
//! test × planner and curves (`flockpath validate` writes them, the Validation page shows them).
//!
//! Files: `units` (scale, body, speeds), `measure` (the measurements on trajectories),
//! `scenes` (one builder per test), `record` (a run sampled into trajectories), `suite` (the
//! tests), `report` (rows and curves), `pedpy` (trajectories in PedPy's text format), `jupedsim` (a
//! scene as a JuPedSim script).

pub mod jupedsim;
pub mod measure;
pub mod pedpy;
pub mod record;
pub mod report;
pub mod scenes;
pub mod suite;
pub mod units;

pub use report::{Curve, Outcome, Report, Row};
pub use suite::{find_test, TestSpec, TESTS};

use crate::model::params::PlannerKind;

/// Runs `tests` × `planners` in table order; `progress(done, total, test, planner)` is called
/// before each run.
pub fn run_suite(
    tests: &[&TestSpec],
    planners: &[PlannerKind],
    mut progress: impl FnMut(usize, usize, &str, &str),
) -> Report {
    let total = tests.len() * planners.len();
    let mut report = Report { px_per_metre: units::PX_PER_METRE, rows: vec![], curves: vec![] };
    for (t, test) in tests.iter().enumerate() {
        for (p, &kind) in planners.iter().enumerate() {
            progress(t * planners.len() + p, total, test.id, kind.name());
            let outcome = test.run(kind);
            report.rows.extend(outcome.rows);
            report.curves.extend(outcome.curves);
        }
    }
    report
}
