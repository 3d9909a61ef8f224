// Cumulative error curves drawn on a <canvas>: x is the error threshold (0 .. max error), y the
// percentage of ground-truth points whose error is at most x.
'use strict';

window.SymembedPlot = (function () {
  // Ten distinguishable colours; variants past ten reuse them with a dash pattern.
  const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2',
    '#17becf', '#7f7f7f', '#bcbd22'];
  const DASHES = [[], [6, 3], [2, 3], [8, 3, 2, 3]];

  function style(index) {
    return {
      colour: COLOURS[index % COLOURS.length],
      dash: DASHES[Math.floor(index / COLOURS.length) % DASHES.length],
    };
  }

  // Fits the canvas's backing store to its CSS size and the device pixel ratio.
  function fit(canvas) {
    const ratio = window.devicePixelRatio || 1;
    const width = canvas.clientWidth || 400;
    const height = canvas.clientHeight || 300;
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
    const context = canvas.getContext('2d');
    context.setTransform(ratio, 0, 0, ratio, 0, 0);
    return { context, width, height };
  }

  // series: [{name, x: [...], y: [... fractions 0..1], index}]; options: {title, xMax}.
  function draw(canvas, series, options) {
    const { context: g, width, height } = fit(canvas);
    const margin = { left: 46, right: 16, top: 24, bottom: 34 };
    const w = width - margin.left - margin.right;
    const h = height - margin.top - margin.bottom;
    const xMax = options.xMax > 0 ? options.xMax : 0.25;
    const px = (x) => margin.left + (Math.min(x, xMax) / xMax) * w;
    const py = (y) => margin.top + (1 - y) * h;
    g.clearRect(0, 0, width, height);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, width, height);
    g.font = '12px sans-serif';
    g.fillStyle = '#222';
    g.textAlign = 'center';
    g.fillText(options.title || '', margin.left + w / 2, 15);

    g.strokeStyle = '#e4e4e4';
    g.lineWidth = 1;
    g.textAlign = 'center';
    g.textBaseline = 'top';
    const xStep = xMax / 5;
    for (let k = 0; k <= 5; ++k) {
      const x = px(k * xStep);
      g.beginPath();
      g.moveTo(x, margin.top);
      g.lineTo(x, margin.top + h);
      g.stroke();
      g.fillText((k * xStep).toFixed(xMax < 0.5 ? 2 : 1), x, margin.top + h + 4);
    }
    g.fillText('geodesic error', margin.left + w / 2, margin.top + h + 18);
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    for (let k = 0; k <= 5; ++k) {
      const y = py(k / 5);
      g.beginPath();
      g.moveTo(margin.left, y);
      g.lineTo(margin.left + w, y);
      g.stroke();
      g.fillText((k * 20) + '%', margin.left - 4, y);
    }
    g.strokeStyle = '#888';
    g.strokeRect(margin.left, margin.top, w, h);

    g.lineWidth = 1.6;
    for (const s of series) {
      const { colour, dash } = style(s.index);
      g.strokeStyle = colour;
      g.setLineDash(dash);
      g.beginPath();
      let started = false;
      for (let i = 0; i < s.x.length; ++i) {
        if (s.x[i] === null || s.y[i] === null) continue;
        const x = px(s.x[i]);
        const y = py(s.y[i]);
        if (started) g.lineTo(x, y); else g.moveTo(x, y);
        started = true;
      }
      g.stroke();
    }
    g.setLineDash([]);
  }

  return { draw, style };
})();
