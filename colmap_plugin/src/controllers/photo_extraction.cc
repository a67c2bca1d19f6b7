// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/photo_extraction.h"

#include <OpenImageIO/imageio.h>
#include <colmap/controllers/feature_extraction.h>
#include <colmap/feature/sift.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <map>
#include <tuple>

#include "controllers/controller_progress.h"
#include "controllers/photo_matching.h"
#include "io/image_numbering.h"
#include "tmr/util/process.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

bool IsPhoto(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const char* known : {".jpg", ".jpeg", ".png", ".tif", ".tiff", ".bmp",
                            ".ppm", ".pgm", ".webp", ".jp2"}) {
    if (ext == known) return true;
  }
  return false;
}

}  // namespace

bool ReadPhotoHeader(const std::string& path, PhotoHeader* header) {
  OIIO::ImageSpec config;
  config["oiio:reorient"] = 0;  // as COLMAP's Bitmap::Read
  const auto input = OIIO::ImageInput::open(path, &config);
  if (!input) {
    OIIO::geterror();  // clears OpenImageIO's pending error
    return false;
  }
  const OIIO::ImageSpec& spec = input->spec();
  header->width = spec.width;
  header->height = spec.height;
  header->make = spec.get_string_attribute("Make").str();
  header->model = spec.get_string_attribute("Model").str();
  header->focal_length = spec.get_float_attribute("Exif:FocalLengthIn35mmFilm");
  if (header->focal_length <= 0)
    header->focal_length = spec.get_float_attribute("Exif:FocalLength");
  input->close();
  return true;
}

std::string FolderOf(const std::string& name) {
  const size_t slash = name.rfind('/');
  return slash == std::string::npos ? "" : name.substr(0, slash);
}

std::vector<std::string> FoldersOfOneCamera(
    const std::vector<PhotoHeader>& photos) {
  std::map<std::string, std::vector<const PhotoHeader*>> by_folder;
  for (const PhotoHeader& photo : photos)
    by_folder[FolderOf(photo.name)].push_back(&photo);
  const auto camera = [](const PhotoHeader& p) {
    return std::tie(p.width, p.height, p.make, p.model, p.focal_length);
  };
  std::vector<std::string> folders;
  for (const auto& [folder, members] : by_folder) {
    if (members.size() < 2) continue;
    bool same = true;
    for (const PhotoHeader* photo : members)
      same = same && camera(*photo) == camera(*members.front());
    if (!same) continue;
    const PhotoHeader& first = *members.front();
    bool shared = first.focal_length > 0;
    if (!shared && first.make.empty() && first.model.empty()) {
      std::vector<std::string> names;
      for (const PhotoHeader* photo : members) names.push_back(photo->name);
      shared = IsNumberedSequence(names);
    }
    if (shared) folders.push_back(folder);
  }
  return folders;
}

bool ListPhotos(const std::string& folder, std::vector<std::string>* names,
                std::string* error) {
  names->clear();
  std::error_code ec;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->is_regular_file(ec) && IsPhoto(it->path()))
      names->push_back(it->path()  // as COLMAP names it: symbolic links kept
                           .lexically_proximate(folder)
                           .lexically_normal()
                           .generic_string());
  }
  if (ec) {
    *error = "cannot read '" + folder + "': " + ec.message();
    return false;
  }
  std::sort(names->begin(), names->end());
  return true;
}

void ExtractPhotoFeatures(
    const ReconstructImagesOptions& options,
    const std::vector<std::string>& names, ReconstructImagesReport* report,
    const std::function<void(const std::string&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::string database = options.MapperOptions().database_path;
  // Photos by folder of one camera ("" key unused), and the others.
  std::map<std::string, std::vector<std::string>> shared;
  std::vector<std::string> others;
  if (options.folder_cameras && !options.single_camera) {
    std::vector<PhotoHeader> headers;
    for (const std::string& name : names) {
      PhotoHeader header;
      header.name = name;
      if (ReadPhotoHeader((fs::path(options.image_path) / name).string(),
                          &header))
        headers.push_back(std::move(header));
    }
    for (const std::string& folder : FoldersOfOneCamera(headers))
      shared[folder];
  }
  size_t num_shared = 0;
  for (const std::string& name : names) {
    const auto folder = shared.find(FolderOf(name));
    if (folder == shared.end()) {
      others.push_back(name);
    } else {
      folder->second.push_back(name);
      ++num_shared;
    }
  }
  report->num_folder_cameras = static_cast<int>(shared.size());
  colmap::FeatureExtractionOptions extraction(
      colmap::FeatureExtractorType::SIFT);
  extraction.use_gpu = false;
  extraction.num_threads = options.num_threads;
  extraction.max_image_size = options.max_image_size;
  extraction.sift->max_num_features = options.max_num_features;
  extraction.sift->estimate_affine_shape = options.estimate_affine_shape;
  // One run per folder of one camera (COLMAP's single_camera on that
  // folder alone), one for the others.
  const auto extract = [&](const std::vector<std::string>& subset,
                           bool one_camera) {
    if (subset.empty()) return;
    colmap::ImageReaderOptions reader;
    reader.image_path = options.image_path;
    reader.image_names = subset;
    reader.camera_model = options.camera_model;
    reader.single_camera = options.single_camera || one_camera;
    auto extractor =
        colmap::CreateFeatureExtractorController(database, reader, extraction);
    RunWithProgress(
        extractor.get(), "features",
        [&] { return CountRows(database, "SELECT COUNT(*) FROM descriptors"); },
        static_cast<int64_t>(names.size()), /*total_is_bound=*/false, progress);
  };
  if (progress) {
    progress(
        "extracting features of " + std::to_string(names.size()) + " photos" +
        (shared.empty() ? ""
                        : " (" + std::to_string(num_shared) + " of them in " +
                              std::to_string(shared.size()) +
                              " folder(s) of one camera each)"));
  }
  for (const auto& [folder, subset] : shared) extract(subset, true);
  extract(others, false);
  // Ids by name, not by which extraction thread finished first. Without
  // it the run goes on, only not repeatable.
  bool renumbered = false;
  std::string numbering_error;
  if (!NumberImagesByName(database, &renumbered, &numbering_error) &&
      progress) {
    progress("warning: " + numbering_error +
             "; the images keep the ids of extraction order");
  }
  if (renumbered && progress) progress("numbered the images by name");
  report->extraction_seconds = SecondsSince(start);
}

}  // namespace tmr
