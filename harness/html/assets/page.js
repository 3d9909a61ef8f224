// Shared by the report page's scripts: the data (window.SYMEMBED_REPORT from data.js), element
// and number helpers, links, and sortable tables. Exposed as window.SymembedPage; the pages
// (experiment.js, pairs.js) add themselves to it and report.js routes between them.
'use strict';

window.SymembedPage = (function () {
  const R = window.SYMEMBED_REPORT;


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

  // Appends children to the page (#app), skipping null ones (DOM append would show "null").
  function show(...children) {
    document.getElementById('app').append(...children.filter((c) => c !== null && c !== undefined));
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

  return {
    R, h, isNumber, fmt, fmtInt, hashParams, pairHash, pairsHash, show, variantByName,
    rotationName, section, sortableTable,
  };
})();
