// Pages that come and go change nothing (ctest browser/reconnect):
//
//   node reconnect.mjs TISSUEFEM SCENE WORKDIR
//
// Runs SCENE (2D, dynamic, prescribed boundary motion, probes) over 20 s of
// simulated time twice with the live view on: once with no page, as fast as
// it can, and once paced to the wall clock while Debian's Chromium opens the
// page, waits for a drawn frame, and closes it, five times; a last page
// then switches the pace to 'as fast as possible' and stays to the end. The
// summary file and probes.csv of the two runs must be the same byte for
// byte, and both runs must end with exit 0.
import fs from 'node:fs';
import path from 'node:path';
import {check, finish, launchBrowser, liveAddress, sleep, startRun} from './harness.mjs';

const [exe, scene, work] = process.argv.slice(2);
fs.rmSync(work, {recursive: true, force: true});

const start = (directory, pace) => startRun(exe, scene, directory, [
  'Output/Live view/Port=0', 'Output/Live view/Pace=' + pace,
  'Time integration/End time=20', 'Output/Summary interval=50']);

const quiet = path.join(work, 'no-page'), busy = path.join(work, 'pages');
const reference = start(quiet, 'as fast as possible');
check(await reference.exited === 0, 'the run without a page exits 0');

const watched = start(busy, 'wall clock');
const url = await liveAddress(busy, watched);
const browser = await launchBrowser();
let visits = 0, ended = false;
watched.exited.then(() => { ended = true; });
try {
  while (!ended && visits < 5) {
    const page = await browser.newPage();
    try {
      await page.goto(url, {timeout: 30000});
      await page.waitForFunction(() => window.tissuefem.lastStep >= 0, {timeout: 30000});
      ++visits;
      await sleep(100 + 50 * (visits % 4));
    } catch (e) {
      console.log('a visit failed: ' + e);
    }
    await page.close();
  }
  if (!ended) {
    const last = await browser.newPage();
    await last.goto(url, {timeout: 30000});
    await last.waitForFunction(() => window.tissuefem.drives, {timeout: 30000});
    await last.select('#pace', 'fast');
    await watched.exited;
  }
} finally {
  await browser.close();
}
const code = await watched.exited;
console.log('pages opened and closed during the run: %d', visits);
check(code === 0, 'the run with pages exits 0');
check(visits === 5, '5 pages came and went');
for (const file of ['output', 'results/probes.csv']) {
  const a = fs.readFileSync(path.join(quiet, file)), b = fs.readFileSync(path.join(busy, file));
  check(a.equals(b), file + ' is the same with and without pages');
}
finish('reconnect', path.join(busy, 'run.log'));
