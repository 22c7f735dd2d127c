import { load, timeOnAir } from './loratrack';

const form = document.querySelector<HTMLFormElement>('#airtime-form')!;
const toa = document.querySelector<HTMLElement>('#toa')!;
const interval = document.querySelector<HTMLElement>('#interval')!;
const error = document.querySelector<HTMLElement>('#airtime-error')!;

function update(): void {
  const data = new FormData(form);
  try {
    const r = timeOnAir({ sf: Number(data.get('sf')), bw: Number(data.get('bw')), payload: Number(data.get('payload')), overhead: 13 });
    toa.textContent = `${(r.timeOnAir * 1e3).toFixed(3)} ms`;
    interval.textContent = `${r.minInterval.toFixed(2)} s`;
    error.hidden = true;
  } catch (e) {
    error.textContent = (e as Error).message;
    error.hidden = false;
  }
}

await load();
form.addEventListener('input', update);
update();
