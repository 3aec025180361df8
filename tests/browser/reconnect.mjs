// Pages that come and go change nothing (ctest browser/reconnect):
//
//   node reconnect.mjs TISSUEFEM SCENE WORKDIR
//
// Runs SCENE (2D, dynamic, prescribed boundary motion, probes) twice with
// the live view on and paced to the wall clock over 8 s of simulated time:
// once with no page, once while Debian's Chromium opens the page, waits for
// a drawn frame, and closes it, over and over (and leaves one page open to
// the end). The summary file and probes.csv of the two runs must be the
// same byte for byte, and both runs must end with exit 0.
import fs from 'node:fs';
import path from 'node:path';
import {spawn} from 'node:child_process';
import puppeteer from 'puppeteer-core';

const [exe, scene, work] = process.argv.slice(2);
fs.rmSync(work, {recursive: true, force: true});
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const failures = [];
const check = (ok, what) => { if (!ok) { failures.push(what); console.log('FAILED:', what); } };

function start(directory) {
  fs.mkdirSync(directory, {recursive: true});
  const log = fs.openSync(path.join(directory, 'run.log'), 'w');
  const run = spawn(exe, [scene, '--set', 'Output/Live view/Port=0',
    '--set', 'Time integration/End time=8', '--set', 'Output/Summary interval=10'],
    {cwd: directory, stdio: ['ignore', log, log]});
  const exited = new Promise((resolve) => run.on('exit', (code) => resolve(code)));
  return {run, exited};
}

async function address(directory) {
  const file = path.join(directory, 'results', 'live_view');
  for (let k = 0; k < 300 && !fs.existsSync(file); ++k) await sleep(50);
  return fs.readFileSync(file, 'utf8').trim();
}

const quiet = path.join(work, 'no-page'), busy = path.join(work, 'pages');
const reference = start(quiet);
check(await reference.exited === 0, 'the run without a page exits 0');

const watched = start(busy);
const url = await address(busy);
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
let visits = 0, ended = false;
watched.exited.then(() => { ended = true; });
try {
  while (!ended) {
    const page = await browser.newPage();
    try {
      await page.goto(url, {timeout: 5000});
      await page.waitForFunction(() => window.tissuefem.lastStep >= 0, {timeout: 5000});
      ++visits;
      await sleep(100 + 50 * (visits % 4));
    } catch (e) {
      // The run may end while a page loads.
    }
    if (!ended) await page.close();
  }
} finally {
  await browser.close();
}
const code = await watched.exited;
console.log('pages opened and closed during the run: %d', visits);
check(code === 0, 'the run with pages exits 0');
check(visits >= 3, "at least 3 pages came and went");
for (const file of ['output', 'results/probes.csv']) {
  const a = fs.readFileSync(path.join(quiet, file)), b = fs.readFileSync(path.join(busy, file));
  check(a.equals(b), file + ' is the same with and without pages');
}
if (failures.length) {
  console.log(fs.readFileSync(path.join(busy, 'run.log'), 'utf8').slice(-3000));
  process.exit(1);
}
console.log('browser reconnect: all checks passed');
