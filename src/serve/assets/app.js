// The page of `voussoir serve`: the scene as sliders and number fields, the drawing and the
// collapse multiplier returned by POST /api/analyze, a chart of lambda over one parameter's
// range from POST /api/sweep, and downloads of what the server returned.
//
// The page holds no policy: parameter ranges, presets and limits come from GET /api/parameters,
// every value is validated by the server, and its errors are shown beside the field they name.
// Live updates: at most one analysis request is in flight; events that arrive meanwhile only
// mark the scene dirty, and the latest scene is sent as soon as the previous answer is drawn,
// so the drawing never lags more than one request behind and the server is never flooded.
'use strict';

(function () {
  const $ = (id) => document.getElementById(id);

  const SECTION_TITLES = {
    arch: 'Arch', piers: 'Piers', material: 'Material', fill: 'Fill',
    seismic: 'Seismic', loads: 'Loads',
  };
  const STATUS_WORDS = {
    collapse: 'Collapse mechanism',
    no_collapse: 'Stands at any λ',
    stands: 'Stands',
    cannot_stand: 'Cannot stand',
  };
  const STATUS_NOTES = {
    no_collapse: 'A thrust line fits for any horizontal acceleration.',
    stands: 'A thrust line fits at this acceleration.',
    cannot_stand: 'No thrust line fits even without horizontal load.',
  };
  // How many points a chart asks for (at most the server's limit).
  const SWEEP_POINTS = 41;
  // The keys that move a range input.
  const SLIDER_KEYS = new Set(['ArrowLeft', 'ArrowRight', 'ArrowUp', 'ArrowDown', 'Home', 'End',
    'PageUp', 'PageDown']);
  // How many update times window.voussoirTimings keeps.
  const TIMINGS_KEPT = 500;

  const state = {
    parameters: [],       // from /api/parameters
    byKey: new Map(),     // key -> parameter
    shapes: [],           // presets: {name, label, scene}
    limits: {},
    initial: null,        // {scene, origin} from /api/scene
    scene: null,          // the scene being edited (JSON with the scene file's keys)
    preset: null,         // name of the preset picked, or null for the scene from the command line
    startPreset: null,    // the preset the start scene is, if it is one (for its slider ranges)
    direction: 'right',
    last: null,           // last successful analysis (the server's object)
    lastOk: false,        // whether the drawing shows the current scene
    lastKey: null,        // the parameter moved last
    // Slider ranges widened to take a value typed beyond them: key -> {min, max, value,
    // confirmed, previous}. Back to `previous` (the last one accepted) when the server refuses
    // the value typed, kept once it accepts it, all forgotten when another structure is picked.
    widened: new Map(),
  };

  // Live analysis: one request in flight, the latest state sent next.
  const live = { inFlight: false, dirty: false, since: null };
  // Sweep chart: one request in flight; a new one aborts the old.
  const chart = { sig: null, key: null, rows: null, controller: null, error: null };

  window.voussoirTimings = [];

  // ---- scene helpers ------------------------------------------------------------------------

  const clone = (x) => JSON.parse(JSON.stringify(x));
  // JSON text with object keys sorted, to compare two scenes.
  const canonical = (x) => JSON.stringify(x, (k, v) => (v && typeof v === 'object' && !Array.isArray(v)
    ? Object.fromEntries(Object.keys(v).sort().map((key) => [key, v[key]])) : v));
  // A dotted scene key as path segments; an entry of a list is written as the scene's errors
  // write it, `loads[1].intensity` (-> ['loads', 1, 'intensity']).
  const segments = (key) => key.replace(/\[(\d+)\]/g, '.$1').split('.')
    .map((s) => (/^\d+$/.test(s) ? Number(s) : s));

  function getKey(obj, key) {
    let cur = obj;
    for (const s of segments(key)) {
      if (cur === null || typeof cur !== 'object' || !(s in cur)) return undefined;
      cur = cur[s];
    }
    return cur;
  }

  function setKey(obj, key, value) {
    const segs = segments(key);
    let cur = obj;
    for (let i = 0; i < segs.length - 1; i++) {
      if (cur[segs[i]] === null || typeof cur[segs[i]] !== 'object') {
        cur[segs[i]] = typeof segs[i + 1] === 'number' ? [] : {};
      }
      cur = cur[segs[i]];
    }
    cur[segs[segs.length - 1]] = value;
  }

  function deleteKey(obj, key) {
    const segs = segments(key);
    let cur = obj;
    for (let i = 0; i < segs.length - 1; i++) {
      if (cur === null || typeof cur !== 'object') return;
      cur = cur[segs[i]];
    }
    if (cur !== null && typeof cur === 'object') delete cur[segs[segs.length - 1]];
  }

  const sectionOf = (p) => p.section || segments(p.key)[0];

  // What an absent key means, from the parameter's `absent` ("inf (joints cannot slide)",
  // "0 (no vertical acceleration)"): 'inf', a number, or undefined (the key is required).
  function absentValue(p) {
    if (typeof p.absent !== 'string') return undefined;
    const word = p.absent.trim().split(/\s+/)[0];
    if (isInfinite(word)) return 'inf';
    const x = Number(word);
    return Number.isFinite(x) ? x : undefined;
  }

  const mayBeInfinite = (p) => absentValue(p) === 'inf';

  // A parameter is shown when the scene has its section (a section whose keys may all be
  // left out, such as [material] or [seismic], counts as there) and, for an arch key, when
  // the scene's arch shape is one of the parameter's `arch_shapes`.
  // A parameter with `not_with` is hidden when the scene has any of those sections (a portal's
  // arch must embrace 180 degrees, so `arch.embrace_deg` is `not_with: ["piers"]`), and the
  // common pier keys are hidden when the scene gives each pier its own table
  // (`[piers.left]`, `[piers.right]`): one slider could not say which pier it moves.
  const hasSection = (name) => state.scene[name] !== undefined && state.scene[name] !== null;

  function perSidePiers() {
    const piers = state.scene.piers;
    return !!piers && typeof piers === 'object'
      && ['left', 'right'].some((side) => piers[side] && typeof piers[side] === 'object');
  }

  // The profile of the scene's piers (`piers.shape`, rectangular when left out).
  function pierShape() {
    const piers = state.scene.piers;
    return piers && typeof piers === 'object' && typeof piers.shape === 'string'
      ? piers.shape : 'rectangular';
  }

  function visible(p) {
    const section = sectionOf(p);
    if (Array.isArray(p.not_with) && p.not_with.some(hasSection)) return false;
    if (section === 'piers' && segments(p.key).length === 2 && perSidePiers()) return false;
    // A pier key the piers' profile does not take (a stepped pier has no `width`, and its
    // courses are its number of widths): a slider that could only be refused.
    if (section === 'piers' && Array.isArray(p.pier_shapes) && p.pier_shapes.length
      && !p.pier_shapes.includes(pierShape())) return false;
    const has = hasSection(section);
    if (!has && !(section === 'material' || absentValue(p) !== undefined)) return false;
    if (getKey(state.scene, p.key) !== undefined) return true;
    // An entry of a list (`loads[1].intensity`) is shown only when the scene has that entry
    // with that key: the second load may be a point load, which has no intensity.
    if (/\[\d+\]/.test(p.key)) return false;
    if (section === 'arch') {
      const archShape = state.scene.arch && state.scene.arch.shape;
      const shapes = p.arch_shapes || p.shapes || [];
      return shapes.includes(archShape);
    }
    return true;
  }

  function isInfinite(v) {
    return v === 'inf' || v === Infinity || v === '+inf';
  }

  // A multiple of a step, written without binary noise (0.7, not 0.7000000000000001).
  const onGrid = (k, step) => Number((k * step).toFixed(10));

  // The step of a parameter's slider and number field: its `shape_steps` entry for the
  // scene's arch shape (a pointed arch needs an even number of voussoirs: 2), else its own
  // (at least 1 for a whole number); 0 when it has none.
  function stepOf(p) {
    const shape = state.scene && state.scene.arch && state.scene.arch.shape;
    const own = p.shape_steps && typeof shape === 'string' ? p.shape_steps[shape] : undefined;
    if (typeof own === 'number' && own > 0) return own;
    if (p.integer) return Math.max(1, p.step || 1);
    return p.step > 0 ? p.step : 0;
  }

  // The slider's range: the preset's own when it narrows it, else the parameter's; widened
  // to a value typed beyond it; for a whole number, its ends on the step's multiples (a
  // pointed arch's voussoir slider runs over even numbers only).
  function rangeOf(p) {
    const name = state.preset || state.startPreset;
    const preset = name && state.shapes.find((s) => s.name === name);
    const r = preset && preset.ranges && preset.ranges[p.key];
    let min = p.min;
    let max = p.max;
    if (Array.isArray(r) && r.length === 2 && r[0] < r[1]) [min, max] = r;
    const wide = state.widened.get(p.key);
    if (wide) {
      min = Math.min(min, wide.min);
      max = Math.max(max, wide.max);
    }
    const step = stepOf(p);
    if (p.integer && step > 0) {
      min = onGrid(Math.ceil(min / step - 1e-9), step);
      max = Math.max(min, onGrid(Math.floor(max / step + 1e-9), step));
    }
    return { min, max, step };
  }

  // The value a field shows: the scene's, else what leaving it out means (`absent`), else
  // nothing (an empty field: the page does not make up a value the scene does not have).
  function shownValue(p) {
    const v = getKey(state.scene, p.key);
    if (v !== undefined) return v;
    return absentValue(p);
  }

  // ---- formatting ---------------------------------------------------------------------------

  const fmt = (x, digits) => (typeof x === 'number' && Number.isFinite(x) ? x.toFixed(digits) : '—');

  // Units as typed in the API ("N/m^3") as they are printed ("N/m³").
  function prettyUnit(unit) {
    return (unit || '').replace(/\^2/g, '²').replace(/\^3/g, '³').replace(/\^-1/g, '⁻¹');
  }

  // A range end, short: 500000 as 5e5.
  function compact(v) {
    if (Math.abs(v) >= 1e5) return v.toExponential().replace('e+', 'e');
    return String(v);
  }

  // A unit with a prefix for large values (Pa -> MPa, N/m -> kN/m), so that a chart's axis
  // labels stay short: the factor the values are divided by, and the unit to print.
  function scaledUnit(unit, maxAbs) {
    const base = unit || '';
    if (!/^(Pa|N|N\/m|N\/m\^2|N\/m\^3)$/.test(base)) return { factor: 1, unit: base };
    if (maxAbs >= 1e6) return { factor: 1e6, unit: 'M' + base };
    if (maxAbs >= 1e4) return { factor: 1e3, unit: 'k' + base };
    return { factor: 1, unit: base };
  }

  // A value in a scaled unit, without binary noise (5000000 Pa -> "5 MPa").
  function scaledValue(v, su) {
    const x = Number((v / su.factor).toPrecision(6));
    return String(x) + (su.unit ? ' ' + prettyUnit(su.unit) : '');
  }

  // Ticks for an axis `width` units long whose labels do not overlap: as many as fit
  // (5 at most) at about 5.6 units per character of the 9.5-unit font, plus a gap.
  function fittingTicks(lo, hi, width) {
    for (let count = 5; count > 1; count--) {
      const ticks = niceTicks(lo, hi, count);
      const longest = Math.max(...ticks.map((v) => tickLabel(v, ticks).length));
      if (ticks.length < 2 || (longest * 5.6 + 6) * ticks.length <= width) return ticks;
    }
    return niceTicks(lo, hi, 1);
  }

  function niceTicks(lo, hi, count) {
    const span = hi - lo;
    if (!(span > 0)) return [lo];
    const raw = span / count;
    const mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || raw;
    const ticks = [];
    for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) {
      ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    }
    return ticks;
  }

  function tickLabel(v, ticks) {
    const step = ticks.length > 1 ? Math.abs(ticks[1] - ticks[0]) : Math.abs(v) || 1;
    const decimals = Math.max(0, Math.min(6, -Math.floor(Math.log10(step) + 1e-9) + (step / Math.pow(10, Math.floor(Math.log10(step))) === 2.5 ? 1 : 0)));
    return v.toFixed(decimals);
  }

  // ---- the parameter form -------------------------------------------------------------------

  function buildForm() {
    const form = $('v-params');
    form.replaceChildren();
    const groups = new Map();
    for (const p of state.parameters) {
      if (!visible(p)) continue;
      const section = segments(p.key)[0];
      if (!groups.has(section)) groups.set(section, []);
      groups.get(section).push(p);
    }
    for (const [section, params] of groups) {
      const fieldset = document.createElement('fieldset');
      fieldset.className = 'panel group';
      fieldset.dataset.section = section;
      const legend = document.createElement('legend');
      legend.textContent = SECTION_TITLES[section] || section.charAt(0).toUpperCase() + section.slice(1);
      fieldset.append(legend);
      for (const p of params) fieldset.append(buildField(p));
      form.append(fieldset);
    }
  }

  function fieldId(key) {
    return 'f-' + key.replace(/[^A-Za-z0-9_-]/g, '-');
  }

  // A list of numbers (a stepped pier's widths, base to top): one text field of
  // comma-separated numbers, no slider, no chart. What does not read as a number is sent as
  // typed, so that the server's message names it.
  function buildListField(p) {
    const id = fieldId(p.key);
    const row = document.createElement('div');
    row.className = 'field field-list';
    row.dataset.key = p.key;
    const head = document.createElement('div');
    head.className = 'field-head';
    const label = document.createElement('label');
    label.htmlFor = id + '-list';
    label.textContent = p.label;
    if (p.help) label.title = p.help;
    const unit = document.createElement('span');
    unit.className = 'unit';
    unit.textContent = prettyUnit(p.unit);
    head.append(label, unit);
    const input = document.createElement('input');
    input.type = 'text';
    input.id = id + '-list';
    input.className = 'list-input';
    input.inputMode = 'decimal';
    input.spellcheck = false;
    const help = document.createElement('p');
    help.className = 'field-note';
    help.id = id + '-help';
    help.textContent = p.help || '';
    const error = document.createElement('p');
    error.className = 'field-error';
    error.id = id + '-error';
    error.setAttribute('aria-live', 'polite');
    input.setAttribute('aria-describedby', error.id + ' ' + help.id);
    row.append(head, input, help, error);
    input.addEventListener('change', (ev) => {
      const t = eventTime(ev);
      const items = input.value.split(/[,;\s]+/).filter((x) => x !== '');
      if (items.length === 0) {
        showFieldError(p.key, 'Enter one width per course, base to top, e.g. 0.6, 0.5, 0.4.');
        return;
      }
      const values = items.map((x) => {
        const v = Number(x);
        return Number.isFinite(v) ? v : x;
      });
      setKey(state.scene, p.key, values);
      changed(p.key, t, ev);
    });
    row._applyRange = () => {};
    row._sync = () => {
      const v = getKey(state.scene, p.key);
      input.value = Array.isArray(v) ? v.join(', ') : '';
      input.placeholder = Array.isArray(v) ? '' : 'not set';
    };
    row._sync();
    return row;
  }

  function buildField(p) {
    if (p.list) return buildListField(p);
    const id = fieldId(p.key);
    const row = document.createElement('div');
    row.className = 'field';
    row.dataset.key = p.key;

    const head = document.createElement('div');
    head.className = 'field-head';
    const label = document.createElement('label');
    label.htmlFor = id + '-number';
    label.textContent = p.label;
    if (p.help) label.title = p.help;
    const entry = document.createElement('span');
    entry.className = 'entry';
    const number = document.createElement('input');
    number.type = 'number';
    number.id = id + '-number';
    number.inputMode = p.integer ? 'numeric' : 'decimal';
    if (Math.max(Math.abs(p.min), Math.abs(p.max)) >= 1e6) number.classList.add('wide');
    // The help (a tooltip for the mouse) is also a description a screen reader reads with
    // the field, shown under it while the field or its slider has the keyboard's focus; so
    // is the field's error when it has one.
    const described = [id + '-error'];
    let help = null;
    if (p.help) {
      help = document.createElement('span');
      help.className = 'field-help visually-hidden';
      help.id = id + '-help';
      help.textContent = p.help;
      described.push(help.id);
    }
    number.setAttribute('aria-describedby', described.join(' '));
    const unit = document.createElement('span');
    unit.className = 'unit';
    unit.textContent = prettyUnit(p.unit);
    entry.append(number, unit);
    head.append(label, entry);

    const slider = document.createElement('input');
    slider.type = 'range';
    slider.id = id + '-range';
    slider.setAttribute('aria-label', p.label + (p.unit ? ' (' + prettyUnit(p.unit) + ')' : ''));
    slider.setAttribute('aria-describedby', described.join(' '));

    const range = document.createElement('div');
    range.className = 'range';
    const lo = document.createElement('span');
    lo.className = 'bound';
    lo.setAttribute('aria-hidden', 'true');
    const hi = document.createElement('span');
    hi.className = 'bound bound-hi';
    hi.setAttribute('aria-hidden', 'true');
    range.append(lo, slider, hi);

    // The slider's range and step, and the number field's step (set again when a typed
    // value widens the range).
    const applyRange = () => {
      const r = rangeOf(p);
      slider.min = String(r.min);
      slider.max = String(r.max);
      slider.step = String(r.step > 0 ? r.step : (r.max - r.min) / 200);
      number.step = p.integer && r.step > 0 ? String(r.step) : 'any';
      lo.textContent = compact(r.min);
      hi.textContent = compact(r.max);
    };
    applyRange();

    // Announced when it appears (a polite live region); empty, it takes no room.
    const error = document.createElement('p');
    error.className = 'field-error';
    error.id = id + '-error';
    error.setAttribute('aria-live', 'polite');

    row.append(head, range);
    if (help) row.append(help);

    let infinite = null;
    if (mayBeInfinite(p)) {
      const box = document.createElement('label');
      box.className = 'infinite';
      infinite = document.createElement('input');
      infinite.type = 'checkbox';
      infinite.id = id + '-inf';
      infinite.setAttribute('aria-label', p.label + ': infinite');
      box.append(infinite, document.createTextNode(' ∞'));
      box.title = 'Infinite (' + p.label + ' left out of the scene)';
      range.append(box);
      infinite.addEventListener('change', (ev) => {
        const t = eventTime(ev);
        if (infinite.checked) deleteKey(state.scene, p.key);
        else setKey(state.scene, p.key, Number(slider.value));
        syncField(p);
        changed(p.key, t, ev);
      });
    }
    row.append(error);

    slider.addEventListener('pointerdown', () => startSweep(p.key));
    // Only a key that moves the slider charts it: Tab through the form must not start (and
    // abort) a sweep per slider, each a run of analyses on the server (slow with crushing).
    slider.addEventListener('keydown', (ev) => {
      if (SLIDER_KEYS.has(ev.key)) startSweep(p.key);
    });
    slider.addEventListener('input', (ev) => {
      const t = eventTime(ev);
      const v = Number(slider.value);
      number.value = slider.value;
      number.placeholder = '';
      row.classList.remove('unset');
      setKey(state.scene, p.key, v);
      changed(p.key, t, ev);
    });
    number.addEventListener('change', (ev) => {
      const t = eventTime(ev);
      const text = number.value.trim();
      const v = Number(text);
      if (text === '' || !Number.isFinite(v)) {
        showFieldError(p.key, 'Enter a number' + (p.unit ? ' in ' + prettyUnit(p.unit) : '') + '.');
        return;
      }
      // A value beyond the slider's range widens it, so that the slider holds the value
      // and its next step starts from there (not from the end it was clamped to).
      const r = rangeOf(p);
      if (v < r.min || v > r.max) {
        const step = r.step > 0 ? r.step : 0;
        const out = (x, round) => (step ? onGrid(round(x / step), step) : x);
        // The widening the server accepted before, to go back to if it refuses this one.
        const before = state.widened.get(p.key);
        state.widened.set(p.key, {
          min: Math.min(r.min, out(v, Math.floor)), max: Math.max(r.max, out(v, Math.ceil)),
          value: v, confirmed: false,
          previous: before && (before.confirmed ? before : before.previous),
        });
        applyRange();
      }
      slider.value = String(v);
      row.classList.remove('unset');
      setKey(state.scene, p.key, v);
      changed(p.key, t, ev);
    });

    row._applyRange = applyRange;
    row._sync = () => {
      const v = shownValue(p);
      const inf = isInfinite(v);
      // A slider whose key the scene does not have sits where it may, faded.
      row.classList.toggle('unset', v === undefined);
      if (infinite) infinite.checked = inf;
      number.disabled = inf;
      slider.disabled = inf;
      if (inf) {
        number.value = '';
        number.placeholder = '∞';
        slider.value = slider.max;
      } else if (v === undefined) {
        // Not in the scene and no meaning for leaving it out: nothing to show.
        number.value = '';
        number.placeholder = 'not set';
      } else {
        number.placeholder = '';
        number.value = String(v);
        slider.value = String(v);
      }
    };
    row._sync();
    return row;
  }

  function fieldRow(key) {
    for (const row of $('v-params').querySelectorAll('.field')) {
      if (row.dataset.key === key) return row;
    }
    return null;
  }

  function syncField(p) {
    const row = fieldRow(p.key);
    if (row) row._sync();
  }

  function syncAll() {
    for (const row of $('v-params').querySelectorAll('.field')) row._sync();
  }

  // When an event happened, on performance.now()'s clock (Event.timeStamp is on it too and
  // includes any wait before the handler ran).
  function eventTime(ev) {
    const now = performance.now();
    return ev && ev.timeStamp > 0 && ev.timeStamp <= now ? ev.timeStamp : now;
  }

  // ---- errors -------------------------------------------------------------------------------

  function clearErrors() {
    for (const row of $('v-params').querySelectorAll('.field.has-error')) {
      row.classList.remove('has-error');
      row.querySelector('.field-error').textContent = '';
    }
    showMessage(null);
  }

  function showFieldError(key, message) {
    const row = key ? fieldRow(key) : null;
    if (!row) return false;
    row.classList.add('has-error');
    row.querySelector('.field-error').textContent = message;
    return true;
  }

  function showMessage(message) {
    const box = $('v-message');
    box.hidden = !message;
    box.textContent = message || '';
  }

  function showError(err, sent) {
    // An earthquake direction means nothing for live loads (the server refuses "left" there):
    // a preset of live loads opened while "left" was pressed goes on to the right.
    if (err.kind === 'not_for_action' && state.direction === 'left') {
      setDirection('right');
      return;
    }
    clearErrors();
    // A slider widened to a typed value the server refuses goes back to its range.
    const wide = err.key ? state.widened.get(err.key) : undefined;
    if (wide && !wide.confirmed && sent && getKey(sent, err.key) === wide.value) {
      if (wide.previous) state.widened.set(err.key, wide.previous);
      else state.widened.delete(err.key);
      const row = fieldRow(err.key);
      if (row) {
        row._applyRange();
        row._sync();
      }
    }
    const text = err.error || 'The server refused the scene.';
    if (!showFieldError(err.key, text)) {
      showMessage(err.key && !text.includes(err.key) ? text + ' (' + err.key + ')' : text);
    }
    state.lastOk = false;
    document.body.classList.add('stale');
    $('v-note').textContent = 'The scene has an error: the last valid result is shown, dimmed.';
    setDownloads(false);
    announce('The scene has an error: ' + text);
  }

  // Screen readers hear the status and lambda (a polite live region apart from the
  // results), once the values have stopped changing: not at every step of a drag.
  let announceTimer = null;
  const ANNOUNCE_AFTER_MS = 700;
  function announce(text) {
    clearTimeout(announceTimer);
    announceTimer = setTimeout(() => {
      if (live.inFlight || live.dirty) return announce(text);
      $('v-announce').textContent = text;
    }, ANNOUNCE_AFTER_MS);
  }

  // ---- live analysis ------------------------------------------------------------------------

  function changed(key, eventTime) {
    state.lastKey = key;
    requestAnalysis(eventTime);
    startSweep(key);
  }

  function requestAnalysis(eventTime) {
    // The latency of an update counts from the first field event the drawing does not show
    // yet (eventTime is null for the first load, a preset or the direction: not timed).
    if (live.since === null && eventTime !== null) live.since = eventTime;
    live.dirty = true;
    pump();
  }

  // <body data-busy>: whether the drawing may still change (a request in flight or pending).
  function markBusy() {
    document.body.dataset.busy = String(live.inFlight || live.dirty);
  }

  async function pump() {
    markBusy();
    if (live.inFlight || !live.dirty) return;
    live.dirty = false;
    const since = live.since;
    live.since = null;
    live.inFlight = true;
    const sent = clone(state.scene);
    const body = JSON.stringify({ scene: sent, direction: state.direction });
    markBusy();
    let outcome;
    try {
      const response = await fetch('/api/analyze', {
        method: 'POST', headers: { 'content-type': 'application/json' }, body,
      });
      outcome = await readJson(response);
    } catch (e) {
      outcome = { ok: false, body: { error: 'The server did not answer (' + e.message + '). Is `voussoir serve` still running?', key: null } };
    }
    try {
      if (outcome.ok) render(outcome.body, since, sent);
      else showError(outcome.body, sent);
    } catch (e) {
      showMessage('The page could not show the answer: ' + e.message);
    } finally {
      // Whatever happened, the next scene goes out: the page never stops updating.
      live.inFlight = false;
      pump();
    }
  }

  async function readJson(response) {
    let body = null;
    try {
      body = await response.json();
    } catch (e) {
      body = null;
    }
    if (response.ok && body) return { ok: true, body };
    if (!body || typeof body !== 'object') {
      const what = response.status === 413
        ? 'The scene is larger than the server accepts (' + (state.limits.max_body_bytes || '?') + ' bytes).'
        : 'The server answered ' + response.status + ' ' + response.statusText + '.';
      body = { error: what, key: null };
    }
    return { ok: false, status: response.status, body };
  }

  function render(result, since, sent) {
    clearErrors();
    // A typed value that widened its slider stands: the range keeps it.
    for (const [key, wide] of state.widened) {
      if (sent && getKey(sent, key) === wide.value) wide.confirmed = true;
    }
    const drawing = $('v-drawing');
    const svg = parseSvg(result.svg);
    if (svg) drawing.replaceChildren(svg);
    else drawing.replaceChildren(placeholder('The server sent no drawing.'));
    state.last = result;
    state.lastScene = sent;
    state.lastOk = true;
    document.body.classList.remove('stale');
    showResult(result);
    setDownloads(true);
    // Lay the new drawing out before stopping the clock (painting follows within a frame).
    drawing.getBoundingClientRect();
    if (since !== null) {
      const ms = performance.now() - since;
      const timings = window.voussoirTimings;
      timings.push(ms);
      if (timings.length > TIMINGS_KEPT) timings.splice(0, timings.length - TIMINGS_KEPT);
      const server = typeof result.elapsed_ms === 'number' ? ' (server ' + result.elapsed_ms.toFixed(1) + ' ms)' : '';
      $('v-timing').textContent = 'updated in ' + ms.toFixed(0) + ' ms' + server;
    }
    drawChart();
    const nonAssociative = showsNonAssociative(result);
    announce((STATUS_WORDS[result.status] || String(result.status || '')) + ', lambda '
      + fmt(governing(result), 4)
      + (nonAssociative ? ', non-associative friction'
        : (result.friction_exact === false ? ', an upper bound (associative friction)' : '')));
  }

  // The multiplier that governs (analyze --json's lambda_governing; lambda_lower from an
  // older server).
  function governing(r) {
    return typeof r.lambda_governing === 'number' ? r.lambda_governing : r.lambda_lower;
  }

  // Whether the answer has a non-associative multiplier worth its own row: joints slide in
  // the static mechanism, or an exact value in a wall (friction_lower_states_possible).
  function showsNonAssociative(r) {
    return (r.friction_exact === false || r.friction_lower_states_possible === true)
      && typeof r.lambda_non_associative === 'number';
  }

  function parseSvg(text) {
    if (typeof text !== 'string' || text === '') return null;
    const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
    const root = doc.documentElement;
    if (!root || root.nodeName !== 'svg') return null;
    root.removeAttribute('width');
    root.removeAttribute('height');
    root.setAttribute('preserveAspectRatio', 'xMidYMid meet');
    root.setAttribute('role', 'img');
    const title = root.querySelector('title');
    if (title) root.setAttribute('aria-label', title.textContent);
    return document.importNode(root, true);
  }

  function placeholder(text) {
    const p = document.createElement('p');
    p.className = 'placeholder';
    p.textContent = text;
    return p;
  }

  function showResult(r) {
    const status = $('v-status');
    status.dataset.status = r.status || '';
    status.textContent = STATUS_WORDS[r.status] || String(r.status || '').replace(/_/g, ' ');
    // The large number is the governing multiplier: the non-associative one when it was
    // computed (joints that slide without opening), the static one otherwise.
    const big = governing(r);
    const lambda = $('v-lambda');
    lambda.textContent = fmt(big, 4);
    lambda.classList.toggle('none', typeof big !== 'number');
    lambda.dataset.value = big === null || big === undefined ? '' : String(big);
    // Live loads (an adequacy factor, docs/geometry.md) have no earthquake: its direction
    // and the vertical acceleration are hidden, as the server ignores or refuses them.
    const live = r.action === 'live';
    $('v-direction').closest('.direction').hidden = live;
    for (const group of $('v-params').querySelectorAll('fieldset[data-section="seismic"]')) {
      group.hidden = live;
    }
    const naRow = $('v-na-row');
    const na = showsNonAssociative(r);
    naRow.hidden = !na;
    $('v-na').textContent = na ? fmt(r.lambda_non_associative, 6) : '';
    naRow.title = na ? (r.non_associative_note || '') : '';
    // lambda_c is certified when the bounds meet; otherwise it lies between them.
    const apart = typeof r.lambda_upper === 'number' && typeof r.lambda_lower === 'number'
      && !(typeof r.gap === 'number' && r.gap < 1e-6);
    // With finite friction the static multiplier is exact only when no joint slides in its
    // mechanism; otherwise it is the associative one, an upper bound of the real collapse
    // (friction_exact false, friction_note in words).
    const associative = r.friction_exact === false;
    // Exact in a wall: a collapse state of real joints, not proved the lowest
    // (friction_lower_states_possible, docs/friction.md).
    const notLowest = !associative && r.friction_lower_states_possible === true;
    $('v-lambda-relation').textContent = (associative || notLowest) ? '≤' : (apart ? '≥' : '=');
    $('v-lower-name').textContent = associative ? 'upper bound'
      : (notLowest ? 'exact, not proved the lowest' : 'lower bound');
    const lowerHow = $('v-lower-how');
    lowerHow.textContent = associative ? 'associative friction' : 'static';
    lowerHow.title = associative ? (r.friction_note || '') : '';
    const caveat = $('v-friction');
    // The words are the server's (friction_note, friction_lower_states_note).
    caveat.textContent = associative ? (r.friction_note || '')
      : (notLowest ? (r.friction_lower_states_note || '') : '');
    caveat.hidden = !(associative || notLowest);
    $('v-lower').textContent = fmt(r.lambda_lower, 6);
    $('v-upper').textContent = fmt(r.lambda_upper, 6);
    // An upper bound from rigid hinges on a structure that crushes is the rigid structure's.
    const how = $('v-upper-how');
    how.textContent = r.upper_rigid ? 'rigid hinges' : 'kinematic';
    how.title = r.upper_rigid
      ? 'Found with hinges at the joints\' ends: it ignores the compressive strength, so it is the rigid structure\'s multiplier (an upper bound of this one\'s, not its collapse).'
      : '';
    let note = STATUS_NOTES[r.status] || '';
    if (r.status === 'collapse') {
      const hinges = Array.isArray(r.hinges) ? r.hinges.length : 0;
      const parts = [hinges + (hinges === 1 ? ' hinge' : ' hinges')];
      if (Array.isArray(r.sliding) && r.sliding.length) parts.push(r.sliding.length + ' sliding');
      if (typeof r.lambda_upper === 'number') {
        parts.push(typeof r.gap === 'number' && r.gap < 1e-6
          ? 'bounds agree'
          : 'gap ' + (100 * (r.gap || 0)).toPrecision(2) + ' %' + (r.sliding_governs ? ' (sliding governs)' : ''));
        if (r.upper_rigid) parts.push('upper bound ignores crushing');
      }
      note = parts.join(' · ');
    }
    $('v-note').textContent = note;
  }

  // ---- downloads ----------------------------------------------------------------------------

  function setDownloads(enabled) {
    for (const id of ['v-dl-toml', 'v-dl-svg', 'v-dl-json', 'v-dl-report']) $(id).disabled = !enabled;
  }

  function baseName() {
    // Named after what was analysed (the last answer), not the fields (which may be ahead).
    const read = (state.last && state.last.scene) || {};
    const name = state.preset || (state.initial && state.initial.origin
      ? state.initial.origin.split(/[\\/]/).pop().replace(/\.toml$/i, '') : 'scene');
    const t = typeof read.thickness === 'number' ? '-t' + read.thickness : '';
    // The TOML holds no direction (its first line says it): the name tells it too.
    const left = state.last && state.last.direction === 'left' ? '-left' : '';
    return (name || 'scene').replace(/[^A-Za-z0-9_.-]+/g, '_') + t + left;
  }

  function download(text, type, filename) {
    const url = URL.createObjectURL(new Blob([text], { type }));
    const a = document.createElement('a');
    a.href = url;
    a.download = filename;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
  }

  // The hand-in report (POST /api/report, what `voussoir report` writes) of the scene last
  // analysed: several analyses on the server, so the button says it is busy meanwhile.
  async function downloadReport() {
    if (!state.last) return;
    const button = $('v-dl-report');
    const name = baseName();
    const body = JSON.stringify({ scene: clone(state.lastScene || state.scene) });
    button.disabled = true;
    button.classList.add('busy');
    try {
      const outcome = await readJson(await fetch('/api/report', {
        method: 'POST', headers: { 'content-type': 'application/json' }, body,
      }));
      if (outcome.ok) download(outcome.body.html, 'text/html', name + '-report.html');
      else showMessage('No report: ' + outcome.body.error);
    } catch (e) {
      showMessage('No report: the server did not answer (' + e.message + ')');
    } finally {
      button.classList.remove('busy');
      button.disabled = !state.last;
    }
  }

  function analysisJson(r) {
    // What `voussoir analyze --json` prints: the answer without the page's extra fields.
    const copy = {};
    for (const [k, v] of Object.entries(r)) {
      if (k !== 'svg' && k !== 'toml' && k !== 'elapsed_ms' && k !== 'upper_rigid') copy[k] = v;
    }
    return JSON.stringify(copy, null, 2) + '\n';
  }

  // ---- sweep chart --------------------------------------------------------------------------

  function sweepSignature(key) {
    const rest = clone(state.scene);
    deleteKey(rest, key);
    const p = state.byKey.get(key);
    const r = p ? rangeOf(p) : {};
    return [key, r.min, r.max, state.direction, JSON.stringify(rest)].join('|');
  }

  async function startSweep(key) {
    const p = state.byKey.get(key);
    if (!p) return;
    // A list (a stepped pier's widths) has no chart: the parameter charted is charted again
    // for the changed scene (or the first one there is).
    if (p.list) {
      const other = chart.key && chart.key !== key && fieldRow(chart.key) ? chart.key : null;
      if (other) startSweep(other);
      else if (!chart.key) firstSweep();
      return;
    }
    // The same sweep is not asked twice (the signature leaves out the charted key's own
    // value); a sweep that failed leaves no signature, so the next event tries again.
    const sig = sweepSignature(key);
    if (chart.sig === sig) return;
    if (chart.controller) chart.controller.abort();
    const controller = new AbortController();
    chart.controller = controller;
    chart.sig = sig;
    chart.key = key;
    chart.rows = null;
    chart.error = null;
    document.body.dataset.sweeping = 'true';
    const maxPoints = state.limits.max_sweep_points || SWEEP_POINTS;
    let points = Math.min(SWEEP_POINTS, maxPoints);
    const { min, max, step } = rangeOf(p);
    let to = max;
    if (p.integer && step > 1) {
      // Only the step's multiples are valid (even voussoir counts for a pointed arch): the
      // points are a whole number of steps apart, the last at or below the range's end.
      const steps = Math.round((max - min) / step);
      const every = Math.max(1, Math.ceil(steps / Math.max(1, points - 1)));
      points = Math.max(2, Math.floor(steps / every) + 1);
      to = Math.min(max, min + (points - 1) * every * step);
    } else if (p.integer) {
      points = Math.max(2, Math.min(points, Math.floor(max - min) + 1));
    }
    const body = {
      scene: state.scene, key, from: min, to, points, direction: state.direction,
    };
    drawChart();
    try {
      const response = await fetch('/api/sweep', {
        method: 'POST', headers: { 'content-type': 'application/json' },
        body: JSON.stringify(body), signal: controller.signal,
      });
      const outcome = await readJson(response);
      if (chart.controller !== controller) return;
      if (outcome.ok) chart.rows = outcome.body.rows || [];
      else {
        chart.error = outcome.body.error || 'The sweep failed.';
        chart.sig = null;
      }
    } catch (e) {
      if (e.name === 'AbortError' || chart.controller !== controller) return;
      chart.error = 'The sweep failed (' + e.message + ').';
      chart.sig = null;
    }
    chart.controller = null;
    document.body.dataset.sweeping = 'false';
    drawChart();
  }

  // No chart: no parameter moved yet that the page shows (a scene of user blocks has no
  // thickness to chart).
  function resetChart() {
    if (chart.controller) chart.controller.abort();
    Object.assign(chart, { sig: null, key: null, rows: null, controller: null, error: null });
    document.body.dataset.sweeping = 'false';
    $('v-chart-title').textContent = 'λ against a parameter';
    $('v-chart').replaceChildren(placeholder('Move a slider to chart λ over its range.'));
    for (const row of $('v-params').querySelectorAll('.field.charted')) row.classList.remove('charted');
  }

  // The first chart: of the parameter moved last, else the thickness, if the page shows it.
  function firstSweep() {
    const key = [state.lastKey, 'arch.thickness'].find((k) => k && state.byKey.has(k)
      && !state.byKey.get(k).list && fieldRow(k));
    if (key) startSweep(key);
    else resetChart();
  }

  const SVG_NS = 'http://www.w3.org/2000/svg';
  function el(name, attrs, text) {
    const e = document.createElementNS(SVG_NS, name);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, String(v));
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function drawChart() {
    const box = $('v-chart');
    const p = chart.key ? state.byKey.get(chart.key) : null;
    if (!p) return;
    $('v-chart-title').textContent = 'λ against ' + p.label.charAt(0).toLowerCase() + p.label.slice(1);
    for (const row of $('v-params').querySelectorAll('.field')) {
      row.classList.toggle('charted', row.dataset.key === chart.key);
    }
    if (chart.error) {
      box.replaceChildren(placeholder(chart.error));
      return;
    }
    const range = rangeOf(p);
    // Large values in a prefixed unit (MPa for a strength in Pa): short, legible labels.
    const su = scaledUnit(p.unit, Math.max(Math.abs(range.min), Math.abs(range.max)));
    const span = scaledValue(range.min, { factor: su.factor, unit: '' }) + '–' + scaledValue(range.max, su);
    if (!chart.rows) {
      box.replaceChildren(placeholder('Computing λ over ' + span + '…'));
      return;
    }
    const usable = chart.rows.filter((r) => !r.error);
    if (usable.length === 0) {
      const first = chart.rows.find((r) => r.error);
      box.replaceChildren(placeholder('No value of ' + p.label + ' in ' + span
        + ' could be analysed' + (first ? ': ' + first.error : '.')));
      return;
    }
    const W = 300, H = 184, L = 46, R = 10, T = 12, B = 34;
    const xs = [range.min, range.max];
    const x = (v) => L + (v - xs[0]) / (xs[1] - xs[0] || 1) * (W - L - R);
    const finite = (v) => typeof v === 'number' && Number.isFinite(v);
    const current = getKey(state.scene, p.key);
    const currentLambda = state.lastOk && state.last ? state.last.lambda_lower : null;
    let ymax = 0;
    for (const r of chart.rows) {
      if (finite(r.lambda_lower)) ymax = Math.max(ymax, r.lambda_lower);
      if (finite(r.lambda_upper)) ymax = Math.max(ymax, r.lambda_upper);
    }
    if (finite(currentLambda)) ymax = Math.max(ymax, currentLambda);
    const yTicks = niceTicks(0, ymax > 0 ? ymax : 1, 5);
    // Headroom: the top gridline is at or above the highest point.
    if (yTicks.length > 1 && yTicks[yTicks.length - 1] < ymax) {
      yTicks.push(yTicks[yTicks.length - 1] + (yTicks[1] - yTicks[0]));
    }
    const ytop = Math.max(yTicks[yTicks.length - 1], ymax > 0 ? ymax : 1);
    const y = (v) => T + (1 - v / ytop) * (H - T - B);

    const svg = el('svg', { viewBox: `0 0 ${W} ${H}`, class: 'chart-svg', role: 'img',
      'aria-label': 'λ against ' + p.label });
    // Bands where the structure cannot stand (red) or stands at any λ (green).
    const step = chart.rows.length > 1 ? Math.abs(chart.rows[1].value - chart.rows[0].value) : 0;
    for (const r of chart.rows) {
      if (r.status !== 'cannot_stand' && r.status !== 'no_collapse') continue;
      const x0 = Math.max(L, x(r.value - step / 2));
      const x1 = Math.min(W - R, x(r.value + step / 2));
      svg.append(el('rect', { x: x0, y: T, width: Math.max(0.5, x1 - x0), height: H - T - B,
        class: r.status === 'cannot_stand' ? 'band-fail' : 'band-stands' }));
    }
    for (const v of yTicks) {
      svg.append(el('line', { x1: L, x2: W - R, y1: y(v), y2: y(v), class: 'grid' }));
      svg.append(el('text', { x: L - 5, y: y(v) + 3.5, class: 'tick', 'text-anchor': 'end' }, tickLabel(v, yTicks)));
    }
    const xTicks = fittingTicks(xs[0] / su.factor, xs[1] / su.factor, W - L - R);
    for (const v of xTicks) {
      const at = x(v * su.factor);
      svg.append(el('line', { x1: at, x2: at, y1: H - B, y2: H - B + 4, class: 'axis' }));
      svg.append(el('text', { x: at, y: H - B + 14, class: 'tick', 'text-anchor': 'middle' }, tickLabel(v, xTicks)));
    }
    svg.append(el('line', { x1: L, x2: W - R, y1: H - B, y2: H - B, class: 'axis' }));
    svg.append(el('line', { x1: L, x2: L, y1: T, y2: H - B, class: 'axis' }));
    svg.append(el('text', { x: (L + W - R) / 2, y: H - 4, class: 'axis-label', 'text-anchor': 'middle' },
      p.label + (su.unit ? ' (' + prettyUnit(su.unit) + ')' : '')));
    svg.append(el('text', { x: 8, y: (T + H - B) / 2 + 4, class: 'axis-label lambda-axis', 'text-anchor': 'middle' }, 'λ'));

    // One polyline per run of rows with a multiplier (rows that failed are skipped; rows
    // without a multiplier break the line).
    const line = (field, cls, include = () => true) => {
      let run = [];
      const flush = () => {
        if (run.length > 1) svg.append(el('polyline', { points: run.join(' '), class: cls }));
        else if (run.length === 1) {
          const [px, py] = run[0].split(',');
          svg.append(el('circle', { cx: px, cy: py, r: 1.5, class: cls + '-dot' }));
        }
        run = [];
      };
      for (const r of chart.rows) {
        if (r.error) continue;
        if (!include(r)) flush();
        else if (finite(r[field])) run.push(x(r.value).toFixed(2) + ',' + y(r[field]).toFixed(2));
        else flush();
      }
      flush();
    };
    // The upper bound, dashed where it differs from the lower one. Where it comes from a
    // search with rigid hinges on a structure that crushes (`upper_rigid`: the certified
    // mechanism about the compressed zones did not apply, e.g. joints that slide), it is the
    // rigid structure's multiplier, not this one's: dotted and named for what it is.
    const apart = (r) => finite(r.lambda_upper) && finite(r.lambda_lower)
      && Math.abs(r.lambda_upper - r.lambda_lower) > 1e-6 * Math.max(1, r.lambda_lower);
    const differs = chart.rows.some((r) => !r.upper_rigid && apart(r));
    const rigid = chart.rows.some((r) => r.upper_rigid && apart(r));
    if (differs) line('lambda_upper', 'series-upper', (r) => !r.upper_rigid);
    if (rigid) line('lambda_upper', 'series-upper-rigid', (r) => !!r.upper_rigid);
    line('lambda_lower', 'series');

    if (typeof current === 'number' && current >= xs[0] && current <= xs[1]) {
      svg.append(el('line', { x1: x(current), x2: x(current), y1: T, y2: H - B, class: 'marker-line' }));
      if (finite(currentLambda)) {
        svg.append(el('circle', { cx: x(current), cy: y(currentLambda), r: 4, class: 'marker' }));
      }
    }
    const failed = chart.rows.filter((r) => r.error).length;
    const nodes = [svg];
    const legend = document.createElement('p');
    legend.className = 'chart-legend';
    const bits = [];
    if (typeof current === 'number' && finite(currentLambda)) {
      bits.push('at ' + scaledValue(current, su) + ': λ = ' + currentLambda.toFixed(4));
    }
    // Where joints slide at collapse the static line is the associative multiplier, an upper
    // bound of the real collapse (friction_exact false, docs/friction.md).
    if (chart.rows.some((r) => r.friction_exact === false)) {
      bits.push('solid: static, associative friction (an upper bound where joints slide)');
    } else if (differs || rigid) bits.push('solid: lower bound');
    if (differs) bits.push('dashed: upper bound');
    if (rigid) bits.push('dotted: upper bound with rigid hinges (ignores crushing)');
    if (chart.rows.some((r) => r.status === 'cannot_stand')) bits.push('red: cannot stand');
    if (chart.rows.some((r) => r.status === 'no_collapse')) bits.push('green: stands at any λ');
    if (failed) bits.push(failed + ' of ' + chart.rows.length + ' values refused');
    if (bits.length) {
      legend.textContent = bits.join(' · ');
      nodes.push(legend);
    }
    box.replaceChildren(...nodes);
  }

  // ---- shape picker and direction -----------------------------------------------------------

  function buildShapePicker() {
    const box = $('v-shapes');
    box.replaceChildren();
    const add = (name, label, title) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.dataset.preset = name;
      b.textContent = label;
      if (title) b.title = title;
      b.addEventListener('click', () => pickPreset(name));
      box.append(b);
    };
    const origin = state.initial.origin || '';
    const file = /\.toml$/i.test(origin) ? origin.split(/[\\/]/).pop() : '';
    add('', file || 'Start scene', origin ? 'The scene voussoir serve was started with: ' + origin : 'The scene voussoir serve was started with');
    // The buttons carry the preset's name in words ("loaded_portal": "Loaded portal"); its
    // label is the tooltip.
    for (const s of state.shapes) {
      const word = s.name.replace(/_/g, ' ');
      add(s.name, word.charAt(0).toUpperCase() + word.slice(1), s.label || '');
    }
    markPreset();
  }

  function markPreset() {
    for (const b of $('v-shapes').querySelectorAll('button')) {
      const on = (b.dataset.preset || null) === state.preset;
      b.setAttribute('aria-pressed', on ? 'true' : 'false');
    }
  }

  function pickPreset(name) {
    const preset = state.shapes.find((s) => s.name === name);
    state.preset = preset ? name : null;
    state.scene = clone(preset ? preset.scene : state.initial.scene);
    state.widened.clear();
    markPreset();
    buildForm();
    $('v-dl-report').addEventListener('click', downloadReport);
    requestAnalysis(null);
    firstSweep();
  }

  function setDirection(direction) {
    state.direction = direction;
    for (const b of $('v-direction').querySelectorAll('button')) {
      b.setAttribute('aria-pressed', b.dataset.direction === direction ? 'true' : 'false');
    }
    requestAnalysis(null);
    if (chart.key && fieldRow(chart.key)) startSweep(chart.key);
  }

  // ---- start --------------------------------------------------------------------------------

  async function start() {
    let params, scene;
    try {
      const [a, b] = await Promise.all([fetch('/api/parameters'), fetch('/api/scene')]);
      params = await readJson(a);
      scene = await readJson(b);
    } catch (e) {
      showMessage('Could not reach the server: ' + e.message);
      return;
    }
    if (!params.ok || !scene.ok) {
      showMessage((params.ok ? scene : params).body.error || 'The server refused the page\'s first request.');
      return;
    }
    state.parameters = params.body.parameters || [];
    state.byKey = new Map(state.parameters.map((p) => [p.key, p]));
    state.shapes = params.body.shapes || [];
    state.limits = params.body.limits || {};
    state.initial = { scene: scene.body.scene, origin: scene.body.origin || '' };
    state.scene = clone(scene.body.scene);
    const same = canonical(state.initial.scene);
    const twin = state.shapes.find((s) => canonical(s.scene) === same);
    state.startPreset = twin ? twin.name : null;
    buildShapePicker();
    buildForm();
    for (const b of $('v-direction').querySelectorAll('button')) {
      b.addEventListener('click', () => setDirection(b.dataset.direction));
    }
    $('v-dl-toml').addEventListener('click', () => {
      if (state.last) download(state.last.toml, 'application/toml', baseName() + '.toml');
    });
    $('v-dl-svg').addEventListener('click', () => {
      if (state.last) download(state.last.svg, 'image/svg+xml', baseName() + '.svg');
    });
    $('v-dl-json').addEventListener('click', () => {
      if (state.last) download(analysisJson(state.last), 'application/json', baseName() + '.json');
    });
    requestAnalysis(null);
    firstSweep();
  }

  // Exposed for the end-to-end tests and the curious: the scene being edited.
  window.voussoir = { state, syncAll };
  start();
})();
