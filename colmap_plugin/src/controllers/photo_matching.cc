// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/photo_matching.h"

#include <colmap/controllers/feature_matching.h>
#include <colmap/math/random.h>
#include <colmap/retrieval/visual_index.h>
#include <colmap/scene/database.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "controllers/controller_progress.h"
#include "controllers/tmr_mapper_options.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

// The user's vocabulary file, or one built from the workspace's features
// (workspace_path/vocab_tree.bin, reused when a rerun finds it). A file
// not built here is read once first: COLMAP's matcher thread would end the
// program on a file that is not a vocabulary.
bool VocabularyPath(const ReconstructImagesOptions& options, int num_images,
                    std::string* path, std::string* error,
                    const std::function<void(const std::string&)>& progress) {
  auto say = [&progress](const std::string& line) {
    if (progress) progress(line);
  };
  *path = options.vocab_tree_path;
  if (path->empty()) {
    *path = (fs::path(options.workspace_path) / "vocab_tree.bin").string();
    std::error_code ec;
    if (!fs::is_regular_file(*path, ec)) {
      VocabularyOptions vocabulary;
      vocabulary.num_visual_words =
          VocabularyWords(num_images, options.vocab_num_words);
      vocabulary.seed = options.mapper.tree.seed;
      say("building a vocabulary tree of up to " +
          std::to_string(vocabulary.num_visual_words) +
          " words from the photos' features");
      const auto start = std::chrono::steady_clock::now();
      const std::string database = options.MapperOptions().database_path;
      if (!RunWithHeartbeat(
              [&] {
                return BuildVocabularyTree(database, *path, vocabulary, error);
              },
              "building the vocabulary tree", progress)) {
        return false;
      }
      std::ostringstream line;
      line << "vocabulary tree built in " << std::fixed << std::setprecision(1)
           << SecondsSince(start) << " s";
      say(line.str());
      return true;
    }
  }
  try {
    colmap::retrieval::VisualIndex::Read(*path);
  } catch (const std::exception& e) {
    *error = "'" + *path + "' is not a COLMAP vocabulary tree: " + e.what();
    return false;
  }
  return true;
}

}  // namespace

bool IsNumberedSequence(const std::vector<std::string>& names) {
  if (names.size() < 3) return false;
  // Numbers by the text around them (folder and prefix, suffix) and by
  // their digit count: COLMAP's sequential matcher orders photos by name,
  // which is the numbers' order only when they are zero-padded alike.
  std::map<std::string, std::vector<int64_t>> numbers;
  for (const std::string& name : names) {
    const fs::path path(name);
    const std::string stem = path.stem().string();
    const size_t last = stem.find_last_of("0123456789");
    if (last == std::string::npos) continue;
    size_t first = last;
    while (first > 0 &&
           std::isdigit(static_cast<unsigned char>(stem[first - 1])))
      --first;
    const size_t digits = last - first + 1;
    if (digits > 18) continue;  // not a frame number
    const std::string pattern =
        (path.parent_path() / stem.substr(0, first)).string() + '\n' +
        std::to_string(digits) + '\n' + stem.substr(last + 1) +
        path.extension().string();
    numbers[pattern].push_back(std::stoll(stem.substr(first, digits)));
  }
  std::vector<int64_t> largest;
  for (auto& [pattern, group] : numbers)
    if (group.size() > largest.size()) largest = std::move(group);
  if (largest.size() < 3 || 10 * largest.size() < 9 * names.size())
    return false;
  std::sort(largest.begin(), largest.end());
  if (std::adjacent_find(largest.begin(), largest.end()) != largest.end())
    return false;  // the same number twice: not one sequence
  return largest.back() - largest.front() <=
         10 * static_cast<int64_t>(largest.size() - 1);
}

std::string ChooseMatcher(const ReconstructImagesOptions& options,
                          const std::vector<std::string>& names,
                          std::string* reason) {
  if (options.matcher != "auto") {
    *reason = "as asked";
    return options.matcher;
  }
  const std::string count = std::to_string(names.size()) + " images";
  const std::string limit = std::to_string(options.max_exhaustive_images);
  if (static_cast<int>(names.size()) <= options.max_exhaustive_images) {
    *reason = count + ", at most " + limit;
    return "exhaustive";
  }
  if (IsNumberedSequence(names)) {
    *reason = count + ", more than " + limit + ", named as a numbered sequence";
    return "sequential";
  }
  *reason = count + ", more than " + limit + ", not a numbered sequence";
  return "retrieval";
}

int VocabularyWords(int num_images, int max_words) {
  return std::min(max_words, std::max(1024, 2 * num_images));
}

bool BuildVocabularyTree(const std::string& database_path,
                         const std::string& path,
                         const VocabularyOptions& options, std::string* error) {
  const std::string partial = path + ".partial";
  try {
    const std::shared_ptr<colmap::Database> database =
        colmap::Database::Open(database_path);
    const int64_t num_descriptors =
        static_cast<int64_t>(database->NumDescriptors());
    const int num_words = static_cast<int>(std::min<int64_t>(
        options.num_visual_words,
        num_descriptors / std::max(1, options.descriptors_per_word)));
    // COLMAP's word search index trains 2 sqrt(words) coarse centroids on
    // the words: with fewer than 100 words, too few points per centroid
    // (64 words gave a vocabulary that retrieved nothing in 1 of 4 builds).
    if (num_words < 100) {
      *error = "too few features (" + std::to_string(num_descriptors) +
               ") for a vocabulary tree";
      return false;
    }
    colmap::SetPRNGSeed(static_cast<unsigned>(options.seed));
    const colmap::FeatureDescriptorsFloat descriptors =
        colmap::LoadRandomDatabaseDescriptors(
            *database, num_words * options.descriptors_per_word);
    colmap::retrieval::VisualIndex::BuildOptions build;
    build.num_visual_words = num_words;
    build.num_iterations = options.num_iterations;
    build.num_rounds = 1;
    // The words' Hamming thresholds differ from run to run when the word
    // search runs on several threads (faiss); on one they are repeatable.
    build.num_threads = 1;
    const std::unique_ptr<colmap::retrieval::VisualIndex> index =
        colmap::retrieval::VisualIndex::Create();
    index->Build(build, descriptors);
    index->Write(partial);
  } catch (const std::exception& e) {
    *error = "cannot build a vocabulary tree: " + std::string(e.what());
    std::error_code ec;
    fs::remove(partial, ec);
    return false;
  }
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) {
    *error = "cannot write '" + path + "': " + ec.message();
    fs::remove(partial, ec);
    return false;
  }
  return true;
}

bool CreatePhotoMatcher(
    const ReconstructImagesOptions& options, const std::string& name,
    int64_t num_images, PhotoMatcher* matcher, std::string* error,
    const std::function<void(const std::string&)>& progress) {
  const std::string database = options.MapperOptions().database_path;
  colmap::FeatureMatchingOptions matching;
  matching.use_gpu = false;
  matching.num_threads = options.num_threads;
  matching.guided_matching = options.guided_matching;
  colmap::TwoViewGeometryOptions geometry;
  // Seeded RANSAC: the same photos verify into the same two-view
  // geometries whichever matching thread takes a pair (unseeded, each
  // thread draws from its own generator).
  geometry.ransac_options.random_seed = ColmapSeed(options.mapper.tree.seed);
  const int64_t n = num_images;
  const int64_t all_pairs = n * (n - 1) / 2;
  // COLMAP retrieves the query photo itself first.
  const int retrieved = options.retrieval_neighbors + 1;
  std::string vocabulary;
  if (name == "retrieval" &&
      !VocabularyPath(options, static_cast<int>(num_images), &vocabulary, error,
                      progress)) {
    return false;
  }
  // Loop detection is an addition: without a vocabulary, sequential
  // matching still runs.
  if (name == "sequential" && options.loop_detection &&
      !VocabularyPath(options, static_cast<int>(num_images), &vocabulary, error,
                      progress)) {
    if (progress) progress("no loop detection: " + *error);
    error->clear();
    vocabulary.clear();
  }
  if (name == "exhaustive") {
    matcher->thread = colmap::CreateExhaustiveFeatureMatcher(
        colmap::ExhaustivePairingOptions(), matching, geometry, database);
    matcher->max_pairs = all_pairs;
    matcher->max_pairs_exact = true;
  } else if (name == "sequential") {
    colmap::SequentialPairingOptions sequential;
    sequential.overlap = options.sequential_overlap;
    sequential.quadratic_overlap = options.quadratic_overlap;
    sequential.loop_detection = !vocabulary.empty();
    sequential.loop_detection_num_images = retrieved;
    sequential.vocab_tree_path = vocabulary;
    sequential.num_threads = options.num_threads;
    matcher->thread = colmap::CreateSequentialFeatureMatcher(
        sequential, matching, geometry, database);
    matcher->max_pairs = std::min<int64_t>(
        all_pairs,
        n * options.sequential_overlap +
            (sequential.loop_detection ? n / sequential.loop_detection_period *
                                             options.retrieval_neighbors
                                       : 0));
  } else if (name == "retrieval") {
    colmap::VocabTreePairingOptions retrieval;
    retrieval.num_images = retrieved;
    retrieval.num_threads = options.num_threads;
    retrieval.vocab_tree_path = vocabulary;
    matcher->thread = colmap::CreateVocabTreeFeatureMatcher(retrieval, matching,
                                                            geometry, database);
    matcher->max_pairs =
        std::min<int64_t>(all_pairs, n * options.retrieval_neighbors);
  } else {
    colmap::SpatialPairingOptions spatial;
    spatial.max_num_neighbors = options.spatial_max_num_neighbors;
    spatial.num_threads = options.num_threads;
    matcher->thread = colmap::CreateSpatialFeatureMatcher(spatial, matching,
                                                          geometry, database);
    matcher->max_pairs =
        std::min<int64_t>(all_pairs, n * options.spatial_max_num_neighbors);
  }
  return true;
}

}  // namespace tmr
