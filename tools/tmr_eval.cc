// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// tmr_eval [--gt GT_MODEL] [--database_path DB] --model DIR [DIR ...]
//          [--output_json FILE]
// Scores COLMAP models against ground truth (or against another model given
// as --gt): registered images, points, reprojection error, position errors
// after a robust sim3 alignment of the camera centres, rotation errors after
// a robust rotation alignment of the orientations, a wrong-merge flag. With
// --database_path, also without ground truth: the verified matches of the
// database that the model's poses contradict.
// A DIR without a model but with numbered sub-folders (mapper output) stands
// for all of them.
#include <boost/program_options.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "tmr/colmap/model_evaluation.h"

#include "command_line.h"
#include "drawing/top_view_picture.h"

namespace fs = std::filesystem;

namespace po = boost::program_options;

namespace {

bool IsModel(const fs::path& dir) {
  return fs::exists(dir / "images.bin") || fs::exists(dir / "images.txt");
}

// Expands mapper output folders (DIR/0, DIR/1, ...) into their models.
std::vector<std::string> ExpandModels(const std::vector<std::string>& paths) {
  std::vector<std::string> models;
  for (const std::string& path : paths) {
    if (IsModel(path) || !fs::is_directory(path)) {
      models.push_back(path);
      continue;
    }
    std::vector<std::pair<int, std::string>> numbered;
    for (const auto& entry : fs::directory_iterator(path)) {
      const std::string name = entry.path().filename().string();
      if (!name.empty() && std::all_of(name.begin(), name.end(), ::isdigit) &&
          IsModel(entry.path())) {
        numbered.emplace_back(std::stoi(name), entry.path().string());
      }
    }
    std::sort(numbered.begin(), numbered.end());
    if (numbered.empty()) models.push_back(path);  // reported as unreadable
    for (const auto& [index, model] : numbered) models.push_back(model);
  }
  return models;
}

}  // namespace

int main(int argc, char** argv) {
  std::string reference, json_path, top_view;
  std::vector<std::string> model_args;
  tmr::ModelEvaluationOptions options;
  po::options_description desc(
      "tmr_eval: score COLMAP models against ground truth or another model");
  desc.add_options()("help,h", "print this help")(
      "gt", po::value(&reference),
      "reference model: ground truth, or another reconstruction")(
      "database_path", po::value(&options.database_path),
      "check the models against the verified matches of this database "
      "(read-only)")(
      "model", po::value(&model_args)->multitoken()->required(),
      "models to score (a folder of numbered models counts as all of them)")(
      "output_json", po::value(&json_path), "also write the scores as JSON")(
      "top_view", po::value(&top_view),
      "also draw the aligned camera centres of every model over the "
      "reference's (PNG)")("inlier_threshold",
                           po::value(&options.inlier_threshold)
                               ->default_value(options.inlier_threshold),
                           "sim3 RANSAC threshold (share of the scene scale)")(
      "displaced_threshold",
      po::value(&options.displaced_threshold)
          ->default_value(options.displaced_threshold),
      "position error that makes an image displaced (share of the scene "
      "scale)")(
      "min_wrong_merge_images",
      po::value(&options.min_wrong_merge_images)
          ->default_value(options.min_wrong_merge_images),
      "displaced images forming a rigid part that make a wrong merge")(
      "seed", po::value(&options.seed)->default_value(options.seed),
      "RANSAC seed")(
      "match_min_tri_angle",
      po::value(&options.match_consistency.min_triangulation_angle_deg)
          ->default_value(
              options.match_consistency.min_triangulation_angle_deg),
      "with --database_path: test only matches whose rays meet at this "
      "angle (degrees) or more")(
      "match_third_view",
      po::value(&options.match_consistency.require_third_view)
          ->default_value(options.match_consistency.require_third_view),
      "with --database_path: test only matches that a third photo confirms "
      "(0: every match)");
  po::variables_map vm;
  if (const auto exit_code =
          tmr::ParseCommandLine("tmr_eval", argc, argv, desc, &vm)) {
    return *exit_code;
  }
  std::string error;
  if (!options.Check(&error)) {
    std::cerr << "tmr_eval: error: " << error << "\n";
    return 2;
  }
  std::vector<tmr::ModelEvaluation> evaluations;
  try {
    for (const std::string& model : ExpandModels(model_args)) {
      evaluations.push_back(tmr::EvaluateModel(reference, model, options));
    }
  } catch (const std::exception& e) {
    std::cerr << "tmr_eval: error: " << e.what() << "\n";
    return 1;
  }
  tmr::PrintEvaluationTable(evaluations, std::cout);
  if (!top_view.empty()) {
    std::vector<tmr::CentreSet> sets;
    for (size_t i = 0; i < evaluations.size(); ++i) {
      const auto& e = evaluations[i];
      sets.push_back({"model " + std::to_string(i) + ": " +
                          std::to_string(e.num_registered_images) + " images" +
                          (e.aligned ? "" : " (not aligned, not drawn)") +
                          (e.wrong_merge ? " (wrong merge)" : ""),
                      e.aligned_centres});
    }
    try {
      if (!tmr::DrawTopView(tmr::ReadCameraCentres(reference), sets,
                            top_view)) {
        std::cerr << "tmr_eval: error: cannot draw '" << top_view << "'\n";
        return 1;
      }
    } catch (const std::exception& e) {
      std::cerr << "tmr_eval: error: " << e.what() << "\n";
      return 1;
    }
  }
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    tmr::WriteEvaluationJson(evaluations, reference, out);
    if (!out) {
      std::cerr << "tmr_eval: error: cannot write '" << json_path << "'\n";
      return 1;
    }
  }
  return 0;
}
