// The live view in a real browser (ctest browser/live_view):
//
//   node live_view.mjs TISSUEFEM SCENE WORKDIR
//
// Starts tissuefem on SCENE (a unit cube held by rollers, otherwise free,
// quasistatic) with the live view on and paused, drives Debian's Chromium
// headless (software WebGL) through puppeteer-core, and checks that
// - the canvas is not blank: many pixels differ from the background and
//   the colours vary (the colour map);
// - play advances the steps; pause stops them; play resumes;
// - dragging the surface with the mouse grasps it: the page shows a
//   non-zero force, and the same force is a row of the run's
//   tool_force.csv with the tool holding and displaced;
// - switching the colour field to von Mises changes the legend's field;
// - after the page closes, the run ends by itself with exit 0.
// Screenshots go to WORKDIR (test artifacts).
import fs from 'node:fs';
import path from 'node:path';
import {check, finish, launchBrowser, liveAddress, openPage, sleep, startRun} from './harness.mjs';

const [exe, scene, work] = process.argv.slice(2);
fs.rmSync(work, {recursive: true, force: true});
const started = startRun(exe, scene, work, [
  'Boundary conditions/Dirichlet=0: x: 0 | 2: y: 0 | 4: z: 0',
  'Output/Live view/Port=0', 'Output/Live view/Start paused=true',
  'Output/Live view/Wait for page=60', 'Mouse/Grasp radius=0.2',
  'Time integration/Time step=0.02', 'Time integration/End time=30']);
const url = await liveAddress(work, started);
const browser = await launchBrowser();
try {
  const {page, errors} = await openPage(browser, url);
  const state = () => page.evaluate(() => ({
    step: window.tissuefem.lastStep, force: window.tissuefem.force,
    forceText: document.getElementById('n-force').textContent,
    legend: document.getElementById('legend-unit').textContent}));

  // Pixel statistics of the drawn canvas.
  const pixels = await page.evaluate(() => window.tissuefem.pixelStatistics());
  console.log('canvas: %s of the pixels drawn, %d colours', pixels.share.toFixed(3), pixels.colours);
  check(pixels.share > 0.02 && pixels.colours > 20, 'the canvas is not blank');
  await page.screenshot({path: path.join(work, '1-loaded.png')});

  // Waits (up to 30 s: the machine may be busy) for @p test in the page.
  const until = (test, arg) => page.waitForFunction(test, {timeout: 30000}, arg).then(() => true, () => false);
  await page.click('#play');
  check(await until(() => window.tissuefem.lastStep > 0), 'play advances the steps');

  // Drag from a point of the drawn surface.
  const {x: x0, y: y0} = await page.evaluate(() => window.tissuefem.surfacePoint());
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  for (let k = 1; k <= 10; ++k) { await page.mouse.move(x0 + 8 * k, y0 - 4 * k); await sleep(50); }
  await until(() => Math.hypot(...window.tissuefem.force) > 0);
  await sleep(500);
  const dragging = await state();
  await page.screenshot({path: path.join(work, '2-dragging.png')});
  const size = Math.hypot(...dragging.force);
  console.log('force shown while dragging: %s (%s)', dragging.force.join(' '), dragging.forceText);
  check(size > 0 && /force units/.test(dragging.forceText), 'the page shows a non-zero force while dragging');
  await page.mouse.up();

  await page.select('#field', 'von Mises');
  await page.waitForFunction(() => /von Mises/.test(document.getElementById('legend-unit').textContent),
                             {timeout: 10000}).catch(() => {});
  check(/von Mises/.test((await state()).legend), 'the legend follows the colour field');
  await page.screenshot({path: path.join(work, '3-von-mises.png')});

  await page.click('#pause');
  // Paused once a frame says so (the play button comes back).
  check(await until(() => !document.getElementById('play').disabled), 'the page shows the pause');
  await sleep(300);
  const paused = (await state()).step;
  await sleep(1000);
  check((await state()).step === paused, 'pause stops the steps');
  await page.click('#play');
  check(await until((p) => window.tissuefem.lastStep > p, paused), 'play resumes');
  check(errors.length === 0, 'no error in the page: ' + errors.join('; '));
  // The rest of the run as fast as it can, then the page goes.
  await page.select('#pace', 'fast');
  await sleep(300);
  await page.close();

  // The run's own record of the drag: the force the page showed (the
  // record of the step before its frame) is a row of tool_force.csv.
  await Promise.race([started.exited, new Promise((r) => setTimeout(r, 60000).unref())]);
  check(started.code() === 0,
        'the run ends by itself with exit 0 after the page closed (' + started.code() + ')');
  const rows = fs.readFileSync(path.join(work, 'results', 'tool_force.csv'), 'utf8')
    .trim().split('\n').slice(1).map((l) => l.split(',').map(Number));
  const held = rows.filter((r) => r[1] === 1);
  check(held.length > 0 && held.some((r) => Math.hypot(r[2], r[3], r[4]) > 0),
        'tool_force.csv shows the tool holding and displaced');
  const same = held.some((r) => [0, 1, 2].every((d) =>
    Math.abs(r[5 + d] - dragging.force[d]) <= 1e-5 * Math.max(size, 1e-12)));
  check(same, 'the force the page showed is a row of tool_force.csv');
} finally {
  await browser.close();
  if (started.code() === null) started.run.kill();
}
finish('live view', path.join(work, 'run.log'));
