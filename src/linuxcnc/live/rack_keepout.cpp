#include "rack_keepout.hpp"

#include "hal_pins_detail.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {

const std::vector<RackPart>& RackKeepout::volume(const Config& config) {
  std::vector<double> rack = {config.keepout_margin(), config.pocket_above_chuck_offset_z,
                              config.keepout_above()};
  for (const auto& [number, pocket] : config.pockets) {
    rack.insert(rack.end(), {static_cast<double>(number), pocket.at.x, pocket.at.y, pocket.at.z});
  }
  if (rack != rack_) {
    rack_ = std::move(rack);
    volume_ = rack_volume(config);
  }
  return volume_;
}

void RackKeepout::poll(HalPins& pins, const Changer& changer, bool machine_ready, NmlLink* nml,
                       double tool_length, Ports& ports) {
  const Config& config = changer.config();
  const auto per_mm = nml ? nml->units_per_mm() : std::nullopt;
  state_ = keepout_state(config, {machine_ready, per_mm.has_value(),
                                  changer.status().moves_into_rack(), *pins.rack_keepout_lift != 0});
  *pins.rack_keepout = static_cast<int>(state_);
  const bool off = state_ == KeepoutState::off;
  if (off && !said_off_) {
    ports.tell(MessageKind::info, "rack keep-out OFF: rack_keepout_all_motion is false in the "
                                  "config; only the changer's own moves are kept out of the rack");
  }
  said_off_ = off;
  *pins.rack_keepout_enable = state_ == KeepoutState::armed;
  // The first count read is where the guard stood when the component started.
  const int trips = *pins.rack_keepout_trips;
  const bool tripped = trips_ && trips != *trips_;
  trips_ = trips;
  if (!per_mm) return;
  // Config units to machine units: the guard compares with axis.L.pos-cmd.
  const double scale = machine_per_unit(config.units, *per_mm);
  const auto& parts = volume(config);
  *pins.rack_keepout_boxes = static_cast<int>(std::min(parts.size(), kGuardBoxes));
  for (std::size_t k = 0; k < kGuardBoxes; ++k) {
    const Box box = k < parts.size() ? parts[k].box : Box{};
    *pins.keepout_x_min[k] = box.low.x * scale;
    *pins.keepout_x_max[k] = box.high.x * scale;
    *pins.keepout_y_min[k] = box.low.y * scale;
    *pins.keepout_y_max[k] = box.high.y * scale;
    *pins.keepout_z_max[k] = box.high.z * scale;
  }
  *pins.rack_keepout_tool_length = tool_length * scale;
  const auto k = static_cast<std::size_t>(*pins.rack_keepout_box);
  if (!tripped || k >= parts.size()) return;
  const Point at{*pins.rack_keepout_at_x / scale, *pins.rack_keepout_at_y / scale,
                 *pins.rack_keepout_at_z / scale};
  const std::string what = nml->what_moves();
  nml->abort();
  ports.tell(MessageKind::error,
             keepout_refusal(config, what, nearest_pocket(parts[k], at), nml->spindle_tool(),
                             tool_length, at));
}

}  // namespace fatc::linuxcnc
