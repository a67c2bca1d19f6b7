// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Command-line options and outputs shared by tmr_mapper and tmr_reconstruct.
#pragma once

#include <boost/program_options.hpp>
#include <functional>
#include <string>

#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// project.ini as COLMAP writes it: one `name=value` line per option given
// or defaulted (not --help).
std::string ProjectIni(const boost::program_options::options_description& desc,
                       const boost::program_options::variables_map& vm);

// The project.ini beside the --plan of the command line (the later stages
// of tmr_mapper, tmr_synth_tasks); "" without --plan.
std::string ProjectIniOfPlan(int argc, char** argv);

// Draws output_path/partition.png from output_path/tree.json and the
// database's similarity graph; false (nothing drawn) above 20,000 images,
// where the layout would take minutes. Throws on unreadable input.
bool DrawMapperPartitionPicture(const TmrMapperOptions& options);

// Prints each progress line to stdout as "[tmr    12.3 s] line", timed
// from the call.
std::function<void(const std::string&)> TimedProgressLines();

}  // namespace tmr
