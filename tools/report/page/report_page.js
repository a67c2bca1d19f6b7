// The report page of a tmr run (tools/report/report_page.h): reads the
// data inline in #tmr-data and draws each section on a canvas; no library,
// no network. When done it writes what it drew to #tmr-status (JSON), which
// the test reads.
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('tmr-data').textContent);
  const run = data.run;
  const status = { drawn: false, errors: window.tmrErrors };

  // ---- helpers ----
  function el(tag, attrs, children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
    }
    for (const c of children || []) e.appendChild(c);
    return e;
  }
  function num(n) { return Number(n).toLocaleString('en-US'); }
  function secs(s) {
    return s < 100 ? s.toFixed(1) + ' s' : num(Math.round(s)) + ' s';
  }
  function row(cells, header) {
    return el('tr', {}, cells.map(function (c) {
      const cell = el(header ? 'th' : 'td', typeof c === 'object' ? c : { text: String(c) });
      return cell;
    }));
  }
  function hue(k) { return (k * 137.508) % 360; }
  function clusterColour(kernel, leaf, numLeaves) {
    if (kernel < 0) return '#999';
    const light = leaf < 0 ? 38 : 48 + (numLeaves > 1 ? 30 * leaf / (numLeaves - 1) : 15);
    return 'hsl(' + hue(kernel).toFixed(0) + ',70%,' + light.toFixed(0) + '%)';
  }
  function canvasPoint(canvas, event) {
    const r = canvas.getBoundingClientRect();
    return [(event.clientX - r.left) * canvas.width / r.width,
            (event.clientY - r.top) * canvas.height / r.height];
  }
  function showTip(tip, canvas, x, y, text) {
    if (!text) { tip.style.display = 'none'; return; }
    tip.textContent = text;
    tip.style.display = 'block';
    const r = canvas.getBoundingClientRect();
    tip.style.left = Math.min(x * r.width / canvas.width + 14, r.width - 200) + 'px';
    tip.style.top = (y * r.height / canvas.height + 14) + 'px';
  }
  function section(name, draw) {
    try { draw(); } catch (e) {
      window.tmrErrors.push(name + ': ' + (e && e.stack ? e.stack : String(e)));
    }
  }
  function evaluationOf(model) {
    if (!data.evaluation) return null;
    for (const e of data.evaluation.models || []) {
      const path = String(e.model).replace(/\/+$/, '');
      if (path.split('/').pop() === model.name) return e;
    }
    return null;
  }

  // ---- summary ----
  section('summary', function () {
    const sizes = run.model_sizes || [];
    const registered = sizes.reduce(function (a, b) { return a + b; }, 0);
    const parts = [
      ['photos', num(run.num_images)],
      ['models', num(sizes.length) + (sizes.length ? ' (largest ' + num(sizes[0]) + ')' : '')],
      ['registered', num(registered)],
      ['wall time', secs(run.total_s)],
      ['after the parallel tasks', (100 * (run.after_tasks_share || 0)).toFixed(0) + '%'],
      ['kernels', num((data.kernels || []).length)],
    ];
    const largest = data.models.length ? evaluationOf(data.models[0]) : null;
    if (largest && largest.aligned) {
      parts.push(['largest model, median rotation error',
                  largest.rotation_error_deg.median.toFixed(3) + '°']);
    }
    const box = document.getElementById('summary');
    for (const [label, value] of parts) {
      box.appendChild(el('span', {}, [document.createTextNode(label + ': '),
                                      el('b', { text: value })]));
    }
    status.photos = run.num_images;
  });

  // ---- models: a table, and a 3D view of the selected model ----
  section('models', function () {
    const models = data.models;
    const table = document.getElementById('model-table');
    const withEval = !!data.evaluation;
    table.appendChild(row(['model', 'photos', 'points', 'drawn', 'reproj. error (px)']
      .concat(withEval ? ['median rot. error', 'median pos. error', 'wrong merge', 'displaced'] : []), true));
    let drawnPoints = 0;
    const rows = models.map(function (m, i) {
      const e = evaluationOf(m);
      const cells = [m.name, num(m.registered), num(m.points), num(m.points_drawn),
                     m.mean_reprojection_error_px.toFixed(3)];
      if (withEval) {
        cells.push(e && e.aligned ? e.rotation_error_deg.median.toFixed(3) + '°' : '—',
                   e && e.aligned ? (100 * e.position_error_relative.median).toFixed(2) + '%' : '—',
                   e ? (e.wrong_merge ? 'yes' : 'no') : '—',
                   e ? num(e.displaced_images || 0) : '—');
      }
      drawnPoints += m.points_drawn;
      const r = row(cells);
      r.className = 'clickable';
      r.addEventListener('click', function () { select(i); });
      table.appendChild(r);
      return r;
    });
    const totalPoints = models.reduce(function (a, m) { return a + m.points; }, 0);
    document.getElementById('models-caption').textContent =
      models.length + ' models, largest first (' + num(drawnPoints) + ' of ' + num(totalPoints) +
      ' points drawn, at most ' + num(data.max_drawn_points) +
      '; points without colours are coloured by height). Click a model to view it; drag to turn it, wheel to zoom. Cameras are drawn as frusta.' +
      (withEval ? ' Errors against the ground truth (' + data.evaluation.reference + ').' : '');
    status.models = rows.length;
    status.points_drawn = drawnPoints;

    const canvas = document.getElementById('model-canvas');
    const ctx = canvas.getContext('2d');
    const view = { yaw: 0.6, pitch: 0.5, zoom: 1 };
    let scene = null;

    function decode(m) {
      const cams = [], pts = new Float32Array(m.xyz.length);
      const o = m.origin, s = m.step;
      for (let i = 0; i < m.xyz.length; i += 3) {
        pts[i] = o[0] + s * m.xyz[i]; pts[i + 1] = o[1] + s * m.xyz[i + 1]; pts[i + 2] = o[2] + s * m.xyz[i + 2];
      }
      for (let i = 0; i < m.cameras.length; i += 12) {
        const c = m.cameras;
        cams.push({ c: [o[0] + s * c[i], o[1] + s * c[i + 1], o[2] + s * c[i + 2]],
                    f: [c[i + 3] / 1e3, c[i + 4] / 1e3, c[i + 5] / 1e3],
                    r: [c[i + 6] / 1e3, c[i + 7] / 1e3, c[i + 8] / 1e3],
                    d: [c[i + 9] / 1e3, c[i + 10] / 1e3, c[i + 11] / 1e3] });
      }
      // The centre of the cameras, the size that holds 90% of cameras and
      // points around it, and "up" against the cameras' mean "down".
      const centre = [0, 0, 0], down = [0, 0, 0];
      for (const cam of cams) for (let k = 0; k < 3; ++k) { centre[k] += cam.c[k] / cams.length; down[k] += cam.d[k]; }
      const dists = cams.map(function (cam) { return Math.hypot(cam.c[0] - centre[0], cam.c[1] - centre[1], cam.c[2] - centre[2]); });
      for (let i = 0; i < pts.length; i += 3) dists.push(Math.hypot(pts[i] - centre[0], pts[i + 1] - centre[1], pts[i + 2] - centre[2]));
      dists.sort(function (a, b) { return a - b; });
      const radius = Math.max(dists.length ? dists[Math.floor(0.9 * (dists.length - 1))] : 1, 1e-6);
      const norm = Math.hypot(down[0], down[1], down[2]) || 1;
      const up = [-down[0] / norm, -down[1] / norm, -down[2] / norm];
      // Two axes across "up" for the orbit.
      const a = Math.abs(up[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
      let e1 = [up[1] * a[2] - up[2] * a[1], up[2] * a[0] - up[0] * a[2], up[0] * a[1] - up[1] * a[0]];
      const n1 = Math.hypot(e1[0], e1[1], e1[2]); e1 = e1.map(function (v) { return v / n1; });
      const e2 = [up[1] * e1[2] - up[2] * e1[1], up[2] * e1[0] - up[0] * e1[2], up[0] * e1[1] - up[1] * e1[0]];
      // Points without colours (a model mapped without --image_path) are
      // coloured by their height instead, from blue to orange.
      let rgb = m.rgb;
      if (!rgb.some(function (v) { return v > 0; })) {
        rgb = new Uint8Array(pts.length);
        const heights = [];
        for (let i = 0; i < pts.length; i += 3) heights.push(up[0] * pts[i] + up[1] * pts[i + 1] + up[2] * pts[i + 2]);
        const sorted = heights.slice().sort(function (x, y) { return x - y; });
        const low = sorted[Math.floor(0.02 * (sorted.length - 1))], high = sorted[Math.floor(0.98 * (sorted.length - 1))];
        heights.forEach(function (h, k) {
          const t = Math.max(0, Math.min(1, (h - low) / (high - low || 1)));
          rgb[3 * k] = 40 + 200 * t; rgb[3 * k + 1] = 90 + 60 * t; rgb[3 * k + 2] = 200 - 170 * t;
        });
      }
      return { model: m, cams: cams, pts: pts, rgb: rgb, centre: centre, radius: radius, up: up, e1: e1, e2: e2 };
    }

    function draw() {
      const w = canvas.width, h = canvas.height;
      ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, h);
      if (!scene) return;
      const cp = Math.cos(view.pitch), sp = Math.sin(view.pitch), cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
      // Viewing direction from the eye to the centre, and the screen axes.
      const back = [0, 1, 2].map(function (k) { return cp * (cy * scene.e1[k] + sy * scene.e2[k]) + sp * scene.up[k]; });
      const right = [0, 1, 2].map(function (k) { return -sy * scene.e1[k] + cy * scene.e2[k]; });
      const upv = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2], back[0] * right[1] - back[1] * right[0]];
      const dist = 2.2 * scene.radius / view.zoom;
      const eye = [0, 1, 2].map(function (k) { return scene.centre[k] + dist * back[k]; });
      const focal = 0.9 * Math.min(w, h) / 2 / Math.tan(Math.PI / 6);
      function project(p) {
        const d = [p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]];
        const z = -(d[0] * back[0] + d[1] * back[1] + d[2] * back[2]);
        if (z <= 1e-6 * scene.radius) return null;
        return [w / 2 + focal * (d[0] * right[0] + d[1] * right[1] + d[2] * right[2]) / z,
                h / 2 - focal * (d[0] * upv[0] + d[1] * upv[1] + d[2] * upv[2]) / z, z];
      }
      // Points into an image with a depth buffer, 2 x 2 pixels each.
      const image = ctx.getImageData(0, 0, w, h), px = image.data;
      const depth = new Float32Array(w * h).fill(Infinity);
      const p = [0, 0, 0];
      for (let i = 0; i < scene.pts.length; i += 3) {
        p[0] = scene.pts[i]; p[1] = scene.pts[i + 1]; p[2] = scene.pts[i + 2];
        const q = project(p);
        if (!q) continue;
        const x0 = Math.floor(q[0]), y0 = Math.floor(q[1]);
        for (let dy = 0; dy < 2; ++dy) for (let dx = 0; dx < 2; ++dx) {
          const x = x0 + dx, y = y0 + dy;
          if (x < 0 || y < 0 || x >= w || y >= h) continue;
          const at = y * w + x;
          if (q[2] >= depth[at]) continue;
          depth[at] = q[2];
          px[4 * at] = scene.rgb[i]; px[4 * at + 1] = scene.rgb[i + 1]; px[4 * at + 2] = scene.rgb[i + 2]; px[4 * at + 3] = 255;
        }
      }
      ctx.putImageData(image, 0, 0);
      // Cameras as frusta: the centre to the four corners at depth `size`.
      const size = 0.04 * scene.radius;
      ctx.strokeStyle = 'rgba(200, 30, 30, 0.8)'; ctx.lineWidth = 1;
      ctx.beginPath();
      for (const cam of scene.cams) {
        const c = project(cam.c);
        if (!c) continue;
        const corners = [[1, 1], [1, -1], [-1, -1], [-1, 1]].map(function (s) {
          return project([0, 1, 2].map(function (k) { return cam.c[k] + size * (cam.f[k] + s[0] * cam.r[k] + s[1] * cam.d[k]); }));
        });
        if (corners.some(function (q) { return !q; })) continue;
        for (const q of corners) { ctx.moveTo(c[0], c[1]); ctx.lineTo(q[0], q[1]); }
        ctx.moveTo(corners[3][0], corners[3][1]);
        for (const q of corners) ctx.lineTo(q[0], q[1]);
      }
      ctx.stroke();
    }

    function select(i) {
      rows.forEach(function (r, k) { r.classList.toggle('selected', k === i); });
      scene = decode(models[i]);
      view.zoom = 1;
      document.getElementById('model-view-caption').textContent =
        'Model ' + models[i].name + ': ' + num(models[i].registered) + ' cameras, ' +
        num(models[i].points_drawn) + ' of ' + num(models[i].points) + ' points drawn.';
      draw();
    }

    let dragging = null;
    canvas.addEventListener('mousedown', function (e) { dragging = [e.clientX, e.clientY]; });
    window.addEventListener('mouseup', function () { dragging = null; });
    window.addEventListener('mousemove', function (e) {
      if (!dragging) return;
      view.yaw += (e.clientX - dragging[0]) * 0.01;
      view.pitch = Math.max(-1.5, Math.min(1.5, view.pitch + (e.clientY - dragging[1]) * 0.01));
      dragging = [e.clientX, e.clientY];
      draw();
    });
    canvas.addEventListener('wheel', function (e) {
      e.preventDefault();
      view.zoom = Math.max(0.2, Math.min(50, view.zoom * Math.exp(-e.deltaY * 0.001)));
      draw();
    }, { passive: false });
    if (models.length) select(0); else draw();
  });

  // ---- the partition map ----
  section('partition', function () {
    const kernels = data.kernels || [];
    const ktable = document.getElementById('kernel-table');
    ktable.appendChild(row(['kernel', 'exemplar', 'kernel photos', 'cluster photos', 'leaf clusters'], true));
    kernels.forEach(function (k, i) {
      ktable.appendChild(row([i, { text: k.exemplar, class: 'text' }, num(k.kernel_images),
                              num(k.cluster_images), { text: k.leaves.join(', '), class: 'text' }]));
    });
    status.kernels = kernels.length;
    const caption = document.getElementById('partition-caption');
    const canvas = document.getElementById('map-canvas');
    const map = data.map;
    if (!map) {
      caption.textContent = kernels.length + ' kernels; no map: more photos than the report lays out.';
      canvas.style.display = 'none';
      status.map_photos = 0;
      return;
    }
    const n = map.names.length, w = canvas.width, margin = 20;
    const xy = new Float32Array(2 * n);
    for (let i = 0; i < 2 * n; ++i) xy[i] = margin + map.xy[i] / 10000 * (w - 2 * margin);
    const neighbours = Array.from({ length: n }, function () { return []; });
    for (let i = 0; i < map.edges.length; i += 3) {
      neighbours[map.edges[i]].push([map.edges[i + 1], map.edges[i + 2]]);
      neighbours[map.edges[i + 1]].push([map.edges[i], map.edges[i + 2]]);
    }
    const numLeaves = kernels.map(function (k) { return k.leaves.length; });
    const radius = Math.max(1.5, Math.min(5, w / Math.sqrt(8 * n)));
    const base = document.createElement('canvas');
    base.width = canvas.width; base.height = canvas.height;
    const b = base.getContext('2d');
    b.fillStyle = '#fff'; b.fillRect(0, 0, w, w);
    b.lineWidth = 0.5;
    for (let i = 0; i < map.edges.length; i += 3) {
      const u = map.edges[i], v = map.edges[i + 1];
      const shade = Math.round(235 - 120 * Math.min(1, map.edges[i + 2] / 300));
      b.strokeStyle = 'rgb(' + shade + ',' + shade + ',' + shade + ')';
      b.beginPath(); b.moveTo(xy[2 * u], xy[2 * u + 1]); b.lineTo(xy[2 * v], xy[2 * v + 1]); b.stroke();
    }
    for (let v = 0; v < n; ++v) {
      const k = map.kernel[v];
      if (k < 0) {
        b.strokeStyle = '#888'; b.lineWidth = 1.2; b.beginPath();
        b.moveTo(xy[2 * v] - radius, xy[2 * v + 1] - radius); b.lineTo(xy[2 * v] + radius, xy[2 * v + 1] + radius);
        b.moveTo(xy[2 * v] + radius, xy[2 * v + 1] - radius); b.lineTo(xy[2 * v] - radius, xy[2 * v + 1] + radius);
        b.stroke();
        continue;
      }
      b.fillStyle = clusterColour(k, map.leaf[v], numLeaves[k]);
      b.beginPath(); b.arc(xy[2 * v], xy[2 * v + 1], radius, 0, 2 * Math.PI); b.fill();
      if (map.leaf[v] < 0) { b.strokeStyle = '#000'; b.lineWidth = 0.8; b.stroke(); }
    }
    b.fillStyle = '#000'; b.font = '13px sans-serif';
    map.exemplars.forEach(function (v, k) {
      const r = 2 * radius + 2;
      b.fillRect(xy[2 * v] - r, xy[2 * v + 1] - r, 2 * r, 2 * r);
      b.fillText(String(k), xy[2 * v] + r + 3, xy[2 * v + 1] - r);
    });
    const ctx = canvas.getContext('2d');
    ctx.drawImage(base, 0, 0);
    caption.textContent = num(n) + ' photos in ' + kernels.length + ' kernels, laid out by their similarity ' +
      '(force-directed): a hue per kernel, a shade per leaf cluster; kernel photos outlined, exemplars as black ' +
      'squares with their kernel number, grey crosses for photos that reach no kernel. Hover a photo for its name, ' +
      'cluster and links.';
    status.map_photos = n;

    const tip = document.getElementById('map-tip');
    canvas.addEventListener('mousemove', function (e) {
      const [x, y] = canvasPoint(canvas, e);
      let best = -1, bestD = (3 * radius + 4) * (3 * radius + 4);
      for (let v = 0; v < n; ++v) {
        const d = (xy[2 * v] - x) * (xy[2 * v] - x) + (xy[2 * v + 1] - y) * (xy[2 * v + 1] - y);
        if (d < bestD) { bestD = d; best = v; }
      }
      ctx.drawImage(base, 0, 0);
      if (best < 0) { showTip(tip, canvas, x, y, ''); return; }
      const links = neighbours[best].slice().sort(function (p, q) { return q[1] - p[1]; });
      ctx.strokeStyle = '#c01c28'; ctx.lineWidth = 1.5; ctx.beginPath();
      for (const [u] of links) { ctx.moveTo(xy[2 * best], xy[2 * best + 1]); ctx.lineTo(xy[2 * u], xy[2 * u + 1]); }
      ctx.stroke();
      const k = map.kernel[best], l = map.leaf[best];
      const place = k < 0 ? 'reaches no kernel' : 'kernel ' + k + (l < 0 ? ' (kernel photo)' : ', leaf cluster ' + k + '.' + l) +
        (map.exemplars[k] === best ? ', its exemplar' : '');
      showTip(tip, canvas, x, y, map.names[best] + '\n' + place + '\n' + links.length + ' links' +
        (links.length ? '; strongest: ' + links.slice(0, 4).map(function (p) {
          return map.names[p[0]] + ' (' + (p[1] / 1000).toFixed(3) + ')';
        }).join(', ') : ''));
    });
    canvas.addEventListener('mouseleave', function () { ctx.drawImage(base, 0, 0); tip.style.display = 'none'; });
  });

  // ---- the timeline ----
  section('timeline', function () {
    const tasks = run.tasks || [];
    const critical = new Set(run.critical_path || []);
    const laneEnds = [], lane = [];
    const order = tasks.map(function (t, i) { return i; }).filter(function (i) { return tasks[i].in_task_graph; })
      .sort(function (a, b) { return tasks[a].start_s - tasks[b].start_s; });
    for (const i of order) {
      const t = tasks[i], end = t.start_s + (t.reused ? 0 : t.seconds);
      let l = laneEnds.findIndex(function (e) { return e <= t.start_s + 1e-3; });
      if (l < 0) { l = laneEnds.length; laneEnds.push(0); }
      laneEnds[l] = end; lane[i] = l;
    }
    const numLanes = laneEnds.length, serialLane = numLanes;
    const canvas = document.getElementById('timeline-canvas');
    const rowH = 26, top = 24, left = 90, w = canvas.width;
    canvas.height = top + (numLanes + 1) * rowH + 30;
    const ctx = canvas.getContext('2d');
    const total = Math.max(run.total_s || 0, 1e-9);
    const xOf = function (s) { return left + (w - left - 10) * s / total; };
    function colour(t) {
      if (!t.success) return '#e01b24';
      if (/^kernel/.test(t.task)) return '#3584e4';
      if (/^leaf/.test(t.task)) return '#33d17a';
      if (/^merge cluster/.test(t.task)) return '#ff7800';
      return '#9141ac';
    }
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, w, canvas.height);
    ctx.fillStyle = '#333'; ctx.font = '12px sans-serif';
    for (let l = 0; l < numLanes; ++l) ctx.fillText('worker ' + (l + 1), 4, top + l * rowH + 17);
    ctx.fillText('one thread', 4, top + serialLane * rowH + 17);
    const bars = [];
    const firstTask = order.length ? tasks[order[0]].start_s : 0;
    bars.push({ x0: xOf(0), x1: xOf(firstTask), lane: serialLane, text: 'partition and task databases: ' + secs(firstTask), fill: '#bbb', critical: false });
    tasks.forEach(function (t, i) {
      const seconds = t.reused ? 0 : t.seconds;
      if (!t.in_task_graph && seconds <= 0) return;  // links: part of their "align" step
      bars.push({ x0: xOf(t.start_s), x1: xOf(t.start_s + seconds), lane: t.in_task_graph ? lane[i] : serialLane,
                  fill: colour(t), critical: critical.has(i),
                  text: t.task + '\nstart ' + secs(t.start_s) + ', ' + secs(t.seconds) + (t.reused ? ' (finished by an earlier run)' : '') +
                        '\n' + num(t.registered) + ' of ' + num(t.images) + ' photos; peak ' + num(t.peak_mib) + ' MiB' +
                        (t.message ? '\n' + t.message : '') + (critical.has(i) ? '\non the critical path' : '') });
    });
    for (const bar of bars) {
      const y = top + bar.lane * rowH + 3;
      ctx.fillStyle = bar.fill;
      ctx.fillRect(bar.x0, y, Math.max(bar.x1 - bar.x0, 1), rowH - 6);
      if (bar.critical) { ctx.strokeStyle = '#000'; ctx.lineWidth = 2; ctx.strokeRect(bar.x0, y, Math.max(bar.x1 - bar.x0, 1), rowH - 6); }
    }
    const tasksEnd = run.tasks_end_s || 0;
    ctx.strokeStyle = '#000'; ctx.setLineDash([4, 3]); ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(xOf(tasksEnd), top - 6); ctx.lineTo(xOf(tasksEnd), top + (numLanes + 1) * rowH); ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = '#000';
    ctx.fillText('tasks end ' + secs(tasksEnd), Math.min(xOf(tasksEnd) + 4, w - 120), 14);
    const axisY = top + (numLanes + 1) * rowH + 16;
    for (let k = 0; k <= 5; ++k) ctx.fillText(secs(total * k / 5), xOf(total * k / 5) - (k === 5 ? 40 : 0), axisY);
    const projected = Object.entries(run.projected_wall_s || {}).map(function (p) { return p[0] + ': ' + secs(p[1]); }).join(', ');
    document.getElementById('timeline-caption').textContent =
      tasks.length + ' steps on ' + (run.workers || numLanes) + ' workers in ' + secs(run.total_s) + '; ' +
      secs(Math.max(0, run.total_s - tasksEnd)) + ' (' + (100 * (run.after_tasks_share || 0)).toFixed(0) +
      '%) after the parallel tasks. Blue kernels, green leaf clusters, orange cluster merges, purple the scene ' +
      'assembly, red failed steps; outlined: the critical path (' + secs(run.critical_path_s || 0) +
      '). The same steps on more workers: ' + projected + '.';
    status.tasks = tasks.length;
    status.critical_path = critical.size;
    const tip = document.getElementById('timeline-tip');
    canvas.addEventListener('mousemove', function (e) {
      const [x, y] = canvasPoint(canvas, e);
      const hit = bars.find(function (bar) {
        const by = top + bar.lane * rowH;
        return y >= by && y < by + rowH && x >= bar.x0 - 2 && x <= Math.max(bar.x1, bar.x0 + 1) + 2;
      });
      showTip(tip, canvas, x, y, hit ? hit.text : '');
    });
    canvas.addEventListener('mouseleave', function () { tip.style.display = 'none'; });
  });

  // ---- merges: each "align" step's graph of models, links held or refused ----
  section('merges', function () {
    const tasks = run.tasks || [];
    const steps = [];
    tasks.forEach(function (t) {
      if (/^align /.test(t.task)) steps.push({ name: t.task, links: [] });
      else if (t.link && steps.length) steps[steps.length - 1].links.push(t);
    });
    const table = document.getElementById('link-table');
    table.appendChild(row(['step', 'models (photos)', 'link', { text: 'what the alignment found', class: 'text' }], true));
    let refused = 0, links = 0;
    steps.forEach(function (step, s) {
      for (const t of step.links) {
        ++links;
        if (!t.success) ++refused;
        const r = row([s + 1, 'm' + t.link[0] + ' (' + num(t.link[2]) + ') – m' + t.link[1] + ' (' + num(t.link[3]) + ')',
                       t.success ? 'held' : 'refused', { text: t.message, class: 'text' }]);
        if (!t.success) r.className = 'refused';
        table.appendChild(r);
      }
    });
    status.links = links;
    status.refused_links = refused;
    const weak = run.weak_links || [];
    const wtable = document.getElementById('weak-table');
    wtable.appendChild(row(['models', 'verified pairs', 'matches', 'shared tracks', 'registered on the other', { text: 'why apart', class: 'text' }], true));
    for (const l of weak) {
      wtable.appendChild(row([l.models.join(' – '), num(l.verified_pairs), num(l.correspondences), num(l.shared_tracks),
                              num(l.registered_images), { text: l.reason, class: 'text' }]));
    }
    status.weak_links = weak.length;
    document.getElementById('merges-caption').textContent =
      (steps.length ? steps.length + ' alignment step' + (steps.length > 1 ? 's' : '') + ' (' +
       steps.map(function (s) { return s.name; }).join('; ') + '): ' + links + ' linked pairs of models, ' +
       refused + ' refused. ' : 'No alignment step: one model, or nothing linked. ') +
      'Each graph: the models of a step (m0 the largest) as discs by size; green links held by the similarity ' +
      'averaging, red dashed links refused; hover a link for the reason. ' + weak.length +
      ' pair' + (weak.length === 1 ? '' : 's') + ' of final models linked by matches stayed apart (table below).';
    const canvas = document.getElementById('links-canvas');
    if (!steps.length) { canvas.style.display = 'none'; return; }
    const panel = 440, perRow = 2;
    canvas.width = Math.min(steps.length, perRow) * panel;
    canvas.height = Math.ceil(steps.length / perRow) * panel;
    const ctx = canvas.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, canvas.width, canvas.height);
    const segments = [];
    steps.forEach(function (step, s) {
      const ox = (s % perRow) * panel, oy = Math.floor(s / perRow) * panel;
      const size = new Map();
      for (const t of step.links) { size.set(t.link[0], t.link[2]); size.set(t.link[1], t.link[3]); }
      const ids = Array.from(size.keys()).sort(function (a, b) { return a - b; });
      const maxSize = Math.max.apply(null, Array.from(size.values()).concat([1]));
      const pos = new Map();
      ids.forEach(function (id, k) {
        const a = 2 * Math.PI * k / ids.length - Math.PI / 2;
        pos.set(id, [ox + panel / 2 + 0.36 * panel * Math.cos(a), oy + panel / 2 + 0.36 * panel * Math.sin(a)]);
      });
      for (const t of step.links) {
        const p = pos.get(t.link[0]), q = pos.get(t.link[1]);
        ctx.strokeStyle = t.success ? '#26a269' : '#c01c28';
        ctx.lineWidth = t.success ? 2 : 1.5;
        ctx.setLineDash(t.success ? [] : [5, 4]);
        ctx.beginPath(); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
        segments.push({ p: p, q: q, text: 'm' + t.link[0] + ' – m' + t.link[1] + ': ' + (t.success ? 'held' : 'refused') + '\n' + t.message });
      }
      ctx.setLineDash([]);
      ctx.font = '12px sans-serif';
      for (const id of ids) {
        const p = pos.get(id), r = 5 + 20 * Math.sqrt(size.get(id) / maxSize);
        ctx.fillStyle = 'hsl(' + hue(id).toFixed(0) + ',60%,75%)';
        ctx.beginPath(); ctx.arc(p[0], p[1], r, 0, 2 * Math.PI); ctx.fill();
        ctx.strokeStyle = '#333'; ctx.lineWidth = 1; ctx.stroke();
        ctx.fillStyle = '#000';
        ctx.textAlign = 'center';
        ctx.fillText('m' + id + ' (' + num(size.get(id)) + ')', p[0], p[1] + r + 14);
        ctx.textAlign = 'start';
      }
      ctx.fillText('step ' + (s + 1), ox + 8, oy + 16);
    });
    const tip = document.getElementById('links-tip');
    canvas.addEventListener('mousemove', function (e) {
      const [x, y] = canvasPoint(canvas, e);
      let best = null, bestD = 36;
      for (const seg of segments) {
        const dx = seg.q[0] - seg.p[0], dy = seg.q[1] - seg.p[1];
        const t = Math.max(0, Math.min(1, ((x - seg.p[0]) * dx + (y - seg.p[1]) * dy) / (dx * dx + dy * dy || 1)));
        const d = Math.pow(seg.p[0] + t * dx - x, 2) + Math.pow(seg.p[1] + t * dy - y, 2);
        if (d < bestD) { bestD = d; best = seg; }
      }
      showTip(tip, canvas, x, y, best ? best.text : '');
    });
    canvas.addEventListener('mouseleave', function () { tip.style.display = 'none'; });
  });

  status.drawn = true;
  document.getElementById('tmr-status').textContent = JSON.stringify(status);
})();
