// The merges: each "align" step's graph of models, links held or refused, and the models that stayed apart (tools/report/report_page.h).
(function () {
  'use strict';
  const { el, num, secs, row, hue, clusterColour, canvasPoint, showTip, evaluationOf } = tmrReport;
  tmrReport.sections.push({ name: 'merges', draw: function (data, run, status) {
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
  } });
})();
