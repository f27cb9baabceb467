#pragma once

// config.json for the rest of the house: what a validated config holds
// (settings.hpp) and the parser that makes one (parse_config.hpp). The files
// of config/ include settings.hpp, never this, so the parser may use them
// without an include running back.

#include "parse_config.hpp"
#include "settings.hpp"
