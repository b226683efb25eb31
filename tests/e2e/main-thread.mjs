// The page's main-thread tasks in CPU time, from a Chromium trace (CDP Tracing, category
// `toplevel`). A long-task observer measures wall time, which grows with whatever else holds the
// core (on a shared 2-core machine a 24 ms slice has been seen at 550 ms); the trace's thread
// time (`tdur`) is what the page itself spent, so "no task over N ms" holds or fails on the page's
// code alone.

/** Top-level task events of Chromium's scheduler; nested ones repeat the same task. */
const TASK_EVENT = 'ThreadControllerImpl::RunTask';

/**
 * Starts tracing `page`; the returned `stop()` ends the trace and resolves to the renderer main
 * thread's tasks of at least `minCpuMs` CPU time, as `{ cpuMs, wallMs }`, longest CPU first.
 */
export async function traceMainThreadTasks(page, { minCpuMs = 50 } = {}) {
  const cdp = await page.context().newCDPSession(page);
  const events = [];
  cdp.on('Tracing.dataCollected', (message) => events.push(...message.value));
  await cdp.send('Tracing.start', {
    traceConfig: { includedCategories: ['toplevel', '__metadata'], enableSampling: false },
    transferMode: 'ReportEvents',
  });
  return {
    async stop() {
      const complete = new Promise((resolve) => cdp.once('Tracing.tracingComplete', resolve));
      await cdp.send('Tracing.end');
      await complete;
      await cdp.detach().catch(() => {});
      const mainThreads = new Set(
        events
          .filter((e) => e.ph === 'M' && e.name === 'thread_name' && e.args?.name === 'CrRendererMain')
          .map((e) => `${e.pid}:${e.tid}`),
      );
      return events
        .filter((e) => e.ph === 'X' && e.name === TASK_EVENT && mainThreads.has(`${e.pid}:${e.tid}`))
        .filter((e) => typeof e.tdur === 'number')
        .map((e) => ({ cpuMs: Math.round(e.tdur / 1000), wallMs: Math.round(e.dur / 1000) }))
        .filter((task) => task.cpuMs >= minCpuMs)
        .sort((a, b) => b.cpuMs - a.cpuMs);
    },
  };
}
