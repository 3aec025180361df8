// What the live view costs and delivers (issue 33's streaming targets),
// measured in one run of this script:
//
//   node benchmarks/live_view.mjs build/tissuefem [muscle liver beam haptic]
//
// (needs tests/browser/install.sh's Chromium and puppeteer-core). For each
// scene, two runs with the live view on, paced as fast as possible,
// alternating: one with no page, one with a headless Chromium page open
// from the first step. From the page: fresh frames drawn per second (new
// steps, sampled each second; median and the lowest after the first
// second) and bytes per frame; from statistics.csv: the step's wall time,
// median and 95th percentile, without and with the page. Targets: at least
// 30 fresh frames per second on the muscle and the liver; an open page adds
// at most 5 % to the median step.
// 'haptic': the muscle palpation driven at 500 Hz by
// tests/live/stream_client.py, with and without a page: the device's
// latency median and 99th percentile (target: a page adds nothing to the
// 99th percentile).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {spawn, spawnSync} from 'node:child_process';
import {createRequire} from 'node:module';

const here = path.dirname(new URL(import.meta.url).pathname);
const require = createRequire(path.join(here, '../tests/browser/package.json'));
const puppeteer = require('puppeteer-core');

const exe = path.resolve(process.argv[2] || 'build/tissuefem');
const wanted = process.argv.slice(3).length ? process.argv.slice(3) : ['muscle', 'liver', 'beam', 'haptic'];
const root = path.resolve(here, '..');
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'live-view-bench-'));

const scenes = {
  muscle: {file: 'parameters/jeffrey_muscle.prm', set: ['Time integration/End time=0.5']},
  liver: {file: 'parameters/liver_gravity.prm', set: ['Time integration/End time=2']},
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

async function run(name, withPage, browser) {
  const s = scenes[name];
  const directory = path.join(work, name + (withPage ? '-page' : '-none'));
  fs.mkdirSync(directory, {recursive: true});
  const args = [path.join(root, s.file), '--set', 'Output/Directory=results',
    '--set', 'Output/VTU/Interval=0', '--set', 'Output/Live view/Port=0',
    '--set', 'Output/Live view/Pace=as fast as possible'];
  if (withPage) args.push('--set', 'Output/Live view/Wait for page=60');
  for (const x of s.set) args.push('--set', x);
  const log = fs.openSync(path.join(directory, 'run.log'), 'w');
  const child = spawn(exe, args, {cwd: directory,
                                  stdio: ['ignore', log, log]});
  const exited = new Promise((resolve) => child.on('exit', resolve));
  const result = {fresh: [], received: [], bytes: 0, vertices: 0};
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
  const steps = stepSeconds(directory);
  result.median = 1e3 * quantile(steps, 0.5);
  result.p95 = 1e3 * quantile(steps, 0.95);
  return result;
}

function haptic(withPage, browser) {
  const directory = path.join(work, 'haptic' + (withPage ? '-page' : '-none'));
  const args = [path.join(root, 'tests/live/stream_client.py'), exe,
    path.join(root, 'parameters/muscle_palpation.prm'), directory, '--seconds', '4', '--dim', '3',
    '--', '--set', 'Contact tool/Live port=0', '--set', 'Time integration/End time=60',
    '--set', 'Output/Live view/Port=0', '--set', 'Output/Live view/Pace=as fast as possible'];
  return new Promise((resolve) => {
    const child = spawn('python3', args, {stdio: ['ignore', 'pipe', 'inherit']});
    let out = '';
    child.stdout.on('data', (d) => { out += d; });
    let page = null;
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

const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const fmt = (x, d = 2) => (Number.isFinite(x) ? x.toFixed(d) : '-');
console.log('live view benchmark (%s): fresh frames per second drawn by headless Chromium ' +
            '(software WebGL), bytes per frame, step wall time (ms) without and with a page', exe);
console.log('| scene | surface vertices | bytes per frame | fresh frames/s, median (lowest) | target | ' +
            'step median, no page / page (ms) | ratio | target | step p95, no page / page (ms) |');
console.log('| --- | --- | --- | --- | --- | --- | --- | --- | --- |');
try {
  for (const name of wanted.filter((n) => scenes[n])) {
    const none = await run(name, false, browser);
    const page = await run(name, true, browser);
    const steady = page.fresh.slice(1);
    const arrivals = page.received.slice(1).map((r, k) => r - page.received[k]);
    console.error('%s: frames received per second %s; drawn fresh %s', name, arrivals.join(' '),
                  page.fresh.join(' '));
    console.log('| %s | %d | %d | %s (%s) | %s | %s / %s | %s | 1.05 | %s / %s |', name, page.vertices,
                page.bytes, fmt(quantile(steady, 0.5), 0), fmt(Math.min(...steady), 0),
                name === 'beam' ? '-' : '30', fmt(none.median), fmt(page.median),
                fmt(page.median / none.median, 3), fmt(none.p95), fmt(page.p95));
  }
  if (wanted.includes('haptic')) {
    const a = await haptic(false, browser), b = await haptic(true, browser);
    console.log('haptic latency (muscle palpation at 500 Hz, ms): no page median %s p99 %s; ' +
                'page median %s p99 %s; p99 ratio %s (target: 1, nothing added)',
                fmt(a.median, 3), fmt(a.p99, 3), fmt(b.median, 3), fmt(b.p99, 3), fmt(b.p99 / a.p99, 3));
  }
} finally {
  await browser.close();
}
console.log('runs kept in %s', work);
