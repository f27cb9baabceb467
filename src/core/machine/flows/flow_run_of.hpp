#pragma once

// The run of one flow; included only by that flow's own file, where its
// event dispatch is generated (for the events of FlowEvent) and nowhere else.

#include "../base/common.hpp"
#include "../base/flow_run.hpp"

namespace fatc::machine {

template <class Front>
class FlowRunOf final : public FlowRun {
 public:
  template <class Request>
  FlowRunOf(Context& ctx, const Request& request) {
    fsm_.ctx = &ctx;
    fsm_.failure = &failure_;
    fsm_.start(request);
  }
  boost::msm::back::HandledEnum take(const FlowEvent& event) override {
    return std::visit([this](const auto& e) { return fsm_.process_event(e); }, event);
  }
  bool flagged(std::type_index flag) const override { return flagged(flag, flag::InFlows{}); }
  FlowEnd take_end() override {
    if (told_) return FlowEnd::running;
    const FlowEnd end = fsm_.template is_flag_active<flag::EndedFinished>()    ? FlowEnd::finished
                        : fsm_.template is_flag_active<flag::EndedCancelled>() ? FlowEnd::cancelled
                        : fsm_.template is_flag_active<flag::EndedFailed>()    ? FlowEnd::failed
                                                                               : FlowEnd::running;
    told_ = end != FlowEnd::running;
    return end;
  }
  const std::string& failure() const override { return failure_; }
  BatchCount batch() const override { return fsm_.batch_count(); }
  void stop() override { fsm_.stop(); }

 private:
  template <class... Flags>
  bool flagged(std::type_index flag, flag::List<Flags...>) const {
    return ((flag == typeid(Flags) && fsm_.template is_flag_active<Flags>()) || ...);
  }
  std::string failure_;
  Machine_of<Front> fsm_;
  bool told_ = false;
};

}  // namespace fatc::machine
