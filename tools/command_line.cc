// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "command_line.h"

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <variant>

namespace tmr {

namespace fs = std::filesystem;
namespace po = boost::program_options;

std::optional<int> ParseCommandLine(
    const std::string& tool, int argc, char** argv,
    const po::options_description& desc, po::variables_map* vm,
    const po::positional_options_description& positional,
    const std::string& config_file) {
  try {
    po::store(po::command_line_parser(argc, argv)
                  .options(desc)
                  .positional(positional)
                  .run(),
              *vm);
    if (!config_file.empty())
      po::store(po::parse_config_file<char>(config_file.c_str(), desc), *vm);
    if (vm->count("help")) {
      std::cout << desc << "\n";
      return 0;
    }
    po::notify(*vm);
  } catch (const po::error& e) {
    std::cerr << tool << ": error: " << e.what() << " (see --help)\n";
    return 2;
  }
  return std::nullopt;
}

void AddOptionRows(po::options_description* desc, const OptionTable& table) {
  for (const OptionRow& row : table.rows()) {
    std::visit(
        [&](auto* field) {
          AddOption(desc, row.name.c_str(), field, row.help.c_str());
        },
        row.value);
  }
}

std::string ProjectIniOfPlan(int argc, char** argv) {
  std::string ini;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::string path;
    if (arg == "--plan" && i + 1 < argc) path = argv[i + 1];
    if (arg.rfind("--plan=", 0) == 0) path = arg.substr(7);
    if (!path.empty())
      ini = (fs::path(path).parent_path() / "project.ini").string();
  }
  return ini;
}

std::string ProjectIni(const po::options_description& desc,
                       const po::variables_map& vm) {
  std::ostringstream ini;
  for (const auto& option : desc.options()) {
    const std::string name = option->long_name();
    if (name == "help" || !vm.count(name)) continue;
    const auto& value = vm[name].value();
    ini << name << "=";
    if (auto* s = boost::any_cast<std::string>(&value))
      ini << *s;
    else if (auto* i = boost::any_cast<int>(&value))
      ini << *i;
    else if (auto* d = boost::any_cast<double>(&value))
      ini << ExactDoubleText(*d);
    else if (auto* b = boost::any_cast<bool>(&value))
      ini << (*b ? 1 : 0);
    else if (auto* u = boost::any_cast<uint64_t>(&value))
      ini << *u;
    ini << "\n";
  }
  return ini.str();
}

}  // namespace tmr
