// The Tune page's Web Worker: loads the same wasm module as the page and advances a `TuneRun` one
// generation per 'next' message, so the page stays responsive and can cancel between (or, by
// terminating the worker, during) generations. Wall-clock time here only feeds the rate display.
//
// Messages in:  {type: 'start', setup}  {type: 'next'}
// Messages out: {type: 'started', population, frames, agents, scene}
//               {type: 'generation', stats, scene, ms}
//               {type: 'error', error: errorData(…), panic}: the page words it in its language

import { loadWasm } from '../core/boot.js';
import { errorData, isPanic } from '../core/errors.js';

let run = null;

self.addEventListener('message', async (event) => {
  const message = event.data;
  try {
    const { module } = await loadWasm();
    if (message.type === 'start') {
      run?.free();
      run = null;
      run = new module.TuneRun(JSON.stringify(message.setup));
      self.postMessage({
        type: 'started',
        population: run.population(),
        frames: run.frames(),
        agents: run.agents(),
        scene: run.best_scene_string(),
      });
    } else if (message.type === 'next') {
      if (run === null) throw new Error('no tuning run has started');
      const start = performance.now();
      const stats = JSON.parse(run.generation());
      const ms = performance.now() - start;
      self.postMessage({ type: 'generation', stats, scene: run.best_scene_string(), ms });
    }
  } catch (error) {
    self.postMessage({ type: 'error', error: errorData(error), panic: isPanic(error) });
  }
});
