// The report page's entry point: routes on the location hash between the experiment page
// (#, experiment.js), a variant's pair table (#pairs=VARIANT&class=C&flipped=1&sort=-mean_direct)
// and a pair view (#pair=VARIANT/SOURCE/TARGET, each part URI-encoded; pairs.js). Everything
// comes from data.js (window.SYMEMBED_REPORT, written by `symembed report`) and, for the pair
// view, from the side files (sidefiles.js).
'use strict';

(function () {
  const { R, h, hashParams, show, experimentPage, pairTablePage, pairViewPage } = window.SymembedPage;

  function route() {
    document.getElementById('app').textContent = '';
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
    if (!R) {
      document.getElementById('app').textContent = 'data.js did not load: this page must stay beside the files symembed report wrote.';
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
