#pragma once

#include <string>
#include <vector>

namespace fatc::linuxcnc {

/// The component's HAL pins, as fixed_atc_probe.<name>. Values are read and
/// written through the pointers HAL gives; only Component touches them.
struct HalPins;

/// Creates the component and every pin, with a pocket sensor's for each of
/// `pockets` (tool numbers); throws std::runtime_error naming the pin that
/// failed. hal_ready is left to the caller, after everything else that can
/// fail has been checked.
HalPins* create_pins(const std::string& component_name, int& component_id,
                     const std::vector<int>& pockets);

}  // namespace fatc::linuxcnc
