//! `flockpath validate`: the validation suite of `flockpath::experiments::validation` (RiMEA
//! tests, Jülich checks, counter-flow lanes) as a table on stdout, a JSON report, the curves as
//! CSV files and, on request, every run's trajectories for PedPy.

use crate::progress::Progress;
use crate::{failed, out, usage, write_file, CliError};
use flockpath::csv::field;
use flockpath::experiments::validation::pedpy::{parse_trajectory_text, trajectory_text};
use flockpath::experiments::validation::suite::Run;
use flockpath::experiments::validation::units::PX_PER_METRE;
use flockpath::experiments::validation::{find_test, Curve, Outcome, Report, TestSpec, TESTS};
use flockpath::PlannerKind;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `flockpath validate`.
#[derive(clap::Args, Debug)]
#[command(
    long_about = "Run the validation suite: the RiMEA guideline's tests that make sense in 2-D (T1, T4, \
                  T6, T7, T8, T9, T12, T15, T16), the Jülich checks (45° rotation, head-on pair) and \
                  counter-flow lanes, each with every planner chosen. Prints the table test × planner \
                  (measured value, criterion, pass/fail); a swarm planner failing a test is a result, \
                  not an error (exit code 0).",
    after_help = "Scenes are drawn at 20 px per metre; walkers have a 0.2 m body radius and a desired \
                  speed of 1.34 m/s unless the test varies it. Runs of different (test, planner) pairs \
                  use every core; results do not depend on the number of threads.\n\
                  Tests: t1-free-walking, t4-fundamental-diagram, t6-corner, juelich-rotation, \
                  juelich-head-on, counter-flow-lanes, t9-four-vs-two-exits, t12-bottleneck, \
                  t7-demographics, t8-speed-sweep, t15-corner-crowd, t16-single-file.",
    args_override_self = true
)]
pub struct ValidateArgs {
    /// Comma-separated planner names, or `all` (default all)
    #[arg(long, value_name = "LIST")]
    planners: Option<String>,
    /// Comma-separated test ids (a unique first word such as `t4`, or a unique prefix, will
    /// do), or `all` (default all)
    #[arg(long, value_name = "LIST")]
    tests: Option<String>,
    /// Write the report JSON: {px_per_metre, rows: [{test, planner, value, unit, measured,
    /// criterion, pass, scene}], curves: [{name, test, planner, columns, rows}]}
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write each curve as DIR/<name>.csv (fundamental diagrams, lane order over time, the T8
    /// sweep, T7 speeds, T9 exits) and the table as DIR/table.csv
    #[arg(long, value_name = "DIR")]
    csv_dir: Option<PathBuf>,
    /// Write every run's trajectories in PedPy's text format, one file per run:
    /// DIR/<test>-<planner>[-<variant>].txt, e.g. t4-fundamental-diagram-orca-rho2.txt,
    /// juelich-rotation-orca-45deg.txt (in the periodic corridors, x 10…30 m, a walker that
    /// wraps gets a new id)
    #[arg(long, value_name = "DIR")]
    pedpy_dir: Option<PathBuf>,
    /// Write every run's set-up as DIR/<run>.json (the scene JSON, the walkers' starts in
    /// metres, each group's desired speed, the periodic band, the run's length and frame
    /// interval): what another simulator needs to run the same (scripts/jupedsim-check.sh)
    #[arg(long, value_name = "DIR")]
    scenes_dir: Option<PathBuf>,
    /// Measure trajectories another simulator wrote instead of simulating: DIR/<test>-<label>
    /// [-<variant>].txt in the --pedpy-dir format (ids in the set-up's walker order, frame rate
    /// in a `# framerate:` line); needs --label and one planner (which sets up the scenes)
    #[arg(long, value_name = "DIR", requires = "label")]
    replay: Option<PathBuf>,
    /// The name the replayed trajectories' rows get instead of the planner's (e.g. jupedsim-cfsm)
    #[arg(long, value_name = "NAME", requires = "replay")]
    label: Option<String>,
}

/// The planners named in `value` (`all` for every one).
fn planners(value: Option<&str>) -> Result<Vec<PlannerKind>, CliError> {
    let Some(value) = value.filter(|v| v.trim() != "all") else { return Ok(PlannerKind::ALL.to_vec()) };
    value
        .split(',')
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(|n| {
            PlannerKind::from_name(n).ok_or_else(|| {
                let known: Vec<&str> = PlannerKind::ALL.iter().map(|k| k.name()).collect();
                usage(format!("--planners: unknown planner {n:?}; available: {}", known.join(", ")))
            })
        })
        .collect()
}

/// The tests named in `value` (ids or unique prefixes; `all` for every one).
fn tests(value: Option<&str>) -> Result<Vec<&'static TestSpec>, CliError> {
    let Some(value) = value.filter(|v| v.trim() != "all") else { return Ok(TESTS.iter().collect()) };
    value
        .split(',')
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(|n| {
            if let Some(t) = find_test(n) {
                return Ok(t);
            }
            // The first word of an id (`t1`, `juelich`), else a prefix.
            let mut matches: Vec<&TestSpec> =
                TESTS.iter().filter(|t| t.id.split('-').next() == Some(n)).collect();
            if matches.is_empty() {
                matches = TESTS.iter().filter(|t| t.id.starts_with(n)).collect();
            }
            match matches.as_slice() {
                [one] => Ok(*one),
                _ => {
                    let known: Vec<&str> = TESTS.iter().map(|t| t.id).collect();
                    Err(usage(format!("--tests: {n:?} names no single test; tests: {}", known.join(", "))))
                }
            }
        })
        .collect()
}

/// Runs the suite and writes what was asked for.
pub fn validate(args: &ValidateArgs) -> Result<(), CliError> {
    let kinds = planners(args.planners.as_deref())?;
    let chosen = tests(args.tests.as_deref())?;
    if kinds.is_empty() || chosen.is_empty() {
        return Err(usage("--planners and --tests need at least one name each"));
    }
    if let Some(dir) = &args.csv_dir {
        std::fs::create_dir_all(dir).map_err(|e| failed(format!("cannot create --csv-dir {dir:?}: {e}")))?;
    }
    for (flag, dir) in [("--pedpy-dir", &args.pedpy_dir), ("--scenes-dir", &args.scenes_dir)] {
        if let Some(dir) = dir {
            std::fs::create_dir_all(dir).map_err(|e| failed(format!("cannot create {flag} {dir:?}: {e}")))?;
        }
    }
    if args.replay.is_some() && kinds.len() != 1 {
        return Err(usage("--replay measures one simulator's runs: name one planner to set up the scenes"));
    }
    let replay_dir = args.replay.clone();
    let load = move |name: &str, period: Option<f32>| -> Result<_, String> {
        let dir = replay_dir.as_deref().unwrap_or(Path::new("."));
        let file = dir.join(format!("{name}.txt"));
        let text = std::fs::read_to_string(&file).map_err(|e| format!("cannot read {file:?}: {e}"))?;
        parse_trajectory_text(&text, period)
    };
    let pairs: Vec<(&TestSpec, PlannerKind)> =
        chosen.iter().flat_map(|&t| kinds.iter().map(move |&k| (t, k))).collect();
    let progress = Progress::new(pairs.len(), "runs");
    let started = std::time::Instant::now();
    // One (test, planner) pair per task; each is deterministic, so the order of finishing does
    // not matter and the report is assembled in table order. With --pedpy-dir a task writes its
    // runs' files as it finishes (so no run's trajectories wait in memory for the others).
    let outcomes: Vec<Outcome> = pairs
        .par_iter()
        .map(|&(t, k)| {
            let wants_runs = args.pedpy_dir.is_some() || args.scenes_dir.is_some();
            let outcome = match (&args.label, wants_runs) {
                (Some(label), _) => {
                    let (outcome, runs) = t.run_replaying(k, label, &load);
                    write_runs(args, &runs)?;
                    outcome
                }
                (None, true) => {
                    let (outcome, runs) = t.run_with_trajectories(k);
                    write_runs(args, &runs)?;
                    outcome
                }
                (None, false) => t.run(k),
            };
            progress.inc();
            Ok(outcome)
        })
        .collect::<Result<_, CliError>>()?;
    let mut report = Report { px_per_metre: PX_PER_METRE, rows: vec![], curves: vec![] };
    for o in outcomes {
        report.rows.extend(o.rows);
        report.curves.extend(o.curves);
    }
    drop(progress);
    if let Some(file) = &args.json {
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| failed(format!("cannot write the report: {e}")))?;
        write_file("--json file", file, &format!("{json}\n"))?;
    }
    if let Some(dir) = &args.csv_dir {
        write_file("table", dir.join("table.csv"), &table_csv(&report))?;
        for c in &report.curves {
            write_file("curve", dir.join(format!("{}.csv", c.name)), &curve_csv(c))?;
        }
    }
    let passed = report.rows.iter().filter(|r| r.pass).count();
    out(&format!(
        "{}\n{passed} of {} passed in {:.1} s\n",
        table_text(&report),
        report.rows.len(),
        started.elapsed().as_secs_f64()
    ))
}

/// `runs` as PedPy files, --pedpy-dir/<run name>.txt, and their set-ups as
/// --scenes-dir/<run name>.json, as asked.
fn write_runs(args: &ValidateArgs, runs: &[Run]) -> Result<(), CliError> {
    for run in runs {
        if let Some(dir) = &args.pedpy_dir {
            let title = format!("flockpath validate run {}", run.name);
            let file = dir.join(format!("{}.txt", run.name));
            write_file("--pedpy-dir file", file, &trajectory_text(&run.traj, run.period, &title))?;
        }
        if let Some(dir) = &args.scenes_dir {
            let json = serde_json::to_string(&run.setup)
                .map_err(|e| failed(format!("cannot write the set-up of {}: {e}", run.name)))?;
            write_file("--scenes-dir file", dir.join(format!("{}.json", run.name)), &format!("{json}\n"))?;
        }
    }
    Ok(())
}

fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        String::new()
    }
}

fn table_csv(report: &Report) -> String {
    let mut out = String::from("test,planner,value,unit,measured,criterion,pass\n");
    for r in &report.rows {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{}",
            field(&r.test),
            field(&r.planner),
            r.value.map_or(String::new(), number),
            field(&r.unit),
            field(&r.measured),
            field(&r.criterion),
            if r.pass { "pass" } else { "fail" }
        );
    }
    out
}

fn curve_csv(c: &Curve) -> String {
    let mut out = c.columns.iter().map(|c| field(c)).collect::<Vec<_>>().join(",");
    out.push('\n');
    for row in &c.rows {
        out.push_str(&row.iter().map(|&x| number(x)).collect::<Vec<_>>().join(","));
        out.push('\n');
    }
    out
}

/// The table as aligned text: test, planner, pass/fail, measurement; each test's criterion
/// once above its rows.
fn table_text(report: &Report) -> String {
    let mut out = String::new();
    let mut last = "";
    for r in &report.rows {
        if r.test != last {
            let _ = writeln!(out, "\n{}  — criterion: {}", r.test, r.criterion);
            last = &r.test;
        }
        let _ =
            writeln!(out, "  {:<10} {:<4}  {}", r.planner, if r.pass { "pass" } else { "FAIL" }, r.measured);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_prefixes_select_tests_and_planners() {
        assert_eq!(tests(Some("t4")).expect("a prefix")[0].id, "t4-fundamental-diagram");
        assert_eq!(tests(Some("t1")).expect("a first word")[0].id, "t1-free-walking");
        assert_eq!(tests(Some("counter")).expect("a prefix")[0].id, "counter-flow-lanes");
        assert!(tests(Some("juelich")).is_err(), "two tests start with juelich");
        assert_eq!(tests(None).expect("all").len(), TESTS.len());
        assert_eq!(planners(Some("boids, pso")).expect("names"), vec![PlannerKind::Boids, PlannerKind::Pso]);
        assert!(planners(Some("nope")).is_err());
    }

    #[test]
    fn csv_quotes_fields_and_leaves_missing_numbers_empty() {
        assert_eq!(field("a, b"), "\"a, b\"");
        let c = Curve {
            name: "x".into(),
            test: "t".into(),
            planner: "p".into(),
            columns: vec!["a".into(), "b".into()],
            rows: vec![vec![1.5, f64::NAN]],
        };
        assert_eq!(curve_csv(&c), "a,b\n1.5,\n");
    }
}
