// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_mapper --database_path DB --image_path IMAGES --output_path OUT:
// the drop-in replacement for `colmap mapper`, reconstructing on the
// TMR-tree. COLMAP's --Mapper.* options pass through; tmr's are --Tmr.*.
//
// The same run in stages, for batch schedulers (docs/distributed.md):
//   tmr_mapper partition --database_path DB --output_path OUT [options]
//   tmr_mapper run_task --plan OUT/plan.txt --task ID [--Mapper.num_threads N]
//   tmr_mapper status --plan OUT/plan.txt
//   tmr_mapper merge --plan OUT/plan.txt [--group merge.G]
//     [--Mapper.num_threads N]
//   tmr_mapper report --plan OUT/plan.txt   (report.html again, e.g. after
//     tmr_eval wrote OUT/eval.json)
// The later stages take the options from OUT/project.ini, which partition
// writes with absolute paths. Each stage is a call of the library
// (tmr/colmap/tmr_mapper.h); `tmr_mapper STAGE --help` lists its options.
#include <boost/program_options.hpp>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>

#include "command_line.h"
#include "progress_lines.h"
#include "report/report_page.h"
#include "tmr/colmap/tmr_mapper.h"
#include "tmr/io/atomic_file.h"

namespace fs = std::filesystem;
namespace po = boost::program_options;

namespace {

// The first line of each stage's --help.
const std::map<std::string, std::string>& StageUsage() {
  static const std::map<std::string, std::string> usage = {
      {"run",
       "tmr_mapper --database_path DB --output_path OUT [options]: COLMAP's "
       "incremental mapper on the TMR-tree (stages: partition, run_task, "
       "status, merge, report; `tmr_mapper STAGE --help`)"},
      {"partition",
       "tmr_mapper partition --database_path DB --output_path OUT [options]: "
       "the TMR-tree, the task plan OUT/plan.txt and OUT/project.ini"},
      {"run_task",
       "tmr_mapper run_task --plan OUT/plan.txt --task ID: one kernel or leaf "
       "task of the plan (options from OUT/project.ini)"},
      {"status",
       "tmr_mapper status --plan OUT/plan.txt: each task of the plan, done or "
       "todo"},
      {"merge",
       "tmr_mapper merge --plan OUT/plan.txt: merges the finished tasks into "
       "the models OUT/0, 1, ... (by parts: --group merge.G merges one "
       "group of the plan)"},
      {"report",
       "tmr_mapper report --plan OUT/plan.txt: writes OUT/report.html again "
       "(with OUT/eval.json when tmr_eval wrote one there)"}};
  return usage;
}

int Error(const std::string& message, int code = 1) {
  std::cerr << "tmr_mapper: error: " << message << "\n";
  return code;
}

bool AsksForHelp(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") return true;
  }
  return false;
}

// Writes OUT/project.ini: the effective options, as COLMAP writes them;
// with absolute paths for the partition stage, whose later stages may run
// on other machines.
void WriteProjectIni(const std::string& stage, const tmr::TmrMapperOptions& o,
                     const po::options_description& desc,
                     po::variables_map vm) {
  if (stage == "partition") {
    for (const char* path : {"database_path", "output_path", "image_path"}) {
      if (vm.count(path)) {
        vm.at(path).value() = fs::absolute(vm[path].as<std::string>())
                                  .lexically_normal()
                                  .string();
      }
    }
  }
  tmr::WriteFileAtomically((fs::path(o.output_path) / "project.ini").string(),
                           tmr::ProjectIni(desc, vm));
}

// partition and status: one line per task (id, images, base images, state
// done or todo, expected memory in MiB), by parts one per group of the
// merge stage (done, ready once its clusters' tasks are done, else waits),
// then the merge stage's (all images; ready once every task is done, else
// waits).
int PlanOrStatus(const std::string& stage, const tmr::TmrMapperOptions& o,
                 const std::function<void(const std::string&)>& progress) {
  tmr::TmrMapperPlan plan;
  std::string error;
  const bool ok = stage == "partition"
                      ? tmr::PlanTmrMapper(o, &plan, &error, progress)
                      : tmr::ReadTmrMapperPlan(o, &plan, &error);
  if (!ok) return Error(error);
  if (stage == "partition" &&
      !tmr::DrawRunPartitionPicture(o.database_path, o.match_graph,
                                    o.output_path))
    progress("partition.png skipped: too many images to draw");
  std::cout << std::fixed << std::setprecision(0);
  for (const tmr::TmrMapperTask& t : plan.tasks) {
    std::cout << t.id << " " << t.num_images << " " << t.num_base_images << " "
              << (t.finished ? "done" : "todo") << " " << t.memory_mib << "\n";
  }
  for (const tmr::TmrMergeGroup& g : plan.merge_groups) {
    std::cout << g.id << " " << g.num_images << " 0 "
              << (g.merged  ? "done"
                  : g.ready ? "ready"
                            : "waits")
              << " " << g.memory_mib << "\n";
  }
  const bool ready = std::all_of(plan.tasks.begin(), plan.tasks.end(),
                                 [](const auto& t) { return t.finished; });
  std::cout << "merge " << plan.num_images << " 0 "
            << (ready ? "ready" : "waits") << " " << plan.merge_memory_mib
            << "\n";
  return 0;
}

int RunTask(const tmr::TmrMapperOptions& o, const std::string& task) {
  tmr::TmrTaskReport row;
  std::string error;
  if (!tmr::RunTmrMapperTask(o, task, &row, &error)) return Error(error);
  std::cout << "tmr_mapper: " << task << ": " << row.num_registered << "/"
            << row.num_images << " images in " << std::fixed
            << std::setprecision(1) << row.seconds << " s"
            << (row.reused ? " (finished earlier)" : "") << "; " << row.message
            << "\n";
  return 0;
}

// run and merge: the models, and a summary line.
int RunOrMerge(const std::string& stage, const tmr::TmrMapperOptions& o,
               const std::function<void(const std::string&)>& progress) {
  tmr::TmrMapperReport report;
  std::string error;
  const bool ok = stage == "merge"
                      ? tmr::MergeTmrMapper(o, &report, &error, progress)
                      : tmr::RunTmrMapper(o, &report, &error, progress);
  if (!ok) return Error(error);
  tmr::WriteRunPictures(o.database_path, o.match_graph, o.output_path,
                        progress);
  std::cout << "tmr_mapper: " << report.num_images << " images, "
            << report.model_sizes.size() << " models (registered:";
  for (const int size : report.model_sizes) std::cout << " " << size;
  std::cout << ") in " << std::fixed << std::setprecision(1)
            << report.total_seconds << " s\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // An optional first word names the stage; none runs them all.
  std::string stage = "run";
  if (argc > 1 && argv[1][0] != '-') {
    stage = argv[1];
    argv[1] = argv[0];
    ++argv;
    --argc;
  }
  if (!StageUsage().count(stage)) {
    return Error("unknown stage '" + stage +
                     "' (partition, run_task, status, merge or report)",
                 2);
  }
  tmr::TmrMapperOptions o;
  bool verbose = false;
  std::string plan, task, group;
  po::options_description desc(StageUsage().at(stage));
  desc.add_options()("help,h", "print this help")(
      "database_path", po::value(&o.database_path)->required(),
      "COLMAP database (read-only)")(
      "image_path", po::value(&o.image_path),
      "images (optional: colours are skipped without)")(
      "output_path", po::value(&o.output_path)->required(),
      "folder for the models 0, 1, ...")(
      "plan", po::value(&plan),
      "run_task, status, merge: OUT/plan.txt of a partition stage")(
      "task", po::value(&task), "run_task: kernel.K or leaf.K.L")(
      "group", po::value(&group),
      "merge: only this group (merge.G) of a merge stage by parts");
  tmr::AddOption(&desc, "verbose", &verbose, "show COLMAP's own log");
  tmr::AddOptionsOf(&desc, &o);

  // The later stages read the partition's options after the command line,
  // whose values win (boost keeps the first value stored).
  const bool from_plan = stage != "run" && stage != "partition";
  const bool help = AsksForHelp(argc, argv);
  const std::string ini =
      from_plan && !help ? tmr::ProjectIniOfPlan(argc, argv) : "";
  if (from_plan && !help && ini.empty())
    return Error(stage + " needs --plan", 2);
  if (!ini.empty() && !fs::is_regular_file(ini)) {
    return Error("no '" + ini + "' beside the plan (run `tmr_mapper " +
                 "partition` first)");
  }
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_mapper", argc, argv, desc, &vm, {}, ini)) {
    return *exit_code;
  }
  if (stage == "run_task" && task.empty())
    return Error("run_task needs --task", 2);
  if (stage != "merge" && !group.empty())
    return Error("--group is an option of the merge stage", 2);
  std::string error;
  if (!o.Check(&error)) return Error(error, 2);
  tmr::ConfigureColmapLogging(argv[0], verbose);
  const auto progress = tmr::TimedProgressLines();
  try {
    std::error_code ec;
    fs::create_directories(o.output_path, ec);
    if (ec) {
      return Error("cannot create output folder '" + o.output_path +
                   "': " + ec.message());
    }
    if (!from_plan) WriteProjectIni(stage, o, desc, vm);
    if (stage == "partition" || stage == "status")
      return PlanOrStatus(stage, o, progress);
    if (stage == "run_task") return RunTask(o, task);
    if (stage == "report") {
      tmr::WriteRunPictures(o.database_path, o.match_graph, o.output_path,
                            progress);
      return 0;
    }
    if (stage == "merge" && !group.empty()) {
      if (!tmr::MergeTmrMapperGroup(o, group, &error, progress))
        return Error(error);
      std::cout << "tmr_mapper: " << group << " merged\n";
      return 0;
    }
    return RunOrMerge(stage, o, progress);
  } catch (const std::exception& e) {
    return Error(e.what());
  }
}
