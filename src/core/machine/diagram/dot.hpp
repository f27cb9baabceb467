#pragma once

// Graphviz of a Boost.MSM machine, read from its transition tables, so the
// diagram in the docs can never drift from the code.

#include <boost/core/demangle.hpp>
#include <boost/mpl/for_each.hpp>
#include <boost/mpl/if.hpp>
#include <boost/mpl/is_sequence.hpp>
#include <boost/mpl/vector.hpp>
#include <boost/msm/back/state_machine.hpp>
#include <boost/msm/front/functor_row.hpp>
#include <boost/msm/front/states.hpp>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>

namespace fatc::machine {

template <class T, class = void>
struct IsComposite : std::false_type {};
template <class Front, class... Policies>
struct IsComposite<boost::msm::back::state_machine<Front, Policies...>> : std::true_type {
  using front = Front;
};
/// A state that runs a flow as a machine of its own (Running<Flow>) is drawn
/// as that flow.
template <class T>
struct IsComposite<T, std::void_t<typename T::flow_front>> : std::true_type {
  using front = typename T::flow_front;
};

template <class T, class = void>
struct IsExitState : std::false_type {};
template <class T>
struct IsExitState<T, std::void_t<typename T::pseudo_exit>> : std::true_type {};

template <class T, class = void>
struct HasEnd : std::false_type {};
template <class T>
struct HasEnd<T, std::void_t<typename T::ends_at>> : std::true_type {};

template <class T, class = void>
struct IsExitPoint : std::false_type {};
template <class T>
struct IsExitPoint<T, std::void_t<typename T::wrapped_exit>> : std::true_type {};

/// The name a reader knows: no namespaces, no enclosing classes, fronts without "_".
inline std::string short_name(std::string name) {
  for (const char* noise : {"fatc::machine::", "fatc::", "boost::msm::front::"}) {
    for (std::size_t at; (at = name.find(noise)) != std::string::npos;) {
      name.erase(at, std::char_traits<char>::length(noise));
    }
  }
  int depth = 0;
  std::size_t last = 0;
  for (std::size_t i = 0; i + 1 < name.size(); ++i) {
    if (name[i] == '<') ++depth;
    if (name[i] == '>') --depth;
    if (depth == 0 && name[i] == ':' && name[i + 1] == ':') last = i + 2;
  }
  name = name.substr(last);
  if (name.rfind("Not<", 0) == 0) name = "!" + name.substr(4, name.size() - 5);
  if (const auto at = name.find("_<"); at != std::string::npos) name.erase(at, 1);
  if (!name.empty() && name.back() == '_') name.pop_back();
  return name;
}

template <class T>
std::string name_of() {
  if constexpr (IsComposite<T>::value) {
    return name_of<typename IsComposite<T>::front>();
  } else {
    return short_name(boost::core::demangle(typeid(T).name()));
  }
}

class DotWriter {
 public:
  std::ostringstream out;

  template <class Front>
  void machine(const std::string& path) {
    // One initial state, or one for each region.
    using Initial = typename Front::initial_state;
    using Initials = typename boost::mpl::if_<boost::mpl::is_sequence<Initial>, Initial,
                                              boost::mpl::vector1<Initial>>::type;
    out << "  \"" << path << "/start\" [shape=point, label=\"\"];\n";
    boost::mpl::for_each<Initials, Wrap<boost::mpl::placeholders::_1>>(StartVisitor{this, path});
    boost::mpl::for_each<typename Front::transition_table, Wrap<boost::mpl::placeholders::_1>>(
        RowVisitor{this, path});
  }

 private:
  template <class T>
  struct Wrap {};

  struct RowVisitor {
    DotWriter* writer;
    std::string path;
    template <class Row>
    void operator()(Wrap<Row>) const {
      writer->row<Row>(path);
    }
  };

  struct StartVisitor {
    DotWriter* writer;
    std::string path;
    template <class State>
    void operator()(Wrap<State>) const {
      const std::string initial = writer->node<State>(path);
      writer->out << "  \"" << path << "/start\" -> \"" << initial << "\";\n";
    }
  };

  std::set<std::string> drawn_;

  template <class T>
  std::string node(const std::string& path) {
    if constexpr (IsExitPoint<T>::value) {
      const std::string owner = path + "/" + name_of<typename T::owner>();
      composite<typename T::owner>(path);
      return owner + "/" + name_of<typename T::wrapped_exit>();
    } else if constexpr (IsComposite<T>::value) {
      composite<T>(path);
      return path + "/" + name_of<T>() + "/start";
    } else {
      const std::string id = path + "/" + name_of<T>();
      if (drawn_.insert(id).second) {
        const bool exit = IsExitState<T>::value;
        out << "  \"" << id << "\" [label=\"" << name_of<T>() << "\""
            << (exit ? ", shape=doublecircle" : ", shape=box, style=rounded") << "];\n";
      }
      return id;
    }
  }

  template <class Composite>
  void composite(const std::string& path) {
    const std::string id = path + "/" + name_of<Composite>();
    if (!drawn_.insert(id).second) return;
    out << "  subgraph \"cluster_" << id << "\" {\n  label=\"" << name_of<Composite>() << "\";\n";
    machine<typename IsComposite<Composite>::front>(id);
    out << "  }\n";
  }

  /// Where a row starts: a flow's end (FlowFinished, ...) at the flow's
  /// exit state, as a submachine's exit point is drawn.
  template <class Row>
  std::string source(const std::string& path) {
    using Source = typename Row::Source;
    const std::string node_id = node<Source>(path);
    if constexpr (IsComposite<Source>::value && HasEnd<typename Row::Evt>::value) {
      return node<typename Row::Evt::ends_at>(path + "/" + name_of<Source>());
    } else {
      return node_id;
    }
  }

  template <class Row>
  void row(const std::string& path) {
    const std::string from = source<Row>(path);
    const bool internal = std::is_same_v<typename Row::Target, boost::msm::front::none>;
    const std::string to = internal ? from : node<typename Row::Target>(path);
    std::string label = std::is_same_v<typename Row::Evt, boost::msm::front::none>
                            ? std::string("at once")
                            : name_of<typename Row::Evt>();
    if (!std::is_same_v<typename Row::Guard, boost::msm::front::none>) {
      label += " [" + name_of<typename Row::Guard>() + "]";
    }
    if (!std::is_same_v<typename Row::Action, boost::msm::front::none>) {
      label += " / " + name_of<typename Row::Action>();
    }
    out << "  \"" << from << "\" -> \"" << to << "\" [label=\"" << label << "\""
        << (internal ? ", style=dashed" : "");
    if (IsComposite<typename Row::Source>::value && !HasEnd<typename Row::Evt>::value && !internal) {
      out << ", ltail=\"cluster_" << path << "/" << name_of<typename Row::Source>() << "\"";
    }
    out << "];\n";
  }
};

template <class Front>
std::string dot_of(const std::string& title) {
  DotWriter writer;
  writer.out << "digraph \"" << title << "\" {\n  compound=true;\n  rankdir=TB;\n"
             << "  node [fontname=\"Helvetica\", fontsize=10];\n"
             << "  edge [fontname=\"Helvetica\", fontsize=8];\n";
  writer.machine<Front>(title);
  writer.out << "}\n";
  return writer.out.str();
}

}  // namespace fatc::machine
