// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tmr/colmap/model_evaluation.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

// From a folder of photos to models: COLMAP's feature extraction (CPU
// SIFT), a COLMAP matcher, then tmr_mapper. The COLMAP options keep
// COLMAP's names and defaults.
struct ReconstructImagesOptions {
  std::string image_path;      // photos (JPEG, PNG, ...), read-only
  std::string workspace_path;  // database.db, sparse/0, 1, ..., summary.txt
  // "exhaustive", "sequential" (photos in file-name order, as from a video
  // or a walk), "retrieval" (each photo with its most similar ones by a
  // vocabulary tree, the paper's matching), "spatial" (by EXIF GPS) or
  // "auto": exhaustive up to max_exhaustive_images photos; above, sequential
  // when the names are a numbered sequence, retrieval otherwise.
  std::string matcher = "auto";     // --matcher
  int max_exhaustive_images = 500;  // --max_exhaustive_images
  // Retrieval: similar photos each photo is matched with (paper: 30); also
  // the photos that sequential loop detection retrieves.
  int retrieval_neighbors = 30;  // --retrieval_neighbors
  // A COLMAP vocabulary tree file; empty: one is built from the photos'
  // own features with 2 words per photo, at least 1,024 and at most
  // vocab_num_words.
  std::string vocab_tree_path;  // --VocabTreeMatching.vocab_tree_path
  int vocab_num_words = 4096;   // --vocab_num_words
  // How the photos were taken, which picks COLMAP's mapper settings:
  // "general" (COLMAP's), "forward" (moving straight ahead along the
  // viewing direction: ForwardMotionMapperOptions) or "auto": forward when
  // most verified pairs move forward, and when a first mapping registers
  // fewer than half the photos, a second one with the other settings (the
  // better result is kept).
  std::string capture = "auto";  // --capture
  // With capture "auto", the forward settings come first when more than
  // this share of the verified pairs move along the viewing direction
  // (1: never first, only as the second mapping).
  double forward_motion_share = 0.5;           // --forward_motion_share
  std::string camera_model = "SIMPLE_RADIAL";  // --ImageReader.camera_model
  bool single_camera = false;                  // --ImageReader.single_camera
  // One camera per folder whose photos share size and EXIF make, model
  // and focal length, or are numbered frames without EXIF (a video); COLMAP
  // alone gives each such photo its own camera unless EXIF names a make and
  // model.
  bool folder_cameras = true;  // --folder_cameras
  // Extraction as `colmap automatic_reconstructor` (its default quality,
  // "high") sets it.
  int max_image_size = 2400;          // --FeatureExtraction.max_image_size
  int max_num_features = 8192;        // --SiftExtraction.max_num_features
  bool estimate_affine_shape = true;  // --SiftExtraction.estimate_affine_shape
  // automatic_reconstructor turns guided matching on; on the CPU it made
  // matching 7.8 times slower for the same models (docs/reconstruct.md).
  bool guided_matching = false;  // --FeatureMatching.guided_matching
  int sequential_overlap = 10;   // --SequentialMatching.overlap
  // COLMAP's default (true) pairs offsets 1, 2, 4, ... 2^(overlap-1); here
  // offsets 1 to overlap, and loop detection finds the returns.
  bool quadratic_overlap = false;  // --SequentialMatching.quadratic_overlap
  // Every tenth photo also with its retrieved ones (COLMAP's default: off).
  bool loop_detection = true;          // --SequentialMatching.loop_detection
  int spatial_max_num_neighbors = 50;  // --SpatialMatching.max_num_neighbors
  // Threads of every stage (-1: all cores); mapper.num_threads follows it.
  int num_threads = -1;  // --num_threads
  // database_path, output_path, image_path and num_threads are set by the
  // run (MapperOptions).
  TmrMapperOptions mapper;

  // `mapper` as the run uses it: workspace_path/database.db in,
  // workspace_path/sparse out, colours from image_path, num_threads.
  TmrMapperOptions MapperOptions() const;

  // Lists the options above and mapper's as rows (tmr/util/option_table.h).
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

struct ReconstructImagesReport {
  int num_photos = 0;  // image files found in image_path
  int num_images = 0;  // images with features in the database
  // Cameras in the database: COLMAP's image reader gives photos with the
  // same EXIF make, model, focal length and size one camera, and every
  // other photo its own.
  int num_cameras = 0;
  int num_cameras_with_exif_focal = 0;  // focal length prior from EXIF
  int num_folder_cameras = 0;  // folders of one camera (folder_cameras)
  int num_verified_pairs = 0;  // pairs with verified two-view geometry
  std::string matcher;         // the matcher that ran
  std::string matcher_reason;  // why (ChooseMatcher)
  double extraction_seconds = 0.0;
  double matching_seconds = 0.0;
  double mapping_seconds = 0.0;  // every mapping pass
  // Verified pairs with a translation direction, and those moving along the
  // viewing direction (MeasureForwardMotion).
  int num_motion_pairs = 0;
  int num_forward_pairs = 0;
  std::string capture;  // the mapper settings of the kept models
  // A second mapping (capture "auto", fewer than half the photos registered
  // by the first): what the first registered, and whether the second's
  // models were kept.
  bool second_pass = false;
  int first_pass_registered = 0;
  bool kept_second_pass = false;
  TmrMapperReport mapper;               // of the kept models
  std::vector<ModelEvaluation> models;  // statistics of sparse/0, 1, ...
};

// Runs the three stages into options.workspace_path. A rerun on the same
// workspace reuses the features and matches already in its database (COLMAP
// skips them) and maps again. `progress` receives one line per step and,
// during extraction and matching, one about every ten seconds. Returns
// false with one reason in `error`.
bool RunReconstructImages(
    const ReconstructImagesOptions& options, ReconstructImagesReport* report,
    std::string* error,
    const std::function<void(const std::string&)>& progress = nullptr);

// The summary written to workspace_path/summary.txt: the stages with their
// times, then one line per model.
std::string ReconstructImagesSummary(const ReconstructImagesReport& report);

}  // namespace tmr
