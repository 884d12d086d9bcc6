// `elastokin live`'s page: the design asked of the server (the page's address ends in its token, so the
// routes are relative), its figures, hardpoints, rates, projections, 3D view and charts shown; a hardpoint
// typed in millimetres, or dragged in a projection (src/live_views.js), sent as an edit in metres, and the
// answer shown with the previous design's curves in grey beneath. A refused edit shows the server's reason
// and leaves the design on screen. What the page did is kept as JSON in <output id="live-state"> for the
// browser test.
(function () {
  'use strict';
  const el = (id) => document.getElementById(id);
  const report = { version: 0, estimated: 0, figures: 0, charts: 0, drawn: 0, ghosts: 0, inputs: 0, projections: 0, guided: 0, edits: 0, refused: 0, errors: [] };
  let current = null;
  let previous = null;
  let busy = false;
  // The hardpoint whose guidance is shown, and the guidance (of the design of its version).
  let selected = null;
  let guidance = null;
  // The figure the projections' arrows are drawn for ('analysis/key').
  let chosen = null;

  function publish() {
    el('live-state').textContent = JSON.stringify(report);
  }

  const put = window.elastokinPut;

  function make(tag, text, className) {
    const e = document.createElement(tag);
    if (text != null) e.textContent = text;
    if (className) e.className = className;
    return e;
  }

  // A figure as written: its SI value times the factor to its unit, at its decimals.
  function written(f) {
    if (f.value == null) return 'n/a';
    const v = f.value * f.factor;
    const s = v.toFixed(f.decimals);
    return (Number(s) === 0 ? (0).toFixed(f.decimals) : s) + (f.unit === '-' ? '' : ' ' + f.unit);
  }

  // Millimetres typed as metres, without the binary rounding of the division showing (39.4 mm is 0.0394).
  function metres(typed) {
    const mm = Number(typed);
    return isFinite(mm) && typed.trim() !== '' ? Number((mm / 1000).toPrecision(15)) : NaN;
  }

  function millimetres(m) {
    return String(Number((m * 1000).toPrecision(12)));
  }

  function figureOf(state, analysis, key) {
    if (!state) return null;
    const a = state.analyses.find((x) => x.name === analysis);
    return a ? a.figures.find((f) => f.key === key) : null;
  }

  // `build` run on a state only when `rowsOf` it differs from those of the state it last built: a table
  // rebuilt lays the page out anew, so the tables below are built when their rows change and else filled
  // in place.
  function builtOnChange(rowsOf, build) {
    let built = null;
    return (state) => {
      const rows = JSON.stringify(rowsOf(state));
      if (rows !== built) {
        build(state);
        built = rows;
      }
    };
  }

  // The figures of each design, a table an analysis, a row a figure.
  let figureCells = new Map();
  const figureTables = builtOnChange(
    (state) => state.analyses.map((a) => [a.name, a.description, a.figures.map((f) => [f.key, f.label])]),
    buildFigures
  );
  function showFigures(state) {
    figureTables(state);
    let count = 0;
    state.analyses.forEach((a) =>
      a.figures.forEach((f) => {
        fillFigure(figureCells.get(a.name + '/' + f.key), a, f, state);
        count += 1;
      })
    );
    report.figures = count;
  }

  function buildFigures(state) {
    const holder = el('figures');
    holder.replaceChildren(make('h2', 'Figures'));
    figureCells = new Map();
    state.analyses.forEach((a) => {
      const table = make('table', null, 'figures');
      table.appendChild(make('caption', a.description));
      const head = make('tr');
      ['figure', 'value', 'before', 'target', 'per mm of the point selected (x, y, z)'].forEach((h) =>
        head.appendChild(make('th', h))
      );
      table.appendChild(make('thead')).appendChild(head);
      const body = table.appendChild(make('tbody'));
      a.figures.forEach((f) => {
        const row = make('tr');
        row.dataset.key = a.name + '/' + f.key;
        row.title = 'click to draw the arrows at the point selected for this figure';
        row.addEventListener('click', () => choose(row.dataset.key));
        row.appendChild(make('td', f.label));
        const cells = { row, value: make('td', null, 'value'), before: make('td', null, 'quiet'), target: make('td') };
        row.appendChild(cells.value);
        row.appendChild(cells.before);
        row.appendChild(cells.target);
        row.appendChild(make('td', '', 'guide quiet'));
        body.appendChild(row);
        figureCells.set(row.dataset.key, cells);
      });
      holder.appendChild(table);
    });
  }

  // A figure's row: its value (in SI, exactly as the server gave it, in `data-si`: what the browser test
  // reads) with its error estimate as the report writes it in its hover text, the previous design's where
  // it moved, and its targets met or not.
  function fillFigure(cells, a, f, state) {
    if (f.value != null) put.attribute(cells.row, 'data-si', String(f.value));
    else delete cells.row.dataset.si;
    put.text(cells.value, written(f));
    put.attribute(
      cells.value,
      'title',
      f.value == null
        ? f.reason || ''
        : f.estimate
          ? f.estimate + ': its error estimate'
          : state.estimated
            ? 'not estimated'
            : 'its error estimate follows once the design rests'
    );
    const before = figureOf(previous, a.name, f.key);
    put.text(cells.before, before && before.value !== f.value ? written(before) : '');
    const targets = state.targets.filter((t) => t.analysis === a.name && t.figure === f.key);
    put.text(cells.target, targets.map((t) => (t.met ? '✓ ' : '✗ ') + t.aim + ' ± ' + t.tolerance).join(', '));
    put.attribute(cells.target, 'class', targets.some((t) => !t.met) ? 'error' : '');
  }

  // The figure the arrows are for: the one chosen while the design has it, else the first with a target,
  // else bump steer, else the first.
  function chosenFigure(state) {
    const has = (key) => key && state.analyses.some((a) => a.figures.some((f) => a.name + '/' + f.key === key));
    if (has(chosen)) return chosen;
    const target = state.targets.find((t) => t.figure);
    const bump = state.analyses.find((a) => a.figures.some((f) => f.key === 'bump_steer'));
    const first = state.analyses.find((a) => a.figures.length);
    if (target) return target.analysis + '/' + target.figure;
    if (bump) return bump.name + '/bump_steer';
    return first ? first.name + '/' + first.figures[0].key : null;
  }

  function choose(key) {
    chosen = key;
    showGuidance();
    publish();
  }

  // The guidance of figure `key` ('analysis/key') at the point selected on the design on screen, with how
  // the figure is written.
  function guidanceOf(key) {
    if (!key || !guidance || !current || guidance.version !== current.version || guidance.point !== selected) return null;
    const [analysis, figure] = key.split('/');
    const a = guidance.analyses.find((x) => x.name === analysis);
    const g = a ? a.figures.find((x) => x.key === figure) : null;
    const f = figureOf(current, analysis, figure);
    return g && f ? { label: f.label, unit: f.unit, factor: f.factor, per_metre: g.per_metre, why_not: g.why_not } : null;
  }

  // Each figure's derivatives to the selected hardpoint's x, y and z, per millimetre in the figure's unit;
  // the chosen figure's drawn as arrows at the point.
  function showGuidance() {
    let guided = 0;
    chosen = current ? chosenFigure(current) : null;
    document.querySelectorAll('#figures tr[data-key]').forEach((row) => {
      row.classList.toggle('chosen', row.dataset.key === chosen);
      const cell = row.querySelector('td.guide');
      const g = guidanceOf(row.dataset.key);
      if (!g) {
        put.text(cell, '');
        return;
      }
      const per = g.per_metre.map((d) => (d == null ? '–' : Number((d * g.factor / 1000).toPrecision(3)).toString()));
      put.text(cell, per.join(', ') + (g.unit === '-' ? '' : ' ' + g.unit) + ' /mm');
      put.attribute(cell, 'title', g.why_not.filter((w) => w).join('; '));
      if (g.per_metre.some((d) => d != null)) guided += 1;
    });
    report.guided = guided;
    report.chosen = chosen;
    views.arrows(selected, guidanceOf(chosen));
  }

  // A POST of `body` as JSON to `route`, never answered from a cache.
  function posted(route, body) {
    return fetch(route, {
      method: 'POST',
      cache: 'no-store',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify(body),
    });
  }

  // The guidance for the hardpoint at `point`, asked of the server for the design on screen.
  async function guide(point) {
    selected = point;
    document.querySelectorAll('#hardpoints tr').forEach((r) => r.classList.toggle('selected', r.dataset.point === point));
    views.select(point);
    try {
      const response = await posted('guidance', { point });
      const answer = await response.json();
      if (!response.ok) return refused(answer.error || 'refused (' + response.status + ')');
      guidance = answer.guidance;
      showGuidance();
      publish();
    } catch (e) {
      refused('the server does not answer: ' + e);
    }
  }

  // The hardpoints, one row a point, each coordinate an input in millimetres; a point's name selects it
  // for guidance.
  const hardpointTable = builtOnChange((state) => state.hardpoints.map((n) => n.pointer), buildHardpoints);
  function showHardpoints(state) {
    hardpointTable(state);
    state.hardpoints.forEach((n) => setNumber(state, n.pointer, millimetres(n.value)));
    return state.hardpoints.length;
  }

  function buildHardpoints(state) {
    const holder = el('hardpoints');
    forgetInputs(holder);
    holder.replaceChildren(make('h2', 'Hardpoints (mm)'));
    const table = make('table', null, 'numbers');
    const head = make('tr');
    ['point', 'x', 'y', 'z'].forEach((h) => head.appendChild(make('th', h)));
    table.appendChild(make('thead')).appendChild(head);
    const body = table.appendChild(make('tbody'));
    const rows = new Map();
    state.hardpoints.forEach((n) => {
      const cut = n.pointer.lastIndexOf('/');
      const point = n.pointer.slice(0, cut);
      if (!rows.has(point)) {
        const name = point.slice(point.lastIndexOf('/') + 1).replace(/~1/g, '/').replace(/~0/g, '~');
        const row = make('tr');
        row.dataset.point = point;
        if (point === selected) row.className = 'selected';
        const cell = row.appendChild(make('td'));
        const button = cell.appendChild(make('button', name, 'point'));
        button.type = 'button';
        button.title = 'how every figure moves with this point';
        button.addEventListener('click', () => guide(point));
        rows.set(point, row);
        body.appendChild(row);
      }
      const input = numberInput(n.pointer, '0.1');
      input.addEventListener('change', () => edit(n.pointer, input));
      rows.get(point).appendChild(make('td')).appendChild(input);
    });
    holder.appendChild(table);
  }

  // Each number's input by its pointer, as built.
  const numberInputs = new Map();

  // The inputs of `holder`, about to be built anew, no longer looked up.
  function forgetInputs(holder) {
    holder.querySelectorAll('input[data-pointer]').forEach((input) => numberInputs.delete(input.dataset.pointer));
  }

  // An input for the number at `pointer`.
  function numberInput(pointer, step) {
    const input = make('input');
    numberInputs.set(pointer, input);
    input.type = 'number';
    input.step = step;
    input.dataset.pointer = pointer;
    input.setAttribute('aria-label', pointer);
    return input;
  }

  // The input of the number at `pointer` showing `value` (text), marked when the design has moved it.
  function setNumber(state, pointer, value) {
    const input = numberInputs.get(pointer);
    if (!input) return;
    if (input.value !== value) input.value = value;
    input.classList.toggle('moved', state.moved.some((m) => m.pointer === pointer));
  }

  // The rates, each an input as the model file stores it (SI: N/m, N·m/rad), named by its keys.
  const rateTable = builtOnChange((state) => state.rates.map((n) => n.pointer), buildRates);
  function showRates(state) {
    rateTable(state);
    state.rates.forEach((n) => setNumber(state, n.pointer, String(n.value)));
    return state.rates.length;
  }

  function buildRates(state) {
    const holder = el('rates');
    forgetInputs(holder);
    holder.replaceChildren();
    if (!state.rates.length) return;
    holder.appendChild(make('h2', 'Rates (N/m, N·m/rad)'));
    const table = make('table', null, 'numbers');
    const body = table.appendChild(make('tbody'));
    state.rates.forEach((n) => {
      const row = make('tr');
      const name = n.pointer.replace(/^\/suspension\/[^/]+\//, '').split('/').join(' ').replace(/~1/g, '/').replace(/~0/g, '~');
      row.appendChild(make('td', name));
      const input = numberInput(n.pointer, 'any');
      input.addEventListener('change', () => {
        const value = input.value.trim() === '' ? NaN : Number(input.value);
        if (!isFinite(value)) return refused(n.pointer + ': type a number');
        report.edits += 1;
        ask('POST', 'edit', { pointer: n.pointer, value });
      });
      row.appendChild(make('td')).appendChild(input);
      body.appendChild(row);
    });
    holder.appendChild(table);
  }

  // The charts of each design: one whose shape is the drawn one's (the same curves, the previous design's
  // beneath from the second design on) takes the new numbers in place; any other is drawn anew.
  let charted = new Map();
  function showCharts(state) {
    const holder = el('charts');
    const next = new Map();
    const order = [];
    let count = 0;
    let drawn = 0;
    let ghosts = 0;
    let anew = 0;
    state.analyses.forEach((a) => {
      const before = previous && previous.analyses.find((x) => x.name === a.name);
      a.charts.forEach((chart) => {
        count += 1;
        // The chart with each axis's curves of the design before beneath its own (its numbers shared, not
        // copied), dashed one pixel wide: a line no wider than a pixel is drawn as a hairline, at a fraction
        // of the cost of a wider one, and every chart's ghosts are drawn again at every design.
        const old = before && before.charts.find((c) => c.title === chart.title);
        const data = Object.assign({}, chart, {
          axes: chart.axes.map((axis, k) => {
            const was = old && old.axes[k] ? old.axes[k].series : [];
            ghosts += was.length;
            const ghost = (s) => ({ name: 'before: ' + s.name, colour: '#8c959f', x: s.x, y: s.y, dash: [4, 4], width: 1 });
            return Object.assign({}, axis, { series: axis.series.concat(was.map(ghost)) });
          }),
        });
        const key = a.name + '\n' + chart.title;
        let shown = charted.get(key);
        charted.delete(key);
        try {
          if (!shown || !shown.plot.elastokinShow(data)) {
            if (shown) shown.plot.destroy();
            const figure = shown ? shown.figure : make('figure', null, 'chart');
            figure.replaceChildren();
            figure.setAttribute('data-chart', JSON.stringify(data));
            // In the page while drawn: the chart takes its width from it.
            if (!figure.parentNode) holder.appendChild(figure);
            shown = { figure, plot: window.elastokinDrawChart(figure) };
            anew += 1;
          }
          drawn += 1;
        } catch (e) {
          report.errors.push(chart.title + ': ' + e);
          if (shown) shown.figure.remove();
          return;
        }
        next.set(key, shown);
        order.push(shown.figure);
      });
    });
    // Charts of analyses no longer shown.
    charted.forEach((shown) => {
      shown.plot.destroy();
      shown.figure.remove();
    });
    charted = next;
    if (order.some((figure, k) => holder.children[k] !== figure) || holder.children.length !== order.length) {
      holder.replaceChildren(...order);
    }
    report.charts = count;
    report.drawn = drawn;
    report.ghosts = ghosts;
    report.anew = anew;
  }

  function show(state) {
    current = state;
    report.version = state.version;
    put.flag(el('undo'), 'disabled', !state.can_undo);
    put.flag(el('redo'), 'disabled', !state.can_redo);
    // Tuning needs a TARGETS file: the button shows when the design is judged against one.
    put.flag(el('tune'), 'hidden', !(state.targets && state.targets.length));
    showFigures(state);
    report.inputs = showHardpoints(state) + showRates(state);
    // The projections as the server drew them, a ring at each hardpoint.
    views.show(state, selected);
    report.projections = el('projections').querySelectorAll('figure.view').length;
    showView3d(state);
    showCharts(state);
    showGuidance();
    if (selected && (!guidance || guidance.version !== state.version)) guide(selected);
    const failed = state.failed.map((f) => f.analysis + ': ' + f.reason);
    put.text(
      el('status'),
      'version ' + state.version + (state.moved.length ? ', ' + state.moved.length + ' numbers moved' : '') +
      (failed.length ? '; failed: ' + failed.join('; ') : '') +
      (tuned && tuned.version === state.version ? ' — tuned: ' + tuned.said : '')
    );
    if (state.estimated) report.estimated = state.version;
    else estimateLater(state.version);
    publish();
  }

  // The error estimates of a design an edit made without them, asked for once it has rested on screen for
  // REST_MS: a run of moves is not slowed by the estimates of designs passed through. Each figure's
  // estimate goes into its hover text; `report.estimated` is the version they are of.
  const REST_MS = 300;
  let resting = null;
  function estimateLater(version) {
    clearTimeout(resting);
    resting = setTimeout(async () => {
      if (busy || !current || current.version !== version) return;
      try {
        const response = await posted('estimate', { version });
        const answer = await response.json();
        // Another design on screen by now (409): its own rest asks for its estimates.
        if (!response.ok || !current || current.version !== answer.version) return;
        answer.analyses.forEach((a) =>
          a.figures.forEach((e) => {
            const f = figureOf(current, a.name, e.key);
            if (f) Object.assign(f, { error: e.error, estimate: e.estimate });
          })
        );
        current.estimated = true;
        showFigures(current);
        report.estimated = answer.version;
        publish();
      } catch (e) {
        report.errors.push('estimate: ' + e);
        publish();
      }
    }, REST_MS);
  }

  // The 3D view drawn anew from the design's poses, the camera kept.
  function showView3d(state) {
    if (!window.elastokinView3d || !state.view3d) return;
    window.elastokinView3d.show(state.view3d);
    const drawn = JSON.parse(el('view3d-state').textContent || '{}');
    report.view3d = { shows: drawn.shows, strokes: drawn.strokes, drawn: drawn.drawn };
  }

  function refused(why) {
    const e = el('error');
    put.text(e, why);
    put.flag(e, 'hidden', !why);
  }

  let tuned = null;

  // A request to the server; its answer's state shown when it is another design than the one on screen,
  // with `animated` the hardpoints moved there first. One asked while another is under way waits for it
  // (the last one asked; those between are dropped).
  let waiting = null;
  async function ask(method, route, body, animated) {
    if (busy) {
      waiting = [method, route, body, animated];
      el('status').textContent = 'solving… (then the next change)';
      return null;
    }
    busy = true;
    clearTimeout(resting);
    el('status').textContent = 'solving…';
    try {
      // A change with a body is POSTed as JSON, as guidance and estimates are.
      const response = await (body ? posted(route, body) : fetch(route, { method, cache: 'no-store' }));
      const answer = await response.json();
      refused(response.ok ? '' : answer.error || 'refused (' + response.status + ')');
      if (!response.ok) report.refused += 1;
      // How a tune ended, said beside the status while its design is on screen.
      if (answer.tuned && answer.state) tuned = { version: answer.state.version, said: answer.tuned };
      if (answer.state && (!current || answer.state.version !== current.version)) {
        if (animated && current) {
          el('status').textContent = 'moving the points…';
          await views.animate(current, answer.state, 500);
        }
        previous = current;
        show(answer.state);
      } else if (current) {
        show(current);
      }
      return answer;
    } catch (e) {
      refused('the server does not answer: ' + e + ' (is `elastokin live` still running?)');
      report.errors.push(String(e));
      publish();
      if (current) el('status').textContent = 'version ' + current.version;
      return null;
    } finally {
      busy = false;
      if (waiting) {
        const next = waiting;
        waiting = null;
        ask(...next);
      }
    }
  }

  // A hardpoint dragged in a projection to `value` (m, on the 0.1 mm grid): the edit typing sends.
  function dragged(pointer, value) {
    report.edits += 1;
    report.dragged = { pointer, value };
    ask('POST', 'edit', { pointer, value });
  }

  const views = window.elastokinLiveViews(el('projections'), {
    edit: dragged,
    select: guide,
    metres,
    millimetres,
    report,
    publish,
    legend: el('arrows-legend'),
  });

  function edit(pointer, input) {
    const value = metres(input.value);
    if (!isFinite(value)) {
      refused(pointer + ': type a number of millimetres');
      return;
    }
    report.edits += 1;
    ask('POST', 'edit', { pointer, value });
  }

  el('undo').addEventListener('click', () => ask('POST', 'undo'));
  el('redo').addEventListener('click', () => ask('POST', 'redo'));
  el('save').addEventListener('click', async () => {
    const answer = await ask('POST', 'save');
    if (answer && answer.saved) el('status').textContent += ' — saved to ' + answer.saved;
  });
  // The TARGETS file's free numbers tuned from this design, one design more, the points it moves moved on
  // screen to where it puts them; how the tune ended said.
  el('tune').addEventListener('click', () => ask('POST', 'tune', null, true));
  // Another tab may have moved the design: asked again whenever this one is shown.
  document.addEventListener('visibilitychange', () => {
    if (document.visibilityState === 'visible') ask('GET', 'state');
  });
  ask('GET', 'state');
})();
