// The catalogue's scatter over `isogami serve` in real headless Chromium (issue 24 item 1 and
// its keyboard part of item 8): every filtered design is in a drawn stack and the stacks add up
// to the API's total; colouring by family lists the families present; brushing a rectangle
// sets the two axes' ranges and narrows the total (and clears); zooming changes the axis
// domain; the tooltip gives a stack's count and list, a click pins it; tick labels never
// overlap, also zoomed into a tiny range; the keyboard moves between stacks and opens them.
// The drawn stacks are read from the page (`#scatter`'s scatterDrawn, set by the draw itself).

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  byTestId, canvasPixels, catalogueTotal, getJson, launchBrowser, newPage, problems, screenshot, startServer,
} from './harness.mjs';

let server;
let browser;

before(async () => {
  server = await startServer();
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

/** The scatter's drawn state once it shows `designs` designs (any number when undefined). */
async function drawn(page, designs) {
  await page.waitForFunction(
    (n) => {
      const d = document.getElementById('scatter')?.scatterDrawn;
      return d && (n === undefined ? d.designs > 0 : d.designs === n);
    },
    designs,
  );
  return page.evaluate(() => document.getElementById('scatter').scatterDrawn);
}

/** Opens the catalogue with `query` and waits for the list and the scatter. */
async function openCatalogue(query = '') {
  const page = await newPage(browser);
  await page.goto(`${server.base}/${query}`);
  const total = await catalogueTotal(page);
  const d = await drawn(page, total);
  return { page, total, d };
}

/** The behaviour with the most designs (a filter that keeps stacks on the quick database). */
async function busiestBehaviour() {
  const facets = await getJson(`${server.base}/api/facets`);
  return facets.behaviour.filter((b) => b.value !== null).sort((a, b) => b.count - a.count)[0].value;
}

/** Pixel position of the canvas's top-left corner on the page. */
async function canvasBox(page) {
  return byTestId(page, 'scatter-canvas').boundingBox();
}

test('every filtered design is in a drawn stack; the stacks add up to the API total', async () => {
  const behaviour = await busiestBehaviour();
  const query = `behaviour=${behaviour}`;
  const { page, total, d } = await openCatalogue(`?${query}`);
  const api = await getJson(`${server.base}/api/designs?${query}&limit=1`);
  const points = await getJson(`${server.base}/api/scatter?x=max_expansion&y=max_area_ratio&${query}`);
  assert.equal(total, api.total);
  assert.equal(points.length, api.total, 'every design has both default measures');
  const sum = d.stacks.reduce((n, s) => n + s.count, 0);
  assert.equal(sum, api.total, 'the drawn stacks hold every filtered design');
  assert.deepEqual(d.stacks.flatMap((s) => s.specs).sort(), points.map((p) => p.spec).sort());
  assert.ok(d.stacks.length <= api.total && d.stacks.length === d.positions);
  assert.ok(d.stacks.some((s) => s.count > 1), 'the quick database has designs on one spot');
  assert.equal(
    (await byTestId(page, 'scatter-count').textContent()).trim(),
    `${api.total} designs at ${d.positions} positions`,
  );
  // A stack of several is drawn larger than a single design, and every stack's centre is painted.
  const single = d.stacks.find((s) => s.count === 1);
  const biggest = d.stacks.reduce((a, b) => (b.count > a.count ? b : a));
  if (single) assert.ok(biggest.r > single.r);
  const pixels = await canvasPixels(page, '[data-testid="scatter-canvas"]');
  const { width, ratio } = await page.$eval('[data-testid="scatter-canvas"]', (c) => ({ width: c.width, ratio: c.width / c.clientWidth }));
  for (const s of d.stacks) {
    const i = (Math.round(s.py * ratio) * width + Math.round(s.px * ratio)) * 4;
    assert.ok(pixels[i + 3] > 100, `the stack at ${s.px},${s.py} (${s.count}) is painted`);
  }
  await screenshot(browser, page, 'scatter-stacks');
  assert.deepEqual(problems(page), []);
});

test('colouring by family lists the families present with their counts', async () => {
  const { page, total } = await openCatalogue();
  const behaviours = await page.$$eval('[data-testid="scatter-legend-entry"]', (els) => els.map((e) => e.dataset.key));
  const facets = await getJson(`${server.base}/api/facets`);
  assert.deepEqual(behaviours.sort(), facets.behaviour.map((b) => b.value ?? 'unclassified').sort());
  await byTestId(page, 'scatter-colour').selectOption('family');
  await page.waitForFunction(() => new URL(location.href).searchParams.get('colour') === 'family');
  const entries = await page.$$eval('[data-testid="scatter-legend-entry"]', (els) =>
    els.map((e) => ({ key: e.dataset.key, count: Number(/\((\d+)\)/.exec(e.textContent)[1]), text: e.textContent })),
  );
  assert.equal(entries.reduce((n, e) => n + e.count, 0), total);
  const families = facets.family;
  for (const e of entries.filter((x) => x.key !== '*other')) {
    assert.equal(e.count, families.find((f) => f.value === e.key).count, e.key);
  }
  assert.ok(entries.length <= 7 && entries.length === Math.min(7, families.length));
  await page.reload();
  await catalogueTotal(page);
  assert.equal(await byTestId(page, 'scatter-colour').inputValue(), 'family');
  assert.deepEqual(problems(page), []);
});

test('brushing a rectangle sets the two ranges and narrows the total; clearing restores it', async () => {
  const { page, total, d } = await openCatalogue();
  const box = await canvasBox(page);
  // The left half of the plotted stacks, top to bottom.
  const xs = d.stacks.map((s) => s.px).sort((a, b) => a - b);
  const ys = d.stacks.map((s) => s.py);
  const cut = (xs[0] + xs[xs.length - 1]) / 2;
  const inside = d.stacks.filter((s) => s.px < cut).reduce((n, s) => n + s.count, 0);
  assert.ok(inside > 0 && inside < total, 'the rectangle holds some designs but not all');
  await page.mouse.move(box.x + xs[0] - 6, box.y + Math.min(...ys) - 6);
  await page.mouse.down();
  await page.mouse.move(box.x + cut, box.y + Math.max(...ys) + 6, { steps: 8 });
  await page.mouse.up();
  await page.waitForFunction(() => new URL(location.href).searchParams.getAll('range').length === 2);
  const ranges = new URL(page.url()).searchParams.getAll('range');
  assert.deepEqual(ranges.map((r) => r.split(':')[0]).sort(), ['max_area_ratio', 'max_expansion']);
  const query = ranges.map((r) => `range=${r}`).join('&');
  const narrowed = (await getJson(`${server.base}/api/designs?${query}&limit=1`)).total;
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), narrowed);
  assert.ok(narrowed >= inside && narrowed < total, `${narrowed} designs after the brush (${inside} inside, ${total} in all)`);
  const after = await drawn(page, narrowed);
  assert.equal(after.stacks.reduce((n, s) => n + s.count, 0), narrowed);
  await byTestId(page, 'scatter-clear').click();
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), total);
  assert.deepEqual(new URL(page.url()).searchParams.getAll('range'), []);
  assert.ok(await byTestId(page, 'scatter-clear').isHidden());
  assert.deepEqual(problems(page), []);
});

test('zooming changes the axis domain and re-ticks the axes; reset restores them', async () => {
  const { page } = await openCatalogue();
  const domain = () => page.$eval('#scatter', (e) => e.dataset.xDomain.split(',').map(Number));
  const ticks = () => page.$$eval('[data-testid="scatter-x-axis"] .tick text', (t) => t.map((x) => x.textContent));
  const [a0, a1] = await domain();
  const before = await ticks();
  await byTestId(page, 'scatter-zoom-in').click();
  await page.waitForFunction((w) => {
    const [b0, b1] = document.getElementById('scatter').dataset.xDomain.split(',').map(Number);
    return b1 - b0 < w * 0.6;
  }, a1 - a0);
  const [b0, b1] = await domain();
  assert.ok(Math.abs((b1 - b0) / (a1 - a0) - 0.5) < 1e-6, 'one click halves the span');
  assert.notDeepEqual(await ticks(), before, 'the axis is ticked again');
  // The wheel zooms too, around the pointer.
  const box = await canvasBox(page);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.wheel(0, -400);
  await page.waitForFunction((w) => {
    const [c0, c1] = document.getElementById('scatter').dataset.xDomain.split(',').map(Number);
    return c1 - c0 < w * 0.99;
  }, b1 - b0);
  assert.match(await byTestId(page, 'scatter-count').textContent(), /in view$/);
  await byTestId(page, 'scatter-zoom-reset').click();
  await page.waitForFunction((w) => {
    const [c0, c1] = document.getElementById('scatter').dataset.xDomain.split(',').map(Number);
    return Math.abs(c0 - w[0]) < 1e-12 && Math.abs(c1 - w[1]) < 1e-12;
  }, [a0, a1]);
  assert.deepEqual(await ticks(), before);
  assert.deepEqual(problems(page), []);
});

test('the tooltip gives a stack its count and list; a click pins it with links, one design opens', async () => {
  const { page, d } = await openCatalogue();
  const box = await canvasBox(page);
  const biggest = d.stacks.reduce((a, b) => (b.count > a.count ? b : a));
  assert.ok(biggest.count > 1);
  await page.mouse.move(box.x + biggest.px, box.y + biggest.py);
  const tip = byTestId(page, 'scatter-tooltip');
  await tip.waitFor({ state: 'visible' });
  assert.equal(await byTestId(page, 'scatter-tip-count').textContent(), `${biggest.count} designs here`);
  const listed = await tip.locator('li code').allTextContents();
  assert.deepEqual(listed, biggest.specs.slice(0, 8));
  if (biggest.count > 8) assert.match(await tip.textContent(), new RegExp(`and ${biggest.count - 8} more`));
  await page.mouse.click(box.x + biggest.px, box.y + biggest.py);
  await page.waitForFunction(() => document.getElementById('scatter').scatterDrawn.pinned);
  const links = tip.locator('li a');
  assert.equal(await links.count(), Math.min(8, biggest.count));
  assert.equal(await links.first().getAttribute('href'), `./design.html?spec=${encodeURIComponent(biggest.specs[0])}`);
  // "show these N in the list" filters the catalogue to the stack.
  await byTestId(page, 'scatter-list-stack').click();
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), biggest.count);
  const shown = await drawn(page, biggest.count);
  assert.deepEqual(shown.stacks.flatMap((s) => s.specs).sort(), [...biggest.specs].sort());

  // A single design opens on a click. Its place is read once the page has settled — every
  // design drawn and the cards loaded (a scroll bar that comes with them narrows the plot and
  // moves every stack).
  await page.goto(`${server.base}/`);
  const total = await catalogueTotal(page);
  await drawn(page, total);
  await page.waitForLoadState('networkidle');
  const all = await drawn(page, total);
  // The lone design farthest from any other stack: the pointer picks the nearest stack, and
  // the first lone design found can stand close to another (CI twice opened IH27 where the
  // lone IH6 was expected).
  const clearance = (s) => Math.min(...all.stacks.filter((o) => o !== s).map((o) => Math.hypot(o.px - s.px, o.py - s.py)));
  const single = all.stacks
    .filter((s) => s.count === 1)
    .reduce((a, b) => (a === null || clearance(b) > clearance(a) ? b : a), null);
  assert.ok(single, 'some design stands alone');
  assert.ok(clearance(single) > 4, `the lone design stands ${clearance(single)} px from another stack`);
  const b2 = await canvasBox(page);
  await page.mouse.move(b2.x + single.px, b2.y + single.py);
  await tip.waitFor({ state: 'visible' });
  assert.equal(await byTestId(page, 'scatter-tip-count').textContent(), '1 design');
  assert.deepEqual(await tip.locator('li code').allTextContents(), single.specs);
  await page.mouse.click(b2.x + single.px, b2.y + single.py);
  await page.waitForURL(/design\.html\?spec=/);
  assert.equal(new URL(page.url()).searchParams.get('spec'), single.specs[0]);
  assert.deepEqual(problems(page), []);
});

/** The stack the pointer at canvas pixel (px, py) picks, as the tooltip names it: its first
 * design, or null where no stack is under the pointer. */
async function hoverPick(page, box, px, py) {
  await page.mouse.move(box.x + px, box.y + py);
  return page.evaluate(() => {
    const tip = document.querySelector('[data-testid="scatter-tooltip"]');
    return tip.hidden ? null : tip.querySelector('li code')?.textContent ?? null;
  });
}

test('each stack owns its centre and most of its disc: small stacks drawn over it take no more (issue 42 item 14)', async () => {
  const { page, total } = await openCatalogue();
  await page.waitForLoadState('networkidle');
  const d = await drawn(page, total);
  const box = await canvasBox(page);
  // Every stack, hovered at its centre, is the one picked (a lone design drawn over a big stack
  // took that stack's centre).
  // Pointer events come in whole pixels, so stacks whose centres lie within 2 px of another's
  // cannot be told apart by a pointer; every other stack is checked.
  const apart = (s) => d.stacks.every((o) => o === s || Math.hypot(o.px - s.px, o.py - s.py) > 2);
  const stolen = [];
  for (const s of d.stacks.filter(apart)) {
    const got = await hoverPick(page, box, s.px, s.py);
    if (got !== s.specs[0]) stolen.push(`${s.count}-design stack at (${s.px.toFixed(1)}, ${s.py.toFixed(1)}) picked ${got}`);
  }
  assert.deepEqual(stolen, [], 'every centre picks its own stack');
  // The disc of each stack drawn with a count (r ≥ 8), sampled on rings at 1/4, 1/2 and 3/4
  // of its radius (12 angles each) and at its centre: at least half the samples pick it.
  const big = d.stacks.filter((s) => s.r >= 8);
  assert.ok(big.length >= 1, 'the quick database has stacks drawn with a count');
  const shares = [];
  for (const s of big) {
    let own = 0;
    let n = 0;
    for (const f of [0, 0.25, 0.5, 0.75]) {
      for (let k = 0; k < (f === 0 ? 1 : 12); k += 1) {
        const a = (2 * Math.PI * k) / 12;
        const got = await hoverPick(page, box, s.px + f * s.r * Math.cos(a), s.py + f * s.r * Math.sin(a));
        own += got === s.specs[0] ? 1 : 0;
        n += 1;
      }
    }
    shares.push({ count: s.count, share: own / n });
  }
  const poor = shares.filter((x) => x.share < 0.5);
  assert.deepEqual(poor, [], `share of each big stack's disc that picks it: ${JSON.stringify(shares)}`);
  assert.deepEqual(problems(page), []);
});

/** Tick label boxes of both axes that overlap another of the same axis. */
async function overlappingTicks(page) {
  return page.evaluate(() => {
    const out = [];
    for (const id of ['scatter-x-axis', 'scatter-y-axis']) {
      const boxes = [...document.querySelectorAll(`[data-testid="${id}"] .tick text`)].map((t) => ({
        text: t.textContent,
        r: t.getBoundingClientRect(),
      }));
      for (let i = 0; i < boxes.length; i += 1) {
        for (let j = i + 1; j < boxes.length; j += 1) {
          const a = boxes[i].r;
          const b = boxes[j].r;
          if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) out.push(`${boxes[i].text} / ${boxes[j].text}`);
        }
      }
      if (new Set(boxes.map((b) => b.text)).size !== boxes.length) out.push(`${id}: repeated labels ${boxes.map((b) => b.text)}`);
    }
    return out;
  });
}

test('tick labels never overlap: default axes, other measures, a tiny range zoomed in', async () => {
  const { page, d } = await openCatalogue();
  assert.deepEqual(await overlappingTicks(page), []);
  for (const [x, y] of [['kerf', 'v0'], ['poisson_min', 'steps'], ['max_tile_rotation', 'min_expansion']]) {
    await page.goto(`${server.base}/?x=${x}&y=${y}`);
    await catalogueTotal(page);
    await drawn(page);
    assert.deepEqual(await overlappingTicks(page), [], `${x} × ${y}`);
  }
  // Zoomed 2^13 times (the + key, around the focused biggest stack): the span is tiny next to
  // the values.
  await page.goto(`${server.base}/`);
  await drawn(page, d.designs);
  await byTestId(page, 'scatter-stage').focus();
  await page.keyboard.press('ArrowUp');
  for (let i = 0; i < 13; i += 1) await page.keyboard.press('+');
  await page.waitForFunction((w) => {
    const [c0, c1] = document.getElementById('scatter').dataset.xDomain.split(',').map(Number);
    return c1 - c0 < w / 4000;
  }, d.xDomain[1] - d.xDomain[0]);
  assert.deepEqual(await overlappingTicks(page), []);
  const zoomed = await page.evaluate(() => document.getElementById('scatter').scatterDrawn);
  assert.ok(zoomed.focused, 'the zoom kept the focused stack in view and focused');
  assert.ok(zoomed.stacks.length >= 1);
  const labels = await page.$$eval('[data-testid="scatter-x-axis"] .tick text', (t) => t.map((x) => x.textContent));
  assert.ok(labels.every((l) => l.length <= 9), `short labels: ${labels}`);
  await screenshot(browser, page, 'scatter-zoomed');
  // Every design of the view has one value on x: one tick, that value in full.
  const points = await getJson(`${server.base}/api/scatter?x=max_expansion&y=max_area_ratio`);
  const v = points[0].x;
  await page.goto(`${server.base}/?range=max_expansion:${v}:${v}`);
  await catalogueTotal(page);
  await drawn(page);
  const one = await page.$$eval('[data-testid="scatter-x-axis"] .tick text', (t) => t.map((x) => x.textContent));
  assert.equal(one.length, 1);
  assert.ok(Math.abs(Number(one[0].replace('\u2212', '-')) - v) <= Math.abs(v) * 1e-11, `${one[0]} is ${v}`);
  assert.deepEqual(await overlappingTicks(page), []);
  assert.deepEqual(problems(page), []);
});

test('the keyboard reaches the scatter, moves between stacks, announces and opens them', async () => {
  const { page, d } = await openCatalogue();
  // Tab from the colour select lands on the plot (the zoom buttons have keys instead).
  await byTestId(page, 'scatter-colour').focus();
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.dataset.testid), 'scatter-stage');
  await page.keyboard.press('ArrowRight');
  let state = await page.evaluate(() => document.getElementById('scatter').scatterDrawn);
  assert.ok(state.focused, 'the first arrow focuses a stack');
  const live = byTestId(page, 'scatter-live');
  assert.match(await live.textContent(), /designs?\b.*at max expansion/);
  await byTestId(page, 'scatter-tooltip').waitFor({ state: 'visible' });
  // Walk right until the last stack on that side: each step goes right.
  let steps = 0;
  for (;;) {
    const from = state.focused;
    await page.keyboard.press('ArrowRight');
    state = await page.evaluate(() => document.getElementById('scatter').scatterDrawn);
    if (state.focused.px === from.px && state.focused.py === from.py) break;
    assert.ok(state.focused.px > from.px, 'ArrowRight moves right');
    steps += 1;
    assert.ok(steps < d.stacks.length);
  }
  assert.ok(steps > 0);
  // Arrow keys toward a stack of several: Enter lists it, Tab reaches its links, Escape closes.
  const toward = async (want) => {
    for (let i = 0; i < 3 * d.stacks.length && !want(state.focused); i += 1) {
      const target = d.stacks.filter(want).reduce((a, b) =>
        Math.hypot(b.px - state.focused.px, b.py - state.focused.py) < Math.hypot(a.px - state.focused.px, a.py - state.focused.py) ? b : a);
      const dx = target.px - state.focused.px;
      const dy = target.py - state.focused.py;
      const keys = Math.abs(dx) > Math.abs(dy)
        ? [dx > 0 ? 'ArrowRight' : 'ArrowLeft', dy > 0 ? 'ArrowDown' : 'ArrowUp']
        : [dy > 0 ? 'ArrowDown' : 'ArrowUp', dx > 0 ? 'ArrowRight' : 'ArrowLeft'];
      const from = state.focused;
      for (const k of keys) {
        await page.keyboard.press(k);
        state = await page.evaluate(() => document.getElementById('scatter').scatterDrawn);
        if (state.focused.px !== from.px || state.focused.py !== from.py) break;
      }
    }
    return want(state.focused);
  };
  assert.ok(await toward((s) => s.count > 1), 'a stack of several was reached by the arrows');
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => document.getElementById('scatter').scatterDrawn.pinned);
  assert.match(await live.textContent(), /designs listed/);
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.tagName), 'A', 'Tab reaches the list');
  await byTestId(page, 'scatter-stage').focus();
  await page.keyboard.press('Escape');
  assert.equal(await page.evaluate(() => document.getElementById('scatter').scatterDrawn.pinned), null);
  // And to a single design, which Enter opens.
  await toward((s) => s.count === 1);
  assert.equal(state.focused.count, 1, 'a single design was reached by the arrows');
  await page.keyboard.press('Enter');
  await page.waitForURL(/design\.html\?spec=/);
  assert.equal(new URL(page.url()).searchParams.get('spec'), state.focused.specs[0]);
  assert.deepEqual(problems(page), []);
});
