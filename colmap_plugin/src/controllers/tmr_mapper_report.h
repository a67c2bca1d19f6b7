// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>

#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// report.json of a run.
std::string ReportJson(const TmrMapperReport& report);

}  // namespace tmr
