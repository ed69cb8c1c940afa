import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  catalogueHref, catalogueSearch, designSearch, pageParams, parseCatalogueState, parseDesignState,
  rememberCatalogue,
} from '../src/url.js';
import { slug } from '../src/schema.js';

test('catalogue view round-trips through the URL', () => {
  const search = '?family=IH1&family=IH28&cell=2x1&behaviour=none&range=max_expansion:0.1:&range=v2::3&sort=-steps&limit=25&offset=50&x=steps&y=kerf&view=table';
  const s = parseCatalogueState(search);
  assert.deepEqual(s.filters.family, ['IH1', 'IH28']);
  assert.deepEqual(s.ranges, [
    { measure: 'max_expansion', min: 0.1, max: null },
    { measure: 'v2', min: null, max: 3 },
  ]);
  assert.deepEqual(s.sort, { key: 'steps', desc: true });
  assert.deepEqual(parseCatalogueState(catalogueSearch(s)), s);
  const api = pageParams(s);
  assert.equal(api.get('limit'), '25');
  assert.equal(api.get('sort'), '-steps');
  assert.deepEqual(api.getAll('range'), ['max_expansion:0.1:', 'v2::3']);
  assert.equal(api.get('x'), null);
});

test('malformed catalogue parameters are dropped, not passed on', () => {
  const s = parseCatalogueState('?range=nope:1:2&range=kerf:x:1&range=kerf::&sort=drop&limit=9999&offset=-3&x=bad');
  assert.deepEqual(s.ranges, []);
  assert.deepEqual(s.sort, { key: 'max_area_ratio', desc: true }, 'the default order: largest area ratio first');
  assert.equal(s.view, 'mechanisms');
  assert.equal(s.limit, 50);
  assert.equal(s.offset, 0);
  assert.equal(s.x, 'max_expansion');
  assert.equal(catalogueSearch(s), '');
});

test('design view round-trips and clamps', () => {
  const s = parseDesignState('?spec=IH1%3A0.1%2C0.2%3A2x1%3A--bbb-&R=3&C=8&kerf=0.02&colour=rotation&t=0.25&cell=1');
  assert.equal(s.spec, 'IH1:0.1,0.2:2x1:--bbb-');
  assert.deepEqual([s.rows, s.cols, s.kerf, s.colour, s.t, s.cell, s.links], [3, 8, 0.02, 'rotation', 0.25, true, true]);
  assert.deepEqual(parseDesignState(designSearch(s)), s);
  const off = parseDesignState('?spec=x&links=0');
  assert.equal(off.links, false, 'linkage loops are drawn unless links=0');
  assert.deepEqual(parseDesignState(designSearch(off)), off);
  const bad = parseDesignState('?spec=x&R=99&C=0&kerf=-1&t=2');
  assert.deepEqual([bad.rows, bad.cols, bad.kerf, bad.t], [4, 4, null, 0]);
});

test('slug: colons to _, commas to ~, anything else unsafe to _', () => {
  assert.equal(slug('IH28:0.1,-0.2:2x1:ab-ba-'), 'IH28_0.1~-0.2_2x1_ab-ba-');
  assert.equal(slug('IH76::2x2:bbbbaaaa'), 'IH76__2x2_bbbbaaaa');
  assert.equal(slug('../x y/~'), '.._x_y__');
});

test('default sort and view stay out of the URL; others round-trip', () => {
  for (const search of ['?sort=spec', '?sort=max_area_ratio', '?view=grid', '?view=table', '?sort=-steps&view=grid']) {
    const s = parseCatalogueState(search);
    assert.equal(catalogueSearch(s), search, search);
    assert.equal(pageParams(s).get('sort') !== null, true, 'the API is always told the order');
  }
  assert.equal(catalogueSearch(parseCatalogueState('?sort=-max_area_ratio&view=mechanisms')), '');
  assert.equal(pageParams(parseCatalogueState('')).get('sort'), '-max_area_ratio');
  assert.equal(parseCatalogueState('?view=cards').view, 'mechanisms');
});

test('the back link carries the catalogue query the tab last had', () => {
  const store = new Map();
  const storage = { getItem: (k) => store.get(k) ?? null, setItem: (k, v) => store.set(k, v) };
  assert.equal(catalogueHref(storage), './index.html');
  rememberCatalogue('?family=IH2&view=table', storage);
  assert.equal(catalogueHref(storage), './index.html?family=IH2&view=table');
  const broken = { getItem: () => { throw new Error('denied'); }, setItem: () => { throw new Error('denied'); } };
  rememberCatalogue('?x=1', broken);
  assert.equal(catalogueHref(broken), './index.html');
  assert.equal(catalogueHref(null), './index.html');
  assert.equal(catalogueHref(), './index.html', 'no sessionStorage outside a browser');
});
