#include <stdexcept>

#include "pin_list.hpp"

namespace fatc::linuxcnc {
namespace {

void check(int result, const std::string& prefix, const std::string& name) {
  if (result != 0) throw std::runtime_error("cannot create pin " + prefix + "." + name);
}
void make(int id, hal_pin_dir_t dir, hal_bit_t** pin, const std::string& prefix,
          const std::string& name) {
  check(hal_pin_bit_newf(dir, pin, id, "%s.%s", prefix.c_str(), name.c_str()), prefix, name);
}
void make(int id, hal_pin_dir_t dir, hal_s32_t** pin, const std::string& prefix,
          const std::string& name) {
  check(hal_pin_s32_newf(dir, pin, id, "%s.%s", prefix.c_str(), name.c_str()), prefix, name);
}
void make(int id, hal_pin_dir_t dir, hal_float_t** pin, const std::string& prefix,
          const std::string& name) {
  check(hal_pin_float_newf(dir, pin, id, "%s.%s", prefix.c_str(), name.c_str()), prefix, name);
}

/// A pocket sensor's pin for each of `pockets`, in HAL memory.
void make_pocket_pins(int id, HalPins* p, const std::string& prefix,
                      const std::vector<int>& pockets) {
  p->pocket_count = static_cast<int>(pockets.size());
  p->pocket_sensors =
      static_cast<hal_bit_t**>(hal_malloc(sizeof(hal_bit_t*) * (pockets.size() + 1)));
  p->pocket_tools = static_cast<int*>(hal_malloc(sizeof(int) * (pockets.size() + 1)));
  if (!p->pocket_sensors || !p->pocket_tools) throw std::runtime_error("hal_malloc failed");
  for (std::size_t i = 0; i < pockets.size(); ++i) {
    p->pocket_tools[i] = pockets[i];
    make(id, HAL_IN, &p->pocket_sensors[i], prefix, pocket_pin(pockets[i]));
  }
}

}  // namespace

const char* type_name(const PinDeclaration& pin) {
  switch (pin.type) {
    case PinDeclaration::Type::s32:
      return "s32";
    case PinDeclaration::Type::real:
    case PinDeclaration::Type::real_per_box:
      return "float";
    default:
      return "bit";
  }
}

const char* dir_name(const PinDeclaration& pin) { return pin.dir == HAL_IN ? "in" : "out"; }

std::string box_pin_name(const PinDeclaration& pin, std::size_t box) {
  std::string name = pin.name;
  return name.replace(name.find("-N-"), 3, "-" + std::to_string(box) + "-");
}

HalPins* create_pins(const std::string& name, int& id, const std::vector<int>& pockets) {
  id = hal_init(name.c_str());
  if (id < 0) throw std::runtime_error("hal_init failed: is LinuxCNC (or halrun) running?");
  auto* p = static_cast<HalPins*>(hal_malloc(sizeof(HalPins)));
  if (!p) throw std::runtime_error("hal_malloc failed");
  for (const PinDeclaration& pin : kPins) {
    switch (pin.type) {
      case PinDeclaration::Type::bit:
        make(id, pin.dir, &(p->*pin.bit), name, pin.name);
        *(p->*pin.bit) = pin.start != 0;
        break;
      case PinDeclaration::Type::sensor:
        make(id, pin.dir, &p->sensors[index(pin.sensor)], name, pin.name);
        *p->sensors[index(pin.sensor)] = false;
        break;
      case PinDeclaration::Type::s32:
        make(id, pin.dir, &(p->*pin.s32), name, pin.name);
        *(p->*pin.s32) = pin.start;
        break;
      case PinDeclaration::Type::real:
        make(id, pin.dir, &(p->*pin.real), name, pin.name);
        *(p->*pin.real) = pin.start;
        break;
      case PinDeclaration::Type::bit_per_pocket:
        make_pocket_pins(id, p, name, pockets);
        break;
      case PinDeclaration::Type::real_per_box:
        for (std::size_t box = 0; box < kGuardBoxes; ++box) {
          make(id, pin.dir, &(p->*pin.per_box)[box], name, box_pin_name(pin, box));
          *(p->*pin.per_box)[box] = 0.0;
        }
        break;
    }
  }
  return p;
}

}  // namespace fatc::linuxcnc
