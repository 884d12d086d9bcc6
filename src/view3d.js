// The report's 3D view (see src/view.rs): places each stroke's and dot's anchored points by the poses of
// the row shown, projects them orthographically and draws them on a 2D canvas. Drag turns the view,
// the wheel zooms, the slider and play move through the analysis's rows. It draws the page's
// <script id="view3d-data"> when there is one; window.elastokinView3d.show(data) draws new data in the
// same view, its controls and listeners set up once.
(function () {
  'use strict';
  var state = document.getElementById('view3d-state');
  var errors = [];
  var summary = {};
  function report() {
    summary.errors = errors;
    state.textContent = JSON.stringify(summary);
  }
  window.addEventListener('error', function (e) {
    errors.push(String(e.message));
    report();
  });

  var data = null;
  // How many times data was given to the view.
  var shows = 0;
  var canvas = document.getElementById('view3d-canvas');
  var ctx = canvas.getContext('2d');
  var select = document.getElementById('view3d-analysis');
  var slider = document.getElementById('view3d-row');
  var label = document.getElementById('view3d-label');
  var play = document.getElementById('view3d-play');
  var VIEWS = {
    '3d': [0.75, 0.35],
    front: [0, 0],
    side: [Math.PI / 2, 0],
    plan: [Math.PI, Math.PI / 2]
  };
  var camera = { yaw: VIEWS['3d'][0], pitch: VIEWS['3d'][1], zoom: 1, view: '3d' };
  var shown = 0;
  var row = 0;
  var timer = null;
  var direction = 1;

  // A body-fixed point [body, x, y, z] placed by the poses [x, y, z, w, i, j, k] of its body.
  function placed(a, poses) {
    var x = a[1], y = a[2], z = a[3];
    if (a[0] < 0) {
      return [x, y, z];
    }
    var p = poses[a[0]];
    var w = p[3], qi = p[4], qj = p[5], qk = p[6];
    // v + 2w (q × v) + 2 q × (q × v), q the vector part.
    var tx = 2 * (qj * z - qk * y), ty = 2 * (qk * x - qi * z), tz = 2 * (qi * y - qj * x);
    return [
      x + w * tx + (qj * tz - qk * ty) + p[0],
      y + w * ty + (qk * tx - qi * tz) + p[1],
      z + w * tz + (qi * ty - qj * tx) + p[2]
    ];
  }

  function strokePoints(s, poses) {
    var pts = s.points.map(function (a) { return placed(a, poses); });
    if (s.pen === 'deflection' && pts.length === 2) {
      var k = data.deflection_scale, i = pts[0], j = pts[1];
      return [j, [j[0] + k * (j[0] - i[0]), j[1] + k * (j[1] - i[1]), j[2] + k * (j[2] - i[2])]];
    }
    return pts;
  }

  // The camera looks at the centre from the direction c = (cos p cos y, cos p sin y, sin p); the page's
  // right is z × c, its up c × right (yaw 0, pitch 0: seen from the front, y to the right).
  function basis() {
    var cy = Math.cos(camera.yaw), sy = Math.sin(camera.yaw);
    var cp = Math.cos(camera.pitch), sp = Math.sin(camera.pitch);
    var right = [-sy, cy, 0];
    var c = [cp * cy, cp * sy, sp];
    var up = [c[1] * right[2] - c[2] * right[1], c[2] * right[0] - c[0] * right[2], c[0] * right[1] - c[1] * right[0]];
    return { right: right, up: up };
  }

  // `element`'s `property` set to `value` where it is not that already: a text or value set anew, even
  // to what it was, has the page laid out again.
  function changed(element, property, value) {
    if (element[property] !== value) {
      element[property] = value;
    }
  }

  var fit = null;
  // The canvas's laid-out size in CSS pixels, once the page has laid it out.
  var seen = null;
  function fitTo(a) {
    var d = data.drawings[a.drawing];
    var lo = [1e300, 1e300, 1e300], hi = [-1e300, -1e300, -1e300];
    a.frames.forEach(function (poses) {
      d.strokes.forEach(function (s) {
        strokePoints(s, poses).forEach(function (p) {
          for (var k = 0; k < 3; k++) {
            if (isFinite(p[k])) {
              lo[k] = Math.min(lo[k], p[k]);
              hi[k] = Math.max(hi[k], p[k]);
            }
          }
        });
      });
    });
    // The envelope's tyres and packaging, on both sides, are in the picture too.
    var grow = function (p, by) {
      [1, -1].forEach(function (side) {
        var q = [p[0], side * p[1], p[2]];
        for (var k = 0; k < 3; k++) {
          lo[k] = Math.min(lo[k], q[k] - by);
          hi[k] = Math.max(hi[k], q[k] + by);
        }
      });
    };
    if (a.envelope) {
      a.envelope.placements.forEach(function (p) { grow(p, a.envelope.tyre[0]); });
      a.envelope.points.forEach(function (p) { grow(p, 0); });
      a.envelope.boxes.forEach(function (b) { grow(b[0], 0); grow(b[1], 0); });
    }
    var centre = [0, 1, 2].map(function (k) { return (lo[k] + hi[k]) / 2; });
    var radius = Math.max(1e-3, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
    fit = { centre: centre, radius: radius };
  }

  function draw() {
    if (!data || !data.analyses.length) {
      return;
    }
    var a = data.analyses[shown];
    var d = data.drawings[a.drawing];
    var poses = a.frames[row];
    var ratio = window.devicePixelRatio || 1;
    // The canvas's size as last laid out (`seen`), read from the page only before the first layout is
    // seen: reading it would lay out a page whose other parts a new design has just changed.
    var width = seen ? seen[0] : canvas.clientWidth || canvas.width;
    var height = seen ? seen[1] : canvas.clientHeight || canvas.height;
    if (canvas.width !== Math.round(width * ratio)) {
      canvas.width = Math.round(width * ratio);
      canvas.height = Math.round(height * ratio);
    }
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, width, height);
    var b = basis();
    var scale = camera.zoom * 0.45 * Math.min(width, height) / fit.radius;
    function screen(p) {
      var dx = p[0] - fit.centre[0], dy = p[1] - fit.centre[1], dz = p[2] - fit.centre[2];
      return [
        width / 2 + scale * (dx * b.right[0] + dy * b.right[1] + dz * b.right[2]),
        height / 2 - scale * (dx * b.up[0] + dy * b.up[1] + dz * b.up[2])
      ];
    }
    var drawn = 0;
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    d.strokes.forEach(function (s) {
      var pts = strokePoints(s, poses).map(screen);
      if (pts.length < 2 || !pts.every(function (p) { return isFinite(p[0]) && isFinite(p[1]); })) {
        return;
      }
      var pen = data.pens[s.pen];
      ctx.strokeStyle = pen.colour;
      ctx.lineWidth = pen.width;
      ctx.setLineDash(pen.dash);
      ctx.beginPath();
      ctx.moveTo(pts[0][0], pts[0][1]);
      for (var k = 1; k < pts.length; k++) {
        ctx.lineTo(pts[k][0], pts[k][1]);
      }
      if (s.closed) {
        ctx.closePath();
      }
      ctx.stroke();
      drawn++;
    });
    ctx.setLineDash([]);
    d.dots.forEach(function (dot) {
      var p = screen(placed(dot.at, poses));
      var spot = data.spots[dot.spot];
      ctx.beginPath();
      if (dot.spot === 'mount') {
        ctx.fillStyle = spot.colour;
        ctx.fillRect(p[0] - spot.radius, p[1] - spot.radius, 2 * spot.radius, 2 * spot.radius);
        return;
      }
      ctx.arc(p[0], p[1], spot.radius, 0, 2 * Math.PI);
      if (dot.spot === 'joint') {
        ctx.fillStyle = '#ffffff';
        ctx.fill();
        ctx.strokeStyle = spot.colour;
        ctx.lineWidth = 1.5;
        ctx.stroke();
      } else {
        ctx.fillStyle = spot.colour;
        ctx.fill();
      }
    });
    var envelope = drawEnvelope(a.envelope, screen);
    var construction = drawConstruction(a.construction[row], screen);
    changed(label, 'textContent', a.labels[row]);
    summary = {
      analyses: data.analyses.length,
      analysis: a.name,
      row: row,
      rows: a.frames.length,
      strokes: d.strokes.length,
      dots: d.dots.length,
      drawn: drawn,
      construction: construction,
      envelope: envelope,
      view: camera.view || 'custom',
      shows: shows
    };
    report();
  }

  // The wheel's swept envelope `e` (the wheel envelope's), whatever the row: each tyre of the grid's
  // points as its two rims, faint, on both sides (the right the left mirrored), and the body's points
  // (crosses) and boxes (their edges) it clears. Returns how many tyres, points and boxes it drew.
  function drawEnvelope(e, screen) {
    if (!e) {
      return null;
    }
    var r = e.tyre[0], half = e.tyre[1] / 2;
    var mirror = function (p) { return [p[0], -p[1], p[2]]; };
    var segments = 32;
    ctx.strokeStyle = data.envelope;
    ctx.lineWidth = 1;
    ctx.globalAlpha = 0.25;
    ctx.setLineDash([]);
    var tyres = 0;
    e.placements.forEach(function (p) {
      [1, -1].forEach(function (side) {
        var c = [p[0], side * p[1], p[2]], s = [p[3], side * p[4], p[5]];
        // Two unit vectors across the spin axis: u horizontal (or x where the axis is vertical), v = s × u.
        var u = Math.abs(s[2]) < 0.9 ? [-s[1], s[0], 0] : [1, 0, 0];
        var n = Math.hypot(u[0], u[1], u[2]);
        u = [u[0] / n, u[1] / n, u[2] / n];
        var v = [s[1] * u[2] - s[2] * u[1], s[2] * u[0] - s[0] * u[2], s[0] * u[1] - s[1] * u[0]];
        [-half, half].forEach(function (offset) {
          ctx.beginPath();
          for (var k = 0; k <= segments; k++) {
            var t = 2 * Math.PI * k / segments, a = r * Math.cos(t), b = r * Math.sin(t);
            var q = screen([
              c[0] + offset * s[0] + a * u[0] + b * v[0],
              c[1] + offset * s[1] + a * u[1] + b * v[1],
              c[2] + offset * s[2] + a * u[2] + b * v[2]
            ]);
            if (k === 0) { ctx.moveTo(q[0], q[1]); } else { ctx.lineTo(q[0], q[1]); }
          }
          ctx.stroke();
        });
        tyres++;
      });
    });
    ctx.globalAlpha = 1;
    ctx.strokeStyle = data.packaging;
    ctx.lineWidth = 1.5;
    e.boxes.forEach(function (b) {
      [false, true].forEach(function (right) {
        var lo = b[0], hi = b[1];
        var corner = function (k) {
          var p = [(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]];
          return screen(right ? mirror(p) : p);
        };
        // The twelve edges: corners differing in one coordinate.
        for (var k = 0; k < 8; k++) {
          [1, 2, 4].forEach(function (bit) {
            if (!(k & bit)) {
              var p = corner(k), q = corner(k | bit);
              ctx.beginPath();
              ctx.moveTo(p[0], p[1]);
              ctx.lineTo(q[0], q[1]);
              ctx.stroke();
            }
          });
        }
      });
    });
    e.points.forEach(function (pt) {
      [pt, mirror(pt)].forEach(function (p) {
        var q = screen(p);
        ctx.beginPath();
        ctx.moveTo(q[0] - 5, q[1] - 5);
        ctx.lineTo(q[0] + 5, q[1] + 5);
        ctx.moveTo(q[0] - 5, q[1] + 5);
        ctx.lineTo(q[0] + 5, q[1] - 5);
        ctx.stroke();
      });
    });
    return { tyres: tyres, points: 2 * e.points.length, boxes: 2 * e.boxes.length };
  }

  // The instant centres' construction of a row `c` (parallel travel's), in the front and side views
  // alone, as the projections draw it: in front, the patch's line through the instant centre on to the
  // roll centre; from the side, the patch's and the wheel centre's lines to the side-view instant centre.
  // An instant centre is a ring, the roll centre a square. Returns the lines drawn.
  function drawConstruction(c, screen) {
    if (!c || (camera.view !== 'front' && camera.view !== 'side')) {
      return 0;
    }
    var lines = [], rings = [], squares = [];
    var x = c.patch[0], y = c.patch[1];
    if (camera.view === 'front') {
      var ic = c.front ? [x, c.front[0], c.front[1]] : null;
      var rc = c.roll ? [x, c.roll[0], c.roll[1]] : null;
      if (ic) { lines.push([c.patch, ic]); rings.push(ic); }
      if (rc) { lines.push([ic || c.patch, rc]); squares.push(rc); }
    } else if (c.side) {
      var sc = [c.side[0], y, c.side[1]];
      lines.push([c.patch, sc], [c.wheel_centre, sc]);
      rings.push(sc);
    }
    ctx.strokeStyle = data.construction;
    ctx.fillStyle = data.construction;
    ctx.lineWidth = 1.5;
    ctx.setLineDash([5, 3]);
    lines.forEach(function (l) {
      var p = screen(l[0]), q = screen(l[1]);
      ctx.beginPath();
      ctx.moveTo(p[0], p[1]);
      ctx.lineTo(q[0], q[1]);
      ctx.stroke();
    });
    ctx.setLineDash([]);
    rings.forEach(function (r) {
      var p = screen(r);
      ctx.beginPath();
      ctx.arc(p[0], p[1], 5, 0, 2 * Math.PI);
      ctx.stroke();
    });
    squares.forEach(function (r) {
      var p = screen(r);
      ctx.fillRect(p[0] - 4.5, p[1] - 4.5, 9, 9);
    });
    return lines.length;
  }

  function choose(k) {
    shown = k;
    var a = data.analyses[k];
    slider.max = String(a.frames.length - 1);
    row = a.design;
    slider.value = String(row);
    fitTo(a);
    draw();
  }

  function setView(name) {
    var v = VIEWS[name];
    if (!v) {
      return;
    }
    camera.yaw = v[0];
    camera.pitch = v[1];
    camera.view = name;
    draw();
  }

  // `next` drawn in the view as it stands: the analysis `wanted` (by name), else the one shown, else the
  // first; the row and the camera kept where the analysis is the one shown before, so that a design
  // changed shows as parts moved in a still view.
  function show(next, wanted) {
    var before = data && data.analyses.length ? data.analyses[shown].name : null;
    data = next;
    shows++;
    // The analyses' choices made anew only when they change: a design changed keeps them.
    var names = data.analyses.map(function (a) { return a.name; });
    var listed = Array.prototype.map.call(select.options, function (o) { return o.textContent; });
    if (names.join('\n') !== listed.join('\n')) {
      select.replaceChildren();
      names.forEach(function (name, k) {
        var option = document.createElement('option');
        option.value = String(k);
        option.textContent = name;
        select.appendChild(option);
      });
    }
    if (!data.analyses.length) {
      summary = { analyses: 0, shows: shows };
      report();
      return;
    }
    var named = function (name) {
      return data.analyses.findIndex(function (a) { return a.name === name; });
    };
    var k = named(wanted || before);
    changed(select, 'value', String(Math.max(k, 0)));
    if (k < 0 || !fit || wanted) {
      choose(Math.max(k, 0));
      return;
    }
    shown = k;
    var last = data.analyses[k].frames.length - 1;
    changed(slider, 'max', String(last));
    row = Math.min(row, last);
    changed(slider, 'value', String(row));
    draw();
  }
  window.elastokinView3d = { show: show };

  select.addEventListener('change', function () { choose(Number(select.value)); });
  slider.addEventListener('input', function () {
    row = Number(slider.value);
    draw();
  });
  play.addEventListener('click', function () {
    if (timer) {
      clearInterval(timer);
      timer = null;
      play.textContent = 'play';
      return;
    }
    play.textContent = 'pause';
    timer = setInterval(function () {
      if (!data || !data.analyses.length) {
        return;
      }
      var last = data.analyses[shown].frames.length - 1;
      if (row + direction > last || row + direction < 0) {
        direction = -direction;
      }
      row = Math.max(0, Math.min(last, row + direction));
      slider.value = String(row);
      draw();
    }, 80);
  });
  Array.prototype.forEach.call(document.querySelectorAll('#view-3d button[data-view]'), function (button) {
    button.addEventListener('click', function () { setView(button.getAttribute('data-view')); });
  });
  var dragging = null;
  canvas.addEventListener('pointerdown', function (e) {
    dragging = [e.clientX, e.clientY];
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', function (e) {
    if (!dragging) {
      return;
    }
    camera.yaw -= (e.clientX - dragging[0]) * 0.01;
    camera.pitch = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, camera.pitch + (e.clientY - dragging[1]) * 0.01));
    camera.view = null;
    dragging = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener('pointerup', function () { dragging = null; });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    camera.zoom = Math.max(0.1, Math.min(50, camera.zoom * Math.exp(-e.deltaY * 0.001)));
    draw();
  }, { passive: false });
  if (typeof ResizeObserver === 'function') {
    new ResizeObserver(function (entries) {
      var box = entries[entries.length - 1].contentRect;
      var next = [box.width || canvas.width, box.height || canvas.height];
      if (!seen || seen[0] !== next[0] || seen[1] !== next[1]) {
        seen = next;
        draw();
      }
    }).observe(canvas);
  } else {
    window.addEventListener('resize', draw);
  }
  // The report's data, in the page; a view and an analysis asked for in the address
  // (report.html?view=side&analysis=steering) are the ones shown first.
  var given = document.getElementById('view3d-data');
  if (given) {
    var named = /[?&]analysis=([a-z0-9-]+)/.exec(window.location.search);
    show(JSON.parse(given.textContent), named ? named[1] : null);
    var asked = /[?&]view=([a-z0-9]+)/.exec(window.location.search);
    if (asked) {
      setView(asked[1]);
    }
  }
})();
