// The contact tool moved by the mouse in a real browser (ctest
// browser/tool):
//
//   node tool.mjs TISSUEFEM SCENE WORKDIR
//
// Starts tissuefem on SCENE (parameters/muscle_palpation.prm: Jeffrey's
// muscle and a spherical probe, the contact tool) with the probe's own
// motion set to 0, so that only the page moves it, and the live view on
// and paused. Drives Debian's Chromium headless (software WebGL) through
// puppeteer-core and checks that
// - the probe is drawn: the colour at its centre on the page is the
//   instrument's grey, not the background;
// - reset starts the run again: the page reconnects by itself and shows
//   step 0, and play runs it;
// - dragging the probe towards the muscle moves it there: the page shows
//   a non-zero force of the tissue on it (force units), the same force is
//   a row of the run's tool_force-contact.csv, and that row has the probe
//   displaced towards the muscle (x < 0);
// - the probe stays where the mouse let it go: its position in the last
//   200 rows of tool_force-contact.csv is one, with x < 0;
// - after the page closes, the run ends by itself with exit 0.
// Screenshots go to WORKDIR (test artifacts).
import fs from 'node:fs';
import path from 'node:path';
import {check, finish, launchBrowser, liveAddress, openPage, sleep, startRun} from './harness.mjs';

const [exe, scene, work] = process.argv.slice(2);
fs.rmSync(work, {recursive: true, force: true});
const started = startRun(exe, scene, work, [
  'Contact/Obstacle 1/Motion=0; 0; 0', 'Output/Directory=results', 'Output/VTU/Interval=0',
  'Output/Live view/Port=0', 'Output/Live view/Start paused=true',
  'Output/Live view/Wait for page=60', 'Time integration/End time=3']);
const url = await liveAddress(work, started);
const browser = await launchBrowser();
try {
  const {page, errors} = await openPage(browser, url);
  const until = (test, arg) => page.waitForFunction(test, {timeout: 30000}, arg).then(() => true, () => false);

  const probe = await page.evaluate(() => window.tissuefem.instrumentPoint());
  check(probe !== null, 'the page knows the probe as the instrument the mouse moves');
  const rgb = await page.evaluate((p) => window.tissuefem.colourAt(p.x, p.y), probe);
  console.log('colour at the probe: %s', rgb.join(' '));
  const grey = Math.max(...rgb) - Math.min(...rgb) < 40 && Math.min(...rgb) > 60;
  check(grey, 'the probe is drawn (grey at its centre, not the background): ' + rgb.join(' '));
  await page.screenshot({path: path.join(work, '1-loaded.png')});

  await page.click('#play');
  check(await until(() => window.tissuefem.lastStep > 2), 'play advances the steps');
  // Reset: the run starts again (paused, as it started) and the page
  // reconnects by itself.
  await page.click('#reset');
  check(await until(() => window.tissuefem.resets === 1 && !window.tissuefem.resetting &&
                          window.tissuefem.lastStep === 0 && window.tissuefem.drives),
        'after a reset the page reconnects and shows step 0');
  await page.screenshot({path: path.join(work, '1-reset.png')});
  await page.click('#play');
  check(await until(() => window.tissuefem.lastStep > 0), 'play advances the steps again');
  // Towards the muscle: the probe sits at x = 0.0255 beside it, screen
  // right is about +x.
  await page.mouse.move(probe.x, probe.y);
  await page.mouse.down();
  for (let k = 1; k <= 12; ++k) { await page.mouse.move(probe.x - 6 * k, probe.y); await sleep(60); }
  const touched = await until(() => window.tissuefem.toolForce &&
                              Math.hypot(...window.tissuefem.toolForce) > 0);
  await sleep(500);
  const shown = await page.evaluate(() => ({force: window.tissuefem.toolForce,
                                             text: document.getElementById('n-tool').textContent}));
  await page.screenshot({path: path.join(work, '2-pressing.png')});
  console.log('force on the probe shown: %s (%s)', shown.force.join(' '), shown.text);
  check(touched && /force units/.test(shown.text), 'the page shows the force of the tissue on the probe');
  await page.mouse.up();
  const step = await page.evaluate(() => window.tissuefem.lastStep);
  check(await until((s) => window.tissuefem.lastStep > s + 5, step), 'the run goes on');
  check(errors.length === 0, 'no error in the page: ' + errors.join('; '));
  await page.select('#pace', 'fast');
  await sleep(300);
  await page.close();

  await Promise.race([started.exited, new Promise((r) => setTimeout(r, 120000).unref())]);
  check(started.code() === 0,
        'the run ends by itself with exit 0 after the page closed (' + started.code() + ')');
  const rows = fs.readFileSync(path.join(work, 'results', 'tool_force-contact.csv'), 'utf8')
    .trim().split('\n').slice(1).map((l) => l.split(',').map(Number));
  const size = Math.hypot(...shown.force);
  const same = rows.filter((r) => [0, 1, 2].every((d) =>
    Math.abs(r[5 + d] - shown.force[d]) <= 1e-5 * Math.max(size, 1e-12)));
  check(same.length > 0, 'the force the page showed is a row of tool_force-contact.csv');
  check(same.every((r) => r[2] < 0), 'that row has the probe moved towards the muscle (x < 0)');
  // The rest of the run (at least 200 steps after the page let go): one
  // position.
  const last = rows.slice(-200), p = last[0];
  console.log('probe at the end: %s', p.slice(2, 5).join(' '));
  check(p[2] < 0 && last.every((r) => [2, 3, 4].every((d) => r[d] === p[d])),
        'the probe stays where the mouse let it go');
} finally {
  await browser.close();
  if (started.code() === null) started.run.kill();
}
finish('tool', path.join(work, 'run.log'));
