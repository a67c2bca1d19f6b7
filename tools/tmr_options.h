// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Command-line options shared by the tools: --Tmr.* for TmrTreeOptions.
#pragma once

#include <boost/program_options.hpp>
#include <ostream>
#include <string>

#include "tmr/partition/tmr_tree.h"

namespace tmr {

// Registers --Tmr.<name> for every field of TmrTreeOptions, with defaults.
void AddTmrTreeOptions(boost::program_options::options_description* desc,
                       TmrTreeOptions* options);

// Writes a file through a temporary name and a rename, so that an
// interrupted run never leaves a half-written file. False on failure.
bool WriteFileAtomically(const std::string& path, const std::string& content);

// Prints kernels, image clusters and leaf clusters with their sizes, the
// unclustered images and the time per stage.
void PrintTreeSummary(const TmrTree& tree, std::ostream& out);

}  // namespace tmr
