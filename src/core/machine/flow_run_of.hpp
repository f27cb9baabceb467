#pragma once

// run_flow for one flow; included only by that flow's own file.

#include "common.hpp"
#include "flow_run.hpp"

namespace fatc::machine {

template <class Front>
class FlowRunOf final : public FlowRun {
 public:
  template <class Request>
  FlowRunOf(Context& ctx, const Request& request) {
    fsm_.ctx = &ctx;
    fsm_.start(request);
  }
  boost::msm::back::HandledEnum take(const boost::any& event) override {
    return fsm_.process_any_event(event);
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
  BatchCount batch() const override { return fsm_.batch_count(); }
  void stop() override { fsm_.stop(); }

 private:
  template <class... Flags>
  bool flagged(std::type_index flag, flag::List<Flags...>) const {
    return ((flag == typeid(Flags) && fsm_.template is_flag_active<Flags>()) || ...);
  }
  Machine_of<Front> fsm_;
  bool told_ = false;
};

template <class Front, class Request>
std::unique_ptr<FlowRun> run_flow(Context& ctx, const Request& request) {
  return std::make_unique<FlowRunOf<Front>>(ctx, request);
}

}  // namespace fatc::machine

/// A flow's event dispatch (favor_compile_time), generated in its own file.
#define FATC_FLOW_DISPATCH(Front) \
  BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::Machine_of<fatc::machine::Front>)
/// A flow's start (run_flow), in its own file or beside its dispatch.
#define FATC_FLOW_RUN(Front, Request)                                                   \
  template std::unique_ptr<fatc::machine::FlowRun>                                      \
  fatc::machine::run_flow<fatc::machine::Front, fatc::Request>(fatc::Context&,          \
                                                               const fatc::Request&);
