// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// ReconstructImagesOptions: the options of tmr_reconstruct, their checks
// and the tmr_mapper options of its mapping stage.
#include <colmap/sensor/models.h>

#include <filesystem>

#include "tmr/colmap/reconstruct_images.h"

namespace tmr {

namespace fs = std::filesystem;

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
         "auto | exhaustive | sequential (file-name order) | retrieval "
         "(vocabulary tree) | spatial (EXIF GPS)");
  t->Add("max_exhaustive_images", &max_exhaustive_images,
         "auto: exhaustive up to this many images; above, sequential for "
         "numbered names, retrieval otherwise")
      .AtLeast(2);
  t->Add("retrieval_neighbors", &retrieval_neighbors,
         "similar photos each photo is matched with (retrieval, loop "
         "detection)")
      .AtLeast(1);
  t->Add("VocabTreeMatching.vocab_tree_path", &vocab_tree_path,
         "vocabulary tree file; empty: built from the photos' features");
  t->Add("vocab_num_words", &vocab_num_words,
         "most words of the vocabulary built from the photos' features (2 "
         "per photo, at least 1024)")
      .AtLeast(100);
  t->Add("capture", &capture,
         "auto | general | forward (moving straight ahead): COLMAP's mapper "
         "settings for the photos");
  t->Add("forward_motion_share", &forward_motion_share,
         "capture auto: forward settings first when more than this share "
         "of verified pairs move along the viewing direction")
      .AtLeast(0)
      .AtMost(1);
  t->Add("ImageReader.camera_model", &camera_model, "COLMAP camera model");
  t->Add("ImageReader.single_camera", &single_camera,
         "one camera for all photos");
  t->Add("folder_cameras", &folder_cameras,
         "one camera per folder of photos with one size and EXIF camera, or "
         "of numbered frames without EXIF");
  t->Add("FeatureExtraction.max_image_size", &max_image_size,
         "photos are downscaled to this size for SIFT")
      .AtLeast(16);
  t->Add("SiftExtraction.max_num_features", &max_num_features,
         "SIFT features per photo")
      .AtLeast(1);
  t->Add("SiftExtraction.estimate_affine_shape", &estimate_affine_shape,
         "affine-covariant SIFT (as automatic_reconstructor)");
  t->Add("FeatureMatching.guided_matching", &guided_matching,
         "guided matching after verification");
  t->Add("SequentialMatching.overlap", &sequential_overlap,
         "neighbours each photo is matched with (sequential)")
      .AtLeast(1);
  t->Add("SequentialMatching.quadratic_overlap", &quadratic_overlap,
         "sequential: neighbours at offsets 1, 2, 4, ... instead of 1 to "
         "overlap");
  t->Add("SequentialMatching.loop_detection", &loop_detection,
         "sequential: every tenth photo also with its retrieved ones");
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
      matcher != "retrieval" && matcher != "spatial") {
    return fail(
        "--matcher must be auto, exhaustive, sequential, retrieval or "
        "spatial, not '" +
        matcher + "'");
  }
  if (std::error_code ec;
      !vocab_tree_path.empty() && !fs::is_regular_file(vocab_tree_path, ec)) {
    return fail("vocabulary tree '" + vocab_tree_path + "' is not a file");
  }
  if (capture != "auto" && capture != "general" && capture != "forward") {
    return fail("--capture must be auto, general or forward, not '" + capture +
                "'");
  }
  if (!colmap::ExistsCameraModelWithName(camera_model))
    return fail("unknown camera model '" + camera_model + "'");
  if (num_threads == 0 || num_threads < -1)
    return fail("num_threads must be -1 or >= 1");
  return CheckOptionRows(*this, error) && MapperOptions().Check(error);
}

}  // namespace tmr
