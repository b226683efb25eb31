// The validation suite's worker: loads the same wasm module as the page and runs one
// (test, planner) pair after another, posting progress before each and the outcome (table rows
// and curves, computed in Rust) after it. The page cancels by terminating the worker.

import init, { validation_run_json } from '../../pkg/flockpath.js';
import { errorData } from '../core/errors.js';

const ready = init();

self.onmessage = async ({ data }) => {
  const { tests, planners } = data;
  try {
    await ready;
    const total = tests.length * planners.length;
    let done = 0;
    const started = performance.now();
    for (const test of tests) {
      for (const planner of planners) {
        self.postMessage({ type: 'progress', done, total, test, planner });
        const outcome = JSON.parse(validation_run_json(test, planner));
        done += 1;
        self.postMessage({ type: 'outcome', outcome, done, total });
      }
    }
    self.postMessage({ type: 'done', seconds: (performance.now() - started) / 1000 });
  } catch (error) {
    // The page words it in its language (errorFromData): a worker does not know the page's.
    self.postMessage({ type: 'error', error: errorData(error) });
  }
};
