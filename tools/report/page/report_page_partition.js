// The partition map and the kernels' table (tools/report/report_page.h).
(function () {
  'use strict';
  const { el, num, secs, row, hue, clusterColour, canvasPoint, showTip, evaluationOf } = tmrReport;
  tmrReport.sections.push({ name: 'partition', draw: function (data, run, status) {
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
  } });
})();
