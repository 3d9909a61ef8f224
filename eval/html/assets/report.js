// The report page: routes on the location hash between the experiment page (#), a variant's
// pair table (#pairs=VARIANT&class=C&flipped=1&sort=-mean_direct) and a pair view
// (#pair=VARIANT/SOURCE/TARGET, each part URI-encoded). Everything comes from data.js
// (window.SYMEMBED_REPORT, written by `symembed report`) and, for the pair view, from the side
// files shapes/*.js and pairs/*.js, loaded on demand through <script> because a page opened
// from file:// may not fetch() local files.
'use strict';

(function () {
  const R = window.SYMEMBED_REPORT;
  let app = null;  // #app, once the document is parsed (this script runs in <head>)

  // ---------------------------------------------------------------- small helpers

  // h('td', {class: 'num', title: 't'}, child, ...): an element; strings become text.
  function h(tag, attributes, ...children) {
    const e = document.createElement(tag);
    for (const [name, value] of Object.entries(attributes || {})) {
      if (value === undefined || value === null || value === false) continue;
      if (name.startsWith('on')) e.addEventListener(name.slice(2), value);
      else if (name === 'text') e.textContent = value;
      else e.setAttribute(name, value === true ? '' : value);
    }
    for (const child of children.flat()) {
      if (child === undefined || child === null || child === false) continue;
      e.appendChild(typeof child === 'string' || typeof child === 'number'
        ? document.createTextNode(String(child)) : child);
    }
    return e;
  }

  function isNumber(x) {
    return typeof x === 'number' && Number.isFinite(x);
  }

  // Three significant digits; integers of four or more digits in full; n/a for no number.
  function fmt(x) {
    if (!isNumber(x)) return 'n/a';
    if (x === 0) return '0';
    const a = Math.abs(x);
    if (a >= 1000) return String(Math.round(x));
    if (a < 0.001) return x.toExponential(2);
    return x.toPrecision(3);
  }

  function fmtInt(x) {
    return isNumber(x) ? String(Math.round(x)) : 'n/a';
  }

  function hashParams() {
    return new URLSearchParams(location.hash.replace(/^#/, ''));
  }

  function pairHash(variant, source, target) {
    return '#pair=' + [variant, source, target].map(encodeURIComponent).join('/');
  }

  function pairsHash(variant, extra) {
    const params = new URLSearchParams(extra || {});
    params.set('pairs', variant);
    return '#' + params.toString();
  }

  // Appends children to the page, skipping null ones (DOM append would show them as "null").
  function show(...children) {
    app.append(...children.filter((c) => c !== null && c !== undefined));
  }

  function variantByName(name) {
    return R.variants.find((v) => v.name === name);
  }

  function rotationName(index) {
    return isNumber(index) && index >= 0 && index < R.rotations.length ? R.rotations[index] : 'n/a';
  }

  function section(title, id, ...children) {
    return h('section', { id }, h('h2', {}, title), ...children);
  }

  // ---------------------------------------------------------------- sortable tables

  // columns: [{key, label, title, type: 'text' | 'num' | 'int', value(row), cell(row) -> node
  // or string, cls}]. options: {sort: {key, desc}, onSort(sort), rowAttributes(row), id}.
  function sortableTable(columns, rows, options) {
    options = options || {};
    let sort = options.sort || null;
    const table = h('table', { class: 'data', id: options.id });
    const thead = h('thead');
    const tbody = h('tbody');
    table.append(thead, tbody);
    const valueOf = (column, row) => (column.value ? column.value(row) : row[column.key]);

    function renderHead() {
      thead.textContent = '';
      const tr = h('tr');
      for (const column of columns) {
        const active = sort && sort.key === column.key;
        tr.appendChild(h('th', {
          title: column.title || 'sort by ' + column.label,
          class: (column.type === 'text' ? '' : 'num') + (active ? ' sorted' : ''),
          'data-key': column.key,
          onclick: () => {
            const numeric = column.type !== 'text';
            sort = active ? { key: column.key, desc: !sort.desc } : { key: column.key, desc: numeric };
            if (options.onSort) options.onSort(sort);
            render();
          },
        }, column.label, active ? (sort.desc ? ' \u25bc' : ' \u25b2') : ''));
      }
      thead.appendChild(tr);
    }

    function sortedRows() {
      if (!sort) return rows;
      const column = columns.find((c) => c.key === sort.key);
      if (!column) return rows;
      const sign = sort.desc ? -1 : 1;
      return rows.slice().sort((a, b) => {
        const x = valueOf(column, a), y = valueOf(column, b);
        const xMissing = x === null || x === undefined || (typeof x === 'number' && !isFinite(x));
        const yMissing = y === null || y === undefined || (typeof y === 'number' && !isFinite(y));
        if (xMissing || yMissing) return xMissing === yMissing ? 0 : xMissing ? 1 : -1;
        if (typeof x === 'number' && typeof y === 'number') return sign * (x - y);
        return sign * String(x).localeCompare(String(y), undefined, { numeric: true });
      });
    }

    function render() {
      renderHead();
      tbody.textContent = '';
      const fragment = document.createDocumentFragment();
      for (const row of sortedRows()) {
        const tr = h('tr', options.rowAttributes ? options.rowAttributes(row) : {});
        for (const column of columns) {
          const value = valueOf(column, row);
          let content;
          if (column.cell) content = column.cell(row);
          else if (column.type === 'text') content = value === null || value === undefined ? '' : String(value);
          else if (column.type === 'int') content = fmtInt(value);
          else content = fmt(value);
          tr.appendChild(h('td', {
            class: (column.type === 'text' ? '' : 'num') + (column.cls ? ' ' + column.cls : ''),
            'data-key': column.key,
            'data-value': isNumber(value) ? String(value) : undefined,
          }, content));
        }
        fragment.appendChild(tr);
      }
      tbody.appendChild(fragment);
    }

    render();
    return table;
  }

  // ---------------------------------------------------------------- experiment page

  const THRESHOLDS = ['0.05', '0.10', '0.25'];

  function summaryColumns() {
    const s = (path) => (v) => path.reduce((o, k) => (o === null || o === undefined ? o : o[k]), v.summary);
    const columns = [
      { key: 'variant', label: 'variant', type: 'text', value: (v) => v.name,
        cell: (v) => h('a', { href: pairsHash(v.name) }, v.name) },
      { key: 'pairs', label: 'pairs', type: 'int', value: s(['pairs']) },
      { key: 'failed_pairs', label: 'failed', type: 'int', value: s(['failed_pairs']) },
      { key: 'mean_direct', label: 'mean direct', title: 'mean geodesic error over all points of all pairs', value: s(['mean_direct']) },
      { key: 'median_direct', label: 'median direct', value: s(['median_direct']) },
      { key: 'mean_flip_tolerant', label: 'mean flip-tol.', title: 'per pair the lower of the direct and mirrored errors', value: s(['mean_flip_tolerant']) },
    ];
    for (const t of THRESHOLDS) {
      columns.push({ key: 'pct_direct_' + t, label: '% \u2264 ' + t + ' direct', value: s(['pct_direct', t]) });
    }
    for (const t of THRESHOLDS) {
      columns.push({ key: 'pct_flip_tolerant_' + t, label: '% \u2264 ' + t + ' flip-tol.', value: s(['pct_flip_tolerant', t]) });
    }
    columns.push(
      { key: 'auc_direct', label: 'AUC direct', value: s(['auc_direct']) },
      { key: 'auc_flip_tolerant', label: 'AUC flip-tol.', value: s(['auc_flip_tolerant']) },
      { key: 'flipped_left_right', label: 'flipped LR', type: 'int', value: s(['flipped_pairs', 'left_right']) },
      { key: 'flipped_front_back', label: 'flipped FB', type: 'int', value: s(['flipped_pairs', 'front_back']) },
      { key: 'flipped_up_down', label: 'flipped UD', type: 'int', value: s(['flipped_pairs', 'up_down']) },
      { key: 'flipped_total', label: 'flipped total', type: 'int', value: s(['flipped_pairs', 'total']) },
      { key: 'time_total_s', label: 'total s', value: s(['time_total_s']) },
      { key: 'time_per_shape_s', label: 's per shape', value: s(['time_per_shape_s']) },
      { key: 'time_per_pair_s', label: 's per pair', value: s(['time_per_pair_s']) },
      { key: 'peak_rss_mb', label: 'peak MB', title: 'peak resident memory', value: s(['peak_rss_mb']) });
    return columns;
  }

  function curvesSection() {
    const shown = new Set(R.variants.map((v) => v.name));
    const direct = h('canvas', { class: 'plot', id: 'curve-direct' });
    const tolerant = h('canvas', { class: 'plot', id: 'curve-flip-tolerant' });
    const maxError = (R.variants[0].summary && R.variants[0].summary.max_error) || 0.25;
    function redraw() {
      const series = (key) => R.variants
        .map((v, index) => ({ v, index }))
        .filter(({ v }) => shown.has(v.name))
        .map(({ v, index }) => ({ name: v.name, index, x: v.curve.threshold, y: v.curve[key] }));
      SymembedPlot.draw(direct, series('direct'), { title: 'direct', xMax: maxError });
      SymembedPlot.draw(tolerant, series('flip_tolerant'), { title: 'flip-tolerant', xMax: maxError });
    }
    const boxes = [];
    const legend = h('div', { class: 'legend' },
      h('button', { type: 'button', onclick: () => { R.variants.forEach((v) => shown.add(v.name)); boxes.forEach((b) => { b.checked = true; }); redraw(); } }, 'all'),
      h('button', { type: 'button', onclick: () => { shown.clear(); boxes.forEach((b) => { b.checked = false; }); redraw(); } }, 'none'),
      R.variants.map((v, index) => {
        const style = SymembedPlot.style(index);
        const box = h('input', { type: 'checkbox', checked: true, onchange: (e) => { if (e.target.checked) shown.add(v.name); else shown.delete(v.name); redraw(); } });
        boxes.push(box);
        return h('label', { class: 'swatch' }, box,
          h('span', { class: 'line', style: 'border-top: 3px ' + (style.dash.length ? 'dashed' : 'solid') + ' ' + style.colour }), v.name);
      }));
    requestAnimationFrame(redraw);
    window.addEventListener('resize', redraw);
    return section('Cumulative error curves', 'curves',
      h('p', { class: 'note' }, 'Percentage of ground-truth points whose geodesic error is at most the threshold (pooled over all pairs). Tick a variant to show or hide it.'),
      h('div', { class: 'plots' }, direct, tolerant), legend);
  }

  // Per-class rows of a variant: pairs, means of pair means, flips, wrong rotations.
  function classStats(variant) {
    const stats = new Map();
    for (const p of variant.pairs) {
      const c = p['class'];
      if (!stats.has(c)) {
        stats.set(c, { pairs: 0, ok: 0, direct: 0, tolerant: 0, left_right: 0, front_back: 0, up_down: 0, wrong: 0 });
      }
      const s = stats.get(c);
      s.pairs += 1;
      if (p.status !== 'ok') continue;
      s.ok += 1;
      s.direct += p.mean_direct;
      s.tolerant += p.mean_flip_tolerant;
      if (p.flip in s) s[p.flip] += 1;
      if (isNumber(p.chosen) && isNumber(p.oracle) && p.chosen >= 0 && p.oracle >= 0 && p.chosen !== p.oracle) s.wrong += 1;
    }
    return stats;
  }

  function allClasses() {
    const classes = new Set();
    for (const v of R.variants) for (const p of v.pairs) classes.add(p['class']);
    return Array.from(classes).sort();
  }

  const CLASS_MEASURES = {
    'mean direct (mean of pair means)': (s) => (s.ok ? s.direct / s.ok : null),
    'mean flip-tolerant (mean of pair means)': (s) => (s.ok ? s.tolerant / s.ok : null),
    'pairs whose rotation is not the oracle\'s': (s) => s.wrong,
    'pairs': (s) => s.pairs,
  };

  function classSection() {
    const classes = allClasses();
    const stats = R.variants.map(classStats);
    const holder = h('div');
    const select = h('select', { id: 'class-measure', onchange: () => draw() },
      Object.keys(CLASS_MEASURES).map((name) => h('option', { value: name }, name)));
    function draw() {
      const measure = CLASS_MEASURES[select.value];
      const integer = select.value.startsWith('pairs');
      const columns = [{ key: 'variant', label: 'variant', type: 'text', value: (r) => r.name,
        cell: (r) => h('a', { href: pairsHash(r.name) }, r.name) }];
      for (const c of classes) {
        columns.push({ key: 'class:' + c, label: c, type: integer ? 'int' : 'num',
          value: (r) => (r.stats.has(c) ? measure(r.stats.get(c)) : null),
          cell: (r) => (r.stats.has(c)
            ? h('a', { href: pairsHash(r.name, { 'class': c }) }, integer ? fmtInt(measure(r.stats.get(c))) : fmt(measure(r.stats.get(c))))
            : '') });
      }
      holder.textContent = '';
      holder.appendChild(sortableTable(columns, R.variants.map((v, i) => ({ name: v.name, stats: stats[i] })), { id: 'class-table' }));
    }
    draw();
    return section('Per class', 'classes', h('p', { class: 'note' }, 'Class of a pair: its source shape\'s class in the dataset. Measure: ', select), holder);
  }

  function flipSection() {
    const classes = allClasses();
    const stats = R.variants.map(classStats);
    const columns = [{ key: 'variant', label: 'variant', type: 'text', value: (r) => r.name }];
    for (const c of classes) {
      columns.push({ key: 'flip:' + c, label: c, type: 'int',
        value: (r) => { const s = r.stats.get(c); return s ? s.left_right + s.front_back + s.up_down : null; },
        cell: (r) => {
          const s = r.stats.get(c);
          if (!s) return '';
          const total = s.left_right + s.front_back + s.up_down;
          const text = total === 0 ? '0' : total + ' (' + s.left_right + '/' + s.front_back + '/' + s.up_down + ')';
          return total === 0 ? text : h('a', { href: pairsHash(r.name, { 'class': c, flipped: '1' }) }, text);
        } });
    }
    return section('Flipped pairs by class', 'flips',
      h('p', { class: 'note' }, 'Flipped pairs, in brackets left-right / front-back / up-down. Front-back and up-down: the chosen rotation is not the oracle\'s; left-right: the mirrored ground truth fits better.'),
      sortableTable(columns, R.variants.map((v, i) => ({ name: v.name, stats: stats[i] })), { id: 'flip-table' }));
  }

  // One table per kind (shape, pair): mean seconds per stage and variant, from timings.csv.
  function stageTable(kind) {
    const names = new Set();
    for (const v of R.variants) for (const name of Object.keys((v.stage_seconds || {})[kind] || {})) names.add(name);
    const columns = [{ key: 'variant', label: 'variant', type: 'text', value: (v) => v.name }];
    for (const name of names) {
      columns.push({ key: name, label: name, title: 'mean seconds per ' + kind,
        value: (v) => ((v.stage_seconds || {})[kind] || {})[name] });
    }
    return [h('h3', {}, 'Seconds per ' + kind), sortableTable(columns, R.variants, { id: kind + '-stage-table' })];
  }

  function stageSection() {
    return section('Time per stage', 'stages',
      h('p', { class: 'note' }, 'Mean wall seconds of each stage per shape and per pair, from timings.csv. A stage read from the cache reports the time it took when it was computed.'),
      stageTable('shape'), stageTable('pair'));
  }

  function configSection() {
    return section('Variants and their configuration', 'configs',
      h('p', { class: 'note' }, 'Each variant\'s resolved config.yaml (every option with its default) and where it differs from ' + R.variants[0].name + '\'s.'),
      R.variants.map((v) => h('details', { class: 'config' },
        h('summary', {}, v.name, ' ',
          h('span', { class: 'note' }, v.config_changes ? (v.config_changes.length + ' setting(s) differ') : (v.config === null ? 'no config.yaml (a symembed eval folder)' : ''))),
        v.config_changes && v.config_changes.length ? h('ul', {}, v.config_changes.map((c) => h('li', {}, h('code', {}, c)))) : null,
        v.views_note ? h('p', { class: 'warning' }, 'No 3D views: ' + v.views_note) : null,
        v.config !== null ? h('pre', {}, v.config) : null)));
  }

  function provenance() {
    const base = R.variants[0].summary || {};
    return h('div', { class: 'provenance' },
      R.description ? h('p', {}, R.description) : null,
      h('p', {}, 'Results folder: ', h('code', {}, R.results_dir)),
      h('p', {}, 'Evaluation: geodesics ', h('code', {}, String(base.evaluation_geodesics)), ', points ',
        h('code', {}, String(base.evaluation_points)), ', curve up to ', h('code', {}, String(base.max_error)), '.'),
      h('p', { class: 'note' }, 'Code version and machine: not recorded in the results folder (summary.json and config.yaml do not carry them).'),
      R.warnings && R.warnings.length
        ? h('details', { class: 'warning' }, h('summary', {}, R.warnings.length + ' warning(s) while writing the report'),
          h('ul', {}, R.warnings.map((w) => h('li', {}, w))))
        : null);
  }

  function experimentPage() {
    document.getElementById('crumbs').textContent = '';
    show(
      provenance(),
      section('Summary', 'summary',
        h('p', { class: 'note' }, 'The columns of comparison.csv, three significant digits. Click a header to sort, a variant to see its pairs.'),
        sortableTable(summaryColumns(), R.variants, { id: 'summary-table' })),
      curvesSection(),
      classSection(),
      flipSection(),
      stageSection(),
      configSection());
  }

  // ---------------------------------------------------------------- pair table

  function stageNames(variant) {
    const names = new Set();
    for (const p of variant.pairs) for (const name of Object.keys(p.seconds || {})) names.add(name);
    return Array.from(names);
  }

  function pairColumns(variant) {
    const columns = [
      { key: 'source', label: 'source', type: 'text' },
      { key: 'target', label: 'target', type: 'text' },
      { key: 'class', label: 'class', type: 'text' },
      { key: 'status', label: 'status', type: 'text' },
      { key: 'mean_direct', label: 'mean direct' },
      { key: 'median_direct', label: 'median' },
      { key: 'max_direct', label: 'max' },
      { key: 'mean_flip_tolerant', label: 'flip-tol.' },
      { key: 'mean_sym', label: 'vs mirrored', title: 'mean error against the mirrored ground truth' },
      { key: 'flip', label: 'flip', type: 'text' },
      { key: 'chosen', label: 'chosen', type: 'text', value: (p) => p.chosen, cell: (p) => rotationName(p.chosen) },
      { key: 'oracle', label: 'oracle', type: 'text', value: (p) => p.oracle, cell: (p) => rotationName(p.oracle) },
    ];
    if (variant.pairs.some((p) => isNumber(p.initial_mean_direct))) {
      columns.push({ key: 'initial_mean_direct', label: 'before refine' },
        { key: 'refine_side', label: 'refine side', type: 'text' });
    }
    for (const name of stageNames(variant)) {
      columns.push({ key: 's:' + name, label: name + ' s', title: 'seconds of stage ' + name, value: (p) => (p.seconds || {})[name] });
    }
    columns.unshift({ key: 'view', label: 'view', type: 'text', value: (p) => (p.view ? 0 : 1),
      cell: (p) => (p.view ? h('a', { href: pairHash(variant.name, p.source, p.target) }, 'view')
        : h('span', { class: 'note', title: p.unavailable || p.message || '' }, p.status !== 'ok' ? 'failed' : 'unavailable')) });
    return columns;
  }

  function filteredPairs(variant, params) {
    const cls = params.get('class') || '';
    const flipped = params.get('flipped') === '1';
    const wrong = params.get('wrong') === '1';
    const failed = params.get('failed') === '1';
    return variant.pairs.filter((p) =>
      (!cls || p['class'] === cls) &&
      (!flipped || (p.status === 'ok' && p.flip !== 'none')) &&
      (!wrong || (p.chosen >= 0 && p.oracle >= 0 && p.chosen !== p.oracle)) &&
      (!failed || p.status !== 'ok'));
  }

  function pairTablePage(params) {
    const variant = variantByName(params.get('pairs')) || R.variants[0];
    document.getElementById('crumbs').textContent = '\u203a pairs of ' + variant.name;
    const update = (changes) => {
      const next = new URLSearchParams(params);
      for (const [k, v] of Object.entries(changes)) {
        if (v === '' || v === false) next.delete(k); else next.set(k, v === true ? '1' : v);
      }
      location.hash = next.toString();
    };
    const sortText = params.get('sort') || '-mean_direct';
    const sort = { key: sortText.replace(/^-/, ''), desc: sortText.startsWith('-') };
    const rows = filteredPairs(variant, params);
    const classes = Array.from(new Set(variant.pairs.map((p) => p['class']))).sort();
    const checkbox = (name, label) => h('label', {},
      h('input', { type: 'checkbox', id: 'filter-' + name, checked: params.get(name) === '1', onchange: (e) => update({ [name]: e.target.checked }) }), ' ' + label);
    show(
      h('h2', {}, 'Pairs of ', variant.name),
      h('div', { class: 'filters' },
        h('label', {}, 'variant ', h('select', { id: 'filter-variant', onchange: (e) => update({ pairs: e.target.value }) },
          R.variants.map((v) => h('option', { value: v.name, selected: v.name === variant.name }, v.name)))),
        h('label', {}, ' class ', h('select', { id: 'filter-class', onchange: (e) => update({ 'class': e.target.value }) },
          h('option', { value: '' }, 'all'),
          classes.map((c) => h('option', { value: c, selected: c === params.get('class') }, c)))),
        checkbox('flipped', 'flipped only'), checkbox('wrong', 'rotation not the oracle\'s'), checkbox('failed', 'failed only'),
        h('button', { type: 'button', onclick: () => update({ sort: '-mean_direct' }) }, 'worst first'),
        h('span', { id: 'pair-count', class: 'note' }, ' ' + rows.length + ' of ' + variant.pairs.length + ' pairs')),
      variant.views_note ? h('p', { class: 'warning' }, 'No 3D views for this variant: ' + variant.views_note) : null,
      sortableTable(pairColumns(variant), rows, {
        id: 'pair-table',
        sort,
        onSort: (s) => {
          const next = new URLSearchParams(params);
          next.set('sort', (s.desc ? '-' : '') + s.key);
          history.replaceState(null, '', '#' + next.toString());
        },
        rowAttributes: (p) => ({ class: p.status !== 'ok' ? 'failed' : p.flip !== 'none' ? 'flipped' : '', title: p.message || p.unavailable || undefined }),
      }));
  }

  // ---------------------------------------------------------------- side files

  const sideData = new Map();
  const loading = new Map();
  window.symembedData = function (kind, key, payload) {
    sideData.set(kind + ':' + key, payload);
  };

  function loadSide(kind, key, file) {
    const id = kind + ':' + key;
    if (sideData.has(id)) return Promise.resolve(sideData.get(id));
    if (loading.has(id)) return loading.get(id);
    const promise = new Promise((resolve, reject) => {
      const script = document.createElement('script');
      script.src = file.split('/').map(encodeURIComponent).join('/');
      script.onload = () => (sideData.has(id) ? resolve(sideData.get(id))
        : reject(new Error(file + ' did not register ' + id)));
      script.onerror = () => reject(new Error('cannot load ' + file + ' (was the report folder moved or cut short?)'));
      document.head.appendChild(script);
    }).finally(() => loading.delete(id));
    loading.set(id, promise);
    return promise;
  }

  async function inflate(bytes) {
    if (typeof DecompressionStream === 'undefined') {
      throw new Error('this browser has no DecompressionStream, which reading the side files needs; use a current Chrome, Firefox or Safari');
    }
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    return new Uint8Array(await new Response(stream).arrayBuffer());
  }

  const ARRAY_TYPES = { u8: Uint8Array, u16: Uint16Array, u32: Uint32Array };

  // An encoded array of eval/html/side_files.h as its raw typed array (shift not applied).
  async function decodeRaw(encoded, what) {
    const Type = ARRAY_TYPES[encoded.type];
    if (!Type) throw new Error(what + ': unknown array type ' + encoded.type);
    const text = atob(encoded.zlib);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    const raw = await inflate(bytes);
    if (raw.byteLength !== encoded.count * Type.BYTES_PER_ELEMENT) {
      throw new Error(what + ': ' + raw.byteLength + ' bytes, expected ' + encoded.count * Type.BYTES_PER_ELEMENT);
    }
    return new Type(raw.buffer, raw.byteOffset, encoded.count);
  }

  async function decodeIds(encoded, what) {
    const raw = await decodeRaw(encoded, what);
    const ids = new Int32Array(raw.length);
    const shift = encoded.shift || 0;
    for (let i = 0; i < raw.length; ++i) ids[i] = raw[i] - shift;
    return ids;
  }

  async function decodePositions(encoded, what) {
    const q = await decodeRaw(encoded, what);
    const positions = new Float32Array(q.length);
    for (let i = 0; i < q.length; ++i) {
      const k = i % 3;
      positions[i] = encoded.lo[k] + (q[i] / 65535) * (encoded.hi[k] - encoded.lo[k]);
    }
    return positions;
  }

  // Unit values: [0, 1] fractions of "max", -1 for unknown.
  async function decodeUnit(encoded, what) {
    const q = await decodeRaw(encoded, what);
    const values = new Float32Array(q.length);
    for (let i = 0; i < q.length; ++i) values[i] = q[i] === 255 ? -1 : q[i] / 254;
    return values;
  }

  const shapes = new Map();  // name -> Promise of the decoded shape

  function shapeData(name) {
    if (shapes.has(name)) return shapes.get(name);
    const promise = (async () => {
      const info = R.shapes[name];
      if (!info) throw new Error('shape ' + name + ' is not in this report');
      if (info.unavailable) throw new Error('shape ' + name + ': ' + info.unavailable);
      const p = await loadSide('shape', name, info.file);
      const what = info.file;
      const shape = {
        name,
        vertices: p.vertices,
        positions: await decodePositions(p.positions, what + ' positions'),
        faces: await decodeIds(p.faces, what + ' faces'),
        gt: p.gt ? await decodeIds(p.gt, what + ' gt') : null,
        gtSym: p.gt_sym ? await decodeIds(p.gt_sym, what + ' gt_sym') : null,
        gtNote: p.gt_note || null,
      };
      shape.graph = SymembedTransfer.adjacency(shape.vertices, shape.faces);
      sideData.delete('shape:' + name);  // the decoded arrays replace the text
      return shape;
    })();
    promise.catch(() => shapes.delete(name));
    shapes.set(name, promise);
    return promise;
  }

  // The pair's map and errors; the map's coding needs both meshes (S, T from shapeData).
  async function pairData(key, S, T) {
    const view = { key, file: 'pairs/' + key + '.js' };
    const p = await loadSide('pair', view.key, view.file);
    if (p.map.coding !== 'ranks') throw new Error(view.file + ': unknown map coding ' + p.map.coding);
    const ranks = await decodeRaw(p.map.ranks, view.file + ' map ranks');
    const ids = await decodeIds(p.map.ids, view.file + ' map ids');
    sideData.delete('pair:' + view.key);
    return {
      map: SymembedTransfer.decodeVertexMap(ranks, ids, S, T),
      errors: p.errors ? await decodeUnit(p.errors, view.file + ' errors') : null,
      errorMax: p.errors ? p.errors.max : null,
      errorsNote: p.errors_note || null,
    };
  }

  // ---------------------------------------------------------------- pair view

  let viewer = null;
  let viewerCanvas = null;
  let viewToken = 0;

  function theViewer() {
    if (!viewer) {
      viewerCanvas = h('canvas', { id: 'viewer-canvas' });
      viewer = { canvas: viewerCanvas, instance: null };
    }
    return viewer;
  }

  function candidateTable(pair) {
    const errors = Array.isArray(pair.candidate_errors) ? pair.candidate_errors : [];
    if (errors.length === 0) return h('p', { class: 'note' }, 'The candidates\' errors were not measured (no ground truth for this pair).');
    return h('table', { class: 'data compact', id: 'candidate-table' },
      h('thead', {}, h('tr', {}, h('th', {}, 'rotation of the target'), h('th', { class: 'num' }, 'mean error (oracle)'), h('th', {}, ''))),
      h('tbody', {}, errors.map((e, i) => h('tr', { class: i === pair.chosen ? 'chosen' : '' },
        h('td', {}, rotationName(i)), h('td', { class: 'num' }, fmt(e)),
        h('td', {}, [i === pair.chosen ? 'chosen' : '', i === pair.oracle ? 'oracle' : ''].filter(Boolean).join(', '))))));
  }

  // The flip scorer's message, split at "; " so that each term is on its own line.
  function messageBlock(title, message) {
    if (!message) return null;
    return h('div', { class: 'message' }, h('h3', {}, title), h('pre', {}, message.split(/;\s+/).join(';\n')));
  }

  function pairViewPage(parts) {
    const [variantName, source, target] = parts;
    const variant = variantByName(variantName);
    if (!variant) throw new Error('no variant ' + variantName + ' in this report');
    const index = variant.pairs.findIndex((p) => p.source === source && p.target === target);
    if (index < 0) throw new Error('no pair ' + source + ' -> ' + target + ' in variant ' + variantName);
    const pair = variant.pairs[index];
    const prev = variant.pairs[index - 1], next = variant.pairs[index + 1];
    const crumbs = document.getElementById('crumbs');
    crumbs.textContent = '';
    crumbs.append('\u203a ', h('a', { href: pairsHash(variant.name) }, 'pairs of ' + variant.name), ' \u203a ' + source + ' \u2192 ' + target);
    const facts = [
      ['class', pair['class']], ['status', pair.status], ['mean direct', fmt(pair.mean_direct)],
      ['median direct', fmt(pair.median_direct)], ['mean flip-tolerant', fmt(pair.mean_flip_tolerant)],
      ['vs mirrored ground truth', fmt(pair.mean_sym)], ['flip class', pair.flip],
      ['chosen rotation', rotationName(pair.chosen)], ['oracle rotation', rotationName(pair.oracle)],
    ];
    if (isNumber(pair.initial_mean_direct)) facts.push(['before refinement', fmt(pair.initial_mean_direct)], ['refine side', pair.refine_side]);
    for (const [stage, seconds] of Object.entries(pair.seconds || {})) facts.push([stage + ' s', fmt(seconds)]);
    const status = h('p', { id: 'view-status', class: 'note' }, 'loading the meshes and the map\u2026');
    const stage = h('div', { class: 'viewer' });
    const presets = h('select', { id: 'view-preset', onchange: (e) => { if (viewer.instance) viewer.instance.resetView(e.target.value); } },
      SymembedViewer.presets.map((p) => h('option', { value: p }, p)));
    show(
      h('h2', {}, variant.name, ': ', source, ' \u2192 ', target),
      h('div', { class: 'pair-nav' },
        prev ? h('a', { href: pairHash(variant.name, prev.source, prev.target) }, '\u2190 ' + prev.source + ' \u2192 ' + prev.target) : '',
        ' ', next ? h('a', { href: pairHash(variant.name, next.source, next.target) }, next.source + ' \u2192 ' + next.target + ' \u2192') : ''),
      h('div', { class: 'pair-layout' },
        h('div', { class: 'pair-3d' }, stage,
          h('div', { class: 'viewer-controls' }, 'Drag to orbit (all panels together), wheel to zoom, double-click to reset. Up axis: ', presets),
          status,
          h('div', { class: 'heat-legend', id: 'heat-legend' })),
        h('div', { class: 'pair-facts' },
          h('table', { class: 'facts', id: 'pair-facts' }, h('tbody', {}, facts.map(([k, v]) => h('tr', {}, h('th', {}, k), h('td', {}, String(v)))))),
          h('h3', {}, 'Candidate rotations'), candidateTable(pair),
          messageBlock('Flip scorer', (pair.flip_message || '')),
          messageBlock('Refinement', pair.refine_message || ''),
          pair.message ? messageBlock('Failure', pair.message) : null,
          h('h3', {}, 'Symmetry plane and canonical axes'),
          h('p', { class: 'note', id: 'frame-note' }, 'Not kept by the run: the results folder records no per-shape symmetry plane or canonical frame (only their measures in shapes.csv), so none is drawn.'))));
    if (pair.status !== 'ok') {
      status.textContent = 'This pair failed, so it has no map: ' + (pair.message || '');
      return;
    }
    if (!pair.view) {
      status.textContent = 'No 3D view: ' + (pair.unavailable || 'its data could not be built');
      status.className = 'warning';
      return;
    }
    drawPair(pair, stage, status).catch((error) => {
      status.textContent = 'The 3D view could not be drawn: ' + (error.message || error);
      status.className = 'warning';
      console.error('pair view: ' + (error.message || error));
    });
  }

  async function drawPair(pair, stage, status) {
    const token = ++viewToken;
    const v = theViewer();
    const labels = ['source ' + pair.source + ': smooth colouring', 'target ' + pair.target + ': colours through the map',
      'source: error per ground-truth point', 'target: colours through the ground truth'];
    stage.append(v.canvas, h('div', { class: 'panel-labels' }, labels.map((l, i) => h('span', { id: 'panel-label-' + i }, l))));
    const [S, T] = await Promise.all([shapeData(pair.source), shapeData(pair.target)]);
    const P = await pairData(pair.view, S, T);
    if (token !== viewToken) return;
    if (!v.instance) v.instance = new SymembedViewer.Viewer(v.canvas, 4, 2);
    const viewerInstance = v.instance;
    const notes = [];
    const sourceColours = SymembedTransfer.smoothColours(S.positions);
    if (P.map.length !== S.vertices) throw new Error('pairs/' + pair.view + '.js: ' + P.map.length + ' map entries, the source has ' + S.vertices + ' vertices');
    const identity = new Int32Array(S.vertices);
    for (let i = 0; i < identity.length; ++i) identity[i] = i;
    const mapped = SymembedTransfer.carry(sourceColours, identity, P.map, T.vertices, T.graph);
    notes.push('the map reaches ' + (100 * mapped.reached / T.vertices).toFixed(1) + '% of the target\'s vertices (the rest take the nearest reached vertex\'s colour)');
    const grey = (n) => new Float32Array(3 * n).fill(0.75);
    let heat = grey(S.vertices), truth = grey(T.vertices);
    const legend = document.getElementById('heat-legend');
    if (S.gt && T.gt) {
      const lines = SymembedTransfer.pairLines(S.gt, T.gt, T.gtSym);
      truth = SymembedTransfer.carry(sourceColours, lines.sources, lines.targets, T.vertices, T.graph).values;
      if (P.errors && P.errors.length === lines.sources.length) {
        const spread = SymembedTransfer.spread(S.vertices, S.graph, lines.sources, P.errors, 1);
        heat = SymembedTransfer.heatColours(spread.values);
        if (legend) {
          legend.append('error 0 ', h('span', { class: 'ramp' }), ' ' + fmt(P.errorMax) + ' and above',
            spread.filled ? ' (' + spread.filled + ' vertices without a ground-truth point take the nearest one\'s error)' : '');
        }
      } else {
        notes.push(P.errorsNote || ('the pair file has ' + (P.errors ? P.errors.length : 0) + ' errors for ' + lines.sources.length + ' ground-truth lines: no heat map'));
        document.getElementById('panel-label-2').textContent = 'source: no per-point errors';
      }
    } else {
      notes.push('no ground truth for this pair' + (S.gtNote || T.gtNote ? ' (' + (S.gtNote || T.gtNote) + ')' : ''));
      document.getElementById('panel-label-2').textContent = 'source: no ground truth';
      document.getElementById('panel-label-3').textContent = 'target: no ground truth';
    }
    viewerInstance.setMesh(0, S.positions, S.faces, sourceColours);
    viewerInstance.setMesh(1, T.positions, T.faces, mapped.values);
    viewerInstance.setMesh(2, S.positions, S.faces, heat);
    viewerInstance.setMesh(3, T.positions, T.faces, truth);
    viewerInstance.resetView(document.getElementById('view-preset').value);
    await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
    if (token !== viewToken) return;
    // A checksum of the decoded map, which the browser test compares with the map file.
    let checksum = 0;
    for (let i = 0; i < P.map.length; ++i) checksum = (checksum + (i + 1) * (P.map[i] + 1)) % 1000000007;
    status.dataset.mapChecksum = String(checksum);
    status.textContent = 'Drawn: ' + viewerInstance.trianglesDrawn + ' triangles in 4 panels; ' + notes.join('; ') + '.';
    status.dataset.state = 'drawn';
  }

  // ---------------------------------------------------------------- routing

  function route() {
    app.textContent = '';
    window.scrollTo(0, 0);
    const params = hashParams();
    try {
      if (params.has('pair')) {
        const parts = location.hash.replace(/^#pair=/, '').split('/').map(decodeURIComponent);
        if (parts.length !== 3) throw new Error('a pair link is #pair=VARIANT/SOURCE/TARGET');
        pairViewPage(parts);
      } else if (params.has('pairs')) {
        pairTablePage(params);
      } else {
        experimentPage();
      }
    } catch (error) {
      show(h('p', { class: 'warning' }, String(error.message || error)));
      throw error;
    }
  }

  // data.js keeps each variant's pairs as {columns, rows}; the page works on row objects.
  function expandPairs() {
    for (const v of R.variants) {
      if (Array.isArray(v.pairs)) continue;
      const { columns, rows } = v.pairs;
      v.pairs = rows.map((row) => {
        const pair = {};
        columns.forEach((c, i) => { pair[c] = row[i]; });
        return pair;
      });
    }
  }

  function start() {
    app = document.getElementById('app');
    if (!R) {
      app.textContent = 'data.js did not load: this page must stay beside the files symembed report wrote.';
      throw new Error('data.js did not define SYMEMBED_REPORT');
    }
    expandPairs();
    document.getElementById('title').textContent = R.title;
    document.title = R.title + ' \u2013 symembed report';
    window.addEventListener('hashchange', route);
    route();
  }

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
  else start();
})();
