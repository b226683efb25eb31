//! The optimizer lab page's bindings (`www/lab.html`, `www/js/lab/`): one optimizer run as an
//! opaque handle, its 2-D picture as a pointer into wasm memory, and single seeded runs for the
//! page's worker. Conversion only; the runs and the pixels are `crate::optim::lab`.

use super::{refusal, refused, to_json};
use crate::experiments::tables::Summary;
use crate::model::refusal::{Code, Message};
use crate::optim::lab::{self, LabRun};
use crate::optim::{Algorithm, Function, Settings};
use wasm_bindgen::prelude::*;

fn algorithm(name: &str) -> Result<Algorithm, JsValue> {
    Algorithm::parse(name).map_err(refusal)
}

fn function(name: &str) -> Result<Function, JsValue> {
    Function::parse(name).map_err(refusal)
}

/// The run's sizes, each refused by name with its range when outside the page's limits (the
/// lab form's maxima, `crate::sim::limits`): a number typed past an input's `max` reaches here.
fn settings(dim: u32, population: u32, iterations: u32) -> Result<Settings, JsValue> {
    use crate::sim::limits::{
        PAGE_LAB_DIMENSION as DIM, PAGE_LAB_ITERATIONS as ITERS, PAGE_LAB_POPULATION as POP,
    };
    for (setting, value, min, max) in [
        (Code::LabDimension, dim, 1, DIM),
        (Code::LabPopulation, population, 2, POP),
        (Code::LabIterations, iterations, 1, ITERS),
    ] {
        if !(min..=max).contains(&value) {
            return Err(refused(
                Message::new(Code::LabOutOfRange)
                    .with("setting", Message::new(setting))
                    .with("value", value)
                    .with("min", min)
                    .with("max", max),
            ));
        }
    }
    Ok(Settings { population: population as usize, iterations, ..Settings::default() })
}

/// One optimizer run in the lab, stepped by the page.
#[wasm_bindgen]
pub struct Lab {
    run: LabRun,
}

#[wasm_bindgen]
impl Lab {
    /// A fresh run: algorithm and function by name (see [`lab_options_json`]), seeded.
    #[wasm_bindgen(constructor)]
    pub fn new(
        algorithm_name: &str,
        function_name: &str,
        dim: u32,
        population: u32,
        iterations: u32,
        seed: u32,
    ) -> Result<Lab, JsValue> {
        console_error_panic_hook::set_once();
        let settings = settings(dim, population, iterations)?;
        let run =
            LabRun::new(algorithm(algorithm_name)?, function(function_name)?, dim as usize, &settings, seed);
        Ok(Lab { run })
    }

    /// Advances `n` iterations (never beyond the budget).
    pub fn step(&mut self, n: u32) {
        self.run.step(n);
    }

    /// Iterations done.
    pub fn iteration(&self) -> u32 {
        self.run.iteration()
    }

    /// The iteration budget.
    pub fn iterations(&self) -> u32 {
        self.run.iterations()
    }

    /// Number of particles.
    pub fn particles(&self) -> u32 {
        self.run.particles() as u32
    }

    /// Best value so far.
    pub fn best_value(&self) -> f64 {
        self.run.best_value()
    }

    /// Best point so far.
    pub fn best_position(&self) -> Vec<f64> {
        self.run.best_position().to_vec()
    }

    /// Current positions, row-major.
    pub fn positions(&self) -> Vec<f64> {
        self.run.positions().to_vec()
    }

    /// Best value after initialisation and after each iteration.
    pub fn curve(&self) -> Vec<f64> {
        self.run.curve().to_vec()
    }

    /// Digest of the run's state: equal natively and in wasm for the same seed.
    pub fn digest(&self) -> String {
        self.run.digest()
    }

    /// Draws the 2-D picture (first two coordinates) at `width × height` px.
    pub fn render(&mut self, width: u32, height: u32) {
        self.run.render(width, height);
    }

    /// Address of the RGBA frame in wasm memory.
    pub fn frame_ptr(&self) -> u32 {
        self.run.pixels().as_ptr() as u32
    }

    /// Length of the RGBA frame in bytes.
    pub fn frame_len(&self) -> u32 {
        self.run.pixels().len() as u32
    }
}

/// The lab's menus as JSON `{algorithms: [{name}], functions: [{name, half_range}]}`.
#[wasm_bindgen]
pub fn lab_options_json() -> Result<String, JsError> {
    let algorithms: Vec<_> = Algorithm::ALL.iter().map(|a| serde_json::json!({ "name": a.name() })).collect();
    let functions: Vec<_> = Function::ALL
        .iter()
        .map(|f| serde_json::json!({ "name": f.name(), "half_range": f.half_range() }))
        .collect();
    to_json(&serde_json::json!({ "algorithms": algorithms, "functions": functions }))
}

/// The final best value of run `run` (stream `run` of `seed`): one entry of the 30-run table.
#[wasm_bindgen]
pub fn lab_best_of_run(
    algorithm_name: &str,
    function_name: &str,
    dim: u32,
    population: u32,
    iterations: u32,
    seed: u32,
    run: u32,
) -> Result<f64, JsValue> {
    let settings = settings(dim, population, iterations)?;
    Ok(lab::best_of_run(
        algorithm(algorithm_name)?,
        function(function_name)?,
        dim as usize,
        &settings,
        seed,
        run,
    ))
}

/// Best, worst, mean, median and count of `values` (the lab's 30-run table row) as JSON
/// `{best, worst, mean, median, runs}`: the same statistics as Table 3's cells (`Summary::of`).
#[wasm_bindgen]
pub fn lab_summary_json(values: Vec<f64>) -> Result<String, JsError> {
    to_json(&Summary::of(&values))
}

/// The digest of the pinned reference run (IGSA, Ackley, d = 5, N = 20, T = 100, seed 3).
#[wasm_bindgen]
pub fn lab_reference_digest() -> String {
    lab::reference_digest()
}
