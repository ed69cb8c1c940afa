// The data layer: one interface over the two ways the pages get data. It fetches
// ./data/site.json first; when that exists the page is a STATIC site (written by
// `isogami site`) and every catalogue query is answered in JS over data/designs.json;
// otherwise it is SERVER mode and every call goes to ./api/... (relative URLs, so both work
// under a sub-path). Errors come back as ApiError with the server's kind and hint.

import * as q from './query.js';
import { filterParams, orderParams, pageParams } from './url.js';
import { slug } from './schema.js';

/** An error with the API's `{error, kind, hint}` shape (or a network/format failure). */
export class ApiError extends Error {
  constructor(message, kind = 'network', hint = '', status = 0) {
    super(message);
    this.kind = kind;
    this.hint = hint;
    this.status = status;
  }
}

async function asJson(res) {
  if (res.ok) return res.json();
  let body = null;
  try {
    body = await res.json();
  } catch {
    body = null;
  }
  if (body && typeof body.error === 'string') {
    throw new ApiError(body.error, body.kind || 'error', body.hint || '', res.status);
  }
  throw new ApiError(`${res.status} ${res.statusText} for ${res.url}`, 'http', '', res.status);
}

/** A file download: the body as a Blob, the file name of its Content-Disposition and the
 * server's warning about it (or null). Errors come back as ApiError with the server's message
 * (no file). */
async function getFile(url, signal) {
  let res;
  try {
    res = await fetch(url, { signal });
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    throw new ApiError(`cannot reach ${url}: ${e.message}`, 'network', 'is `isogami serve` still running?');
  }
  if (!res.ok) await asJson(res);
  // The library's warning about the sheet written (a raw rectangle's DOF), percent-encoded.
  const warning = res.headers.get('x-isogami-warning');
  return {
    blob: await res.blob(),
    disposition: res.headers.get('content-disposition') || '',
    warning: warning ? decodeURIComponent(warning.replace(/\+/g, ' ')) : null,
  };
}

async function getJson(url, options) {
  let res;
  try {
    res = await fetch(url, options);
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    throw new ApiError(`cannot reach ${url}: ${e.message}`, 'network', 'is `isogami serve` still running?');
  }
  return asJson(res);
}

/** SERVER mode: the JSON API of `isogami serve`. */
class ServerData {
  constructor() {
    this.mode = 'server';
    this.live = true;
  }

  stats() {
    return (this._stats ??= getJson('./api/stats'));
  }

  families() {
    return (this._families ??= getJson('./api/families'));
  }

  dictionary() {
    return (this._dictionary ??= getJson('./api/dictionary'));
  }

  /** The measures ranges, sorts and scatter axes take, with their dictionary entries
   * (GET /api/measures): schema.js's setMeasures makes them the page's. */
  measures() {
    return (this._measures ??= getJson('./api/measures'));
  }

  designs(state) {
    return getJson(`./api/designs?${pageParams(state)}`);
  }

  facets(state) {
    return getJson(`./api/facets?${filterParams(state)}`);
  }

  scatter(state, x, y) {
    const p = filterParams(state);
    p.set('x', x);
    p.set('y', y);
    return getJson(`./api/scatter?${p}`);
  }

  design(spec) {
    return getJson(`./api/design?spec=${encodeURIComponent(spec)}`);
  }

  /** Any design's view: the stored one, or a live deployment when it is not stored or is
   * asked at another kerf (`kerf` null: the stored one, else the library's) — one request,
   * none failing for a design that is not stored (GET /api/design?fallback=live). */
  designView(spec, kerf = null) {
    const q = new URLSearchParams({ spec, fallback: 'live' });
    if (kerf !== null && kerf !== undefined) q.set('kerf', String(kerf));
    return getJson(`./api/design?${q}`);
  }

  deploy(body, signal) {
    return getJson('./api/deploy', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
      signal,
    });
  }

  /** The mechanisms view: matching designs grouped by motion class (filters and sort of
   * `state`; GET /api/motions). */
  motions(state) {
    return getJson(`./api/motions?${orderParams(state, filterParams(state))}`);
  }

  /** The class of topologies that move like the stored design `spec` ({class: … | null}). */
  motion(spec) {
    return getJson(`./api/motion?spec=${encodeURIComponent(spec)}`);
  }

  /** Shape class, constraints and pinned parameters of a design (GET /api/shape). */
  shape(spec, signal) {
    return getJson(`./api/shape?design=${encodeURIComponent(spec)}`, { signal });
  }

  /** Moves shape parameter `index` to `value`, the others following the constraints that
   * keep one degree of freedom (POST /api/shape/follow). */
  followShape(spec, index, value) {
    return getJson('./api/shape/follow', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify({ design: spec, index, value }),
    });
  }

  /** Each shape parameter's valid range, the others fixed, at `kerf` (GET /api/shape/ranges). */
  shapeRanges(spec, kerf, signal) {
    const k = kerf === null || kerf === undefined ? '' : `&kerf=${encodeURIComponent(kerf)}`;
    return getJson(`./api/shape/ranges?design=${encodeURIComponent(spec)}${k}`, { signal });
  }

  /** A finite region of a design: DOF, floppy tiles, completion, finite deployment
   * (URLSearchParams of GET /api/sheet). */
  sheet(params, signal) {
    return getJson(`./api/sheet?${params}`, { signal });
  }

  save(body) {
    return getJson('./api/designs', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
    });
  }

  thumbnailUrl(spec) {
    return `./api/thumbnail?spec=${encodeURIComponent(spec)}`;
  }

  gifUrl(spec) {
    return `./api/gif?spec=${encodeURIComponent(spec)}`;
  }

  /** Export formats, their settings fields, defaults and limits. */
  exportCatalog() {
    return (this._export ??= getJson('./api/export/formats'));
  }

  /** An export (URLSearchParams of GET /api/export) as {blob, disposition}. */
  exportFile(params, signal) {
    return getFile(`./api/export?${params}`, signal);
  }

  /** Inverse design: defaults, caps, saving allowed, database name, running job. */
  inverseSettings() {
    return getJson('./api/inverse');
  }

  /** Starts an inverse-design job; {id}. */
  startInverse(body) {
    return getJson('./api/inverse', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
    });
  }

  /** An inverse-design job's state, progress and result. */
  inverseJob(id) {
    return getJson(`./api/inverse/${encodeURIComponent(id)}`);
  }

  /** Stops an inverse-design job; its state. */
  stopInverse(id) {
    return getJson(`./api/inverse/${encodeURIComponent(id)}`, { method: 'DELETE' });
  }

  /** Saves a finished job's refined designs; {saved: [{spec, saved, note}]}. */
  saveInverse(id) {
    return getJson(`./api/inverse/${encodeURIComponent(id)}/save`, { method: 'POST' });
  }
}

/** STATIC mode: files written by `isogami site`, queries answered by query.js. */
class StaticData {
  constructor(site) {
    this.mode = 'static';
    this.live = false;
    this.site = site;
  }

  async stats() {
    return this.site.stats;
  }

  async families() {
    return this.site.families;
  }

  async dictionary() {
    return this.site.dictionary;
  }

  /** site.json's `measures` (a site written before it has none: the page's own list stays). */
  async measures() {
    return this.site.measures ?? null;
  }

  rows() {
    return (this._rows ??= getJson('./data/designs.json'));
  }

  async designs(state) {
    return q.page(await this.rows(), state);
  }

  async facets(state) {
    return q.facetCounts(await this.rows(), state);
  }

  async scatter(state, x, y) {
    return q.scatter(await this.rows(), state, x, y);
  }

  /** Each classed topology's representative (sites written before it: none computed). */
  motionClasses() {
    return (this._motions ??= getJson('./data/motions.json').catch((e) => {
      if (e.status === 404) return { computed: false, classes: {} };
      throw e;
    }));
  }

  async motions(state) {
    return q.motionGroups(await this.rows(), await this.motionClasses(), state);
  }

  async motion(spec) {
    return q.motionOf(await this.rows(), await this.motionClasses(), spec);
  }

  async design(spec) {
    try {
      return await getJson(`./data/design/${encodeURIComponent(slug(spec))}.json`);
    } catch (e) {
      if (e.status === 404) {
        throw new ApiError(
          `design ${spec} is not in this static catalogue`,
          'not_found',
          'live design needs `isogami serve`',
          404,
        );
      }
      throw e;
    }
  }

  async deploy() {
    throw new ApiError('live design needs `isogami serve`', 'static', 'run `isogami serve --db FILE` and open it there');
  }

  async save() {
    return this.deploy();
  }

  async sheet() {
    throw new ApiError('the finite sheet needs `isogami serve`', 'static', 'run `isogami sheet` from the command line, or `isogami serve --db FILE` and open the design there');
  }

  thumbnailUrl(spec) {
    return `./thumbs/${encodeURIComponent(slug(spec))}.svg`;
  }

  gifUrl() {
    return null;
  }

  /** The export formats the site was written with (older sites have none). */
  async exportCatalog() {
    if (!this.site.export) throw new ApiError('this static site lists no export formats', 'static');
    return this.site.export;
  }

  async exportFile() {
    throw new ApiError('downloads need `isogami serve`', 'static', 'run the command shown, or `isogami serve --db FILE` and download from there');
  }

  /** The inverse-design settings the site was written with (older sites have none). */
  async inverseSettings() {
    return this.site.inverse ?? { defaults: { top: 3, budget: 80 }, limits: {}, save: false, database: null, running: null };
  }

  async startInverse() {
    throw new ApiError('inverse design needs `isogami serve`', 'static', 'run the command shown, or `isogami serve --db FILE` and run it there');
  }

  async inverseJob() {
    return this.startInverse();
  }

  async stopInverse() {
    return this.startInverse();
  }

  async saveInverse() {
    return this.startInverse();
  }
}

/** Detects the mode once per page. */
export async function openData() {
  let res = null;
  try {
    res = await fetch('./data/site.json');
  } catch {
    res = null;
  }
  if (res && res.ok) {
    let site = null;
    try {
      site = await res.json();
    } catch {
      site = null;
    }
    if (site && site.mode === 'static') return new StaticData(site);
  }
  return new ServerData();
}
