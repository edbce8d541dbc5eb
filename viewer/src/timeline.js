// The time slider (issue #25 item 1): frames or load steps with play/pause; frames whose verdict is
// "clash" are marked on the slider.
import { VERDICT_COLORS, hexToCss } from './colors.js';
import { el } from './format.js';

const PLAY_MS = 600;

export function buildTimeline(root, frames, onFrame) {
  const n = frames.labels.length;
  const play = el('button', { id: 'play', type: 'button', title: 'Play / pause' }, '▶');
  const slider = el('input', { id: 'frame-slider', type: 'range', min: 0, max: Math.max(0, n - 1), step: 1, value: 0 });
  const label = el('span', { id: 'frame-label' });
  const marks = el('div', { className: 'marks' });
  frames.verdicts.forEach((v, k) => {
    if (v !== 'clash' && v !== 'contact') return;
    const m = el('span', { className: 'mark', title: `${frames.labels[k]}: ${v}` });
    m.style.left = n > 1 ? `${(k / (n - 1)) * 100}%` : '0';
    m.style.background = hexToCss(VERDICT_COLORS[v]);
    m.dataset.frame = String(k);
    marks.append(m);
  });
  root.append(play, el('div', { className: 'track' }, slider, marks), label);
  root.hidden = false;

  let timer = null;
  const show = (k) => {
    slider.value = String(k);
    const t = frames.times.length === n && Number.isFinite(frames.times[k]) ? ` · t = ${frames.times[k]}` : '';
    const v = frames.verdicts[k] ? ` · ${frames.verdicts[k]}` : '';
    label.textContent = `${k + 1}/${n} ${frames.labels[k]}${t}${v}`;
  };
  const stop = () => {
    clearInterval(timer);
    timer = null;
    play.textContent = '▶';
  };
  slider.addEventListener('input', () => onFrame(Number(slider.value)));
  play.addEventListener('click', () => {
    if (timer !== null) return stop();
    play.textContent = '❚❚';
    timer = setInterval(() => onFrame((Number(slider.value) + 1) % n), PLAY_MS);
  });
  return { show, stop };
}
