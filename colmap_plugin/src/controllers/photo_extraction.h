// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The extraction stage of tmr_reconstruct (RunReconstructImages), and which
// photos share a camera. COLMAP's image reader
// gives photos with the same EXIF make, model, focal length and size one
// camera and every other photo its own; frames of a video (no EXIF) and
// phone photos with an EXIF focal length but no make or model then get a
// camera each, whose focal lengths drift apart in bundle adjustment. Here a
// folder whose photos agree in size and EXIF camera fields shares one.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tmr/colmap/reconstruct_images.h"

namespace tmr {

struct PhotoHeader {
  std::string name;  // COLMAP's image name: relative path, '/'-separated
  int width = 0;
  int height = 0;
  std::string make;         // EXIF; empty when absent
  std::string model;        // EXIF; empty when absent
  double focal_length = 0;  // EXIF (35 mm equivalent, else mm); 0: absent
};

// Reads a photo's size and EXIF camera fields without decoding its pixels
// (OpenImageIO, unrotated as COLMAP reads it). False when it cannot be read.
bool ReadPhotoHeader(const std::string& path, PhotoHeader* header);

// Folders ("" for the top folder) whose photos may share one camera: at
// least two photos, all of the same size and the same EXIF make, model and
// focal length, with at least a focal length; or with no EXIF camera field
// at all and numbered as a sequence (IsNumberedSequence: a video's frames).
std::vector<std::string> FoldersOfOneCamera(
    const std::vector<PhotoHeader>& photos);

// The folder of a COLMAP image name ("" for the top folder).
std::string FolderOf(const std::string& name);

// The photos (JPEG, PNG, TIFF, BMP, PPM, PGM, WebP, JPEG 2000) under
// `folder`, sub-folders
// too (COLMAP's image reader reads them), by COLMAP image name, sorted.
// False with one reason in `error`.
bool ListPhotos(const std::string& folder, std::vector<std::string>* names,
                std::string* error);

// COLMAP's SIFT extraction (CPU) of the photos `names` of options.image_path
// into the workspace database; COLMAP skips photos already there. With
// options.folder_cameras, the photos of FoldersOfOneCamera share one camera
// per folder. Then numbers the images by name (NumberImagesByName), so that
// the same photos give the same database; when that fails, `progress` gets
// a warning and the ids stay. Sets report's extraction_seconds and
// num_folder_cameras.
void ExtractPhotoFeatures(
    const ReconstructImagesOptions& options,
    const std::vector<std::string>& names, ReconstructImagesReport* report,
    const std::function<void(const std::string&)>& progress);

}  // namespace tmr
