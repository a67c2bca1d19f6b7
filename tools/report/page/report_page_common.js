// The report page's shared helpers (tools/report/report_page.h). Each
// section's file adds itself to tmrReport.sections as
// {name, draw(data, run, status)}; report_page_main.js draws them in order.
var tmrReport = (function () {
  'use strict';
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
  // The scores tmr_eval wrote for a model (data.evaluation), or null.
  function evaluationOf(data, model) {
    if (!data.evaluation) return null;
    for (const e of data.evaluation.models || []) {
      const path = String(e.model).replace(/\/+$/, '');
      if (path.split('/').pop() === model.name) return e;
    }
    return null;
  }

  return { sections: [], el, num, secs, row, hue, clusterColour, canvasPoint, showTip, evaluationOf };
})();
