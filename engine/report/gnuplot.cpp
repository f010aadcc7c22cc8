#include "engine/report/gnuplot.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/common/bounded_read.h"
#include "engine/net/child_process.h"

namespace hitl::report {
namespace {

constexpr std::size_t kMaxSvgBytes = 64u << 20;

/// A gnuplot string literal in single quotes (no escapes inside them but '' for ').
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out + "'";
}

std::string style_of(SeriesStyle style, std::size_t plain_index) {
  static const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
  switch (style) {
    case SeriesStyle::Setpoint: return "lc rgb '#7f7f7f' lw 1.5 dt 2";
    case SeriesStyle::Truth: return "lc rgb '#1f77b4' lw 1.5";
    case SeriesStyle::Estimate: return "lc rgb '#ff7f0e' lw 1.2";
    case SeriesStyle::Reference: return "lc rgb '#555555' lw 1 dt 3";
    case SeriesStyle::Plain: return std::string("lc rgb '") + kPalette[plain_index % 8] + "' lw 1.2";
  }
  return "";
}

const char* marker_color(Severity s) {
  switch (s) {
    case Severity::Info: return "#2ca02c";
    case Severity::Notice: return "#1f77b4";
    case Severity::Warning: return "#ff7f0e";
    case Severity::Error: return "#d62728";
  }
  return "#2ca02c";
}


}  // namespace

std::string gnuplot_script(const std::vector<Plot>& plots, const TimeMarks& marks, const std::string& dir,
                           const GnuplotOptions& options) {
  std::ostringstream s;
  s.precision(9);
  for (std::size_t p = 0; p < plots.size(); ++p) {
    const auto& plot = plots[p];
    for (std::size_t k = 0; k < plot.series.size(); ++k) {
      s << "$d" << p << "_" << k << " << EOD\n";
      for (std::size_t i = 0; i < plot.series[k].x.size(); ++i)
        if (std::isfinite(plot.series[k].x[i]) && std::isfinite(plot.series[k].y[i]))  // a damaged log's NaN is not drawn
          s << plot.series[k].x[i] << ' ' << plot.series[k].y[i] << '\n';
      s << "EOD\n";
    }
  }
  for (std::size_t p = 0; p < plots.size(); ++p) {
    const auto& plot = plots[p];
    s << "reset\n";
    s << "set terminal svg size " << options.width_px << ',' << (plot.equal_axes ? options.width_px * 2 / 3 : options.height_px)
      << " dynamic noenhanced font 'sans,11' background rgb 'white'\n";
    s << "set output " << quoted(dir + "/" + plot.id + ".svg") << "\n";
    s << "set title " << quoted(plot.title) << "\nset xlabel " << quoted(plot.x_label) << "\nset ylabel " << quoted(plot.y_label) << "\n";
    s << "set grid\nset key outside right top vertical\nset border 3\nset tics nomirror\n";
    if (plot.equal_axes) s << "set size ratio -1\n";
    if (plot.log_axes) s << "set logscale xy\nset format y '%.0e'\n";
    if (plot.time_axis && plot.x_max > plot.x_min) s << "set xrange [" << plot.x_min << ":" << plot.x_max << "]\n";
    if (plot.time_axis) {
      static const char* const kModeTints[] = {"#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#bcbd22", "#17becf", "#e377c2", "#7f7f7f"};
      std::vector<std::string> mode_names;
      int object = 1;
      for (const auto& m : marks.modes) {
        auto at = std::find(mode_names.begin(), mode_names.end(), m.label);
        if (at == mode_names.end()) at = mode_names.insert(mode_names.end(), m.label);
        const auto tint = kModeTints[static_cast<std::size_t>(at - mode_names.begin()) % 8];
        s << "set object " << object++ << " rect from first " << m.start_s << ", graph 0 to first " << m.end_s
          << ", graph 1 behind fc rgb '" << tint << "' fs transparent solid 0.08 noborder\n";
        if (m.end_s - m.start_s >= 0.04 * (plot.x_max - plot.x_min))  // a name only where it fits
          s << "set label " << object << " " << quoted(m.label) << " at first " << m.start_s
            << ", graph 0.03 left offset 0.3,0 tc rgb '#777777' font ',8' front\n";
      }
      for (const auto& f : marks.faults) {
        s << "set object " << object++ << " rect from first " << f.start_s << ", graph 0 to first " << f.end_s
          << ", graph 1 behind fc rgb '#d62728' fs transparent solid 0.13 noborder\n";
        s << "set label " << object << " " << quoted(f.label) << " at first " << f.start_s
          << ", graph 0.95 left offset 0.3,0 tc rgb '#b00000' font ',9' front\n";
      }
    }
    if (plot.time_axis)
      for (const auto& m : marks.events)
        s << "set arrow from " << m.t_s << ", graph 0 to " << m.t_s << ", graph 1 nohead back lc rgb '" << marker_color(m.severity)
          << "' lw 0.8 dt 3\n";
    s << "plot ";
    std::size_t plain = 0;
    for (std::size_t k = 0; k < plot.series.size(); ++k) {
      const auto& series = plot.series[k];
      s << (k ? ", " : "") << "$d" << p << "_" << k << " using 1:2 with lines "
        << style_of(series.style, series.style == SeriesStyle::Plain ? plain++ : 0) << " title " << quoted(series.title);
    }
    s << "\nunset output\n";
  }
  return s.str();
}

namespace {

/// gnuplot's complaint, as one short line: its last non-empty line.
std::string last_line(const std::string& text) {
  std::string line, last;
  std::istringstream in(text);
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t^") != std::string::npos) last = line;
  return last.size() > 200 ? last.substr(0, 200) + "..." : last;
}

}  // namespace

Expected<std::vector<std::string>> render_svgs(const std::vector<Plot>& plots, const TimeMarks& marks,
                                               const GnuplotOptions& options, std::vector<std::string>* failed) {
  const auto gnuplot = net::find_on_path("gnuplot");
  if (!gnuplot)
    return Error::unavailable("gnuplot is not installed (Debian/Ubuntu: apt-get install gnuplot-nox); hitl report draws its plots with it");
  std::string tmpl = (std::filesystem::temp_directory_path() / "hitl-report-XXXXXX").string();
  if (::mkdtemp(tmpl.data()) == nullptr) return Error::failed("cannot make a temporary directory under " + std::filesystem::temp_directory_path().string());
  const std::string dir = tmpl;
  struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } cleanup{dir};
  const std::string script_path = dir + "/report.gp";
  // Draws `some` of the plots in one run; gnuplot's exit code and complaint.
  auto draw = [&](const std::vector<Plot>& some) -> Expected<std::pair<int, std::string>> {
    {
      std::ofstream script(script_path, std::ios::trunc);
      script << gnuplot_script(some, marks, dir, options);
      if (!script.flush()) return Error::failed("cannot write " + script_path);
    }
    auto ran = net::run_program(*gnuplot, {script_path}, options.timeout_ms);
    if (!ran) return ran.error();
    return std::pair{ran->exit_code, ran->err};
  };
  auto all = draw(plots);
  if (!all) return all.error();
  std::vector<bool> drawn(plots.size(), all->first == 0);
  if (all->first != 0) {  // one plot gnuplot cannot draw stops the script: draw each on its own
    for (std::size_t i = 0; i < plots.size(); ++i) {
      auto one = draw({plots[i]});
      if (!one) return one.error();
      drawn[i] = one->first == 0;
      if (!drawn[i] && failed != nullptr) failed->push_back(plots[i].title + ": " + last_line(one->second));
    }
    if (std::find(drawn.begin(), drawn.end(), true) == drawn.end())
      return Error::failed("gnuplot failed (exit " + std::to_string(all->first) + "): " + all->second);
  }
  std::vector<std::string> svgs;
  for (std::size_t i = 0; i < plots.size(); ++i) {
    if (!drawn[i]) {
      svgs.emplace_back();
      continue;
    }
    auto svg = read_bounded_file(dir + "/" + plots[i].id + ".svg", "gnuplot's " + plots[i].id + ".svg", kMaxSvgBytes);
    if (!svg) return svg.error();
    svgs.push_back(std::move(svg.value()));
  }
  return svgs;
}

}  // namespace hitl::report
