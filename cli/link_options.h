// The connection options every board-operating command shares (engine/vehicle/vehicle_link.h).
#pragma once

#include <CLI/CLI.hpp>

#include "engine/vehicle/vehicle_link.h"

namespace hitl::cli {

void add_link_options(CLI::App* command, vehicle::LinkOptions& options);

}  // namespace hitl::cli
