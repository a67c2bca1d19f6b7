// Draws the report page (tools/report/report_page.h): reads the data
// inline in #tmr-data, writes the summary, then each section of
// tmrReport.sections (report_page_*.js) on its canvases; no library, no
// network. When done it writes what it drew to #tmr-status (JSON), which
// the test reads.
(function () {
  'use strict';
  const { el, num, secs, evaluationOf } = tmrReport;
  const data = JSON.parse(document.getElementById('tmr-data').textContent);
  const run = data.run;
  const status = { drawn: false, errors: window.tmrErrors };
  function section(name, draw) {
    try { draw(data, run, status); } catch (e) {
      window.tmrErrors.push(name + ': ' + (e && e.stack ? e.stack : String(e)));
    }
  }
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
    const largest = data.models.length ? evaluationOf(data, data.models[0]) : null;
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
  for (const s of tmrReport.sections) section(s.name, s.draw);
  status.drawn = true;
  document.getElementById('tmr-status').textContent = JSON.stringify(status);
})();
