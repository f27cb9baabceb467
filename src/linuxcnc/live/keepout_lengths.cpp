#include "keepout_lengths.hpp"

#include "core/dry_run/sequence_check.hpp"
#include "core/program/tool_table.hpp"
#include "io/files.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {

void KeepoutLengths::soft_limits(std::optional<SoftLimits> limits) {
  limits_ = std::move(limits);
  configs_taken_.reset();
}

void KeepoutLengths::read_table(const Config& config, double per_mm) {
  if (!path_) return;
  const auto before = io::stamp_of(*path_);
  if (!before || before == table_read_) return;
  std::string error;
  const auto text = io::read_small_file(*path_, error);
  // LinuxCNC rewrites the file in place: one changed while it was read is
  // read again at the next poll, whole.
  if (!text || io::stamp_of(*path_) != before) return;
  table_read_ = before;
  lengths_.table = tool_lengths(parse_tool_table(*text), config.units, per_mm);
}

void KeepoutLengths::poll(Changer& changer, const NmlLink* nml, Ports& ports) {
  if (!rehearsing_) {
    changer.rehearse_with(&dry_run_);
    rehearsing_ = true;
  }
  const Config& config = changer.config();
  if (configs_taken_ != changer.configs_taken()) {
    configs_taken_ = changer.configs_taken();
    lengths_.longest = longest_carried(config, check_sequences(config, limits_));
  }
  const auto per_mm = nml ? nml->units_per_mm() : std::nullopt;
  if (per_mm) {
    read_table(config, *per_mm);
    if (const int tool = nml->spindle_tool(); tool > 0) {
      lengths_.table[tool] = nml->spindle_tool_length() / machine_per_unit(config.units, *per_mm);
    }
  }
  if (!given_ || given_->table != lengths_.table || given_->longest != lengths_.longest) {
    changer.keepout_lengths(lengths_);
    given_ = lengths_;
  }
  const int spindle = nml ? nml->spindle_tool() : changer.tools().spindle;
  spindle_length_ = lengths_.of(spindle, changer.tools().lengths).length;
  // Told once the table is read: before, every length would look missing.
  if (per_mm && spindle > 0 && told_.insert(spindle).second) {
    const std::string words =
        keepout_length_words(config, lengths_, spindle, changer.tools().lengths);
    if (!words.empty()) ports.tell(MessageKind::info, words);
  }
}

}  // namespace fatc::linuxcnc
