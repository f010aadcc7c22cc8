#include "engine/campaign/campaign_page_script.h"

namespace hitl::campaign {

const char* const kCampaignPageScript = R"hitljs((function () {
  'use strict';
  var started = Date.now();
  var data = JSON.parse(document.getElementById('hitl-campaign-data').textContent);
  var graphs = [], ids = [];
  function escaped(text) {
    return String(text).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
  }
  function number(v) { return v === null || v === undefined || isNaN(v) ? '-' : String(+Number(v).toPrecision(4)); }
  // Categories on the x axis (0, 1, 2, ...): as many labels as fit, each label's parts on lines of
  // their own (dygraphs puts a label in as HTML: escaped here).
  function categories(names, separator) {
    var longest = 1;
    names.forEach(function (n) { n.split(separator).forEach(function (p) { longest = Math.max(longest, p.length); }); });
    var labelPx = Math.ceil(longest * 6.5) + 10;  // 11 px labels
    return {
      ticker: function (min, max, pixels) {
        var first = Math.max(0, Math.ceil(min)), last = Math.min(names.length - 1, Math.floor(max)), ticks = [];
        var step = Math.max(1, Math.ceil((last - first + 1) * labelPx / Math.max(pixels, 1)));
        for (var i = first; i <= last; i += step) ticks.push({v: i, label: names[i].split(separator).map(escaped).join('<br>')});
        return ticks;
      },
      valueFormatter: function (x) { return names[Math.round(x)] || ''; },
      axisLabelWidth: labelPx,
      axisLabelFontSize: 11,
      drawGrid: false
    };
  }
  // Each cell's min to max as a whisker with caps, its median as a dot (customBars: [min, median, max]).
  function whiskers(e) {
    var ctx = e.drawingContext, area = e.plotArea;
    ctx.save();
    ctx.strokeStyle = e.color;
    ctx.fillStyle = e.color;
    ctx.lineWidth = 2;
    e.points.forEach(function (p) {
      if (p.yval === null || isNaN(p.canvasy)) return;
      var top = isNaN(p.y_top) ? p.canvasy : area.h * p.y_top + area.y;
      var bottom = isNaN(p.y_bottom) ? p.canvasy : area.h * p.y_bottom + area.y;
      ctx.beginPath();
      ctx.moveTo(p.canvasx, top); ctx.lineTo(p.canvasx, bottom);
      ctx.moveTo(p.canvasx - 6, top); ctx.lineTo(p.canvasx + 6, top);
      ctx.moveTo(p.canvasx - 6, bottom); ctx.lineTo(p.canvasx + 6, bottom);
      ctx.stroke();
      ctx.beginPath();
      ctx.arc(p.canvasx, p.canvasy, 4, 0, 2 * Math.PI);
      ctx.fill();
    });
    ctx.restore();
  }
  function showValues(figure, text) { figure.querySelector('.values').textContent = text; }
  function draw(figure, rows, options, idle) {
    showValues(figure, idle);
    options.legend = 'never';
    options.unhighlightCallback = function () { showValues(figure, idle); };
    var g = new Dygraph(figure.querySelector('.graph'), rows, options);
    graphs.push(g);
    ids.push(figure.id);
  }

  data.distributions.forEach(function (d) {
    var figure = document.getElementById(d.id);
    if (!figure) return;
    // The limit is drawn when it is near the figures (within their span of them); far from them it
    // would squeeze the spread flat, and the caption says where it is.
    var low = Infinity, high = -Infinity;
    d.rows.forEach(function (r) { if (r) { low = Math.min(low, r[0]); high = Math.max(high, r[2]); } });
    var span = Math.max(high - low, 0.1 * Math.max(Math.abs(low), Math.abs(high)), 1e-9);
    var near = d.limit >= low - span && d.limit <= high + span;
    var limitNote = near ? 'dashed: the limit ' + d.limit_text
                         : 'the limit ' + d.limit_text + ' is ' + (d.limit > high ? 'above' : 'below') + ' the plot';
    var rows = d.rows.map(function (r, i) { return [i, r, near ? [d.limit, d.limit, d.limit] : null]; });
    var n = data.cells.length;
    draw(figure, rows, {
      labels: ['cell', 'median', 'limit'],  // fixed names: a criterion may be called anything
      customBars: true,
      title: escaped(d.criterion),
      ylabel: escaped(d.figure),
      xAxisHeight: 40,
      dateWindow: [-0.5, n - 0.5],
      colors: ['#1f77b4', '#d62728'],
      plotter: [Dygraph.Plotters.linePlotter],
      series: {median: {plotter: whiskers}, limit: {strokePattern: [6, 4], strokeWidth: 1.5}},
      axes: {x: categories(data.cells, ' / '), y: {axisLabelFormatter: number}},
      highlightCallback: function (event, x, points, row) {
        var r = d.rows[row];
        showValues(figure, data.cells[row] + ': ' + (r ? 'min ' + number(r[0]) + ', median ' + number(r[1]) + ', max ' + number(r[2])
                                                      : 'no figure') + ' (limit ' + d.limit_text + ')');
      }
    }, d.criterion + ': ' + d.figure + ' per cell; ' + limitNote + '; the cursor on a cell shows its figures');
  });

  data.trends.forEach(function (t) {
    var figure = document.getElementById(t.id);
    if (!figure) return;
    var numeric = t.series.length > 1;
    var labels = ['run'].concat(t.series), rows = t.rows.map(function (r, i) { return [i].concat(r); });
    var limitNote = '';
    if (numeric && t.limit !== null) {
      var low = Infinity, high = -Infinity;
      t.rows.forEach(function (r) { [r[0], r[1]].forEach(function (v) { if (v !== null) { low = Math.min(low, v); high = Math.max(high, v); } }); });
      var span = Math.max(high - low, 0.1 * Math.max(Math.abs(low), Math.abs(high)), 1e-9);
      if (t.limit >= low - span && t.limit <= high + span) {
        labels.push('limit');
        rows.forEach(function (r) { r.push(t.limit); });
        limitNote = '; dashed: the limit';
      } else {
        limitNote = '; the limit is ' + (t.limit > high ? 'above' : 'below') + ' the plot';
      }
    }
    var series = {'broke it': {axis: numeric ? 'y2' : 'y', stepPlot: true, strokePattern: [2, 3]},
                  limit: {strokePattern: [6, 4], drawPoints: false}};
    var n = t.runs.length;
    draw(figure, rows, {
      labels: labels,
      title: escaped(t.criterion),
      ylabel: numeric ? escaped(t.figure) : 'flights that broke it',
      y2label: numeric ? 'flights that broke it' : undefined,
      drawPoints: true,
      pointSize: 3,
      xAxisHeight: 40,
      dateWindow: [-0.5, n - 0.5],
      colors: ['#1f77b4', '#ff7f0e', '#7f7f7f', '#d62728'].slice(0, labels.length - 1),
      series: series,
      axes: {x: categories(t.ticks, '\n'), y: {axisLabelFormatter: number}, y2: {independentTicks: true, axisLabelFormatter: number}},
      underlayCallback: function (ctx, area, g) {
        if (!t.regression) return;
        var left = g.toDomXCoord(n - 1.5), right = g.toDomXCoord(n - 0.5);
        ctx.fillStyle = 'rgba(214,39,40,0.15)';
        ctx.fillRect(left, area.y, right - left, area.h);
      },
      highlightCallback: function (event, x, points, row) {
        var r = t.rows[row], parts = t.series.map(function (name, i) { return name + ' ' + number(r[i]); });
        showValues(figure, t.runs[row] + ': ' + parts.join(', '));
      }
    }, t.criterion + ': ' + t.figure + ' ' + t.limit_text + limitNote + (t.regression ? ' (REGRESSION in the latest run, shaded)' : ''));
  });

  window.hitlCampaign = {graphs: graphs, ids: ids, drawn_ms: Date.now() - started};
})();
)hitljs";

}  // namespace hitl::campaign
