// The swarm panel's choices in the page's link: each select's id is its key (`swarmDrones=100`),
// kept where it is not the panel's default (the option index.html marks selected), so that a
// copied link, or an embed of the panel, opens the panel as it was. The options themselves are
// the panel's: a value that is not one of them falls back to the default, with a sentence.

/** The swarm panel's selects, in its order. */
export const swarmSelects = (): HTMLSelectElement[] => [...document.querySelectorAll<HTMLSelectElement>('.swarm-controls select')];

const defaultOf = (s: HTMLSelectElement): string => ([...s.options].find((o) => o.defaultSelected) ?? s.options[0]).value;

/** The choices away from their defaults, as link keys and values. */
export function swarmQuery(): Record<string, string> {
  return Object.fromEntries(swarmSelects().flatMap((s) => (s.value === defaultOf(s) ? [] : [[s.id, s.value]])));
}

/** Puts every choice of the panel back to its default (the page's Reset). */
export function resetSwarmChoices(): void {
  for (const s of swarmSelects()) s.value = defaultOf(s);
}

/** Sets the panel from the link's keys; returns a sentence for each value that is not one of its
 * select's options (that select keeps its default). */
export function readSwarmQuery(q: URLSearchParams): string[] {
  return swarmSelects().flatMap((s) => {
    const v = q.get(s.id);
    if (v === null) return [];
    const values = [...s.options].map((o) => o.value);
    if (values.includes(v)) {
      s.value = v;
      return [];
    }
    return [`The link's ${s.id}=${v.slice(0, 40)} is not one of the swarm panel's choices (${values.join(', ')}); it keeps ${defaultOf(s)}.`];
  });
}
