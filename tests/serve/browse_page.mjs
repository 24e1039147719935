// Debian's chromium, headless, driven by puppeteer-core (pinned in
// package-lock.json), opens the live page of a running `vkfuse run --serve`
// and checks what a person would see: no console error, one image per sensor
// and setting and one fused image per sensor drawn, the metric plots moving.
// Then it freezes the page and writes what each canvas shows (topic, cycle,
// RGBA pixels) to OUT/canvases.json and a screenshot to OUT/page.png, for
// check_live.py to compare with the run's fused PNGs.
//
//   node browse_page.mjs URL OUT
//   node browse_page.mjs URL OUT --watch SECONDS   (tools/bench_serve.sh: keeps the
//       page open and drawing that long, then prints its draws per second)
import { writeFile } from "node:fs/promises";
import puppeteer from "puppeteer-core";

const [url, out] = process.argv.slice(2);
const problems = [];
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  headless: true,
  // As root (CI) chromium's sandbox cannot start; the page is our own.
  args: ["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,1000"],
});
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1400, height: 1000 });
  page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()}`));
  const response = await page.goto(url, { waitUntil: "load", timeout: 30000 });
  if (!response.ok()) problems.push(`GET ${url}: ${response.status()}`);
  await page.waitForFunction(() => window.vkfuseLive && window.vkfuseLive.ready(), { timeout: 90000, polling: 200 });
  if (process.argv[4] === "--watch") {
    const seconds = Number(process.argv[5]);
    const start = await page.evaluate(() => window.vkfuseLive.stats().drawn);
    await new Promise((r) => setTimeout(r, seconds * 1000));
    const end = await page.evaluate(() => window.vkfuseLive.stats().drawn);
    console.log(`page: ${((end - start) / seconds).toFixed(1)} images drawn per second over ${seconds} s`);
    await browser.close();
    process.exit(problems.length ? 1 : 0);
  }
  await page.waitForFunction(() => window.vkfuseLive.points() >= 5, { timeout: 90000, polling: 200 });
  const before = await page.evaluate(() => window.vkfuseLive.points());
  await page.waitForFunction((n) => window.vkfuseLive.points() > n + 3, { timeout: 60000, polling: 200 }, before);
  const plotted = await page.evaluate(() => [...document.querySelectorAll("canvas[data-metric]")].map((c) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let lit = 0;
    for (let i = 3; i < d.length; i += 4) lit += d[i] > 0;
    return { metric: c.dataset.metric, lit };
  }));
  for (const p of plotted) if (p.lit < 200) problems.push(`plot ${p.metric}: nothing drawn`);
  // Frozen at an instant when every fused image's cycle is known (its
  // metrics message, which names the cycle, comes right after the image).
  let canvases = [];
  for (let tries = 0; tries < 100; ++tries) {
    await page.evaluate(() => window.vkfuseLive.freeze());
    canvases = await page.evaluate(() => window.vkfuseLive.canvases());
    if (canvases.every((c) => !c.topic.includes("/fused") || c.cycle >= 0)) break;
    await page.evaluate(() => window.vkfuseLive.unfreeze());
    await new Promise((r) => setTimeout(r, 150));
  }
  const stats = await page.evaluate(() => window.vkfuseLive.stats());
  if (stats.errors.length) problems.push(...stats.errors.map((e) => `server status: ${e}`));
  await page.screenshot({ path: `${out}/page.png`, fullPage: true });
  await writeFile(`${out}/canvases.json`, JSON.stringify({ canvases, stats, plotted, points: before }));
  console.log(`page: ${canvases.length} images, ${stats.drawn} draws, ${stats.metrics} metric messages, plots ${before} points and growing`);
} catch (e) {
  problems.push(String(e));
} finally {
  await browser.close();
}
if (problems.length) {
  for (const p of problems) console.error(p);
  process.exit(1);
}
