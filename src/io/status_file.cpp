#include "status_file.hpp"

#include <nlohmann/json.hpp>

#include "file_writer.hpp"

namespace fatc::io {
namespace {

constexpr std::size_t kMessagesKept = 8;

const char* kind_word(MessageKind kind) {
  switch (kind) {
    case MessageKind::info:
      return "info";
    case MessageKind::prompt:
      return "prompt";
    case MessageKind::error:
      return "error";
  }
  return "?";
}

}  // namespace

void StatusFile::said(MessageKind kind, const std::string& text) {
  messages_.push_back({kind, text});
  if (messages_.size() > kMessagesKept) messages_.pop_front();
  ++serial_;
}

void StatusFile::io_check(IoCheckWords words) {
  if (words == io_check_) return;
  io_check_ = std::move(words);
  ++io_check_serial_;
}

void StatusFile::datum(std::string refusal) {
  if (refusal == datum_) return;
  datum_ = std::move(refusal);
  ++io_check_serial_;
}

void StatusFile::write(const Status& status, const std::optional<InProgress>& cut_off,
                       const std::string& keepout) {
  // Called every poll: compare what it shows before building anything.
  const std::string key = std::to_string(static_cast<int>(status.phase)) + "/" +
                          std::to_string(static_cast<int>(status.awaiting)) + "/" +
                          std::to_string(serial_) + "/" + std::to_string(status.pocket) + "/" +
                          std::to_string(status.batch_done) + "/" + status.activity + "/" +
                          (cut_off ? cut_off->sequence + cut_off->step : std::string("-")) + "/" +
                          keepout + "/" + status.rule + "/" + std::to_string(status.spindle_probe) +
                          "/" + std::to_string(io_check_serial_);
  if (key == shown_) return;
  shown_ = key;  // a failed write is not retried every poll; the next change writes again
  nlohmann::json root = {{"phase", phase_word(status.phase)},
                         {"state", static_cast<int>(status.phase)},
                         {"awaiting", static_cast<int>(status.awaiting)},
                         {"activity", status.activity},
                         {"pocket", status.pocket},
                         {"batch", {{"done", status.batch_done}, {"total", status.batch_total}}},
                         {"cut_off", nullptr},
                         {"messages", nlohmann::json::array()},
                         {"keepout", keepout},
                         {"rule", status.rule},
                         {"spindle_held", status.spindle_probe != 0},
                         {"serial", serial_}};
  nlohmann::json refusals = nlohmann::json::object();
  for (const auto& [action, why] : io_check_.refusals) refusals[action] = why;
  root["datum"] = datum_;
  root["io_check"] = {{"sensors", io_check_.sensors},
                      {"refusals", refusals},
                      {"last", io_check_.last},
                      {"held", io_check_.held}};
  if (cut_off) {
    root["cut_off"] = {
        {"sequence", cut_off->sequence}, {"step", cut_off->step}, {"pocket", cut_off->pocket}};
  }
  for (const Message& m : messages_)
    root["messages"].push_back({{"kind", kind_word(m.kind)}, {"text", m.text}});
  // Messages may hold any bytes a user typed: never fail on them.
  std::string text = root.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  if (text == written_) return;
  try {
    // Not fsynced: rewritten at every step, and losing it loses nothing. Not
    // waited for: the poll loop must not stall on a display aid.
    write_file(path_, text, std::chrono::milliseconds(0), {false, std::nullopt});
    written_ = std::move(text);
  } catch (const std::exception&) {
    // A display aid: the panel keeps the last one it read; the next change writes again.
  }
}

}  // namespace fatc::io
