// The Tune page's Web Worker: loads the same wasm module as the page and advances a `TuneRun` one
// generation per 'next' message, so the page stays responsive and can cancel between (or, by
// terminating the worker, during) generations. Wall-clock time here only feeds the rate display.
//
// Messages in:  {type: 'start', setup}  {type: 'next'}
// Messages out: {type: 'started', population, frames, agents, scene}
//               {type: 'generation', stats, scene, ms}
//               {type: 'error', message, panic}

import init, { TuneRun } from '../../pkg/flockpath.js';

let loaded = null;
let run = null;

function messageOf(error) {
  return error instanceof Error ? error.message || String(error) : String(error);
}

self.addEventListener('message', async (event) => {
  const message = event.data;
  try {
    loaded ??= init();
    await loaded;
    if (message.type === 'start') {
      run?.free();
      run = null;
      run = new TuneRun(JSON.stringify(message.setup));
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
    const panic = typeof WebAssembly !== 'undefined' && error instanceof WebAssembly.RuntimeError;
    self.postMessage({ type: 'error', message: messageOf(error), panic });
  }
});
