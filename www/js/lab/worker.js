// The lab's 30-run worker: loads the same wasm module as the page and runs one seeded optimizer
// run after another, posting progress after each and one table row per algorithm. The page
// cancels by terminating the worker, so a long run never has to poll for a flag.

import init, { lab_best_of_run } from '../../pkg/flockpath.js';

const ready = init();

/** Median of a sorted array. */
const median = (sorted) => {
  const n = sorted.length;
  return n % 2 ? sorted[(n - 1) / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
};

self.onmessage = async ({ data }) => {
  const { algorithms, fn, dim, population, iterations, seed, runs } = data;
  try {
    await ready;
    const total = algorithms.length * runs;
    let done = 0;
    const started = performance.now();
    for (const algorithm of algorithms) {
      const values = [];
      for (let run = 0; run < runs; run += 1) {
        values.push(lab_best_of_run(algorithm, fn, dim, population, iterations, seed, run));
        done += 1;
        self.postMessage({ type: 'progress', done, total });
      }
      const sorted = [...values].sort((a, b) => a - b);
      const mean = values.reduce((a, b) => a + b, 0) / values.length;
      self.postMessage({
        type: 'row',
        row: { algorithm, best: sorted[0], worst: sorted[sorted.length - 1], mean, median: median(sorted), runs: values.length },
      });
    }
    self.postMessage({ type: 'done', seconds: (performance.now() - started) / 1000 });
  } catch (error) {
    self.postMessage({ type: 'error', message: String(error?.message ?? error) });
  }
};
