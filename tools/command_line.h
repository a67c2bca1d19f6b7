// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Command-line parsing shared by the tools: options from their tables
// (tmr/util/option_table.h), --help, one error line, project.ini.
#pragma once

#include <boost/program_options.hpp>
#include <optional>
#include <string>

#include "tmr/util/option_table.h"

namespace tmr {

// Parses the command line of `tool`. Returns nothing when the tool should
// go on, or its exit code: 0 after printing --help, 2 after printing one
// "TOOL: error: ..." line for bad options.
// `positional` names the options that plain arguments fill, in order.
// Options the command line leaves out are then read from `config_file`
// (name=value lines, as project.ini) if given.
std::optional<int> ParseCommandLine(
    const std::string& tool, int argc, char** argv,
    const boost::program_options::options_description& desc,
    boost::program_options::variables_map* vm,
    const boost::program_options::positional_options_description& positional =
        {},
    const std::string& config_file = "");

// Registers --NAME with the current value of *value as its default.
template <typename T>
void AddOption(boost::program_options::options_description* desc,
               const char* name, T* value, const char* help) {
  desc->add_options()(
      name, boost::program_options::value(value)->default_value(*value), help);
}

// Registers --NAME for every row, with the field's current value as its
// default (tmr/util/option_table.h).
void AddOptionRows(boost::program_options::options_description* desc,
                   const OptionTable& table);

// Registers every row of options->AddTo(OptionTable*): --Tmr.* for
// TmrTreeOptions, --Mapper.* and --Tmr.* for TmrMapperOptions.
template <typename Options>
void AddOptionsOf(boost::program_options::options_description* desc,
                  Options* options) {
  OptionTable table;
  options->AddTo(&table);
  AddOptionRows(desc, table);
}

// project.ini as COLMAP writes it: one `name=value` line per option given
// or defaulted (not --help).
std::string ProjectIni(const boost::program_options::options_description& desc,
                       const boost::program_options::variables_map& vm);

// The project.ini beside the --plan of the command line (the later stages
// of tmr_mapper, tmr_synth_tasks); "" without --plan.
std::string ProjectIniOfPlan(int argc, char** argv);

}  // namespace tmr
