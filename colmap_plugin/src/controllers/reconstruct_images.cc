// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/reconstruct_images.h"

#include <colmap/controllers/feature_extraction.h>
#include <colmap/controllers/feature_matching.h>
#include <colmap/feature/sift.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <thread>

#include "sfm/forward_motion.h"
#include "tmr/io/atomic_file.h"
#include "tmr/io/database_reader.h"
#include "tmr/io/sqlite.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

bool IsPhoto(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const char* known :
       {".jpg", ".jpeg", ".png", ".tif", ".tiff", ".bmp", ".ppm", ".pgm"}) {
    if (ext == known) return true;
  }
  return false;
}

// Image files under `folder`, recursively (COLMAP's image reader reads
// sub-folders too).
int CountPhotos(const std::string& folder, std::string* error) {
  std::error_code ec;
  int count = 0;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->is_regular_file(ec) && IsPhoto(it->path())) ++count;
  }
  if (ec) *error = "cannot read '" + folder + "': " + ec.message();
  return count;
}

// One COUNT(*) on the workspace database while COLMAP may be writing it
// (WAL journal: readers do not block the writer); -1 when it cannot be
// read right now.
int64_t CountRows(const std::string& database, const std::string& sql) {
  try {
    const SqliteDatabase db(database, SqliteDatabase::Mode::kReadOnly,
                            /*busy_timeout_ms=*/1000);
    SqliteStatement stmt(db, sql);
    return stmt.Step() ? stmt.Int(0) : -1;
  } catch (const DatabaseError&) {
    return -1;
  }
}

// Runs a COLMAP controller thread to its end; about every ten seconds
// reports `count()` of `total` with a rate-based ETA.
void RunWithProgress(colmap::Thread* thread, const std::string& what,
                     const std::function<int64_t()>& count, int64_t total,
                     const std::function<void(const std::string&)>& progress) {
  const auto start = Clock::now();
  const int64_t initial = std::max<int64_t>(0, count());
  thread->Start();
  auto last = start;
  while (!thread->IsFinished()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (!progress || Clock::now() - last < std::chrono::seconds(10)) continue;
    last = Clock::now();
    const int64_t done = count();
    if (done < 0) continue;
    std::ostringstream line;
    line << what << ": " << done << " of " << total;
    const double seconds = SecondsSince(start);
    if (done > initial && done < total) {
      line << "; ETA " << std::fixed << std::setprecision(0)
           << seconds / (done - initial) * (total - done) << " s";
    }
    progress(line.str());
  }
  thread->Wait();
}

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
    *error = "cannot move '" + source + "' to '" + target + "': " + ec.message();
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
    if (forward) o.mapper = ForwardMotionMapperOptions(o.mapper, keep_intrinsics);
    return o;
  };
  const bool forward = options.capture == "forward" ||
                       (options.capture == "auto" && motion.MostlyForward());
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
             std::to_string(report->num_images) + " photos: mapping again with " +
             SettingsName(!forward) + " settings");
  }
  TmrMapperReport second;
  std::string second_error;
  const bool mapped =
      RunTmrMapper(settings(!forward, second_path), &second, &second_error,
                   progress);
  if (mapped &&
      (LargestModel(second) > LargestModel(report->mapper) ||
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
  std::string list_error;
  report->num_photos = CountPhotos(options.image_path, &list_error);
  if (!list_error.empty()) return fail(list_error);
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

  // Features: COLMAP skips images already in the database.
  {
    const auto start = Clock::now();
    colmap::ImageReaderOptions reader;
    reader.image_path = options.image_path;
    reader.camera_model = options.camera_model;
    reader.single_camera = options.single_camera;
    colmap::FeatureExtractionOptions extraction(
        colmap::FeatureExtractorType::SIFT);
    extraction.use_gpu = false;
    extraction.num_threads = options.num_threads;
    extraction.max_image_size = options.max_image_size;
    extraction.sift->max_num_features = options.max_num_features;
    extraction.sift->estimate_affine_shape = options.estimate_affine_shape;
    say("extracting features of " + std::to_string(report->num_photos) +
        " photos");
    auto extractor =
        colmap::CreateFeatureExtractorController(database, reader, extraction);
    RunWithProgress(
        extractor.get(), "features",
        [&] { return CountRows(database, "SELECT COUNT(*) FROM descriptors"); },
        report->num_photos, progress);
    report->extraction_seconds = SecondsSince(start);
  }
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
    report->matcher = options.matcher;
    if (report->matcher == "auto") {
      report->matcher = report->num_images <= options.max_exhaustive_images
                            ? "exhaustive"
                            : "sequential";
    }
    colmap::FeatureMatchingOptions matching;
    matching.use_gpu = false;
    matching.num_threads = options.num_threads;
    matching.guided_matching = options.guided_matching;
    colmap::TwoViewGeometryOptions geometry;
    const int64_t n = report->num_images;
    int64_t pairs = n * (n - 1) / 2;
    std::unique_ptr<colmap::Thread> matcher;
    if (report->matcher == "exhaustive") {
      matcher = colmap::CreateExhaustiveFeatureMatcher(
          colmap::ExhaustivePairingOptions(), matching, geometry, database);
    } else if (report->matcher == "sequential") {
      colmap::SequentialPairingOptions sequential;
      sequential.overlap = options.sequential_overlap;
      pairs = std::min<int64_t>(pairs, n * options.sequential_overlap * 3 / 2);
      matcher = colmap::CreateSequentialFeatureMatcher(sequential, matching,
                                                       geometry, database);
    } else {
      colmap::SpatialPairingOptions spatial;
      spatial.max_num_neighbors = options.spatial_max_num_neighbors;
      spatial.num_threads = options.num_threads;
      pairs = std::min<int64_t>(pairs, n * options.spatial_max_num_neighbors);
      matcher = colmap::CreateSpatialFeatureMatcher(spatial, matching, geometry,
                                                    database);
    }
    say("matching " + std::to_string(n) + " images (" + report->matcher + ")");
    RunWithProgress(
        matcher.get(), "matched pairs",
        [&] { return CountRows(database, "SELECT COUNT(*) FROM matches"); },
        pairs, progress);
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
         "focal length and size share one)\n"
      << "verified pairs: " << report.num_verified_pairs << " ("
      << report.matcher << " matching, " << report.matching_seconds << " s)\n"
      << "motion: " << report.num_forward_pairs << " of "
      << report.num_motion_pairs
      << " verified pairs move along the viewing direction\n";
  if (report.second_pass) {
    const bool first_forward =
        (report.capture == "forward") != report.kept_second_pass;
    out << "mapping: " << SettingsName(first_forward)
        << " settings registered " << report.first_pass_registered << " of "
        << report.num_images << " photos; "
        << SettingsName(!first_forward) << " settings "
        << (report.kept_second_pass ? "did better: kept"
                                    : "did not do better");
  } else {
    out << "mapping: " << SettingsName(report.capture == "forward")
        << " settings";
  }
  out << "\nmodels: " << report.models.size() << " ("
      << report.mapping_seconds << " s)\n";
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
