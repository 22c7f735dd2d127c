// Runs simulations off the main thread so the page never freezes. One message in, one out:
//   { id, params, distances? }  →  { id, progress }* then { id, report } | { id, error }
//                                   then, with distances, { id, sweep: [{ distance, report }] }
import { load, simulate, type SimReport, type SimulateParams } from './loratrack';

export interface Request {
  id: number;
  params: SimulateParams;
  distances?: number[];
}

export type Response =
  | { id: number; progress: number }
  | { id: number; report: SimReport; millis: number }
  | { id: number; error: string }
  | { id: number; sweep: { distance: number; report: SimReport }[] };

const ready = load();

self.onmessage = async (event: MessageEvent<Request>) => {
  await ready;
  const { id, params, distances } = event.data;
  const post = (r: Response) => (self as unknown as Worker).postMessage(r);
  try {
    const t0 = performance.now();
    let last = 0;
    const report = simulate({ ...params, series: true }, (done, total) => {
      // A few dozen messages at most: one per 2 % of the work.
      if (done / total - last >= 0.02 || done === total) {
        last = done / total;
        post({ id, progress: last });
      }
    });
    post({ id, report, millis: performance.now() - t0 });
    if (distances?.length) {
      // Only the link changes between these runs: the drone filters come from the cache.
      const sweep = distances.map((distance) => ({ distance, report: simulate({ ...params, distance, series: false }) }));
      post({ id, sweep });
    }
  } catch (e) {
    post({ id, error: e instanceof Error ? e.message : String(e) });
  }
};
