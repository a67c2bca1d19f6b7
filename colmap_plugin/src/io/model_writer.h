// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/reconstruction.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <unordered_set>

namespace tmr {

// Writes one COLMAP binary model (rigs, cameras, frames, images, points3D
// .bin) from parts appended one after another, so that a model larger than
// memory can be written from parts that each fit: the join of a merge stage
// by parts writes the models of its groups so (docs/distributed.md). Each
// part's records are written by COLMAP's own binary writers; the record
// counts at the head of each file are summed and written by Finish. A part's
// points get new ids above every id written before; the cameras and rigs of
// its registered images are written unless an earlier part wrote them (the
// first part's stay, as AppendReconstruction keeps the target's). Parts
// must not register the same image twice.
//
// The files go to `path`.tmp, renamed to `path` by Finish: a writer that
// does not finish leaves no model at `path`.
class ModelWriter {
 public:
  explicit ModelWriter(std::string path);
  ~ModelWriter();

  // False when the folder cannot be made or a file not opened.
  bool Open();

  // Writes the registered images of `part`, their frames, and its points.
  // Takes the points of `part` (renumbered in place, since ids of parts
  // overlap); false when a file cannot be written.
  bool Append(colmap::Reconstruction* part);

  // Writes the counts and renames the folder into place; false on failure.
  bool Finish();

  size_t NumRegImages() const { return counts_[kImages]; }

 private:
  enum File { kRigs, kCameras, kFrames, kImages, kPoints3D, kNumFiles };

  // Appends `write`'s output to file `f` without its leading count, which
  // is added to counts_[f].
  template <typename Write>
  bool AppendRecords(File f, const Write& write);

  std::string path_;
  std::string temporary_;
  std::array<std::ofstream, kNumFiles> files_;
  std::array<uint64_t, kNumFiles> counts_{};
  std::unordered_set<colmap::camera_t> written_cameras_;
  std::unordered_set<colmap::rig_t> written_rigs_;
  colmap::point3D_t last_point_id_ = 0;
  bool finished_ = false;
};

}  // namespace tmr
