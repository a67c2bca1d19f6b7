// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Table and JSON output of model evaluations.
#include <algorithm>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "tmr/colmap/model_evaluation.h"

namespace tmr {
namespace {

std::string JsonString(const std::string& s) {
  std::ostringstream out;
  out << '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out << '\\' << c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c)
          << std::dec << std::setfill(' ');
    } else {
      out << c;
    }
  }
  out << '"';
  return out.str();
}

void JsonStats(std::ostream& out, const char* name, const ErrorStatistics& s) {
  out << "\"" << name << "\": {\"median\": " << s.median
      << ", \"p90\": " << s.p90 << ", \"max\": " << s.max << "}";
}

}  // namespace

void PrintEvaluationTable(const std::vector<ModelEvaluation>& evaluations,
                          std::ostream& out) {
  out << std::left << std::setw(28) << "model" << std::right << std::setw(7)
      << "images" << std::setw(9) << "points" << std::setw(8) << "reproj"
      << std::setw(7) << "common" << std::setw(10) << "rot med" << std::setw(10)
      << "rot p90" << std::setw(10) << "pos med" << std::setw(10) << "pos p90"
      << std::setw(10) << "pos max"
      << "  wrong merge\n";
  out << std::fixed;
  for (const ModelEvaluation& e : evaluations) {
    std::string name = e.model_path;
    if (name.size() > 27) name = "..." + name.substr(name.size() - 24);
    out << std::left << std::setw(28) << name << std::right << std::setw(7)
        << e.num_registered_images << std::setw(9) << e.num_points3D
        << std::setprecision(3) << std::setw(8) << e.mean_reprojection_error_px
        << std::setw(7) << e.num_common_images;
    if (e.aligned) {
      out << std::setprecision(3) << std::setw(9) << e.rotation_error_deg.median
          << "°" << std::setw(9) << e.rotation_error_deg.p90 << "°"
          << std::setprecision(2) << std::setw(9)
          << 100 * e.position_error.median << "%" << std::setw(9)
          << 100 * e.position_error.p90 << "%" << std::setw(9)
          << 100 * e.position_error.max << "%";
    } else {
      out << std::setw(50) << "not aligned";
    }
    if (e.wrong_merge) {
      out << "  YES: " << e.num_displaced_images << " images displaced by "
          << std::setprecision(1) << 100 * e.displacement
          << "% of scale, rotated " << e.displacement_rotation_deg << "°";
    } else {
      out << "  no";
    }
    out << "\n";
  }
  for (const ModelEvaluation& e : evaluations) {
    if (!e.match_consistency) continue;
    const MatchConsistency& c = *e.match_consistency;
    out << "match consistency of " << e.model_path << ": " << c.num_inconsistent
        << " of " << c.num_matches << " verified matches ("
        << std::setprecision(2) << 100.0 * c.InconsistentShare() << "%) and "
        << c.num_inconsistent_pairs << " of " << c.num_pairs
        << " pairs inconsistent: "
        << (e.match_consistent ? "consistent" : "INCONSISTENT") << "\n";
  }
  out << std::defaultfloat
      << "(rotation in degrees; position as a share of the scene scale: the "
         "RMS distance of\n"
         " the reference cameras from their centroid)\n";
}

void WriteEvaluationJson(const std::vector<ModelEvaluation>& evaluations,
                         const std::string& reference_path, std::ostream& out) {
  out << std::setprecision(9);
  out << "{\"reference\": " << JsonString(reference_path) << ", \"models\": [";
  for (size_t i = 0; i < evaluations.size(); ++i) {
    const ModelEvaluation& e = evaluations[i];
    out << (i ? ",\n  " : "\n  ") << "{\"model\": " << JsonString(e.model_path)
        << ", \"registered_images\": " << e.num_registered_images
        << ", \"points3D\": " << e.num_points3D
        << ", \"mean_reprojection_error_px\": " << e.mean_reprojection_error_px
        << ", \"mean_track_length\": " << e.mean_track_length
        << ", \"reference_images\": " << e.num_reference_images
        << ", \"common_images\": " << e.num_common_images
        << ", \"aligned\": " << (e.aligned ? "true" : "false")
        << ", \"alignment_inliers\": " << e.num_alignment_inliers
        << ", \"scene_scale\": " << e.scene_scale << ", ";
    JsonStats(out, "rotation_error_deg", e.rotation_error_deg);
    out << ", ";
    JsonStats(out, "centre_aligned_rotation_error_deg",
              e.centre_aligned_rotation_error_deg);
    out << ", ";
    JsonStats(out, "position_error_relative", e.position_error);
    out << ", \"wrong_merge\": " << (e.wrong_merge ? "true" : "false")
        << ", \"displaced_images\": " << e.num_displaced_images
        << ", \"displaced_image_names\": [";
    for (size_t k = 0; k < e.displaced_image_names.size(); ++k) {
      out << (k ? ", " : "") << JsonString(e.displaced_image_names[k]);
    }
    out << "]"
        << ", \"displacement_relative\": " << e.displacement
        << ", \"displacement_rotation_deg\": " << e.displacement_rotation_deg
        << ", \"track_length_histogram\": [";
    for (size_t k = 0; k < e.track_length_histogram.size(); ++k) {
      out << (k ? ", " : "") << e.track_length_histogram[k];
    }
    out << "]";
    if (const auto& c = e.match_consistency) {
      out << ", \"match_consistency\": {\"matches\": " << c->num_matches
          << ", \"unconfirmed\": " << c->num_unconfirmed
          << ", \"low_angle\": " << c->num_low_angle
          << ", \"tested\": " << c->num_tested
          << ", \"inconsistent\": " << c->num_inconsistent
          << ", \"pairs\": " << c->num_pairs
          << ", \"inconsistent_pairs\": " << c->num_inconsistent_pairs
          << ", \"consistent\": " << (e.match_consistent ? "true" : "false")
          << "}";
    }
    out << "}";
  }
  std::unordered_map<std::string, int> models_of;
  for (const ModelEvaluation& e : evaluations)
    for (const std::string& name : e.image_names) ++models_of[name];
  const auto shared = std::count_if(models_of.begin(), models_of.end(),
                                    [](const auto& n) { return n.second > 1; });
  out << "\n], \"images_in_several_models\": " << shared << "}\n";
}

}  // namespace tmr
