// The report's pair pages: a variant's pair table (sort, filters) and the pair view (the four
// linked 3D panels of viewer.js coloured by transfer.js, the candidate rotations and the flip
// scorer's message).
'use strict';

(function () {
  const {
    R, h, isNumber, fmt, pairHash, pairsHash, show, variantByName, rotationName, sortableTable
  } = window.SymembedPage;
  const { shapeData, pairData } = window.SymembedSideFiles;

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
    if (errors.length === 0) {
      return h('p', { class: 'note' }, 'Not recorded for this pair: a run records the oracle\'s error of each candidate when the dataset has ground truth; symembed eval scores maps only.');
    }
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
    // A variant with its own meshes under the shapes' names names them by their ids.
    const [S, T] = await Promise.all(
        [shapeData(pair.source_shape || pair.source), shapeData(pair.target_shape || pair.target)]);
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

  window.SymembedPage.pairTablePage = pairTablePage;
  window.SymembedPage.pairViewPage = pairViewPage;
})();
