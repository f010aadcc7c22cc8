#include "engine/report/page_script.h"

namespace hitl::report {

const char* const kPageScript = R"hitljs((function () {
  'use strict';
  var data = JSON.parse(document.getElementById('hitl-data').textContent);
  var palette = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22'];
  var styled = {setpoint: ['#7f7f7f', [7, 4]], truth: ['#1f77b4', null], estimate: ['#ff7f0e', null], reference: ['#555555', [2, 3]]};
  var severityColor = {info: '#2ca02c', notice: '#1f77b4', warning: '#ff7f0e', error: '#d62728'};
  var modeTints = ['rgba(31,119,180,0.08)', 'rgba(44,160,44,0.09)', 'rgba(148,103,189,0.09)', 'rgba(140,86,75,0.09)',
                   'rgba(188,189,34,0.10)', 'rgba(23,190,207,0.09)', 'rgba(227,119,194,0.09)', 'rgba(127,127,127,0.09)'];
  var modeNames = [];
  data.modes.forEach(function (m) { if (modeNames.indexOf(m.mode) < 0) modeNames.push(m.mode); });
  function modeTint(mode) { return modeTints[modeNames.indexOf(mode) % modeTints.length]; }

  function escaped(text) {
    return String(text).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
  }
  function number(v) { return Math.abs(v) >= 1e5 ? v.toExponential(4) : String(+v.toFixed(4)); }
  // Delta-coded milliseconds to seconds.
  function times(coded) {
    var t = new Array(coded.length), ms = 0;
    for (var i = 0; i < coded.length; ++i) { ms += coded[i]; t[i] = ms / 1000; }
    return t;
  }
  // dygraphs' table: the union of the series' times, null where a series has no sample; the log's
  // first and last time as empty rows, so that every time plot spans the same axis.
  function table(ts, ys, range) {
    var k = ts.length, at = [], out = [], j, x, row;
    for (j = 0; j < k; ++j) at.push(0);
    function empty(t) { var r = [t]; for (var n = 0; n < k; ++n) r.push(null); return r; }
    for (;;) {
      x = Infinity;
      for (j = 0; j < k; ++j) if (at[j] < ts[j].length && ts[j][at[j]] < x) x = ts[j][at[j]];
      if (x === Infinity) break;
      if (out.length === 0 && range && range[0] < x) out.push(empty(range[0]));
      row = [x];
      for (j = 0; j < k; ++j) {
        if (at[j] < ts[j].length && ts[j][at[j]] === x) row.push(ys[j][at[j]++]);
        else row.push(null);
      }
      out.push(row);
    }
    if (range && out.length > 0 && range[1] > out[out.length - 1][0]) out.push(empty(range[1]));
    return out;
  }
  // A series' value at time x: its last sample at or before x (null before its first).
  function valueAt(t, y, x) {
    var lo = 0, hi = t.length - 1;
    if (hi < 0 || x < t[0]) return null;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (t[mid] <= x) lo = mid; else hi = mid - 1;
    }
    return y[lo];
  }
  function legend(ts, ys) {
    return function (d) {
      var vis = d.dygraph.visibility(), html = d.x === undefined ? '' : '<b>t = ' + d.x.toFixed(3) + ' s</b>';
      for (var i = 0; i < d.series.length; ++i) {
        var s = d.series[i], value = '';
        if (d.x !== undefined) {
          var v = valueAt(ts[i], ys[i], d.x);
          value = ': ' + (v === null ? '-' : number(v));
        }
        html += '<span class="series' + (vis[i] ? '' : ' off') + '" data-i="' + i + '" title="click: show or hide">' +
                '<i style="background:' + s.color + '"></i>' + escaped(s.label) + value + '</span>';
      }
      return html;
    };
  }
  function underlay(ctx, area, g) {
    ctx.save();
    ctx.beginPath();
    ctx.rect(area.x, area.y, area.w, area.h);
    ctx.clip();
    ctx.font = '10px sans-serif';
    function span(t0, t1) {
      var a = Math.max(area.x, g.toDomXCoord(t0)), b = Math.min(area.x + area.w, g.toDomXCoord(t1));
      return b > a ? [a, b] : null;
    }
    data.modes.forEach(function (m) {
      var s = span(m.t0, m.t1);
      if (!s) return;
      ctx.fillStyle = modeTint(m.mode);
      ctx.fillRect(s[0], area.y, s[1] - s[0], area.h);
      if (s[1] - s[0] > 40) { ctx.fillStyle = '#777'; ctx.fillText(m.mode, s[0] + 3, area.y + area.h - 4); }
    });
    data.faults.forEach(function (f, i) {
      var s = span(f.t0, f.t1);
      if (!s) return;
      ctx.fillStyle = 'rgba(214,39,40,0.13)';
      ctx.fillRect(s[0], area.y, Math.max(2, s[1] - s[0]), area.h);
      ctx.fillStyle = '#b00';
      ctx.fillText(f.label, s[0] + 3, area.y + 11 + 11 * (i % 3));
    });
    data.events.forEach(function (e) {
      var x = g.toDomXCoord(e.t);
      if (x < area.x || x > area.x + area.w) return;
      ctx.strokeStyle = severityColor[e.severity] || '#2ca02c';
      ctx.setLineDash([2, 3]);
      ctx.beginPath();
      ctx.moveTo(x, area.y);
      ctx.lineTo(x, area.y + area.h);
      ctx.stroke();
    });
    ctx.restore();
  }

  var graphs = [], ids = [];
  data.plots.forEach(function (p, index) {
    var figure = document.getElementById('plot-' + p.id);
    var ts = p.series.map(function (s) { return times(s.t); }), ys = p.series.map(function (s) { return s.y; });
    var labels = ['t'], colors = [], perSeries = {}, plain = 0;
    p.series.forEach(function (s) {
      var look = styled[s.style] || [palette[plain++ % palette.length], null];
      labels.push(s.title);
      colors.push(look[0]);
      perSeries[s.title] = {strokePattern: look[1], strokeWidth: s.style === 'reference' ? 1 : 1.4};
    });
    var values = figure.querySelector('.values');
    var g = new Dygraph(figure.querySelector('.graph'), table(ts, ys, data.x_range), {
      labels: labels, colors: colors, series: perSeries, title: p.title, xlabel: data.time_label, ylabel: p.y_label,
      connectSeparatedPoints: true, legend: 'always', labelsDiv: values, labelsShowZeroValues: true,
      legendFormatter: legend(ts, ys), underlayCallback: underlay, showRangeSelector: index === 0, rangeSelectorHeight: 32,
      axes: {x: {valueFormatter: function (x) { return x.toFixed(3) + ' s'; }}}, animatedZooms: false
    });
    values.addEventListener('click', function (e) {
      var item = e.target.closest('[data-i]');
      if (item) g.setVisibility(+item.getAttribute('data-i'), !g.visibility()[+item.getAttribute('data-i')]);
    });
    graphs.push(g);
    ids.push(p.id);
  });
  // The row of g nearest to time x (the plots' rows are at different times: the synchronizer's own
  // selection link finds only a row at exactly x).
  function nearestRow(g, x) {
    var lo = 0, hi = g.numRows() - 1;
    if (hi < 0) return null;
    while (lo < hi) {
      var mid = (lo + hi) >> 1;
      if (g.getValue(mid, 0) < x) lo = mid + 1; else hi = mid;
    }
    if (lo > 0 && Math.abs(g.getValue(lo - 1, 0) - x) < Math.abs(g.getValue(lo, 0) - x)) --lo;
    return lo;
  }
  if (graphs.length > 1) {
    Dygraph.synchronize(graphs, {zoom: true, selection: false, range: false});
    var linking = false;
    graphs.forEach(function (g) {
      g.updateOptions({
        highlightCallback: function (e, x) {
          if (linking) return;
          linking = true;
          graphs.forEach(function (other) {
            var row = other === g ? null : nearestRow(other, x);
            if (row !== null) other.setSelection(row);
          });
          linking = false;
        },
        unhighlightCallback: function () {
          if (linking) return;
          linking = true;
          graphs.forEach(function (other) { if (other !== g) other.clearSelection(); });
          linking = false;
        }
      }, true);
    });
  }
  window.hitlReport = {graphs: graphs, ids: ids, drawn_ms: performance.now()};
})();
)hitljs";

}  // namespace hitl::report
