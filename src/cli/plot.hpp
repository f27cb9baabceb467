#pragma once

#include <string>

#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/tool_state.hpp"

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

}  // namespace fatc::io
