// The live view's page (live_view.cpp fills in /*CHART_JS*/ and
// /*INITIAL_DATA*/). Fixed geometry, so a screenshot can be checked by
// pixel: the heatmap's cell (r, c) covers x in [20 + 60c, 80 + 60c),
// y in [60 + 60r, 120 + 60r) at device scale 1. Colour: blue (0) to red
// (the frame's maximum), linear in value / max. "/?static" draws the data
// embedded at request time and does not poll.
#pragma once

namespace eskin::stream {

inline constexpr const char* kLiveViewPage = R"PAGE(<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>eskin live</title>
<style>
body { margin: 0; font: 14px sans-serif; background: #fafafa; color: #222; }
h1 { position: absolute; left: 20px; top: 8px; margin: 0; font-size: 20px; }
#heat { position: absolute; left: 20px; top: 60px; }
#heatinfo { position: absolute; left: 20px; top: 8px; margin-top: 28px; font-size: 12px; }
#link { position: absolute; left: 20px; top: 400px; border-collapse: collapse; font-size: 12px; }
#link td { border: 1px solid #ccc; padding: 2px 6px; }
#ampbox { position: absolute; left: 420px; top: 40px; width: 760px; height: 320px; }
#spikebox { position: absolute; left: 420px; top: 380px; width: 760px; height: 320px; }
</style></head>
<body>
<h1>eskin live view</h1>
<div id="heatinfo"></div>
<canvas id="heat" width="60" height="60"></canvas>
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
function drawHeat(tx) {
  const c = document.getElementById('heat');
  if (!tx || tx.rows === 0) return;
  c.width = tx.cols * CELL; c.height = tx.rows * CELL;
  const ctx = c.getContext('2d');
  const max = Math.max(1, ...tx.values);
  for (let r = 0; r < tx.rows; ++r)
    for (let k = 0; k < tx.cols; ++k) {
      const v = tx.values[r * tx.cols + k];
      ctx.fillStyle = colour(v / max);
      ctx.fillRect(k * CELL, r * CELL, CELL, CELL);
      ctx.fillStyle = '#fff'; ctx.font = '11px sans-serif';
      ctx.fillText(String(v), k * CELL + 4, r * CELL + CELL - 6);
    }
  document.getElementById('heatinfo').textContent =
      'taxels at sample ' + tx.t + ' (' + tx.rows + 'x' + tx.cols + ', max ' + max + ')';
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
function drawAmps(a) {
  if (!a.length) return;
  const k = a[0].amp.length;
  ampChart.data.datasets = [];
  for (let i = 0; i < k; ++i)
    ampChart.data.datasets.push({ label: 'carrier ' + i, borderColor: palette[i % palette.length],
      borderWidth: 1, data: a.map(f => ({ x: f.t, y: f.amp[i] })) });
  ampChart.update();
}
function drawSpikes(s) {
  for (let l = 0; l < 2; ++l)
    spikeChart.data.datasets[l].data =
        s.filter(e => (e.layer > 0 ? 1 : 0) === l).map(e => ({ x: e.t, y: e.neuron }));
  spikeChart.update();
}
function drawLink(d) {
  const rows = [];
  const add = (o, prefix) => { if (o) for (const [k, v] of Object.entries(o))
    if (k !== 'type') rows.push('<tr><td>' + prefix + k + '</td><td>' + v + '</td></tr>'); };
  add(d.link, ''); add(d.status, 'fpga.');
  document.getElementById('link').innerHTML = rows.join('');
}
function draw(d) { drawHeat(d.taxels); drawAmps(d.amplitudes); drawSpikes(d.spikes); drawLink(d); }
if (initial) draw(initial);
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
