// The models: a table, and a 3D view of the selected model (tools/report/report_page.h).
(function () {
  'use strict';
  const { el, num, secs, row, hue, clusterColour, canvasPoint, showTip, evaluationOf } = tmrReport;
  tmrReport.sections.push({ name: 'models', draw: function (data, run, status) {
    const models = data.models;
    const table = document.getElementById('model-table');
    const withEval = !!data.evaluation;
    table.appendChild(row(['model', 'photos', 'points', 'drawn', 'reproj. error (px)']
      .concat(withEval ? ['median rot. error', 'median pos. error', 'wrong merge', 'displaced'] : []), true));
    let drawnPoints = 0;
    const rows = models.map(function (m, i) {
      const e = evaluationOf(data, m);
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
      // Smaller and lighter where cameras are many, so that the points show.
      const many = scene.cams.length;
      const size = Math.min(0.04, 0.5 / Math.sqrt(many)) * scene.radius;
      ctx.strokeStyle = many > 1000 ? 'rgba(200, 30, 30, 0.35)' : 'rgba(200, 30, 30, 0.8)';
      ctx.lineWidth = 1;
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
  } });
})();
