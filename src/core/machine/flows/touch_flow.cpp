// Touching the rack: the words of its request, whether it can start (its own
// rule; Operating rehearses it after) and its run. The flow's event dispatch
// is generated here and nowhere else (flow_run_of.hpp).

#include "touch_flow.hpp"

#include <cmath>

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

namespace {

/// The probe's length as LinuxCNC applies it: the tool table's, else the
/// changer's own measurement. The touch's tip is that far below the nose.
std::optional<double> probe_length(const Context& c, int probe) {
  const auto& table = c.motion.keepout_lengths.table;
  if (const auto z = table.find(probe); z != table.end() && z->second > 0.0) return z->second;
  if (const auto measured = c.tools.lengths.find(probe); measured != c.tools.lengths.end()) {
    return measured->second;
  }
  return std::nullopt;
}

bool feature_is_hollow(const RackTouch& touch) { return touch.feature != TouchFeature::faces; }

}  // namespace

std::vector<int> TouchFlow_::touched_pockets(const Context& c, const TouchRequest& e) {
  if (!e.pockets.empty()) return e.pockets;
  const bool hollow = c.config.rack_touch && feature_is_hollow(*c.config.rack_touch);
  std::vector<int> every;
  for (const auto& [number, pocket] : c.config.pockets) {
    if (!(hollow && c.tools.holds(number))) every.push_back(number);
  }
  return every;
}

void TouchFlow_::end_early(std::string why) {
  problem = why;
  ctx->activity.stopped = std::move(why);
}

int TouchFlow_::feature_pocket() const {
  if (goal == TouchRequest::Goal::pockets) return features.at(feature);
  return ctx->config.rack_touch->datum_pocket;
}

void TouchFlow_::begin_feature() {
  const Config& c = ctx->config;
  const double length = *probe_length(*ctx, tool);
  if (goal == TouchRequest::Goal::pockets) {
    const int number = features.at(feature);
    touching = FeatureTouch::of_pocket(c, number, c.pockets.at(number).at, length);
  } else {
    touching = FeatureTouch::of_datum(c, length);
  }
  touch = touching->next();
  made.reset();
  ctx->record_progress("touching " + touching->name(), feature_pocket());
}

template <class Event, class Fsm, class Source, class Target>
void TouchFlow_::TakeFeature::operator()(const Event&, Fsm& fsm, Source&, Target&) const {
  if (const auto found = fsm.touching->found()) {
    fsm.found.push_back(*found);
    return;
  }
  fsm.end_early(fsm.touching->problem() + "; nothing written");
}

template <class Fsm, class Source, class Target>
void TouchFlow_::SayNoTouch::operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
  const Config& c = fsm.ctx->config;
  const fatc::Touch& touch = *fsm.touch;
  const std::string axis(1, axis_letter(touch.axis));
  if (e.tripped_before) {
    fsm.end_early(touch.label + ": the probe was already touching before it moved, at " + axis + " " +
             format_length(c, coordinate(touch.start, touch.axis)) + "; nothing written");
  } else {
    const double travelled = std::abs(e.z - coordinate(touch.start, touch.axis));
    fsm.end_early(touch.label + ": no touch within " +
             format_length(c, std::abs(touch.limit - coordinate(touch.start, touch.axis))) +
             " (travelled " + format_length(c, travelled) + " from " + axis + " " +
             format_length(c, coordinate(touch.start, touch.axis)) +
             "): the rack is not where config.json puts it, or the probe missed its feature; "
             "nothing written");
  }
}

template <class Event, class Fsm, class Source, class Target>
void TouchFlow_::Accept::operator()(const Event&, Fsm& fsm, Source&, Target&) const {
  Context& c = *fsm.ctx;
  const bool datum = fsm.goal == TouchRequest::Goal::teach_datum;
  if (datum) {
    c.tools.datum = {};
    c.datum_checked = true;
    c.ports.save(c.tools);
  }
  c.ports.write_found(fsm.found, datum);
}

template <class Event, class Fsm, class Source, class Target>
void TouchFlow_::JudgeDrift::operator()(const Event&, Fsm& fsm, Source&, Target&) const {
  Context& c = *fsm.ctx;
  const Found& datum = fsm.found.back();
  const Drift drift = drift_of(c.config, datum.before, datum.at);
  c.datum_checked = true;
  c.tools.datum.changes = 0;
  c.tools.datum.drift = drift.within ? std::string() : drift.words;
  c.ports.save(c.tools);
  c.tell(drift.within ? MessageKind::info : MessageKind::error, drift.words);
}

int TouchRack::tool(const Context& c, const TouchRequest&) { return c.tools.spindle; }

std::string TouchRack::name(const TouchRequest& e) {
  switch (e.goal) {
    case TouchRequest::Goal::teach_datum:
      return "teaching the rack datum by touch";
    case TouchRequest::Goal::check_datum:
      return "checking the rack datum";
    case TouchRequest::Goal::pockets:
      break;
  }
  if (e.pockets.empty()) return "teaching every pocket by touch";
  std::string names;
  for (const int pocket : e.pockets) names += (names.empty() ? "" : ", ") + std::to_string(pocket);
  return std::string(e.pockets.size() == 1 ? "teaching pocket " : "teaching pockets ") + names +
         " by touch";
}

std::optional<std::string> TouchRack::why_not(const Context& c, const TouchRequest& e) {
  if (c.machine.task_busy) return c.machine.task_busy;
  if (auto busy = why_not_busy(c)) return busy;
  if (auto turning = why_spindle_turning(c)) return turning;
  if (!c.config.rack_touch) {
    return std::string(
        "config.json has no rack_touch: say what the probe touches first (docs/setup.md, "
        "teaching by touch)");
  }
  const RackTouch& touch = *c.config.rack_touch;
  const int probe = c.tools.spindle;
  if (probe == 0 || !c.config.is_probe(probe)) {
    return std::string(probe == 0 ? "the spindle is empty"
                                  : "the spindle holds " + tool_name(probe) + ", no probe") +
           ": put the probe (a tool of \"kind\": \"probe\") in the spindle first";
  }
  if (!probe_length(c, probe)) {
    return "probe " + tool_name(probe) +
           " has no length in LinuxCNC's tool table: measure it first (its tip is where it "
           "touches)";
  }
  if (e.goal != TouchRequest::Goal::pockets) {
    if (touch.datum_pocket == 0) {
      return std::string("rack_touch has no datum: name its pocket (rack_touch.datum.pocket)");
    }
    if (e.goal == TouchRequest::Goal::check_datum && !touch.datum) {
      return std::string("the rack datum was never taught: teach it by touch first (teach-datum)");
    }
    const int pocket = touch.datum_pocket;
    if (feature_is_hollow(touch) && c.tools.holds(pocket)) {
      return "the datum is pocket " + std::to_string(pocket) + "'s bore, which holds " +
             tool_name(c.tools.tool_of(pocket)) + ": unload it first";
    }
    return std::nullopt;
  }
  const std::vector<int> pockets = TouchFlow_::touched_pockets(c, e);
  if (pockets.empty()) {
    return std::string(
        "every pocket holds its tool, and their bores are touched empty: unload "
        "the tools first");
  }
  for (const int pocket : pockets) {
    if (!c.config.has_pocket(pocket)) {
      return "pocket " + std::to_string(pocket) + " is not in config.json";
    }
    if (feature_is_hollow(touch) && c.tools.holds(pocket)) {
      return "pocket " + std::to_string(pocket) + " holds " + tool_name(c.tools.tool_of(pocket)) +
             ": its bore is touched empty; unload it first or leave the pocket out";
    }
  }
  return std::nullopt;
}

std::string TouchRack::busy(const Context& c) {
  return "the changer is busy " +
         (c.tools.in_progress ? c.tools.in_progress->sequence : std::string("touching the rack"));
}

std::unique_ptr<FlowRun> TouchRack::run(Context& c, const TouchRequest& e) {
  return std::make_unique<FlowRunOf<TouchFlow_>>(c, e);
}

}  // namespace fatc::machine
