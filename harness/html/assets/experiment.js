// The experiment page of the report: summary table, curves, per-class, flipped-by-class and
// per-stage tables, and each variant's configuration.
'use strict';

(function () {
  const {
    R, h, isNumber, fmt, fmtInt, pairsHash, show, section, sortableTable
  } = window.SymembedPage;

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

  window.SymembedPage.experimentPage = experimentPage;
})();
