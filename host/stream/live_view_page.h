// The live view's page (live_view.cpp fills in /*CHART_JS*/ and
// /*INITIAL_DATA*/). Fixed geometry, so a screenshot can be checked by
// pixel: the heatmap's cell (r, c) covers x in [20 + 60c, 80 + 60c),
// y in [60 + 60r, 120 + 60r) at device scale 1. Colour: blue (0) to red
// (the frame's maximum), linear in value / max, the value in the taxel
// unit when the stream has one (kPa with --scene), else the code. The
// colour bar beside it: x in [20 + 60 cols + 12, +16), the map's height,
// red at the top (the maximum, labelled) to blue at the bottom (0). The
// link's health (#health) sits above the amplitude chart, red when any
// error count is not 0; the command form (#cmd) below the map. "/?static"
// draws the data embedded at request time and does not poll.
#pragma once

namespace eskin::stream {

// The geometry above, for tests that read a screenshot.
struct LiveViewGeometry {
  static constexpr int kCell = 60, kHeatX = 20, kHeatY = 60;
  static constexpr int kBarGap = 12, kBarWidth = 16;
  static constexpr int bar_x(int cols) { return kHeatX + kCell * cols + kBarGap; }
};

inline constexpr const char* kLiveViewPage = R"PAGE(<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>eskin live</title>
<style>
body { margin: 0; font: 14px sans-serif; background: #fafafa; color: #222; }
h1 { position: absolute; left: 20px; top: 8px; margin: 0; font-size: 20px; }
#heat { position: absolute; left: 20px; top: 60px; }
#heatinfo { position: absolute; left: 20px; top: 8px; margin-top: 28px; font-size: 12px; }
#link { position: absolute; left: 20px; top: 430px; border-collapse: collapse; font-size: 12px; }
#bar { position: absolute; top: 60px; }
#barmax, #barmin { position: absolute; font-size: 12px; }
#health { position: absolute; left: 420px; top: 8px; width: 760px; padding: 3px 6px;
  font-size: 13px; background: #e6f4e6; }
#health.bad { background: #f8d0d0; font-weight: bold; }
#cmd { position: absolute; left: 20px; top: 300px; width: 380px; font-size: 12px; }
#cmd select, #cmd input, #cmd button { font-size: 12px; margin: 2px 2px 2px 0; }
#cmdargs input { width: 70px; }
#verdict { margin-top: 4px; }
#link td { border: 1px solid #ccc; padding: 2px 6px; }
#ampbox { position: absolute; left: 420px; top: 40px; width: 760px; height: 320px; }
#spikebox { position: absolute; left: 420px; top: 380px; width: 760px; height: 320px; }
</style></head>
<body>
<h1>eskin live view</h1>
<div id="heatinfo"></div>
<canvas id="heat" width="60" height="60"></canvas>
<canvas id="bar" width="16" height="60"></canvas>
<div id="barmax"></div><div id="barmin"></div>
<div id="health"></div>
<div id="cmd"><b>command</b> <select id="cmdname"></select><span id="cmdargs"></span>
<button id="cmdsend">send</button><div id="cmdhelp"></div><div id="verdict"></div></div>
<table id="link"></table>
<div id="ampbox"><canvas id="amp"></canvas></div>
<div id="spikebox"><canvas id="spikes"></canvas></div>
<script>/*CHART_JS*/</script>
<script>
const CELL = 60;
const initial = /*INITIAL_DATA*/null;
function colour(f) {
  const r = Math.round(20 + 210 * f), g = Math.round(40 - 10 * f), b = Math.round(160 - 130 * f);
  return 'rgb(' + r + ',' + g + ',' + b + ')';
}
const fmt = v => (Math.abs(v) >= 100 || Number.isInteger(v)) ? String(Math.round(v)) : v.toFixed(1);
function drawHeat(tx) {
  const c = document.getElementById('heat');
  if (!tx || tx.rows === 0) return;
  const vals = tx.values_unit || tx.values, unit = tx.unit || 'code';
  c.width = tx.cols * CELL; c.height = tx.rows * CELL;
  const ctx = c.getContext('2d');
  const max = Math.max(tx.values_unit ? 1e-9 : 1, ...vals);
  for (let r = 0; r < tx.rows; ++r)
    for (let k = 0; k < tx.cols; ++k) {
      const v = vals[r * tx.cols + k];
      ctx.fillStyle = colour(v / max);
      ctx.fillRect(k * CELL, r * CELL, CELL, CELL);
      ctx.fillStyle = '#fff'; ctx.font = '11px sans-serif';
      ctx.fillText(fmt(v), k * CELL + 4, r * CELL + CELL - 6);
    }
  // The colour bar: the same ramp, maximum at the top.
  const bar = document.getElementById('bar'), x = CELL * tx.cols + 32;
  bar.style.left = x + 'px'; bar.height = tx.rows * CELL;
  const b = bar.getContext('2d');
  for (let y = 0; y < bar.height; ++y) {
    b.fillStyle = colour(1 - y / (bar.height - 1)); b.fillRect(0, y, bar.width, 1);
  }
  const top = document.getElementById('barmax'), bottom = document.getElementById('barmin');
  top.style.left = bottom.style.left = (x + 20) + 'px';
  top.style.top = '60px'; bottom.style.top = (60 + tx.rows * CELL - 14) + 'px';
  top.textContent = fmt(max) + ' ' + unit; bottom.textContent = '0 ' + unit;
  document.getElementById('heatinfo').textContent =
      'taxels at sample ' + tx.t + ' (' + tx.rows + 'x' + tx.cols + ', max ' + fmt(max) + ' ' + unit +
      (tx.unit ? '' : ': conductance code, UQ1.15; give --scene for kPa') + ')';
}
const palette = ['#1f77b4','#ff7f0e','#2ca02c','#d62728','#9467bd','#8c564b','#e377c2','#7f7f7f'];
const ampChart = new Chart(document.getElementById('amp'), {
  type: 'line', data: { datasets: [] },
  options: { animation: false, parsing: false, responsive: true, maintainAspectRatio: false,
    plugins: { title: { display: true, text: 'carrier amplitudes' } },
    elements: { point: { radius: 0 } },
    scales: { x: { type: 'linear', title: { display: true, text: 'sample' } },
              y: { title: { display: true, text: 'magnitude' } } } } });
const spikeChart = new Chart(document.getElementById('spikes'), {
  type: 'scatter', data: { datasets: [
    { label: 'layer 0 (receptors)', data: [], pointRadius: 2, backgroundColor: '#222' },
    { label: 'layer 1 (weighted)', data: [], pointRadius: 2, backgroundColor: '#d62728' }] },
  options: { animation: false, parsing: false, responsive: true, maintainAspectRatio: false,
    plugins: { title: { display: true, text: 'spike raster' } },
    scales: { x: { type: 'linear', title: { display: true, text: 'sample' } },
              y: { title: { display: true, text: 'neuron (taxel)' } } } } });
// The x axis on the data's extent; Chart.js's round ticks inside it.
function tight(chart, lo, hi) {
  if (!(hi > lo)) return;
  const x = chart.options.scales.x;
  x.min = lo; x.max = hi; x.ticks = Object.assign(x.ticks || {}, { includeBounds: false });
}
let carriers = [];
function drawAmps(a) {
  if (!a.length) return;
  const k = a[0].amp.length;
  ampChart.data.datasets = [];
  for (let i = 0; i < k; ++i)
    ampChart.data.datasets.push({ label: carriers[i] || ('carrier ' + i), borderColor: palette[i % palette.length],
      borderWidth: 1, data: a.map(f => ({ x: f.t, y: f.amp[i] })) });
  tight(ampChart, a[0].t, a[a.length - 1].t);
  ampChart.update();
}
function drawSpikes(s) {
  for (let l = 0; l < 2; ++l)
    spikeChart.data.datasets[l].data =
        s.filter(e => (e.layer > 0 ? 1 : 0) === l).map(e => ({ x: e.t, y: e.neuron }));
  if (s.length) tight(spikeChart, s[0].t, s[s.length - 1].t);
  spikeChart.update();
}
function drawLink(d) {
  const rows = [];
  const add = (o, prefix) => { if (o) for (const [k, v] of Object.entries(o))
    if (k !== 'type') rows.push('<tr><td>' + prefix + k + '</td><td>' + v + '</td></tr>'); };
  add(d.link, ''); add(d.status, 'fpga.');
  document.getElementById('link').innerHTML = rows.join('');
}
// The link's health at a glance: errors and losses, red when any is not 0.
function drawHealth(l) {
  const h = document.getElementById('health');
  if (!l) { h.textContent = 'link: no statistics'; return; }
  const bad = ['framing_errors', 'crc_errors', 'payload_errors', 'seq_gaps', 'lost_packets'];
  const errors = bad.reduce((n, k) => n + (l[k] || 0), 0);
  h.className = errors ? 'bad' : '';
  h.textContent = 'link: ' + l.frames_ok + ' packets, framing errors ' + l.framing_errors +
      ', CRC errors ' + l.crc_errors + ', payload errors ' + l.payload_errors + ', sequence gaps ' +
      l.seq_gaps + ', lost packets ' + l.lost_packets + ', reconnects ' + Math.max(0, l.connects - 1);
}
function draw(d) {
  if (d.carriers && d.carriers.length) carriers = d.carriers;
  drawHeat(d.taxels); drawAmps(d.amplitudes); drawSpikes(d.spikes); drawLink(d); drawHealth(d.link);
}
// The command form: the list from /commands.json, the verdict from POST /command.
let commands = [];
function showArgs() {
  const c = commands[document.getElementById('cmdname').selectedIndex];
  const span = document.getElementById('cmdargs');
  span.innerHTML = '';
  if (!c) return;
  for (const a of c.args) {
    const i = document.createElement('input'); i.placeholder = a; span.appendChild(i);
  }
  document.getElementById('cmdhelp').textContent = c.help;
}
async function loadCommands() {
  try { commands = await (await fetch('/commands.json')).json(); } catch (e) { return; }
  const sel = document.getElementById('cmdname');
  for (const c of commands) {
    const o = document.createElement('option'); o.textContent = c.name; sel.appendChild(o);
  }
  sel.onchange = showArgs; showArgs();
}
document.getElementById('cmdsend').onclick = async () => {
  const c = commands[document.getElementById('cmdname').selectedIndex];
  if (!c) return;
  const args = [...document.querySelectorAll('#cmdargs input')].map(i => i.value);
  const v = document.getElementById('verdict');
  v.textContent = c.name + ': sent';
  try {
    const r = await (await fetch('/command', { method: 'POST',
        body: JSON.stringify({ command: c.name, args: args }) })).json();
    v.textContent = c.name + ' ' + args.join(' ') + ': ' + (r.ok === false ? 'error: ' + r.error :
        r.ack + (r.message && r.message !== r.ack ? ' (' + r.message + ')' : ''));
  } catch (e) { v.textContent = c.name + ': ' + e; }
};
if (initial) draw(initial);
loadCommands();
// ?static: draw the data embedded in the page and stop (screenshots: a page
// that keeps polling never lets a headless browser's virtual time settle).
const polling = !new URLSearchParams(location.search).has('static');
async function poll() {
  try { draw(await (await fetch('/data.json', { cache: 'no-store' })).json()); } catch (e) {}
  setTimeout(poll, 250);
}
if (polling) setTimeout(poll, 250);
</script></body></html>
)PAGE";

}  // namespace eskin::stream
