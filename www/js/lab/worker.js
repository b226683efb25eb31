// The lab's 30-run worker: loads the same wasm module as the page and runs one seeded optimizer
// run after another, posting progress after each and one table row per algorithm (its statistics
// computed in Rust). The page cancels by terminating the worker, so a long run never has to poll
// for a flag.

import { loadWasm } from '../core/boot.js';
import { errorData } from '../core/errors.js';

self.onmessage = async ({ data }) => {
  const { algorithms, fn, dim, population, iterations, seed, runs } = data;
  try {
    const { module } = await loadWasm();
    const total = algorithms.length * runs;
    let done = 0;
    const started = performance.now();
    for (const algorithm of algorithms) {
      const values = [];
      for (let run = 0; run < runs; run += 1) {
        values.push(module.lab_best_of_run(algorithm, fn, dim, population, iterations, seed, run));
        done += 1;
        self.postMessage({ type: 'progress', done, total });
      }
      // Best, worst, mean and median as Table 3 computes them (Summary::of in Rust).
      const summary = JSON.parse(module.lab_summary_json(Float64Array.from(values)));
      self.postMessage({ type: 'row', row: { algorithm, ...summary } });
    }
    self.postMessage({ type: 'done', seconds: (performance.now() - started) / 1000 });
  } catch (error) {
    // The page words it in its language (errorFromData): a worker does not know the page's.
    self.postMessage({ type: 'error', error: errorData(error) });
  }
};
