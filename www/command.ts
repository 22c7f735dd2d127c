// The command line that gives the numbers a panel shows, as the core writes it from the settings
// of the run that made them (`commandLine`), at the end of the panel's "What this shows", with a
// button that copies it: the results' (`loratrack simulate`) and the largest swarm's.
import { commandLine, type SimulateParams } from './loratrack';
import { $ } from './dom';
import { listed } from './format';
import { store } from './store';

/** The panels whose numbers have a command line: the `data-command` of its paragraph. */
export type CommandPanel = 'results' | 'swarm';

/** Shows in `panel` the command that runs `params` (for a swarm, with `loratrack swarm`), naming
 * the files it reads: an uploaded flight and plan, by their names. Written in a task of its own,
 * after the numbers it belongs to are on screen: the module's first call of `commandLine` on a
 * load took 3–14 ms, in the task that showed the first results. */
export function showCommand(panel: CommandPanel, params: SimulateParams): void {
  store.commands[panel] = { params };
  setTimeout(() => writeCommand(panel), 0);
}

/** The command line of `panel`'s numbers on show (written now if its task has not yet run), or
 * undefined before any. */
export function commandOf(panel: CommandPanel): string | undefined {
  const c = store.commands[panel];
  if (c && c.line === undefined) c.line = commandLine(c.params, panel === 'swarm' ? 'swarm' : 'simulate');
  return c?.line;
}

function writeCommand(panel: CommandPanel): void {
  const params = store.commands[panel]?.params;
  const line = commandOf(panel);
  if (!params || line === undefined) return;
  const p = paragraph(panel);
  p.querySelector('code')!.replaceChildren(...commandWords(line));
  const files = [params.trajectoryName, params.planName].filter((f): f is string => Boolean(f));
  p.querySelector('.command-files')!.textContent = files.length ? `, run where ${listed(files)} ${files.length > 1 ? 'are' : 'is'}` : '';
  p.querySelector('.copy-status')!.textContent = '';
  p.hidden = false;
}

/** Makes each panel's Copy command button copy its command. */
export function setUpCopyCommand(): void {
  for (const panel of ['results', 'swarm'] as const) {
    const p = paragraph(panel);
    p.querySelector('button')!.addEventListener('click', async () => {
      const status = p.querySelector('.copy-status')!;
      try {
        await navigator.clipboard.writeText(commandOf(panel) ?? '');
        status.textContent = 'Command copied.';
      } catch {
        status.textContent = 'Select the command to copy it.';
      }
    });
  }
}

const paragraph = (panel: CommandPanel) => $(`[data-command="${panel}"]`);

/** A command line's words, each option with its value, in spans a line may break between (and the
 * spaces between them as text, so that a selection copies the command as it is). */
function commandWords(line: string): (HTMLElement | string)[] {
  // A word: quoted parts, escaped quotes and plain characters up to a space (the core quotes as
  // a POSIX shell reads it).
  const words = line.match(/(?:'[^']*'|\\'|[^\s'\\])+/g) ?? [];
  const groups: string[] = [];
  for (let i = 0; i < words.length; i++) {
    const joined = i === 0 || (words[i].startsWith('--') && i + 1 < words.length && !words[i + 1].startsWith('--'));
    groups.push(joined ? `${words[i]} ${words[++i] ?? ''}`.trim() : words[i]);
  }
  return groups.flatMap((g, i) => {
    const span = document.createElement('span');
    span.textContent = g;
    return i === 0 ? [span] : [' ', span];
  });
}
