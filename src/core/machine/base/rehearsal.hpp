#pragma once

#include <functional>
#include <optional>
#include <string>

namespace fatc {

class Changer;
class Context;

/// A request run on a copy of the changer before the changer takes it, with
/// nothing moving: every move of its whole sequence is checked with the
/// length of the tool it carries, so a change that would carry a tip into a
/// holder is refused before its first move, not at the move. The machine
/// declares it; the Simulator's DryRun carries it out.
class Rehearsal {
 public:
  virtual ~Rehearsal() = default;
  /// Why `request`, made of a copy of the changer `ctx` is the context of,
  /// would break the keep-out or the soft limits; nothing if it would not.
  virtual std::optional<std::string> why_not(
      const Context& ctx, const std::function<void(Changer&)>& request) const = 0;
};

}  // namespace fatc
