// The timeline: tasks on their workers, the assembly on one thread, the critical path (tools/report/report_page.h).
(function () {
  'use strict';
  const { el, num, secs, row, hue, clusterColour, canvasPoint, showTip, evaluationOf } = tmrReport;
  tmrReport.sections.push({ name: 'timeline', draw: function (data, run, status) {
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
  } });
})();
