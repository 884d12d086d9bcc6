// The reports' interactive charts (and the live page's, drawn by `window.elastokinDrawChart`): each <figure class="chart"> carries its chart as JSON (data-chart),
// drawn here with uPlot (inlined before this script) in place of the SVG drawn for it, which stays for
// scripts off and for print. The pointer reads every curve's value out in the legend; a click on a legend
// entry shows or hides its curve; dragging zooms, a double click zooms back out.
(function () {
  'use strict';
  const state = { charts: 0, drawn: 0, errors: [] };
  const plots = [];
  const fmt = (v) => (v == null || !isFinite(v) ? '–' : Number(v.toPrecision(4)).toString());

  // One x for all curves: the union of their points' x, each curve null where it has no point.
  function aligned(chart) {
    const curves = chart.axes.flatMap((axis, a) => axis.series.map((s) => ({ s, a })));
    const keep = (x) => isFinite(x) && (!chart.x_log || x > 0);
    // Every curve on the same increasing x (most charts, and the live page's previous design's): that x.
    const first = curves.length ? curves[0].s.x : [];
    const same = (x) => x === first || (x.length === first.length && x.every((v, i) => v === first[i]));
    if (curves.every(({ s }) => same(s.x)) && first.every((x, i) => keep(x) && (i === 0 || x > first[i - 1]))) {
      return { curves, data: [first, ...curves.map(({ s }) => first.map((x, i) => (isFinite(s.y[i]) ? s.y[i] : null)))] };
    }
    const xs = Array.from(new Set(curves.flatMap(({ s }) => s.x.filter(keep)))).sort((p, q) => p - q);
    const at = new Map(xs.map((x, i) => [x, i]));
    const ys = curves.map(({ s }) => {
      const y = new Array(xs.length).fill(null);
      s.x.forEach((x, i) => {
        if (at.has(x) && isFinite(s.y[i])) y[at.get(x)] = s.y[i];
      });
      return y;
    });
    return { curves, data: [xs, ...ys] };
  }

  // What a chart draws besides its numbers and its design's mark: a chart of the same shape takes new ones
  // in place.
  const shapeOf = (chart) =>
    JSON.stringify([
      chart.title,
      chart.x_label,
      chart.x_log,
      chart.axes.map((axis) => [
        axis.label,
        axis.log,
        axis.series.map((s) => [s.name, s.colour, s.dash, s.width, s.x.length <= 20]),
      ]),
    ]);

  function draw(figure) {
    const chart = JSON.parse(figure.getAttribute('data-chart'));
    const { curves, data } = aligned(chart);
    const shape = shapeOf(chart);
    const font = '13px system-ui, sans-serif';
    const labelFont = '14px system-ui, sans-serif';
    const scale = (a) => (a === 0 ? 'y' : 'y2');
    const axes = [{ label: chart.x_label, font, labelFont, labelSize: 22, values: (u, v) => v.map(fmt) }];
    chart.axes.forEach((axis, a) =>
      axes.push({
        scale: scale(a),
        side: a === 0 ? 3 : 1,
        label: axis.label,
        font,
        labelFont,
        labelSize: 22,
        size: 64,
        values: (u, v) => v.map(fmt),
        grid: { show: a === 0 },
      })
    );
    const scales = { x: { time: false, distr: chart.x_log ? 3 : 1 } };
    chart.axes.forEach((axis, a) => (scales[scale(a)] = { distr: axis.log ? 3 : 1 }));
    const series = [{ label: chart.x_label, value: (u, v) => fmt(v) }].concat(
      curves.map(({ s, a }) => ({
        label: chart.axes.length > 1 && a > 0 ? s.name + ' (right axis)' : s.name,
        scale: scale(a),
        stroke: s.colour,
        width: s.width || 2,
        // A right-axis curve is dashed, as in the SVG: a left one under it shows between the dashes. A
        // curve may say its own (the live page's previous design).
        dash: s.dash || (a === 0 ? undefined : [9, 6]),
        points: { show: s.x.length <= 20 },
        spanGaps: true,
        value: (u, v) => fmt(v),
      }))
    );
    // The design's mark, where the chart shown last says (a new design may move it).
    let marked = chart.design_x;
    const marker = (u) => {
      if (marked == null) return;
      const x = u.valToPos(marked, 'x', true);
      const ctx = u.ctx;
      ctx.save();
      ctx.setLineDash([6, 4]);
      ctx.strokeStyle = '#606060';
      ctx.lineWidth = devicePixelRatio;
      ctx.beginPath();
      ctx.moveTo(x, u.bbox.top);
      ctx.lineTo(x, u.bbox.top + u.bbox.height);
      ctx.stroke();
      ctx.restore();
    };
    const size = () => {
      const width = Math.max(280, figure.clientWidth - 2);
      return { width, height: Math.round(0.62 * width) };
    };
    const holder = document.createElement('div');
    holder.className = 'live-chart';
    figure.appendChild(holder);
    const opts = Object.assign(size(), {
      title: chart.title,
      scales,
      axes,
      series,
      cursor: { drag: { x: true, y: true, uni: 40 } },
      legend: { live: true },
      hooks: { draw: [marker] },
    });
    const plot = new uPlot(opts, data, holder);
    // The live page's next design: its numbers drawn in this chart when its shape is this one's (true),
    // else nothing done (false: the chart must be drawn anew).
    plot.elastokinShow = (next) => {
      if (shapeOf(next) !== shape) return false;
      marked = next.design_x;
      plot.setData(aligned(next).data);
      return true;
    };
    figure.classList.add('live');
    if (typeof ResizeObserver === 'function') {
      // Sized by the figure's width alone: its height follows the legend, which every new set of numbers
      // may change.
      let width = null;
      new ResizeObserver((entries) => {
        const seen = entries[entries.length - 1].contentRect.width;
        if (seen !== width) {
          width = seen;
          plot.setSize(size());
        }
      }).observe(figure);
    }
    return plot;
  }

  function drawAll() {
    const figures = document.querySelectorAll('figure.chart[data-chart]');
    state.charts = figures.length;
    figures.forEach((figure) => {
      try {
        plots.push(draw(figure));
        state.drawn += 1;
      } catch (e) {
        state.errors.push((figure.id || 'chart') + ': ' + e);
      }
    });
    window.elastokinCharts = plots;
    const out = document.getElementById('charts-state');
    if (out) out.textContent = JSON.stringify(state);
  }

  // The live page draws its charts as the design changes.
  window.elastokinDrawChart = draw;

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', drawAll);
  else drawAll();
})();
