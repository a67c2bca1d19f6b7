// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/reconstruct_images.h"

#include <colmap/scene/database.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "controllers/controller_progress.h"
#include "controllers/forward_motion_options.h"
#include "controllers/photo_extraction.h"
#include "controllers/photo_matching.h"
#include "sfm/forward_motion.h"
#include "tmr/io/atomic_file.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int NumRegistered(const TmrMapperReport& report) {
  int registered = 0;
  for (const int size : report.model_sizes) registered += size;
  return registered;
}

int LargestModel(const TmrMapperReport& report) {
  return report.model_sizes.empty() ? 0 : report.model_sizes.front();
}

std::string SettingsName(bool forward) {
  return forward ? "forward-motion" : "COLMAP's";
}

// Replaces the folder `target` with `source` (both complete model folders).
bool ReplaceFolder(const std::string& source, const std::string& target,
                   std::string* error) {
  std::error_code ec;
  const std::string old = target + ".old";
  fs::remove_all(old, ec);
  if (!ec && fs::exists(target, ec)) fs::rename(target, old, ec);
  if (!ec) fs::rename(source, target, ec);
  if (ec) {
    *error =
        "cannot move '" + source + "' to '" + target + "': " + ec.message();
    return false;
  }
  fs::remove_all(old, ec);
  return true;
}

// tmr_mapper with the mapper settings for how the photos were taken
// (ReconstructImagesOptions::capture), and with capture "auto" a second
// mapping with the other settings when the first registers fewer than half
// the photos; the result with the larger largest model (then more
// registered photos) is kept in mapper.output_path.
bool MapPhotos(const ReconstructImagesOptions& options,
               const TmrMapperOptions& mapper, ReconstructImagesReport* report,
               std::string* error,
               const std::function<void(const std::string&)>& progress) {
  const ForwardMotionStats motion =
      MeasureForwardMotion(*colmap::Database::Open(mapper.database_path),
                           MapperPassThroughOptions().init_max_forward_motion);
  report->num_cameras = motion.num_cameras;
  report->num_cameras_with_exif_focal = motion.num_cameras_with_prior_focal;
  report->num_motion_pairs = motion.num_pairs;
  report->num_forward_pairs = motion.num_forward;
  const bool keep_intrinsics =
      motion.num_cameras > 0 &&
      motion.num_cameras_with_prior_focal == motion.num_cameras;
  const auto settings = [&](bool forward, const std::string& output_path) {
    TmrMapperOptions o = mapper;
    o.output_path = output_path;
    if (forward)
      o.mapper = ForwardMotionMapperOptions(o.mapper, keep_intrinsics);
    return o;
  };
  const bool forward = options.capture == "forward" ||
                       (options.capture == "auto" &&
                        motion.MovesForward(options.forward_motion_share));
  if (progress) {
    progress(std::to_string(motion.num_forward) + " of " +
             std::to_string(motion.num_pairs) +
             " verified pairs move along the viewing direction: mapping with " +
             SettingsName(forward) + " settings");
  }
  if (!RunTmrMapper(settings(forward, mapper.output_path), &report->mapper,
                    error, progress)) {
    return false;
  }
  report->capture = forward ? "forward" : "general";
  const int registered = NumRegistered(report->mapper);
  if (options.capture != "auto" || 2 * registered >= report->num_images)
    return true;

  report->second_pass = true;
  report->first_pass_registered = registered;
  const std::string second_path = mapper.output_path + ".second";
  std::error_code ec;
  fs::remove_all(second_path, ec);
  if (progress) {
    progress("registered " + std::to_string(registered) + " of " +
             std::to_string(report->num_images) +
             " photos: mapping again with " + SettingsName(!forward) +
             " settings");
  }
  TmrMapperReport second;
  std::string second_error;
  const bool mapped = RunTmrMapper(settings(!forward, second_path), &second,
                                   &second_error, progress);
  if (mapped && (LargestModel(second) > LargestModel(report->mapper) ||
                 (LargestModel(second) == LargestModel(report->mapper) &&
                  NumRegistered(second) > registered))) {
    if (!ReplaceFolder(second_path, mapper.output_path, error)) return false;
    report->mapper = std::move(second);
    report->capture = forward ? "general" : "forward";
    report->kept_second_pass = true;
  } else {
    if (progress && !mapped)
      progress("the second mapping failed: " + second_error);
    fs::remove_all(second_path, ec);
  }
  return true;
}

}  // namespace

bool RunReconstructImages(
    const ReconstructImagesOptions& options, ReconstructImagesReport* report,
    std::string* error,
    const std::function<void(const std::string&)>& progress) {
  auto fail = [error](const std::string& message) {
    *error = message;
    return false;
  };
  auto say = [&progress](const std::string& line) {
    if (progress) progress(line);
  };
  if (!options.Check(error)) return false;
  if (!fs::is_directory(options.image_path))
    return fail("image folder '" + options.image_path + "' does not exist");
  std::vector<std::string> photos;
  if (!ListPhotos(options.image_path, &photos, error)) return false;
  report->num_photos = static_cast<int>(photos.size());
  if (report->num_photos < 2) {
    return fail("found " + std::to_string(report->num_photos) +
                " photo(s) in '" + options.image_path + "'; need at least 2");
  }
  std::error_code ec;
  fs::create_directories(options.workspace_path, ec);
  if (ec) {
    return fail("cannot create workspace '" + options.workspace_path +
                "': " + ec.message());
  }
  const TmrMapperOptions mapper = options.MapperOptions();
  const std::string& database = mapper.database_path;

  ExtractPhotoFeatures(options, photos, report, progress);
  report->num_images = static_cast<int>(
      CountRows(database, "SELECT COUNT(*) FROM descriptors WHERE rows > 0"));
  if (report->num_images < 2) {
    return fail("features were found in " +
                std::to_string(std::max(report->num_images, 0)) +
                " image(s) of '" + options.image_path +
                "'; need at least 2 readable photos");
  }

  // Matches: COLMAP skips pairs already matched.
  {
    const auto start = Clock::now();
    std::vector<std::string> names;
    for (const colmap::Image& image :
         colmap::Database::Open(database)->ReadAllImages())
      names.push_back(image.Name());
    report->matcher = ChooseMatcher(options, names, &report->matcher_reason);
    PhotoMatcher matcher;
    if (!CreatePhotoMatcher(options, report->matcher, report->num_images,
                            &matcher, error, progress)) {
      return false;
    }
    say("matching " + std::to_string(report->num_images) + " images (" +
        report->matcher + ": " + report->matcher_reason + ")");
    RunWithProgress(
        matcher.thread.get(), "matched pairs",
        [&] { return CountRows(database, "SELECT COUNT(*) FROM matches"); },
        matcher.max_pairs, !matcher.max_pairs_exact, progress);
    report->matching_seconds = SecondsSince(start);
  }
  report->num_verified_pairs = static_cast<int>(CountRows(
      database, "SELECT COUNT(*) FROM two_view_geometries WHERE rows > 0"));
  if (report->num_verified_pairs < 1) {
    return fail("no image pair of '" + options.image_path +
                "' has a verified geometry: the photos do not overlap" +
                (report->matcher == "spatial"
                     ? " (or have no GPS position for --matcher spatial)"
                     : ""));
  }
  say("features in " + std::to_string(report->num_images) + " images, " +
      std::to_string(report->num_verified_pairs) + " verified pairs");

  const auto mapping_start = Clock::now();
  if (!MapPhotos(options, mapper, report, error, progress)) return false;
  report->mapping_seconds = SecondsSince(mapping_start);

  report->models.clear();
  for (size_t i = 0; i < report->mapper.model_sizes.size(); ++i) {
    report->models.push_back(EvaluateModel(
        "", (fs::path(mapper.output_path) / std::to_string(i)).string(), {}));
  }
  if (!WriteFileAtomically(
          (fs::path(options.workspace_path) / "summary.txt").string(),
          ReconstructImagesSummary(*report))) {
    return fail("cannot write summary.txt in '" + options.workspace_path + "'");
  }
  return true;
}

std::string ReconstructImagesSummary(const ReconstructImagesReport& report) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1);
  out << "photos: " << report.num_photos
      << ", with features: " << report.num_images << " ("
      << report.extraction_seconds << " s)\n"
      << "cameras: " << report.num_cameras << " ("
      << report.num_cameras_with_exif_focal
      << " with an EXIF focal length; photos of the same EXIF make, model, "
         "focal length and size share one"
      << (report.num_folder_cameras > 0
              ? ", and so do those of " +
                    std::to_string(report.num_folder_cameras) +
                    " folder(s) of photos of one size and EXIF camera or "
                    "numbered frames without EXIF"
              : std::string())
      << ")\n"
      << "verified pairs: " << report.num_verified_pairs << " ("
      << report.matcher << " matching: " << report.matcher_reason << "; "
      << report.matching_seconds << " s)\n"
      << "motion: " << report.num_forward_pairs << " of "
      << report.num_motion_pairs
      << " verified pairs move along the viewing direction\n";
  if (report.second_pass) {
    const bool first_forward =
        (report.capture == "forward") != report.kept_second_pass;
    out << "mapping: " << SettingsName(first_forward) << " settings registered "
        << report.first_pass_registered << " of " << report.num_images
        << " photos; " << SettingsName(!first_forward) << " settings "
        << (report.kept_second_pass ? "did better: kept" : "did not do better");
  } else {
    out << "mapping: " << SettingsName(report.capture == "forward")
        << " settings";
  }
  out << "\nmodels: " << report.models.size() << " (" << report.mapping_seconds
      << " s)\n";
  for (size_t i = 0; i < report.models.size(); ++i) {
    const ModelEvaluation& m = report.models[i];
    out << "  sparse/" << i << ": " << m.num_registered_images << " images, "
        << m.num_points3D << " points, mean reprojection error "
        << std::setprecision(2) << m.mean_reprojection_error_px
        << " px, mean track length " << m.mean_track_length
        << std::setprecision(1) << "\n";
  }
  int registered = 0;
  for (const ModelEvaluation& m : report.models)
    registered += m.num_registered_images;
  out << "registered: " << registered << " of " << report.num_images
      << " images\n";
  return out.str();
}

}  // namespace tmr
