// What the live view costs and delivers (issue 33's streaming targets),
// measured in one run of this script:
//
//   node benchmarks/live_view.mjs build/tissuefem [muscle liver beam haptic]
//
// (needs tests/browser/install.sh's Chromium and puppeteer-core). For each
// scene, three runs with the live view on, paced as fast as possible, one
// after the other: with no page; with a reader (benchmarks/view_reader.py:
// a WebSocket client that takes every frame and draws nothing, the
// streaming's own cost); with a headless Chromium page (software WebGL,
// started with nice 19 so that on two cores the rendering yields to the
// simulation, as a GPU would take it off the cores). From the reader:
// frames received per second; from the page: fresh frames drawn per second
// (new steps, sampled each second; median and the lowest after the first
// second) and bytes per frame; from statistics.csv: the step's wall time,
// median and 95th percentile. Targets: at least 30 fresh frames per second
// on the muscle and the liver; an open page adds at most 5 % to the median
// step. 'haptic': the muscle palpation driven at 500 Hz by
// tests/live/stream_client.py with no page, the reader and the page: the
// device's latency median and 99th percentile (target: a page adds nothing
// to the 99th percentile).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {spawn, spawnSync} from 'node:child_process';
import {createRequire} from 'node:module';

const here = path.dirname(new URL(import.meta.url).pathname);
const require = createRequire(path.join(here, '../tests/browser/package.json'));
const puppeteer = require('puppeteer-core');

// Options: --threads N (tissuefem's threads per run; default: its own
// choice, all cores), --nice N (Chromium's niceness; default 19),
// --repeats R (each mode R times, alternating; the figures are the median
// over the repeats, the ranges [lowest, highest]; default 3).
const options = {threads: null, nice: 19, repeats: 3};
const positional = [];
for (let k = 2; k < process.argv.length; ++k)
  if (process.argv[k] === '--threads') options.threads = process.argv[++k];
  else if (process.argv[k] === '--nice') options.nice = Number(process.argv[++k]);
  else if (process.argv[k] === '--repeats') options.repeats = Number(process.argv[++k]);
  else positional.push(process.argv[k]);
const exe = path.resolve(positional[0] || 'build/tissuefem');
const wanted = positional.slice(1).length ? positional.slice(1) : ['muscle', 'liver', 'beam', 'haptic'];
const threads = options.threads ? ['--threads', options.threads] : [];
const root = path.resolve(here, '..');
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'live-view-bench-'));

const scenes = {
  muscle: {file: 'parameters/jeffrey_muscle.prm', set: ['Time integration/End time=0.5']},
  liver: {file: 'parameters/liver_gravity.prm', set: ['Time integration/End time=30']},
  beam: {file: 'parameters/sofa/beam_large.prm', set: ['Time integration/End time=1']},
};

function quantile(values, q) {
  const v = [...values].sort((a, b) => a - b);
  return v.length ? v[Math.min(v.length - 1, Math.floor(q * v.length))] : NaN;
}

function stepSeconds(directory) {
  const lines = fs.readFileSync(path.join(directory, 'results', 'statistics.csv'), 'utf8').trim().split('\n');
  const column = lines[0].split(',').indexOf('step_seconds');
  return lines.slice(1).map((l) => Number(l.split(',')[column]));
}

// A reader of every frame (no drawing), started on the run's address file.
function reader(directory) {
  const child = spawn('python3', [path.join(here, 'view_reader.py'),
                                  path.join(directory, 'results', 'live_view')],
                      {stdio: ['ignore', 'pipe', 'inherit']});
  let out = '';
  child.stdout.on('data', (d) => { out += d; });
  return new Promise((resolve) => child.on('exit', () => {
    try { resolve(JSON.parse(out)); } catch (e) { resolve({frames: 0, bytes: 0, seconds: 1}); }
  }));
}

let runCount = 0;
async function run(name, mode, browser) {
  const s = scenes[name];
  const withPage = mode === 'page';
  const directory = path.join(work, name + '-' + mode + '-' + (++runCount));
  fs.mkdirSync(directory, {recursive: true});
  const args = [path.join(root, s.file), ...threads, '--set', 'Output/Directory=results',
    '--set', 'Output/VTU/Interval=0', '--set', 'Output/Live view/Port=0',
    '--set', 'Output/Live view/Pace=as fast as possible'];
  if (mode !== 'none') args.push('--set', 'Output/Live view/Wait for page=60');
  for (const x of s.set) args.push('--set', x);
  const log = fs.openSync(path.join(directory, 'run.log'), 'w');
  const child = spawn(exe, args, {cwd: directory,
                                  stdio: ['ignore', log, log]});
  const exited = new Promise((resolve) => child.on('exit', resolve));
  const result = {fresh: [], received: [], bytes: 0, vertices: 0};
  const reading = mode === 'reader' ? reader(directory) : null;
  if (withPage) {
    const file = path.join(directory, 'results', 'live_view');
    for (let k = 0; k < 1200 && !fs.existsSync(file); ++k) await sleep(50);
    const page = await browser.newPage();
    await page.setViewport({width: 1200, height: 800});
    await page.goto(fs.readFileSync(file, 'utf8').trim());
    let done = false;
    exited.then(() => { done = true; });
    while (!done) {
      await sleep(1000);
      if (done) break;
      const s2 = await page.evaluate(() => ({
        fresh: window.tissuefem.freshPerSecond, received: window.tissuefem.framesReceived,
        bytes: window.tissuefem.bytesPerFrame,
        n: window.tissuefem.topology ? window.tissuefem.topology.n : 0,
        ended: window.tissuefem.ended}));
      if (s2.ended) break;
      result.fresh.push(s2.fresh);
      result.received.push(s2.received);
      result.bytes = s2.bytes;
      result.vertices = s2.n;
    }
    await page.close();
  }
  const code = await exited;
  if (code !== 0) throw new Error(name + ': tissuefem exited ' + code + ', see ' + directory);
  if (reading) result.reader = await reading;
  const steps = stepSeconds(directory);
  result.median = 1e3 * quantile(steps, 0.5);
  result.p95 = 1e3 * quantile(steps, 0.95);
  return result;
}

function haptic(mode, browser) {
  const withPage = mode === 'page';
  const directory = path.join(work, 'haptic-' + mode + '-' + (++runCount));
  const args = [path.join(root, 'tests/live/stream_client.py'), exe,
    path.join(root, 'parameters/muscle_palpation.prm'), directory, '--seconds', '4', '--dim', '3',
    '--', ...threads, '--set', 'Contact/Obstacle 1/Motion=0', '--set', 'Contact tool/Live port=0',
    '--set', 'Time integration/End time=60',
    '--set', 'Output/Live view/Port=0', '--set', 'Output/Live view/Pace=as fast as possible'];
  return new Promise((resolve) => {
    const child = spawn('python3', args, {stdio: ['ignore', 'pipe', 'inherit']});
    let out = '';
    child.stdout.on('data', (d) => { out += d; });
    let page = null;
    if (mode === 'reader') reader(directory);
    if (withPage)
      (async () => {
        const file = path.join(directory, 'results', 'live_view');
        for (let k = 0; k < 400 && !fs.existsSync(file); ++k) await sleep(25);
        page = await browser.newPage();
        await page.goto(fs.readFileSync(file, 'utf8').trim()).catch(() => {});
      })();
    child.on('exit', async () => {
      if (page) await page.close().catch(() => {});
      const m = /median ([\d.]+), 99th percentile ([\d.]+)/.exec(out);
      resolve(m ? {median: Number(m[1]), p99: Number(m[2])} : {median: NaN, p99: NaN, out});
    });
  });
}

const niced = path.join(work, 'chromium-nice');
fs.writeFileSync(niced, '#!/bin/sh\nexec nice -n ' + options.nice + ' ' +
                 (process.env.CHROMIUM || '/usr/bin/chromium') + ' "$@"\n');
fs.chmodSync(niced, 0o755);
const browser = await puppeteer.launch({
  executablePath: niced, headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const fmt = (x, d = 2) => (Number.isFinite(x) ? x.toFixed(d) : '-');
console.log('live view benchmark (%s, tissuefem threads %s, Chromium at nice %d): fresh frames per ' +
            'second drawn by headless Chromium (software WebGL), bytes per frame, step wall time (ms) ' +
            'without and with a page', exe, options.threads || 'default', options.nice);
console.log('| scene | surface vertices | bytes per frame | frames/s to the reader | fresh frames/s drawn [range over repeats] | target | ' +
            'step median (ms): none / reader / page | ratio to none: reader, page [range] | target | step p95 (ms): none / reader / page |');
console.log('| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |');
const median = (v) => quantile(v, 0.5);
const range = (v, d = 2) => '[' + fmt(Math.min(...v), d) + ', ' + fmt(Math.max(...v), d) + ']';
try {
  for (const name of wanted.filter((n) => scenes[n])) {
    const r = {none: [], reader: [], page: []};
    for (let k = 0; k < options.repeats; ++k)
      for (const mode of ['none', 'reader', 'page']) r[mode].push(await run(name, mode, browser));
    const fresh = r.page.map((p) => median(p.fresh.slice(1)));
    const lowest = Math.min(...r.page.map((p) => Math.min(...p.fresh.slice(1))));
    const rate = r.reader.map((x) => x.reader.frames / x.reader.seconds);
    const med = (mode) => r[mode].map((x) => x.median), p95 = (mode) => r[mode].map((x) => x.p95);
    // Ratios within each repeat (runs next to each other), then their median.
    const ratio = (mode) => med(mode).map((m, k) => m / med('none')[k]);
    console.log('| %s | %d | %d | %s | %s %s (lowest %s) | %s | %s / %s / %s | %s %s, %s %s | 1.05 | %s / %s / %s |',
                name, r.page[0].vertices, r.page[0].bytes, fmt(median(rate), 0), fmt(median(fresh), 0),
                range(fresh, 0), fmt(lowest, 0), name === 'beam' ? '-' : '30', fmt(median(med('none'))),
                fmt(median(med('reader'))), fmt(median(med('page'))), fmt(median(ratio('reader')), 3),
                range(ratio('reader')), fmt(median(ratio('page')), 3), range(ratio('page')),
                fmt(median(p95('none'))), fmt(median(p95('reader'))), fmt(median(p95('page'))));
  }
  if (wanted.includes('haptic')) {
    const r = {none: [], reader: [], page: []};
    for (let k = 0; k < options.repeats; ++k)
      for (const mode of ['none', 'reader', 'page']) r[mode].push(await haptic(mode, browser));
    const m = (mode, key) => fmt(median(r[mode].map((x) => x[key])), 3) + ' ' +
                             range(r[mode].map((x) => x[key]), 3);
    console.log('haptic latency (muscle palpation driven at 500 Hz, ms), median / 99th percentile: ' +
                'no page %s / %s; reader %s / %s; page %s / %s (target: the 99th percentile unchanged)',
                m('none', 'median'), m('none', 'p99'), m('reader', 'median'), m('reader', 'p99'),
                m('page', 'median'), m('page', 'p99'));
  }
} finally {
  await browser.close();
}
console.log('runs kept in %s', work);
