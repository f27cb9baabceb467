#pragma once

#include <iosfwd>
#include <string>

#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/tool_state.hpp"
#include "options.hpp"

namespace fatc::io {

/// The rack seen from above (machine X right, Y up) as an SVG document: each
/// pocket with its number, the tool that belongs in it (and whether it sits
/// there), its approach (an arrow from its side, or "top") and its keep-out
/// column; safe, loading and the touch-off sensor, each visible where they
/// share a place; when `plan` is given, the XY path of its moves from safe
/// (rapids dashed, slow moves solid; moves along Z alone show as the points
/// they start and end at); when `travel` is given (the INI's soft limits),
/// the machine's travel in XY as an outline. `title` heads the drawing.
/// Pure: the caller writes the text where it likes.
std::string rack_svg(const Config& config, const ToolState& tools, const Simulator* plan,
                     const SoftLimits* travel, const std::string& title);

/// --plot: the rack from above into an SVG file, with the path of one change
/// if asked; 0 written, 1 the config or state is invalid or the change
/// refused, 2 the drawing cannot be written.
int plot(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
