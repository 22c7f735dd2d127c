// Drawing in steps: each panel is drawn in a task of its own, so the page paints the numbers
// (and answers input) between charts instead of freezing while it draws them all. A step queued
// under a name replaces the one still waiting under that name: only the latest settings' chart
// is drawn, once, however fast they change.

type Step = () => void | Promise<void>;

const waiting = new Map<string, Step>();
let running = false;
let onChange: () => void = () => {};

/** Lets the browser paint and handle input, then resumes (`scheduler.yield` where there is one). */
export function nextTask(): Promise<void> {
  const s = (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler;
  if (s?.yield) return s.yield();
  return new Promise((resolve) => {
    // A message, unlike setTimeout, is not clamped to 4 ms once nested.
    const { port1, port2 } = new MessageChannel();
    port1.onmessage = () => resolve();
    port2.postMessage(null);
  });
}

/** Draws `step` in a later task, after the steps queued before it under other names. */
export function later(name: string, step: Step): void {
  waiting.delete(name);
  waiting.set(name, step);
  if (!running) void drain();
}

/** Whether a step is waiting or being drawn. */
export function drawingLater(): boolean {
  return running;
}

/** Calls `callback` whenever drawing starts or the last waiting step has been drawn. */
export function onDrawing(callback: () => void): void {
  onChange = callback;
}

async function drain(): Promise<void> {
  running = true;
  onChange();
  try {
    while (waiting.size > 0) {
      await nextTask();
      const [name, step] = waiting.entries().next().value as [string, Step];
      waiting.delete(name);
      const start = performance.now();
      try {
        await step();
        // Seen in the browser's performance tools (and the e2e suite's timing report).
        performance.measure(`draw ${name}`, { start });
      } catch (e) {
        // One panel failing to draw must not stop the others; the console says which.
        console.error(`drawing ${name}:`, e);
      }
    }
  } finally {
    running = false;
    onChange();
  }
}
