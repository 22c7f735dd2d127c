// The one module that imports the generated WebAssembly package. Everything else (UI, worker)
// imports these typed functions from here.
import init, * as wasm from './pkg/loratrack.js';
import wasmUrl from './pkg/loratrack_bg.wasm?url';

let ready: Promise<void> | undefined;

/** Loads and instantiates the WebAssembly module once; later calls return the same promise. */
export function load(): Promise<void> {
  ready ??= init({ module_or_path: wasmUrl }).then(() => undefined);
  return ready;
}

export type Ldro = 'auto' | 'on' | 'off';

/** Input of timeOnAir: the CLI's `airtime` options in camelCase (SPEC §9). */
export interface AirtimeParams {
  sf: number;
  bw: number;
  payload: number;
  overhead?: number;
  cr?: number;
  preamble?: number;
  implicitHeader?: boolean;
  noCrc?: boolean;
  ldro?: Ldro;
  dutyCycle?: number;
}

/** Output of timeOnAir (seconds, symbols, bytes). */
export interface AirtimeReport {
  timeOnAir: number;
  symbolTime: number;
  payloadSymbols: number;
  phyPayloadBytes: number;
  lowDataRateOptimize: boolean;
  minInterval: number;
}

/** Time on air and 1 % duty-cycle interval of one packet. Throws an Error on bad input. */
export function timeOnAir(params: AirtimeParams): AirtimeReport {
  return wasm.timeOnAir(params) as AirtimeReport;
}
