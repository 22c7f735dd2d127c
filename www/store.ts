// The page's one state store: what the form says, what the numbers on show were made from, what
// came with the link. Every module of the page reads and changes that state here and nowhere
// else, so "which settings made these numbers?" has one answer.
import { presenting } from './dom';
import type { SimReport, SimulateParams } from './loratrack';
import { fromQuery, toQuery, type Settings } from './state';
import { swarmQuery } from './swarmChoices';

// Outside a page (the unit tests) there is no link: the defaults.
const search = typeof location === 'undefined' ? '' : location.search;
const query = new URLSearchParams(search);
const parsed = fromQuery(search);

export interface Store {
  /** The link's query, as the page was opened. */
  query: URLSearchParams;
  /** Shown in an iframe with only some panels (`?embed=1`). */
  embed: boolean;
  /** The panels an embed shows, comma-separated. */
  panels: string;
  /** The settings in the form (the last valid ones). */
  settings: Settings;
  /** The settings that made `report`: the form may have moved on since. */
  reportSettings: Settings;
  /** The numbers on show. */
  report?: SimReport;
  /** What the command lines that give the numbers on show are written from, the results' and the
   * largest swarm's: the runs' parameters, and the line once written (command.ts). */
  commands: { results?: { params: SimulateParams; line?: string }; swarm?: { params: SimulateParams; line?: string } };
  /** The swarms on show: the drone settings they were made from, and whether every drone flew
   * the form's SF (a fixed SF plan) or the drones were dealt SF7..SF12 in turn. The caption of an
   * embed of the swarm panel says what they rest on, whatever the panel's choices say since. */
  swarm?: { settings: Settings; fixedSf: boolean };
  /** The pinned baseline and the settings that made it. */
  baseline?: { report: SimReport; settings: Settings };
  /** An uploaded CSV flight (never in the URL), kept as its bytes in a Blob: the workers read its
   * text, so that neither decoding 31 MB nor copying it to each worker holds up the page. */
  csv?: { file: Blob; name: string };
  /** The uploaded flight's mission plan (never in the URL): what the mission station flies. */
  plan?: { text: string; name: string };
  /** Sentences about the link: values replaced, unknown panels, a baseline that failed. */
  notices: string[];
  /** The id of the lesson on show beside the results, which the page's URL keeps. */
  lesson?: string;
  /** While no results are on show because the core refused the settings: the status line's
   * words, which an embed of charts alone (without the status) carries in its caption. */
  refused?: string;
}

export const store: Store = {
  query,
  embed: query.get('embed') === '1',
  panels: 'results,error',
  settings: parsed.settings,
  reportSettings: parsed.settings,
  notices: [...parsed.problems],
  commands: {},
};

/** The page's URL query: the settings, the swarm panel's choices, the pinned baseline's settings,
 * the embed choice and the lesson on show. */
export function pageQuery(): string {
  const extra: Record<string, string> = { ...swarmQuery(), ...(store.embed ? { embed: '1', panels: store.panels } : {}) };
  if (presenting()) extra.present = '1';
  if (store.baseline) extra.baseline = toQuery(store.baseline.settings);
  if (store.lesson) extra.lesson = store.lesson;
  return toQuery(store.settings, extra);
}

