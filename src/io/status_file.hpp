#pragma once

#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/machine/base/ports.hpp"
#include "core/machine/base/status.hpp"
#include "core/rack/tool_state.hpp"

namespace fatc::io {

/// The words HAL cannot carry: what the changer does, the prompt or the fault
/// in full, and the last messages, as a small JSON file beside the state file
/// (STATE.status) for panels to show. Rewritten (temporary file and rename)
/// only when something in it changed; losing it loses nothing.
class StatusFile {
 public:
  explicit StatusFile(std::string path) : path_(std::move(path)) {}
  /// Remembers a message for the file's `messages` (the newest few).
  void said(MessageKind kind, const std::string& text);
  /// Writes the file if the status, the cut-off sequence, the messages or the
  /// rack keep-out's state (in words) changed.
  void write(const Status& status, const std::optional<InProgress>& cut_off,
             const std::string& keepout);
  const std::string& path() const { return path_; }

  /// The I/O check's words (linuxcnc/live/io_check_driver): each wired sensor
  /// against what it should read, each output's refusal (empty: allowed), the
  /// last answer timed; the file's `io_check`, written with the next write.
  struct IoCheckWords {
    std::vector<std::string> sensors;
    std::vector<std::pair<std::string, std::string>> refusals;  ///< action name, why not
    std::string last;
    bool held = false;  ///< an output is held otherwise than the changer commanded it
    bool operator==(const IoCheckWords& o) const {
      return sensors == o.sensors && refusals == o.refusals && last == o.last && held == o.held;
    }
  };
  void io_check(IoCheckWords words);
  /// Why the rack datum refuses M6 (a drift found, a check due), empty when
  /// it does not: the file's `datum`, written with the next write.
  void datum(std::string refusal);

 private:
  struct Message {
    MessageKind kind;
    std::string text;
  };
  std::string path_;
  std::deque<Message> messages_;
  long serial_ = 0;
  std::string written_;
  std::string shown_;  ///< what the last write was asked to show
  IoCheckWords io_check_;
  long io_check_serial_ = 0;  ///< changes of io_check_ and datum_, for the write's key
  std::string datum_;
};

}  // namespace fatc::io
