#include "plot.hpp"

#include <algorithm>
#include <ostream>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/config/quote.hpp"
#include "core/formatted.hpp"
#include "core/rack/geometry.hpp"
#include "inputs.hpp"
#include "io/file_writer.hpp"
#include "io/files.hpp"

namespace fatc::io {

namespace {

constexpr double kSize = 900.0;         ///< the drawing's larger side, in pixels
constexpr double kMargin = 70.0;        ///< room for the labels around it
constexpr double kTitle = 40.0;         ///< the title's band at the top
constexpr double kLegendLine = 18.0;    ///< each line of the legend's band at the bottom
constexpr double kLegendWidth = 820.0;  ///< its longest line, with the margins

/// `text` as XML 1.0 character data: & < > and quotes as entities, and what
/// XML forbids or a drawing would hide (control characters, U+FFFE, U+FFFF,
/// bytes that are not UTF-8) as visible escapes: \x01, \u{fffe}.
std::string escaped(std::string_view text) {
  std::string out;
  char buffer[16];
  for (std::size_t at = 0; at < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[at]);
    char32_t code = c;
    const std::size_t length = c < 0x80 ? 1 : decode_utf8(text, at, code);
    if (length == 0 || code < 0x20 || code == 0x7F) {
      std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
      out += buffer;
      ++at;
      continue;
    }
    if (code == 0xFFFE || code == 0xFFFF) {
      std::snprintf(buffer, sizeof buffer, "\\u{%04x}", static_cast<unsigned>(code));
      out += buffer;
    } else if (c == '&') {
      out += "&amp;";
    } else if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '"') {
      out += "&quot;";
    } else if (c == '\'') {
      out += "&apos;";
    } else {
      out.append(text.substr(at, length));
    }
    at += length;
  }
  return out;
}

/// A position or size in the drawing's pixels.
std::string number(double value) { return formatted("%.1f", value); }

/// A machine length for a label as config.json's units write it (4 decimals
/// in mm, 5 in inch) without the zeros after them, however long it is: 0.75,
/// 12.5, -1000000000.
std::string length_words(Units units, double value) {
  std::string text = formatted("%.*f", units == Units::inch ? 5 : 4, value);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text == "-0" ? "0" : text;
}

/// Machine XY to the drawing's pixels: X right, Y up, the whole rack in view.
class View {
 public:
  void include(const Point& p, double around = 0.0) {
    min_x_ = std::min(min_x_, p.x - around);
    max_x_ = std::max(max_x_, p.x + around);
    min_y_ = std::min(min_y_, p.y - around);
    max_y_ = std::max(max_y_, p.y + around);
  }
  void fit() {
    const double span = std::max({max_x_ - min_x_, max_y_ - min_y_, 1e-9});
    scale_ = kSize / span;
  }
  double x(double machine_x) const { return kMargin + (machine_x - min_x_) * scale_; }
  double y(double machine_y) const { return kTitle + kMargin + (max_y_ - machine_y) * scale_; }
  double length(double machine) const { return machine * scale_; }
  // At least as wide as the legend's longest line.
  double width() const { return std::max(2 * kMargin + (max_x_ - min_x_) * scale_, kLegendWidth); }
  double height(std::size_t legend_lines) const {
    return kTitle + 2 * kMargin + (max_y_ - min_y_) * scale_ + kLegendLine * (legend_lines + 1);
  }

 private:
  double min_x_ = std::numeric_limits<double>::infinity();
  double max_x_ = -std::numeric_limits<double>::infinity();
  double min_y_ = std::numeric_limits<double>::infinity();
  double max_y_ = -std::numeric_limits<double>::infinity();
  double scale_ = 1.0;
};

/// The XY points the plan's moves pass, from safe, each with whether the
/// move to it was slow.
std::vector<std::pair<Point, bool>> path_of(const Simulator& plan, const Point& start) {
  std::vector<std::pair<Point, bool>> path{{start, false}};
  Point at = start;
  for (const Step& step : plan.motion_steps()) {
    if (step.axes & axis_x) at.x = step.target.x;
    if (step.axes & axis_y) at.y = step.target.y;
    if (step.axes & axis_z) at.z = step.target.z;
    path.emplace_back(at, step.kind != StepKind::rapid);
  }
  return path;
}

/// A station: its marker, `name` its class, and its label, `dy` below its
/// centre. Loading, the sensor and safe often share their XY or lie close:
/// the sensor is a ring, drawn first, loading a smaller dot inside it, safe
/// the smallest, on top; their labels one above another, clear of the ring.
struct Station {
  const char* name;
  const char* colour;
  const char* label;
  double radius;
  bool ring;
  double dy;
};
constexpr Station kSensor{"sensor", "#d70", "touch-off sensor", 11, true, 20};
constexpr Station kLoading{"loading", "#26c", "loading", 7, false, -10};
constexpr Station kSafe{"safe", "#2a2", "safe", 4, false, 5};

void station(std::ostringstream& svg, const View& view, const Point& p, const Station& s) {
  svg << "<circle class=\"" << s.name << "\" cx=\"" << number(view.x(p.x)) << "\" cy=\""
      << number(view.y(p.y)) << "\" r=\"" << number(s.radius) << "\" "
      << (s.ring ? std::string("fill=\"none\" stroke-width=\"3\" stroke=\"")
                 : std::string("fill=\""))
      << s.colour << "\"/>\n"
      << "<text x=\"" << number(view.x(p.x) + kSensor.radius + 4) << "\" y=\""
      << number(view.y(p.y) + s.dy) << "\" fill=\"" << s.colour << "\">" << s.label << "</text>\n";
}

/// The machine's travel in XY (its soft limits) as a grey outline, and its limits in words.
void travel_outline(std::ostringstream& svg, const View& view, const SoftLimits& travel,
                    Units units) {
  const double left = view.x(travel.x.min);
  const double top = view.y(travel.y.max);
  svg << "<rect class=\"travel\" x=\"" << number(left) << "\" y=\"" << number(top) << "\" width=\""
      << number(view.x(travel.x.max) - left) << "\" height=\"" << number(view.y(travel.y.min) - top)
      << "\" fill=\"none\" stroke=\"#888\" stroke-width=\"2\"/>\n"
      << "<text x=\"" << number(left) << "\" y=\"" << number(top - 8) << "\" fill=\"#888\">"
      << "travel X " << length_words(units, travel.x.min) << " to "
      << length_words(units, travel.x.max) << ", Y " << length_words(units, travel.y.min) << " to "
      << length_words(units, travel.y.max) << "</text>\n";
}

}  // namespace

std::string rack_svg(const Config& config, const ToolState& tools, const Simulator* plan,
                     const SoftLimits* travel, const std::string& title) {
  const double margin = config.keepout_margin();
  View view;
  for (const auto& [n, pocket] : config.pockets) {
    const PocketWaypoints w = pocket_waypoints(config, n);
    view.include(w.pocket, margin);
    if (pocket.approach == Approach::side) view.include(w.side);
  }
  for (const Point& p : {config.safe, config.loading, config.probe_limit}) view.include(p);
  std::vector<std::pair<Point, bool>> path;
  if (plan) path = path_of(*plan, config.safe);
  for (const auto& [p, slow] : path) view.include(p);
  if (travel) {
    view.include({travel->x.min, travel->y.min, 0});
    view.include({travel->x.max, travel->y.max, 0});
  }
  view.fit();

  std::vector<std::string> legend = {
      "Seen from above, machine X to the right, Y up. Dashed squares: each pocket's keep-out (" +
          length_words(config.units, margin) + " around it);",
      "arrows: the side approach, from the side into the pocket; circles: top pockets.",
      "Green dot: safe; blue dot: loading; orange ring: the touch-off sensor."};
  if (travel)
    legend.push_back("Grey outline: the machine's travel, the INI's soft limits in X and Y.");
  if (plan) {
    legend.push_back(
        "The change: blue dashed rapids, red solid slow moves (pocket_feed); moves along Z alone "
        "are not drawn.");
  }

  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(view.width())
      << "\" height=\"" << number(view.height(legend.size())) << "\" viewBox=\"0 0 "
      << number(view.width()) << " " << number(view.height(legend.size()))
      << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
      << "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
         "markerWidth=\"7\" markerHeight=\"7\" orient=\"auto-start-reverse\">"
         "<path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#444\"/></marker></defs>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << number(kMargin) << "\" y=\"26\" font-size=\"16\">" << escaped(title)
      << "</text>\n";
  if (travel) travel_outline(svg, view, *travel, config.units);

  for (const auto& [n, pocket] : config.pockets) {
    const PocketWaypoints w = pocket_waypoints(config, n);
    const double x = view.x(w.pocket.x);
    const double y = view.y(w.pocket.y);
    const double half = view.length(margin);
    svg << "<rect x=\"" << number(x - half) << "\" y=\"" << number(y - half) << "\" width=\""
        << number(2 * half) << "\" height=\"" << number(2 * half)
        << "\" fill=\"#fbe3e3\" stroke=\"#c66\" stroke-dasharray=\"4 3\"/>\n";
    if (pocket.approach == Approach::side) {
      svg << "<line x1=\"" << number(view.x(w.side.x)) << "\" y1=\"" << number(view.y(w.side.y))
          << "\" x2=\"" << number(x) << "\" y2=\"" << number(y)
          << "\" stroke=\"#444\" stroke-width=\"1.5\" marker-end=\"url(#arrow)\"/>\n";
    } else {
      svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y) << "\" r=\""
          << number(std::max(half * 0.6, 8.0)) << "\" fill=\"none\" stroke=\"#444\"/>\n";
    }
    svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y)
        << "\" r=\"4\" fill=\"black\"/>\n";
    const int tool = tools.tool_of(n);
    const std::string holds = tool == 0               ? "empty"
                              : tools.holds(n)        ? "T" + std::to_string(tool)
                              : tools.spindle == tool ? "T" + std::to_string(tool) + " (spindle)"
                                                      : "T" + std::to_string(tool) + " (out)";
    svg << "<text x=\"" << number(x) << "\" y=\"" << number(y + half + 16)
        << "\" text-anchor=\"middle\" font-weight=\"bold\">pocket " << n << "</text>\n"
        << "<text x=\"" << number(x) << "\" y=\"" << number(y + half + 31)
        << "\" text-anchor=\"middle\">" << escaped(holds)
        << (pocket.approach == Approach::top ? ", top" : "") << "</text>\n";
  }

  if (!path.empty()) {
    for (std::size_t i = 1; i < path.size(); ++i) {
      const auto& [a, unused] = path[i - 1];
      const auto& [b, slow] = path[i];
      if (a.x == b.x && a.y == b.y) continue;
      svg << "<line x1=\"" << number(view.x(a.x)) << "\" y1=\"" << number(view.y(a.y)) << "\" x2=\""
          << number(view.x(b.x)) << "\" y2=\"" << number(view.y(b.y))
          << (slow ? "\" stroke=\"#c00\" stroke-width=\"3\""
                   : "\" stroke=\"#36c\" stroke-width=\"2\" stroke-dasharray=\"8 4\"")
          << " marker-end=\"url(#arrow)\"/>\n";
    }
  }

  station(svg, view, config.probe_limit, kSensor);
  station(svg, view, config.loading, kLoading);
  station(svg, view, config.safe, kSafe);

  double line_y = view.height(legend.size()) - kLegendLine * legend.size();
  for (const std::string& line : legend) {
    svg << "<text x=\"" << number(kMargin) << "\" y=\"" << number(line_y) << "\" fill=\"#555\">"
        << line << "</text>\n";
    line_y += kLegendLine;
  }
  svg << "</svg>\n";
  return svg.str();
}

int plot(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config || loaded.problems > 0) return 1;
  const Config& config = *loaded.config;
  auto rack = rack_of(options, config, err);
  if (!rack) return 1;
  std::string title = shown_path(options.config_path);
  std::optional<Simulator> change;
  if (options.from_tool) {
    rack->put_in_spindle(*options.from_tool);
    change = plan_change(config, *rack, *options.to_tool, config.probe_limit.z);
    if (const auto why = refusal(*change)) {
      err << *why << "\n";
      return 1;
    }
    title += ": M6 T" + std::to_string(*options.to_tool) + " with " +
             spindle_words(*options.from_tool) + ", the " +
             (config.path == Path::direct ? "direct" : "prototype") + " path";
  }
  try {
    const std::string drawing = rack_svg(config, *rack, change ? &*change : nullptr,
                                         loaded.limits ? &*loaded.limits : nullptr, title);
    write_file(options.plot_path, drawing, kCommandLineWait);
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 2;
  }
  out << "wrote " << shown_path(options.plot_path) << ": " << config.pockets.size()
      << (config.pockets.size() == 1 ? " pocket" : " pockets")
      << (change ? ", and the path of the change" : "") << ", " << rack_words(options) << "\n";
  return 0;
}

}  // namespace fatc::io
