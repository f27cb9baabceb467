#pragma once

#include "machine.hpp"

namespace fatc::machine {

/// The machine with its context, behind the Changer. Built and destroyed in
/// engine.cpp: constructing the whole tree of states is the heaviest part of
/// the machine to compile, and only one file need do it.
class Engine {
 public:
  Engine(const Config& config, Ports& ports, ToolState tools);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  Context context;
  Machine fsm;
};

}  // namespace fatc::machine
