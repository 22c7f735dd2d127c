// Embedding: `?embed=1&panels=…` shows only the chosen panels in an iframe, with a caption of
// the settings and every notice, no Pin, and the frame's height posted to the host page; the
// Embed dialog builds the snippet that uses it.
import { $ } from './dom';
import { caption, describe } from './format';
import { restingNotes } from './results';
import { swarmSettings, toQuery } from './state';
import { store } from './store';
import { swarmQuery } from './swarmChoices';

/** Every panel an embed can show, by its `data-panel` name. */
export const PANELS = ['controls', 'results', 'trajectory', 'error', 'axes', 'distance', 'sf', 'link', 'swarm', 'airtime'];

/** The panels that show the single drone's run (its flight and seeds). */
const SINGLE_DRONE_PANELS = ['results', 'trajectory', 'error', 'axes', 'distance', 'sf'];

/** Of those, the charts that run it again at other SFs or distances: what each sweeps. */
const SWEEP_CHARTS: Record<string, string> = { sf: 'SFs', distance: 'distances' };

/** Hides every panel but the chosen ones, explains unknown names, and starts posting the height. */
export function setUpEmbed(): void {
  if (!store.embed) return;
  document.body.classList.add('embed');
  const asked = (store.query.get('panels') ?? store.panels).split(',').map((p) => p.trim()).filter(Boolean);
  const known = asked.filter((p) => PANELS.includes(p));
  if (known.length < asked.length || known.length === 0) {
    store.notices.push(`Unknown panel${asked.length - known.length === 1 ? '' : 's'} in the link (${asked.filter((p) => !PANELS.includes(p)).join(', ') || 'none named'}); the panels are ${PANELS.join(', ')}.`);
  }
  store.panels = (known.length ? known : store.panels.split(',')).join(',');
  for (const el of document.querySelectorAll<HTMLElement>('[data-panel]')) el.hidden = !store.panels.split(',').includes(el.dataset.panel!);
  // The heading stays for screen readers, the credit and a way to the full page stay visible.
  for (const el of document.querySelectorAll<HTMLElement>('[data-chrome]')) el.classList.add('visually-hidden');
  const full = $<HTMLAnchorElement>('#open-full');
  const url = new URL(location.href);
  url.searchParams.delete('embed');
  url.searchParams.delete('panels');
  full.href = url.toString();
  full.hidden = false;
  // An embed says which settings it shows; Pin compares runs, which an embed does not make.
  $('#embed-caption').hidden = false;
  $('#pin').hidden = true;
  // The host page can grow the frame to its content (README: the snippet that listens).
  if (window.parent !== window) {
    let last = 0;
    new ResizeObserver(() => {
      const height = Math.ceil(document.documentElement.scrollHeight);
      if (height === last) return;
      last = height;
      window.parent.postMessage({ loratrackHeight: height }, '*');
    }).observe(document.body);
  }
}

/** In an embed: the settings behind the numbers, and every notice (the form is not shown) that the
 * embed's panels do not show themselves. The caption is kept on the full page too, hidden: a
 * printed page shows it instead of the form, with the link's notices from the top of the form, and
 * prints the results' own notes where they stand. */
export function updateEmbedCaption(): void {
  // An embed of the swarm panel without the single drone's results or charts is captioned with
  // what its swarms rest on (the flights they chain, one seed), not the single drone's flight.
  const shown = store.panels.split(',');
  const swarmAlone = store.embed && shown.includes('swarm') && !shown.some((p) => SINGLE_DRONE_PANELS.includes(p));
  // The swarms on show, or before any the ones Run swarm would run; a spread swarm's drones are
  // dealt SF7..SF12 in turn, not the form's SF.
  const swarm = store.swarm ?? { settings: swarmSettings(store.reportSettings), fixedSf: $<HTMLSelectElement>('#swarmPlan').value === 'fixed' };
  const settings = swarmAlone ? caption(swarm.settings, '', { fixedSf: swarm.fixedSf }) : caption(store.reportSettings);
  $('#embed-settings').textContent = `Settings: ${settings}.`;
  const lines = [...store.notices];
  const results = $('[data-panel="results"]');
  // An embed with the results panel shows its notes and its old or partial label there, once;
  // an embed of charts alone carries them here.
  if (store.embed && results.hidden) {
    if (store.refused) lines.push(store.refused);
    const notes = restingNotes();
    // Beside the SF or distance chart alone, the run's notes ("These errors cover 17 % of the flight
    // time") read as if about every point of the chart, which sweeps past the settings above.
    const sweeps = shown.filter((p) => p in SWEEP_CHARTS);
    const runShown = shown.some((p) => SINGLE_DRONE_PANELS.includes(p) && !(p in SWEEP_CHARTS));
    if (notes.length && sweeps.length && !runShown) {
      lines.push(`These notes are about the one run at these settings, not ${sweeps.length > 1 ? "the charts'" : "the chart's"} other ${sweeps.map((p) => SWEEP_CHARTS[p]).join(' and ')}:`);
    }
    lines.push(...notes);
    if (results.classList.contains('stale')) lines.push('The numbers shown are for the previous settings.');
    if (results.classList.contains('partial')) lines.push('The numbers shown are the first flight’s alone; the rest of the set is still running.');
  }
  $('#embed-notices').hidden = lines.length === 0;
  $('#embed-notices').textContent = lines.join(' ');
}

/** A panel's title as the page shows it: its heading. */
const panelTitle = (panel: HTMLElement): string => panel.querySelector('h2')?.textContent?.trim() ?? panel.dataset.panel!;

/** The Embed dialog: pick panels, copy a snippet that sizes its frame. */
export function setUpEmbedDialog(): void {
  const embedDialog = $<HTMLDialogElement>('#embed-dialog');
  // Each panel by the title the reader sees over it, in the page's order (the link's name, which
  // the snippet writes, in its tooltip).
  for (const panel of document.querySelectorAll<HTMLElement>('[data-panel]')) {
    const name = panel.dataset.panel!;
    const label = document.createElement('label');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.value = name;
    box.checked = ['results', 'error'].includes(name);
    label.title = `panels=${name} in the link`;
    label.append(box, ` ${panelTitle(panel)}`);
    $('#embed-panels').append(label);
  }

  function embedSnippet(): string {
    const chosen = [...document.querySelectorAll<HTMLInputElement>('#embed-panels input:checked')].map((b) => b.value);
    const url = new URL(location.href);
    url.search = `?${toQuery(store.settings, { ...(chosen.includes('swarm') ? swarmQuery() : {}), embed: '1', panels: (chosen.length ? chosen : ['results']).join(',') })}`;
    return `<iframe id="loratrack" src="${url.toString().replace(/&/g, '&amp;')}" title="loratrack: LoRa tracking playground (${describe(store.settings)})" style="width: 100%; border: 0" height="600" loading="lazy"></iframe>
<script>
  // The frame posts its content height; grow it to fit.
  addEventListener('message', (e) => {
    const frame = document.getElementById('loratrack');
    if (e.source === frame.contentWindow && e.data && e.data.loratrackHeight) frame.style.height = e.data.loratrackHeight + 'px';
  });
</script>`;
  }

  $('#embed-open').addEventListener('click', () => {
    $<HTMLTextAreaElement>('#embed-snippet').value = embedSnippet();
    $('#embed-status').textContent = '';
    embedDialog.showModal();
  });
  $('#embed-panels').addEventListener('change', () => ($<HTMLTextAreaElement>('#embed-snippet').value = embedSnippet()));
  $('#embed-close').addEventListener('click', () => embedDialog.close());
  $('#embed-copy').addEventListener('click', async () => {
    const snippet = $<HTMLTextAreaElement>('#embed-snippet').value;
    try {
      await navigator.clipboard.writeText(snippet);
      $('#embed-status').textContent = 'Snippet copied.';
    } catch {
      $<HTMLTextAreaElement>('#embed-snippet').select();
      $('#embed-status').textContent = 'Select the snippet and copy it (the clipboard is not available here).';
    }
  });
}
