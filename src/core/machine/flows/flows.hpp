#pragma once

// Every flow the changer runs, listed once. A flow is its own files in this
// folder: NAME.hpp (its request and declaration: the phase the `state` pin
// shows, how Operating answers its end), NAME_flow.hpp (its transition table)
// and NAME_flow.cpp (its words, its own rule and its run). Operating's rows,
// the refusals of the other states, the status, the requests the changer takes
// and the run of each flow are derived from this list.

#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <variant>

#include "../base/events.hpp"
#include "air_run.hpp"
#include "change.hpp"
#include "chuck_atom.hpp"
#include "load.hpp"
#include "measure_all.hpp"
#include "touch.hpp"
#include "unload.hpp"
#include "verify.hpp"

namespace fatc::machine {

template <class... Kinds>
struct FlowList {
  /// Calls `f(Kind{})` for each, in order, until one returns true.
  template <class F>
  static bool any(F&& f) {
    return (f(Kinds{}) || ...);
  }
  using requests = std::variant<typename Kinds::request...>;
};
/// Every flow, in the order Operating lists them.
using Flows = FlowList<Change, Load, Unload, MeasureAll, Verify, ChuckAtom, AirRun, TouchRack>;
/// A request of any flow (Changer::request).
using FlowRequest = Flows::requests;

/// The flow `Request` starts.
template <class Request, class List = Flows>
struct KindOf;
template <class Request, class... Kinds>
struct KindOf<Request, FlowList<Kinds...>> {
  static constexpr bool found[] = {std::is_same_v<Request, typename Kinds::request>...};
  static constexpr std::size_t index() {
    std::size_t i = 0;
    while (!found[i]) ++i;
    return i;
  }
  using type = std::tuple_element_t<index(), std::tuple<Kinds...>>;
};
template <class Request>
using kind_of = typename KindOf<Request>::type;

/// "M6 T3", "load of tool 3 into pocket 2": a request in a message.
template <class Request>
std::string request_name(const Request& e) {
  return kind_of<Request>::name(e);
}
inline std::string request_name(const ConfigChanged& e) { return e.request; }

}  // namespace fatc::machine
