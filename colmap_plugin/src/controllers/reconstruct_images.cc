// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/colmap/reconstruct_images.h"

#include <colmap/controllers/feature_extraction.h>
#include <colmap/controllers/feature_matching.h>
#include <colmap/feature/sift.h>
#include <colmap/sensor/models.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <thread>

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

}  // namespace

TmrMapperOptions ReconstructImagesOptions::MapperOptions() const {
  TmrMapperOptions o = mapper;
  o.database_path = (fs::path(workspace_path) / "database.db").string();
  o.output_path = (fs::path(workspace_path) / "sparse").string();
  o.image_path = image_path;
  o.num_threads = num_threads;
  return o;
}

void ReconstructImagesOptions::AddTo(OptionTable* t) {
  t->Add("num_threads", &num_threads, "threads of every stage (-1: all cores)");
  t->Add("matcher", &matcher,
         "auto | exhaustive | sequential (file-name order) | spatial (EXIF "
         "GPS)");
  t->Add("max_exhaustive_images", &max_exhaustive_images,
         "auto: exhaustive up to this many images, sequential above")
      .AtLeast(2);
  t->Add("ImageReader.camera_model", &camera_model, "COLMAP camera model");
  t->Add("ImageReader.single_camera", &single_camera,
         "one camera for all photos");
  t->Add("FeatureExtraction.max_image_size", &max_image_size,
         "photos are downscaled to this size for SIFT")
      .AtLeast(16);
  t->Add("SiftExtraction.max_num_features", &max_num_features,
         "SIFT features per photo")
      .AtLeast(1);
  t->Add("FeatureMatching.guided_matching", &guided_matching,
         "guided matching after verification");
  t->Add("SequentialMatching.overlap", &sequential_overlap,
         "neighbours each photo is matched with (sequential)")
      .AtLeast(1);
  t->Add("SpatialMatching.max_num_neighbors", &spatial_max_num_neighbors,
         "GPS neighbours each photo is matched with (spatial)")
      .AtLeast(1);
  mapper.AddTo(t);
}

bool ReconstructImagesOptions::Check(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (image_path.empty()) return fail("no image folder given");
  if (workspace_path.empty()) return fail("no workspace folder given");
  if (matcher != "auto" && matcher != "exhaustive" && matcher != "sequential" &&
      matcher != "spatial") {
    return fail(
        "--matcher must be auto, exhaustive, sequential or spatial, not '" +
        matcher + "'");
  }
  if (!colmap::ExistsCameraModelWithName(camera_model))
    return fail("unknown camera model '" + camera_model + "'");
  if (num_threads == 0 || num_threads < -1)
    return fail("num_threads must be -1 or >= 1");
  return CheckOptionRows(*this, error) && MapperOptions().Check(error);
}

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

  if (!RunTmrMapper(mapper, &report->mapper, error, progress)) return false;

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
      << "verified pairs: " << report.num_verified_pairs << " ("
      << report.matcher << " matching, " << report.matching_seconds << " s)\n"
      << "models: " << report.models.size() << " ("
      << report.mapper.total_seconds << " s)\n";
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
