// `elastokin live`'s projections made to be handled (src/live.js gives them the design): each hardpoint a
// ring at its coordinates in the model, placed by the server's frame of each projection. A ring dragged
// moves its point along one of the view's two axes (the one the pointer first moves most along), in steps
// of 0.1 mm, and is sent as one edit when released; Escape cancels, a click selects the point. The
// guidance for the selected point is drawn as an arrow in each view, the way that raises the figure
// chosen; a tune's move is shown as the rings moving from the old design's places to the new. Each design
// after the first changes only what moved in the views shown (the lines of the server's SVG that differ,
// the rings' places); `window.elastokinPut` is the page's way of writing only what changes.
(function () {
  'use strict';
  const SVG = 'http://www.w3.org/2000/svg';
  const AXES = ['x', 'y', 'z'];
  // Pixels the pointer moves before a drag picks its axis.
  const PICK = 4;
  const RING = 6;
  const RING_COLOUR = '#0969da';
  const SELECTED_COLOUR = '#cf222e';
  const ARROW_COLOUR = '#8250df';

  function svgElement(tag, attributes, text) {
    const e = document.createElementNS(SVG, tag);
    Object.entries(attributes || {}).forEach(([k, v]) => e.setAttribute(k, String(v)));
    if (text != null) e.textContent = text;
    return e;
  }

  // The live page's writes to what it shows, each left undone where it would change nothing: a text or an
  // attribute set anew, even to what it was, has its element laid out and painted anew.
  const put = {
    // `e`'s text, into the text node it holds when it holds one alone.
    text(e, text) {
      const only = e.firstChild && !e.firstChild.nextSibling && e.firstChild.nodeType === Node.TEXT_NODE ? e.firstChild : null;
      if (only ? only.nodeValue === text : e.textContent === text) return;
      if (only) only.nodeValue = text;
      else e.textContent = text;
    },
    // `e`'s attribute `name`, `value` written as text.
    attribute(e, name, value) {
      const text = String(value);
      if (e.getAttribute(name) !== text) e.setAttribute(name, text);
    },
    // `e`'s property `name` (disabled, hidden) set to `on`.
    flag(e, name, on) {
      if (e[name] !== on) e[name] = on;
    },
  };
  window.elastokinPut = put;

  // A line of the server's SVG with its attribute values and texts taken out: two lines alike differ in
  // those alone.
  function skeleton(line) {
    return line.replace(/"[^"]*"/g, '""').replace(/>[^<]+</g, '><');
  }

  // How many elements a line of the server's SVG starts.
  function started(line) {
    return (line.match(/<[a-zA-Z]/g) || []).length;
  }

  // Where a projection puts a global point `p` (m) on its SVG: by its frame from the server.
  function place(frame, p) {
    return [
      frame.origin[0] + frame.scale * frame.horizontal[1] * p[frame.horizontal[0]],
      frame.origin[1] - frame.scale * frame.vertical[1] * p[frame.vertical[0]],
    ];
  }

  // Each hardpoint of a state by its pointer: its [x, y, z] (m).
  function pointsOf(state) {
    const points = new Map();
    state.hardpoints.forEach((n) => {
      const cut = n.pointer.lastIndexOf('/');
      const point = n.pointer.slice(0, cut);
      if (!points.has(point)) points.set(point, [NaN, NaN, NaN]);
      points.get(point)[Number(n.pointer.slice(cut + 1))] = n.value;
    });
    return points;
  }

  // A point's name: the last token of its pointer, unescaped.
  function nameOf(point) {
    return point.slice(point.lastIndexOf('/') + 1).replace(/~1/g, '/').replace(/~0/g, '~');
  }

  // A rate per millimetre with its sign, to three significant digits.
  function signed(v) {
    const s = Number(Math.abs(v).toPrecision(3)).toString();
    return (v > 0 ? '+' : v < 0 ? '−' : '') + s;
  }

  // The views in `holder` (the server's projections), `hooks` the page's: edit(pointer, value) to send
  // an edit, select(point), metres(typed mm) and millimetres(m) as the page writes numbers, the page's
  // `report`, and the `legend` that says what the arrows show.
  window.elastokinLiveViews = function (holder, hooks) {
    const report = hooks.report;
    report.handles = 0;
    report.arrows = 0;
    report.cancelled = 0;
    let frames = [];
    let points = new Map();
    let drag = null;

    function svgOf(frame) {
      return holder.querySelector('#' + frame.id + ' svg');
    }

    function ringsOf(point) {
      return Array.from(holder.querySelectorAll('circle.handle')).filter((r) => r.dataset.point === point);
    }

    // `ring` put where the point `p` (m) lands in the view of `frame`.
    function putRing(ring, frame, p) {
      const [x, y] = place(frame, p);
      put.attribute(ring, 'cx', x);
      put.attribute(ring, 'cy', y);
    }

    // Every ring of `point` put where the point `p` (m) lands in its view.
    function placeRings(point, p) {
      ringsOf(point).forEach((ring) => {
        const frame = frames.find((f) => f.id === ring.dataset.view);
        if (frame) putRing(ring, frame, p);
      });
    }

    // The server's projections as last drawn: their lines, and the elements each line started (in the
    // page, in the order of the lines).
    let drawn = null;

    // The server's projections (`html`: SVG, every text in it escaped there; an element, or its end, a
    // line) shown. Drawn as the ones shown with other numbers (every design after the first, unless the
    // views change), only the lines that differ are read and only their attributes and texts that differ
    // changed, so only what moved is laid out and painted anew; any other drawing replaces them.
    function draw(html) {
      const lines = html.split('\n');
      if (drawn && lines.length === drawn.lines.length && patch(lines)) {
        drawn.lines = lines;
        return;
      }
      const next = document.createElement('template');
      next.innerHTML = html;
      holder.replaceChildren(next.content);
      const elements = Array.from(holder.querySelectorAll('*'));
      let count = 0;
      const of = lines.map((line) => {
        const first = count;
        count += started(line);
        return elements.slice(first, count);
      });
      drawn = count === elements.length ? { lines, of } : null;
    }

    // The projections shown made `lines`, alike line for line: false, nothing changed, where a line is
    // not its drawn one's alike. The lines that differ are read at once, each within an element of its
    // own (the first element it starts is in SVG or not).
    function patch(lines) {
      const differ = [];
      for (let i = 0; i < lines.length; i++) {
        if (lines[i] === drawn.lines[i]) continue;
        if (!drawn.of[i].length || skeleton(lines[i]) !== skeleton(drawn.lines[i])) return false;
        differ.push(i);
      }
      const read = document.createElement('template');
      read.innerHTML = differ
        .map((i) => (drawn.of[i][0].namespaceURI === SVG ? '<svg>' + lines[i] + '</svg>' : '<div>' + lines[i] + '</div>'))
        .join('');
      const changes = [];
      for (let j = 0; j < differ.length; j++) {
        const i = differ[j];
        const shown = drawn.of[i];
        const parsed = read.content.children[j] ? read.content.children[j].querySelectorAll('*') : [];
        if (parsed.length !== shown.length) return false;
        for (let k = 0; k < parsed.length; k++) {
          const [a, b] = [shown[k], parsed[k]];
          for (const name of b.getAttributeNames()) {
            const value = b.getAttribute(name);
            if (a.getAttribute(name) !== value) changes.push(() => a.setAttribute(name, value));
          }
          // The text of an element that holds text alone, ended on its line.
          const text = b.textContent;
          if (!b.childElementCount && !a.childElementCount && lines[i].includes('</' + b.localName) && a.textContent !== text) {
            changes.push(() => (a.textContent = text));
          }
        }
      }
      changes.forEach((change) => change());
      return true;
    }

    // The server's projections, and a ring for every hardpoint in every view over everything drawn: the
    // rings shown moved where they are the same points, else drawn anew.
    function show(state, selected) {
      if (drag) cancel();
      draw(state.projections || '');
      frames = state.projection_frames || [];
      points = pointsOf(state);
      const placed = Array.from(points).filter(([, p]) => p.every((c) => isFinite(c)));
      let count = 0;
      frames.forEach((frame) => {
        const svg = svgOf(frame);
        if (!svg) return;
        let g = svg.querySelector(':scope > g.handles');
        if (g) g.querySelectorAll('text.dragged').forEach((label) => label.remove());
        const rings = g ? g.children : [];
        if (!g || rings.length !== placed.length || placed.some(([point], k) => rings[k].dataset.point !== point)) {
          if (g) g.remove();
          g = svgElement('g', { class: 'handles' });
          placed.forEach(([point]) => {
            const ring = svgElement('circle', { class: 'handle', r: RING, 'fill-opacity': 0.2, 'stroke-width': 1.5 });
            ring.dataset.point = point;
            ring.dataset.view = frame.id;
            ring.appendChild(svgElement('title', {}, nameOf(point) + ': drag to move it, click to select it'));
            g.appendChild(ring);
          });
          svg.appendChild(g);
        }
        placed.forEach(([, p], k) => putRing(g.children[k], frame, p));
        count += placed.length;
      });
      select(selected);
      report.handles = count;
    }

    // The selected point's rings marked.
    function select(point) {
      holder.querySelectorAll('circle.handle').forEach((ring) => {
        const colour = ring.dataset.point === point ? SELECTED_COLOUR : RING_COLOUR;
        put.attribute(ring, 'fill', colour);
        put.attribute(ring, 'stroke', colour);
      });
    }

    // A drag begun on a ring: the page listens to the pointer and the keyboard until it ends.
    function begin(e) {
      const ring = e.target.closest ? e.target.closest('circle.handle') : null;
      if (!ring || e.button !== 0 || drag) return;
      const frame = frames.find((f) => f.id === ring.dataset.view);
      const from = points.get(ring.dataset.point);
      if (!frame || !from) return;
      e.preventDefault();
      drag = { ring, frame, point: ring.dataset.point, from, start: [e.clientX, e.clientY], axis: null, value: null, label: null };
      window.addEventListener('pointermove', move);
      window.addEventListener('pointerup', release);
      window.addEventListener('pointercancel', cancel);
      window.addEventListener('keydown', escape);
    }

    function end() {
      window.removeEventListener('pointermove', move);
      window.removeEventListener('pointerup', release);
      window.removeEventListener('pointercancel', cancel);
      window.removeEventListener('keydown', escape);
      drag = null;
    }

    // The pointer moved: the axis picked once it has moved a few pixels, the value along it snapped to
    // 0.1 mm in the model's coordinates, the point's rings moved there and its coordinate written by it.
    function move(e) {
      const dx = e.clientX - drag.start[0];
      const dy = e.clientY - drag.start[1];
      const frame = drag.frame;
      if (drag.axis == null) {
        if (Math.hypot(dx, dy) < PICK) return;
        drag.along = Math.abs(dx) >= Math.abs(dy) ? 'horizontal' : 'vertical';
        drag.axis = frame[drag.along][0];
      }
      // The pointer's move in the SVG's own units (it may be drawn at another size than its viewBox).
      const m = drag.ring.ownerSVGElement.getScreenCTM().inverse();
      const [axis, sign] = frame[drag.along];
      const metres = drag.along === 'horizontal'
        ? (m.a * dx + m.c * dy) / (frame.scale * sign)
        : -(m.b * dx + m.d * dy) / (frame.scale * sign);
      const tenths = Math.round((drag.from[axis] + metres) * 1e4);
      drag.value = hooks.metres(String(tenths / 10));
      const p = drag.from.slice();
      p[axis] = drag.value;
      placeRings(drag.point, p);
      writeCoordinate(p);
    }

    // The dragged coordinate in mm, beside the ring dragged.
    function writeCoordinate(p) {
      if (!drag.label) {
        drag.label = svgElement('text', { class: 'dragged', 'font-size': 12, fill: SELECTED_COLOUR, stroke: '#fff', 'stroke-width': 3, 'paint-order': 'stroke', 'pointer-events': 'none' });
        drag.ring.parentNode.appendChild(drag.label);
      }
      const [x, y] = place(drag.frame, p);
      drag.label.setAttribute('x', String(x + 9));
      drag.label.setAttribute('y', String(y - 9));
      drag.label.textContent = nameOf(drag.point) + ' ' + AXES[drag.axis] + ' ' + hooks.millimetres(drag.value) + ' mm';
    }

    // Released: a click selects the point; a drag that moved the value is sent as one edit.
    function release() {
      const d = drag;
      end();
      if (d.axis == null) {
        hooks.select(d.point);
      } else if (d.value === d.from[d.axis]) {
        putBack(d);
      } else {
        hooks.edit(d.point + '/' + d.axis, d.value);
      }
    }

    function putBack(d) {
      placeRings(d.point, d.from);
      if (d.label) d.label.remove();
    }

    function cancel() {
      const d = drag;
      end();
      if (d) putBack(d);
      report.cancelled += 1;
      hooks.publish();
    }

    function escape(e) {
      if (e.key !== 'Escape') return;
      e.preventDefault();
      cancel();
    }

    holder.addEventListener('pointerdown', begin);

    // The guidance at `point` for one figure (`g`: its `label`, `unit`, `factor` and `per_metre`, the
    // derivatives to x, y and z in SI) as an arrow in each view along the in-plane part of its gradient,
    // the way that raises the figure, and the way that lowers it; none where that part is zero or missing.
    function arrows(point, g) {
      holder.querySelectorAll('g.guide-arrow').forEach((a) => a.remove());
      const legend = hooks.legend;
      const p = point ? points.get(point) : null;
      report.arrows = 0;
      if (!p || !g) {
        put.flag(legend, 'hidden', true);
        return;
      }
      const per = g.per_metre;
      const known = per.filter((d) => d != null && isFinite(d));
      const full = Math.hypot(...known);
      const unit = g.unit === '-' ? '' : ' ' + g.unit;
      const words = (k) => signed(per[k] * g.factor / 1000) + unit + ' per mm along ' + AXES[k];
      frames.forEach((frame) => {
        const [a, sa] = frame.horizontal;
        const [b, sb] = frame.vertical;
        const svg = svgOf(frame);
        if (!svg || per[a] == null || per[b] == null || (per[a] === 0 && per[b] === 0)) return;
        const rates = [a, b].filter((k) => per[k] !== 0).map(words).join('; ');
        const share = Math.hypot(per[a], per[b]) / full;
        svg.appendChild(arrow(svg, place(frame, p), [sa * per[a], -sb * per[b]], share, g.label, rates));
        report.arrows += 1;
      });
      legend.textContent = 'Arrows at ' + nameOf(point) + ': the way that raises ' + g.label + ' (↑; ↓ lowers it): ' +
        [0, 1, 2].map((k) => (per[k] == null ? 'no rate along ' + AXES[k] : words(k))).join(', ') + '.';
      legend.hidden = false;
    }

    // An arrow on `svg` from `at` along `direction` (the SVG's), its length growing with `share` (the
    // in-plane part of the gradient over all of it), labelled with the figure's name and its `rates` as its
    // tooltip. Each label runs towards the middle of the view; where the arrow lies flat, the figure's
    // below its end and the lowering one's above.
    function arrow(svg, at, direction, share, label, rates) {
      const n = Math.hypot(direction[0], direction[1]);
      const [u, v] = [direction[0] / n, direction[1] / n];
      const length = 22 + 38 * share;
      const tip = [at[0] + length * u, at[1] + length * v];
      const tail = [at[0] - 0.5 * length * u, at[1] - 0.5 * length * v];
      const g = svgElement('g', { class: 'guide-arrow', stroke: ARROW_COLOUR, fill: ARROW_COLOUR, 'pointer-events': 'none' });
      g.appendChild(svgElement('title', {}, label + ' rises ' + rates));
      g.appendChild(svgElement('line', { class: 'raise', x1: at[0], y1: at[1], x2: tip[0], y2: tip[1], 'stroke-width': 2.5 }));
      g.appendChild(svgElement('line', { class: 'lower', x1: at[0], y1: at[1], x2: tail[0], y2: tail[1], 'stroke-width': 1.5, 'stroke-dasharray': '3 3' }));
      const head = [[0, 0], [-9, 4.5], [-9, -4.5]].map(([s, t]) => [tip[0] + s * u - t * v, tip[1] + s * v + t * u]);
      g.appendChild(svgElement('polygon', { points: head.map((q) => q.join(',')).join(' '), stroke: 'none' }));
      const middle = svg.viewBox.baseVal.width / 2;
      const text = (q, said, away) => svgElement('text', {
        x: q[0] + away * 8 * u,
        y: q[1] + away * 8 * v + (Math.abs(u) <= 0.7 ? 4 : away > 0 ? 16 : -6),
        'text-anchor': q[0] < middle ? 'start' : 'end',
        'font-size': 12, stroke: '#fff', 'stroke-width': 3, 'paint-order': 'stroke',
      }, said);
      g.appendChild(text(tip, label + ' ↑', 1));
      g.appendChild(text(tail, '↓', -1));
      return g;
    }

    // The rings of each point that `to` moves, from where `from` has them to where `to` has them, over
    // `ms` milliseconds; resolved once there (at once when nothing moves or the page is not shown).
    function animate(from, to, ms) {
      const before = pointsOf(from);
      const moving = [];
      pointsOf(to).forEach((q, point) => {
        const p = before.get(point);
        if (p && p.some((c, k) => c !== q[k])) moving.push([point, p, q]);
      });
      report.animation = { points: moving.length, frames: 0, ms: 0 };
      if (!moving.length || document.visibilityState !== 'visible') return Promise.resolve();
      holder.querySelectorAll('g.guide-arrow').forEach((a) => a.remove());
      return new Promise((resolve) => {
        const start = performance.now();
        const step = (now) => {
          const t = Math.max(0, Math.min(1, (now - start) / ms));
          const s = t * t * (3 - 2 * t);
          moving.forEach(([point, p, q]) => placeRings(point, p.map((c, k) => c + s * (q[k] - c))));
          report.animation.frames += 1;
          report.animation.ms = now - start;
          if (t < 1) requestAnimationFrame(step);
          else resolve();
        };
        requestAnimationFrame(step);
      });
    }

    return { show, select, arrows, animate };
  };
})();
