// The design page's "Export / make it" panel: a form built from the export catalogue (the
// formats with their descriptions, and for each settings group its fields, shown only for
// the formats that use it), the patch rows × columns, the sheet (the rectangle's completion to
// one degree of freedom, or the raw rectangle), the scale (mean edge or patch width in
// mm) and the state (closed, the slider's t, open). It exports what is on screen: the
// design page tells it the current spec, kerf and t. Download fetches GET /api/export and
// saves the answer under the server's file name; an error is shown in the panel and nothing
// is saved. Under the form, the `isogami export …` command that writes the same file; on a
// static site that command is the way to make the file. Rows × columns are checked against the
// catalogue's limits as they are typed (the message beside them, Download disabled); the state
// is disabled, with the reason, for formats that do not use it (laser: the closed sheet). A
// design whose catalogue row says it has no one-DOF sheet (buildable.js) gets the raw rectangle
// chosen before any click, with the reason and what to do instead (another region, or a design
// of the same family that has a sheet, named by the catalogue) beside the choice.

import { h } from './dom.js';
import { findNeighbour, neighbourHref, percentText, sheetStatus } from './buildable.js';
import { designHref } from './url.js';
import {
  attachmentName, cliCommand, exportFileName, exportParams, formatOf, patchProblem, usesState,
} from './export-request.js';

/** Bytes as "12.3 kB". */
function size(n) {
  if (n < 1000) return `${n} B`;
  if (n < 1e6) return `${(n / 1000).toFixed(1)} kB`;
  return `${(n / 1e6).toFixed(1)} MB`;
}

/** Draws the panel into `container`. `current()` gives {spec, kerf, t, tiles, family, summary}
 * of what is on screen (tiles: the cell's tile count; summary: its catalogue row, null for a
 * live design; null before a design is shown); `initial` the rows and columns to start with. */
export function createExportPanel(container, { data, current, initial }) {
  let catalog = null;
  let inflight = null;
  const settings = {}; // group → field name → text (or boolean for flags) the user set
  const el = {};
  let sheetTouched = false; // the user chose the sheet: advice no longer changes the choice
  let advisedFor = null; // the spec the sheet advice was last made for
  let neighbourAsked = 0;

  const form = () => {
    const now = current();
    if (!now || !catalog) return null;
    return {
      spec: now.spec,
      kerf: now.kerf,
      t: now.t,
      format: el.format.value,
      rows: Number(el.rows.value),
      cols: Number(el.cols.value),
      sheet: container.querySelector('input[name="export-sheet"]:checked')?.value ?? 'completed',
      scale: el.scale.value,
      mm: el.mm.value.trim() === '' ? catalog.defaults.edge_mm : Number(el.mm.value),
      state: container.querySelector('input[name="export-state"]:checked')?.value ?? 'closed',
      settings,
    };
  };

  function sheetChoice(value) {
    const radio = container.querySelector(`input[name="export-sheet"][value="${value}"]`);
    if (radio) radio.checked = true;
  }

  /** The design's finite sheet as its catalogue row says: for a design without a one-DOF
   * sheet the raw rectangle is chosen (unless the user chose; the completed sheet for one with a
   * sheet) and the note says why and what to do; the choice is made again only when the design
   * changes. */
  function adviseSheet(now) {
    const status = sheetStatus(now?.summary);
    if (now && now.spec !== advisedFor) {
      advisedFor = now.spec;
      // A live edit (no catalogue row: unknown) keeps the choice the design it came from had.
      if (!sheetTouched && status.kind !== 'unknown') sheetChoice(status.kind === 'none' ? 'raw' : 'completed');
      el.neighbour.replaceChildren();
      if (status.kind === 'none') findSheetNeighbour(now);
    }
    const none = status.kind === 'none';
    el.sheetNote.hidden = !none;
    el.sheetNote.dataset.sheet = status.kind;
    el.completedNone.hidden = !none;
    if (!none) return;
    const chosen = container.querySelector('input[name="export-sheet"]:checked')?.value;
    el.sheetReason.textContent = `This design has no one-DOF sheet: its 6×6-cell patch as cut has ${status.rawDof} DOF (its boundary tiles flop) and no completion of it reaches one DOF, so the completed sheet is refused. `;
    el.sheetChosen.textContent = chosen === 'raw'
      ? 'The raw rectangle is chosen: it is written as it is, floppy boundary included. '
      : 'Choose the raw rectangle to export it as it is (floppy boundary included). ';
  }

  /** The design of the same family with the largest one-DOF sheet, as a link (else the
   * catalogue's list of designs with one). */
  async function findSheetNeighbour(now) {
    const asked = ++neighbourAsked;
    let found = null;
    try {
      found = await findNeighbour(data, now.family, now.spec);
    } catch {
      found = null;
    }
    if (asked !== neighbourAsked) return;
    const all = h('a', { href: neighbourHref(null), testid: 'export-sheet-all' }, 'the designs that have one');
    el.neighbour.replaceChildren(
      found
        ? h('span', {}, 'a design of the same family that has one: ', h('a', { href: designHref(found.spec), testid: 'export-sheet-neighbour', 'data-spec': found.spec }, h('code', {}, found.spec)), ` (keeps ${percentText(found.finite_covered)} %), or `, all)
        : h('span', {}, `no design of ${now.family || 'its family'} in this catalogue has one; see `, all),
      '.',
    );
  }

  function update() {
    if (!catalog) return;
    adviseSheet(current());
    const f = form();
    const format = formatOf(catalog, el.format.value);
    el.description.textContent = format.description;
    for (const [name, box] of Object.entries(el.groups)) box.hidden = !format.settings.includes(name);
    const now = current();
    el.currentT.textContent = now ? Number(now.t).toFixed(3) : '–';
    const command = f ? cliCommand(f, catalog) : '';
    if (el.command.textContent !== command) el.command.textContent = command;
    const stateful = usesState(catalog, el.format.value);
    el.state.disabled = !stateful;
    el.stateNote.hidden = stateful;
    const problem = f ? patchProblem(f, catalog, now?.tiles) : null;
    el.patchError.textContent = problem ? problem.message : '';
    el.patchError.hidden = !problem;
    el.rows.setAttribute('aria-invalid', String(problem?.field === 'rows' || problem?.field === 'patch'));
    el.cols.setAttribute('aria-invalid', String(problem?.field === 'cols' || problem?.field === 'patch'));
    el.button.disabled = !data.live || Boolean(problem) || Boolean(inflight);
  }

  function numberInput(id, attrs) {
    return h('input', { id, type: 'number', inputmode: 'decimal', ...attrs, oninput: update, onchange: update });
  }

  function settingInput(group, field) {
    const id = `export-${group.name}-${field.name}`;
    const values = (settings[group.name] ??= {});
    const set = (value) => {
      if (value === '' || value === null) delete values[field.name];
      else values[field.name] = value;
      update();
    };
    let input;
    if (field.kind === 'choice') {
      input = h(
        'select',
        { id, testid: id, onchange: (e) => choose(group, field, e.target.value, set) },
        h('option', { value: '' }, 'none (defaults)'),
        field.choices.map((c) => h('option', { value: c.value }, c.label)),
      );
    } else if (field.kind === 'flag') {
      input = h('input', { id, testid: id, type: 'checkbox', checked: field.default === true, onchange: (e) => set(e.target.checked) });
      return h('div', { class: 'export-field flag' }, input, h('label', { for: id, title: field.help }, field.label));
    } else if (field.kind === 'colour') {
      input = h('input', {
        id, testid: id, type: 'text', size: 8, placeholder: field.default, pattern: '#[0-9a-fA-F]{6}', spellcheck: 'false',
        oninput: (e) => set(e.target.value.trim()),
      });
    } else {
      input = h('input', {
        id, testid: id, type: 'number', inputmode: 'decimal', step: 'any', min: 0, placeholder: String(field.default),
        oninput: (e) => set(e.target.value.trim()),
      });
    }
    const unit = field.unit ? h('span', { class: 'unit' }, field.unit) : null;
    return h('div', { class: 'export-field' }, h('label', { for: id, title: field.help }, field.label), input, unit);
  }

  /** A preset choice: its values become the placeholders of the fields it sets. */
  function choose(group, field, value, set) {
    const choice = field.choices.find((c) => c.value === value);
    for (const other of group.fields) {
      if (other.kind !== 'number') continue;
      const input = container.querySelector(`#export-${group.name}-${other.name}`);
      if (input) input.placeholder = String(choice?.sets?.[other.name] ?? other.default);
    }
    set(value);
  }

  async function download() {
    const f = form();
    if (!f || patchProblem(f, catalog, current()?.tiles)) return;
    if (inflight) inflight.abort();
    const controller = new AbortController();
    inflight = controller;
    el.error.replaceChildren();
    el.error.hidden = true;
    el.button.disabled = true;
    el.status.textContent = 'exporting…';
    try {
      const { blob, disposition, warning } = await data.exportFile(exportParams(f, catalog), controller.signal);
      const name = attachmentName(disposition) ?? exportFileName(f.spec, f.rows, f.cols, formatOf(catalog, f.format));
      const url = URL.createObjectURL(blob);
      const a = h('a', { href: url, download: name, hidden: true });
      document.body.append(a);
      a.click();
      a.remove();
      setTimeout(() => URL.revokeObjectURL(url), 10000);
      el.status.textContent = `saved ${name} (${size(blob.size)})${warning ? `; warning: ${warning}` : ''}`;
    } catch (e) {
      if (e.name === 'AbortError') return;
      el.status.textContent = '';
      el.error.replaceChildren(h('strong', {}, e.message), e.hint ? h('p', { class: 'hint' }, e.hint) : null);
      el.error.dataset.kind = e.kind || 'error';
      el.error.hidden = false;
    } finally {
      if (inflight === controller) {
        inflight = null;
        update();
      }
    }
  }

  async function copyCommand() {
    try {
      await navigator.clipboard.writeText(el.command.textContent);
      el.copyStatus.textContent = 'copied';
    } catch {
      const range = document.createRange();
      range.selectNodeContents(el.command);
      getSelection().removeAllRanges();
      getSelection().addRange(range);
      el.copyStatus.textContent = 'selected: press Ctrl+C';
    }
  }

  function render() {
    const max = catalog.limits.max_patch;
    el.format = h(
      'select',
      { id: 'export-format', testid: 'export-format', onchange: update },
      catalog.formats.map((f) => h('option', { value: f.name, title: f.description }, `${f.name} — ${f.description}`)),
    );
    el.description = h('p', { class: 'help', id: 'export-format-help', testid: 'export-format-help' });
    el.format.setAttribute('aria-describedby', 'export-format-help');
    el.rows = numberInput('export-rows', { testid: 'export-rows', min: 1, max, step: 1, value: initial.rows, required: true, 'aria-describedby': 'export-patch-error' });
    el.cols = numberInput('export-cols', { testid: 'export-cols', min: 1, max, step: 1, value: initial.cols, required: true, 'aria-describedby': 'export-patch-error' });
    el.patchError = h('p', { id: 'export-patch-error', class: 'field-error', testid: 'export-patch-error', 'aria-live': 'polite', hidden: true });
    el.scale = h(
      'select',
      { id: 'export-scale', testid: 'export-scale', onchange: update },
      h('option', { value: 'edge' }, 'mean edge length'),
      h('option', { value: 'width' }, 'patch width'),
    );
    el.mm = numberInput('export-mm', { testid: 'export-mm', min: 0, step: 'any', value: catalog.defaults.edge_mm, required: true });
    el.currentT = h('span', { testid: 'export-current-t' });
    const radio = (value, ...label) =>
      h(
        'label',
        { class: 'radio' },
        h('input', { type: 'radio', name: 'export-state', value, testid: `export-state-${value}`, checked: value === 'current', onchange: update }),
        ' ',
        ...label,
      );
    const sheetRadio = (value, label) =>
      h(
        'label',
        { class: 'radio' },
        h('input', {
          type: 'radio', name: 'export-sheet', value, testid: `export-sheet-${value}`, checked: value === 'completed', 'aria-describedby': 'export-sheet-note',
          onchange: () => {
            sheetTouched = true;
            update();
          },
        }),
        ' ',
        label,
      );
    el.completedNone = h('span', { class: 'field-error', testid: 'export-sheet-completed-none', hidden: true }, ' — none for this design');
    el.sheetReason = h('span');
    el.sheetChosen = h('span');
    el.neighbour = h('span', { testid: 'export-sheet-neighbours' });
    el.sheetNote = h(
      'p',
      { id: 'export-sheet-note', class: 'sheet-advice', testid: 'export-sheet-note', role: 'status', hidden: true },
      el.sheetReason,
      el.sheetChosen,
      'For a sheet that opens with one motion, try another region in the Finite sheet panel above, or cut ',
      el.neighbour,
    );
    el.groups = {};
    const groups = catalog.settings.map((g) => {
      const box = h('fieldset', { class: 'export-group', testid: `export-group-${g.name}` }, h('legend', {}, g.label), g.fields.map((f) => settingInput(g, f)));
      el.groups[g.name] = box;
      return box;
    });
    el.button = h('button', { type: 'button', testid: 'export-download', onclick: download, disabled: !data.live }, 'Download');
    el.status = h('span', { class: 'muted', testid: 'export-status', 'aria-live': 'polite' });
    el.error = h('div', { class: 'notice notice-error', role: 'alert', testid: 'export-error', hidden: true });
    el.command = h('code', { id: 'export-command', testid: 'export-command' });
    el.copyStatus = h('span', { class: 'muted', 'aria-live': 'polite' });
    container.replaceChildren(
      h('div', { class: 'export-field wide' }, h('label', { for: 'export-format' }, 'format'), el.format),
      el.description,
      h(
        'div',
        { class: 'export-row' },
        h('label', { for: 'export-rows' }, 'rows'),
        el.rows,
        h('span', { 'aria-hidden': 'true' }, '×'),
        h('label', { for: 'export-cols' }, 'columns'),
        el.cols,
      ),
      el.patchError,
      h(
        'fieldset',
        { class: 'export-sheet' },
        h('legend', {}, 'sheet'),
        h('span', {}, sheetRadio('completed', 'completed sheet (one DOF)'), el.completedNone),
        sheetRadio('raw', 'raw rectangle'),
        el.sheetNote,
        h(
          'p',
          { class: 'help' },
          'The completed sheet is the rectangle with the tiles that would flop at its boundary removed and the ring that closes its open loops added, so it opens with the design’s one motion; it is refused, with the reason, when there is none. The raw rectangle is every tile of the rows × columns as it is.',
        ),
      ),
      h(
        'div',
        { class: 'export-row' },
        h('label', { for: 'export-scale' }, 'scale by'),
        el.scale,
        h('label', { for: 'export-mm' }, 'length'),
        el.mm,
        h('span', { class: 'unit' }, 'mm'),
      ),
      (el.state = h(
        'fieldset',
        { class: 'export-state', testid: 'export-state' },
        h('legend', {}, 'state'),
        radio('closed', 'closed (t = 0)'),
        radio('current', 'the slider’s t = ', el.currentT),
        radio('open', 'open (contact limit)'),
        (el.stateNote = h(
          'p',
          { class: 'help', testid: 'export-state-note', hidden: true },
          'A laser cuts the flat sheet: SVG and DXF are always the closed state (t = 0), so the state does not apply.',
        )),
      )),
      ...groups,
      h('p', {}, el.button, ' ', el.status),
      el.error,
      h('p', { class: 'help' }, data.live ? 'The same file from the command line:' : 'Downloads need `isogami serve`. On this static site, make the file with:'),
      h('pre', { class: 'command' }, el.command),
      h('p', {}, h('button', { type: 'button', testid: 'export-copy-command', onclick: copyCommand }, 'Copy command'), ' ', el.copyStatus),
    );
  }

  async function start() {
    try {
      catalog = await data.exportCatalog();
    } catch (e) {
      container.replaceChildren(h('p', { class: 'notice', testid: 'export-unavailable' }, `Export: ${e.message}. ${e.hint || ''}`));
      return;
    }
    render();
    update();
  }

  const ready = start();
  return {
    /** Redraws the command after the design, its kerf or t changed. */
    update,
    ready,
  };
}
