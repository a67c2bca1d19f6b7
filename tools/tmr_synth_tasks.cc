// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_synth_tasks --plan OUT/plan.txt --model_path GT: writes the result of
// every kernel and leaf task of a `tmr_mapper partition` plan from the
// ground truth of a tmr_synth scene, with noise, each model in a frame of
// its own, as the tasks would leave them; `tmr_mapper merge --plan
// OUT/plan.txt` then runs the merge stage alone (docs/distributed.md).
#include <boost/program_options.hpp>

#include <filesystem>
#include <iostream>

#include "command_line.h"
#include "progress_lines.h"
#include "tmr/colmap/synthetic_task_results.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;

namespace {

int Error(const std::string& message, int code = 1) {
  std::cerr << "tmr_synth_tasks: error: " << message << "\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  tmr::TmrMapperOptions o;
  tmr::SyntheticTaskResultsOptions noise;
  std::string plan, ground_truth, image_path;
  bool verbose = false;
  po::options_description desc(
      "tmr_synth_tasks --plan OUT/plan.txt --model_path GT: every task of "
      "the plan from the ground truth of a tmr_synth scene (options of the "
      "plan from OUT/project.ini)");
  desc.add_options()("help,h", "print this help")(
      "plan", po::value(&plan)->required(),
      "OUT/plan.txt of `tmr_mapper partition`")(
      "model_path", po::value(&ground_truth)->required(),
      "ground-truth model of the scene (tmr_synth --model_path)")(
      "database_path", po::value(&o.database_path)->required(),
      "the plan's database (from project.ini)")(
      "output_path", po::value(&o.output_path)->required(),
      "the plan's folder (from project.ini)")(
      "image_path", po::value(&image_path), "unused (from project.ini)");
  tmr::AddOption(&desc, "verbose", &verbose, "unused (from project.ini)");
  tmr::AddOptionsOf(&desc, &o);
  tmr::AddOptionsOf(&desc, &noise);
  const std::string ini = tmr::ProjectIniOfPlan(argc, argv);
  if (!ini.empty() && !fs::is_regular_file(ini))
    return Error("no '" + ini +
                 "' beside the plan (run `tmr_mapper "
                 "partition` first)");
  po::variables_map vm;
  if (const auto exit_code = tmr::ParseCommandLine("tmr_synth_tasks", argc,
                                                   argv, desc, &vm, {}, ini)) {
    return *exit_code;
  }
  std::string error;
  if (!o.Check(&error)) return Error(error, 2);
  tmr::ConfigureColmapLogging(argv[0], verbose);
  try {
    if (!tmr::WriteTaskResultsFromGroundTruth(o, ground_truth, noise, &error,
                                              tmr::TimedProgressLines()))
      return Error(error);
  } catch (const std::exception& e) {
    return Error(e.what());
  }
  return 0;
}
