#include "tool_table_pockets.hpp"

#include <stdexcept>

#include "core/program/tool_table.hpp"
#include "io/file_writer.hpp"
#include "io/files.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {

void ToolTablePockets::poll(const ToolState& tools, NmlLink& nml, Ports& ports) {
  if (!path_) return;
  // Task refused or missed it: the file holds the rack, LinuxCNC's memory not yet.
  if (reload_ && nml.load_tool_table()) reload_ = false;
  const auto stamp = io::stamp_of(*path_);
  if (!stamp) return;
  if (rack_ == tools.pockets && stamp == changed_) return;
  try {
    // The writer's lock from the read to the replace: a --teach or a second
    // component writes no table between them.
    const io::FileWriter writer(*path_, io::kComponentWait);
    std::string error;
    const auto text = io::read_small_file(*path_, error);
    if (!text) throw std::runtime_error(error);
    const PocketRewrite rewrite = with_rack_pockets(*text, tools);
    std::vector<PocketChange> edited;
    for (const PocketChange& change : rewrite.changes) {
      // A P other than the one left there was written by someone else (a
      // GUI's tool page), or the file is new to this run.
      const auto left = left_.find(change.tool);
      if (left == left_.end() || left->second != change.was) edited.push_back(change);
    }
    if (rewrite.text != *text) {
      writer.replace(rewrite.text);
      reload_ = !nml.load_tool_table();
    }
    if (!edited.empty()) ports.tell(MessageKind::info, pocket_disagreement_words(edited));
    changed_ = io::stamp_of(*path_);
    rack_ = tools.pockets;
    left_ = rewrite.p_of;
    failed_said_ = false;
  } catch (const std::runtime_error& e) {
    // Tried again at the next change of the rack or the file.
    rack_ = tools.pockets;
    changed_ = stamp;
    if (!failed_said_) {
      ports.tell(MessageKind::error,
                 std::string("cannot write the rack's pockets into the tool table: ") + e.what());
    }
    failed_said_ = true;
  }
}

}  // namespace fatc::linuxcnc
