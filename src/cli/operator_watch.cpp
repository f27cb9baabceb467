#include "operator_watch.hpp"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/config/quote.hpp"

namespace fatc::io {
namespace {

using Action = OperatorRequest::Action;

// The `state` pin's codes (docs/pins.md) and `awaiting`'s operator.
constexpr int kIdle = 1;
constexpr int kFault = 5;
constexpr int kAwaitsOperator = 5;

const char* const kExpected =
    "expected load:T, unload:T, continue, cancel, clear-fault, measure-all, "
    "measure-all:never, measure-all:program, verify:P, io, io:OUTPUT, touch, touch:P, "
    "teach-datum, check-datum or clear-datum-drift";

/// 1 to 999999999, digits only: what a tool or pocket number may be.
std::optional<int> positive(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  if (!std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  const int number = std::stoi(text);
  return number > 0 ? std::optional<int>(number) : std::nullopt;
}

bool contains(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

/// Requests whose end writes config.json once the operator accepted.
bool writes_config(Action action) { return action == Action::touch || action == Action::teach_datum; }

}  // namespace

std::optional<OperatorRequest> parse_operator_action(const std::string& text, std::string& error) {
  const std::size_t colon = text.find(':');
  const std::string verb = text.substr(0, colon);
  const std::optional<std::string> value =
      colon == std::string::npos ? std::nullopt : std::optional<std::string>(text.substr(colon + 1));
  const struct {
    const char* verb;
    Action action;
    const char* number;  ///< what the number after the colon is; nullptr: none
    bool number_optional = false;
  } verbs[] = {{"load", Action::load, "a tool number"},
               {"unload", Action::unload, "a tool number"},
               {"continue", Action::continue_prompt, nullptr},
               {"cancel", Action::cancel, nullptr},
               {"clear-fault", Action::clear_fault, nullptr},
               {"measure-all", Action::measure_all, nullptr},
               {"verify", Action::verify, "a pocket number"},
               {"touch", Action::touch, "a pocket number", true},
               {"teach-datum", Action::teach_datum, nullptr},
               {"check-datum", Action::check_datum, nullptr},
               {"clear-datum-drift", Action::clear_datum_drift, nullptr}};
  if (verb == "io") {
    OperatorRequest request{Action::io, 0, std::nullopt};
    if (!value) return request;
    request.io = io_action_named(*value);
    if (request.io) return request;
    std::string names;
    for (const IoActionDeclaration& a : kIoActions) names += std::string(names.empty() ? "" : ", ") + "io:" + a.name;
    error = "--operator io: expected io (the sensors, live) or one of " + names + ", got " + quote(text);
    return std::nullopt;
  }
  for (const auto& v : verbs) {
    if (verb != v.verb) continue;
    OperatorRequest request{v.action, 0, std::nullopt};
    if (v.action == Action::measure_all && value) {
      // measure-which: 1 the tools never measured, 2 the loaded program's.
      if (*value != "never" && *value != "program") break;
      request.number = *value == "never" ? 1 : 2;
      return request;
    }
    if (!value && (!v.number || v.number_optional)) return request;
    if (!v.number) break;
    const auto number = value ? positive(*value) : std::nullopt;
    if (!number) {
      error = "--operator " + verb + ": expected " + verb + ":N, N " + v.number +
              " above 0, got " + quote(text);
      return std::nullopt;
    }
    request.number = *number;
    return request;
  }
  error = std::string("--operator: ") + kExpected + ", got " + quote(text);
  return std::nullopt;
}

namespace {

/// Each outcome once: its exit status and the last line's first word.
struct OutcomeDeclaration {
  OperatorOutcome outcome;
  int status;
  const char* word;
};
constexpr OutcomeDeclaration kOutcomes[] = {
    {OperatorOutcome::done, 0, "done"},           {OperatorOutcome::refused, 1, "refused"},
    {OperatorOutcome::fault, 3, "fault"},         {OperatorOutcome::cancelled, 4, "cancelled"},
    {OperatorOutcome::timeout, 5, "timeout"},     {OperatorOutcome::not_running, 6, "not running"},
    {OperatorOutcome::failed, 7, "failed"},
};

const OutcomeDeclaration* declaration_of(OperatorOutcome outcome) {
  for (const auto& declared : kOutcomes) {
    if (declared.outcome == outcome) return &declared;
  }
  return nullptr;
}

}  // namespace

int operator_exit_status(OperatorOutcome outcome) {
  const auto* declared = declaration_of(outcome);
  return declared ? declared->status : 2;
}

const char* outcome_word(OperatorOutcome outcome) {
  const auto* declared = declaration_of(outcome);
  return declared ? declared->word : "?";
}

Press press_of(const OperatorRequest& request, std::optional<int> into, std::optional<int> spindle,
               std::optional<bool> pocket_holds) {
  switch (request.action) {
    case Action::load:
      return {{{"tool-number", request.number}, {"pocket-number", into.value_or(0)}}, "load"};
    case Action::unload:
      return {{{"tool-number", request.number}}, "unload"};
    case Action::continue_prompt:
      return {{}, "continue"};
    case Action::cancel:
      return {{}, "cancel"};
    case Action::clear_fault:
      return {{{"confirm-tool", spindle.value_or(-1)},
               {"confirm-pocket", pocket_holds ? (*pocket_holds ? 1 : 0) : -1}},
              "clear-fault"};
    case Action::measure_all:
      return {{{"measure-which", request.number}}, "measure-all"};
    case Action::verify:
      return {{{"pocket-number", request.number}}, "verify-pocket"};
    case Action::touch:
      return {{{"pocket-number", request.number}}, "touch-pockets"};
    case Action::teach_datum:
      return {{}, "teach-datum"};
    case Action::check_datum:
      return {{}, "check-datum"};
    case Action::clear_datum_drift:
      return {{}, "clear-datum-drift"};
    case Action::io:
      // --holding-tool's pin is set by the command itself, and dropped after.
      return {{}, request.io ? declared(*request.io).pin : "io-check-chuck-clamp"};
  }
  return {{}, "continue"};
}

namespace {

/// A whole number of the status file from `lowest` to `highest`; nullopt for
/// anything else (a fraction, 6e22, text), which get<int>() would convert
/// with undefined behaviour.
std::optional<long> whole(const nlohmann::json& value, long lowest, long highest) {
  if (value.is_number_unsigned()) {
    const auto number = value.get<unsigned long>();
    return number <= static_cast<unsigned long>(highest) ? std::optional<long>(number)
                                                         : std::nullopt;
  }
  if (!value.is_number_integer()) return std::nullopt;
  const auto number = value.get<long>();
  return number >= lowest && number <= highest ? std::optional<long>(number) : std::nullopt;
}

}  // namespace

std::optional<StatusWords> parse_status_words(const std::string& text) {
  const auto root = nlohmann::json::parse(text, nullptr, false);
  if (!root.is_object()) return std::nullopt;
  try {
    StatusWords words;
    // The pins' codes, and the count of messages said (from 0: a difference of two never
    // overflows).
    const auto state = whole(root.at("state"), 0, 1000);
    const auto awaiting = whole(root.at("awaiting"), 0, 1000);
    const auto serial = whole(root.at("serial"), 0, std::numeric_limits<long>::max() / 2);
    if (!state || !awaiting || !serial) return std::nullopt;
    words.state = static_cast<int>(*state);
    words.awaiting = static_cast<int>(*awaiting);
    words.activity = root.at("activity").get<std::string>();
    words.serial = *serial;
    for (const auto& message : root.at("messages")) {
      words.messages.emplace_back(message.at("kind").get<std::string>(),
                                  message.at("text").get<std::string>());
    }
    // A component older than the I/O check writes none.
    if (const auto io = root.find("io_check"); io != root.end()) {
      for (const auto& line : io->at("sensors")) words.io_sensors.push_back(line.get<std::string>());
      for (const auto& [action, why] : io->at("refusals").items()) {
        words.io_refusals.emplace_back(action, why.get<std::string>());
      }
    }
    return words;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

std::string nothing_to_act_on(const OperatorRequest& request, const ComponentPins& pins) {
  // The component's own words for a button with nothing to act on (docs/reference.md).
  if (request.action == Action::continue_prompt && !pins.waiting_for_operator) {
    return "Continue: nothing is waiting for the operator";
  }
  if (request.action == Action::cancel && !pins.can_cancel) {
    return "Cancel: nothing is waiting for the operator";
  }
  if (request.action == Action::clear_fault && !pins.fault) return "clear fault: there is no fault";
  return "";
}

OperatorWatch::OperatorWatch(OperatorRequest request, bool answer_yes, long seen_serial)
    : request_(request), answer_yes_(answer_yes), seen_serial_(seen_serial) {}

OperatorWatch::Turn OperatorWatch::observe(const std::optional<StatusWords>& status,
                                           const ComponentPins& pins) {
  Turn turn;
  if (!status) return turn;  // rewritten just now: the next poll reads it
  // The messages said since the last poll; the file keeps the newest eight.
  const long fresh = status->serial - seen_serial_;
  if (fresh > 0) {
    const std::size_t count = std::min<std::size_t>(fresh, status->messages.size());
    for (std::size_t i = status->messages.size() - count; i < status->messages.size(); ++i) {
      const auto& [kind, text] = status->messages[i];
      // The file's words, not its control characters: a newline would start a line of its own
      // ("outcome: done"), an escape sequence clear or recolour the terminal.
      turn.lines.push_back(escape(kind, kMaxMessageLine) + ": " + escape(text, kMaxMessageLine));
      refused_ = refused_ || (kind == "error" && contains(text, " refused: "));
      prompt_pending_ = prompt_pending_ || kind == "prompt";
      if (writes_config(request_.action)) {
        if (kind == "prompt") awaits_write_ = true;
        if (text.rfind("taught ", 0) == 0) awaits_write_ = false;
        // Config.json refused what was found: the request failed, nothing was written.
        if (kind == "error" && contains(text, "teach ") && contains(text, " refused: ")) {
          awaits_write_ = false;
          failed_ = true;
        }
      }
      cancelled_ = cancelled_ || contains(text, " cancelled");
      failed_ = failed_ || (kind == "error" && !contains(text, " refused: "));
    }
    seen_serial_ = status->serial;
    answered_ = true;
  }
  if (refused_ && !started_) {
    turn.outcome = OperatorOutcome::refused;
    return turn;
  }
  switch (request_.action) {
    case Action::continue_prompt:
      // Taken once the prompt is gone (the next one may follow at once).
      if (!pins.waiting_for_operator || answered_) turn.outcome = OperatorOutcome::done;
      return turn;
    case Action::cancel:
      if (!pins.can_cancel || answered_) turn.outcome = OperatorOutcome::done;
      return turn;
    case Action::clear_fault:
      if (!pins.fault && status->state != kFault) turn.outcome = OperatorOutcome::done;
      return turn;
    case Action::clear_datum_drift:
      // No flow: the component's one message is its answer.
      if (answered_) turn.outcome = OperatorOutcome::done;
      return turn;
    default:
      break;
  }
  // A flow: it runs while the changer is neither idle, in fault nor not ready.
  const bool running = status->state != kIdle && status->state != kFault && status->state != 0;
  if (running) started_ = answered_ = true;
  if (!started_) return turn;
  // Pin and file agree, and its words are printed before its answer.
  if (answer_yes_ && prompt_pending_ && pins.waiting_for_operator &&
      status->awaiting == kAwaitsOperator) {
    turn.lines.push_back("continue (--yes)");
    turn.press_continue = true;
    prompt_pending_ = false;
  }
  if (status->state == kFault || status->state == 0) {
    turn.outcome = OperatorOutcome::fault;
  } else if (status->state == kIdle && !(awaits_write_ && !cancelled_ && !failed_)) {
    turn.outcome = cancelled_ ? OperatorOutcome::cancelled
                   : failed_  ? OperatorOutcome::failed
                              : OperatorOutcome::done;
  }
  return turn;
}

}  // namespace fatc::io
