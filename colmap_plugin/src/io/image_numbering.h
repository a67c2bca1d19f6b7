// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <string>

namespace tmr {

// Numbers the images of a COLMAP 4 database by name: image k of the names
// in sorted order gets id k, and its frame and pose prior follow it.
// COLMAP's feature extraction writes each image when its thread finishes,
// so two extractions of the same photos number them differently (68 of 200
// differed), and tmr_mapper, whose partition and seeds follow image ids,
// then maps them differently. Run between extraction and matching, this
// makes tmr_reconstruct repeatable from photos.
//
// Rigs, cameras, keypoints and descriptors are copied with COLMAP's
// Database class into a new file beside `database_path`, which replaces it
// when complete (a run killed before leaves the old file as it was). A
// database whose images are already in name order, or that holds matches or
// two-view geometries (their pair ids name image ids), is left as it is;
// `renumbered` (may be null) says whether it was rewritten. False with a
// reason in `error`, the database unchanged, when it cannot be read or
// written or another process holds it open.
bool NumberImagesByName(const std::string& database_path, bool* renumbered,
                        std::string* error);

}  // namespace tmr
