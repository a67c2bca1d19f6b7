// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/io/database_reader.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "tmr/io/sqlite.h"

namespace tmr {
namespace {

// COLMAP encodes an image pair as image_id1 * kMaxNumImages + image_id2 with
// image_id1 < image_id2 (scene/database.cc).
constexpr int64_t kMaxNumImages = std::numeric_limits<int32_t>::max();

void RequireSchema(const SqliteDatabase& db) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> kNeeded =
      {{"images", {"image_id", "name", "camera_id"}},
       {"keypoints", {"image_id", "rows"}},
       {"two_view_geometries", {"pair_id", "rows", "cols", "data", "config"}}};
  for (const auto& [table, columns] : kNeeded) {
    if (!db.HasTable(table)) {
      db.Fail("has no table '" + table + "' (not a COLMAP database?)");
    }
    for (const std::string& column : columns) {
      if (!db.HasColumn(table, column)) {
        db.Fail("table '" + table + "' has no column '" + column + "'");
      }
    }
  }
}

std::vector<MatchGraphImage> ReadImages(const SqliteDatabase& db) {
  std::vector<MatchGraphImage> images;
  SqliteStatement stmt(db, "SELECT image_id, name, camera_id FROM images");
  while (stmt.Step()) {
    const int64_t id = stmt.Int(0);
    if (id < 1 || id > kMaxNumImages) {
      db.Fail("image_id " + std::to_string(id) + " is out of range");
    }
    MatchGraphImage image;
    image.image_id = static_cast<uint32_t>(id);
    image.name = stmt.Text(1);
    image.camera_id = static_cast<uint32_t>(stmt.Int(2));
    images.push_back(std::move(image));
  }
  std::sort(images.begin(), images.end(),
            [](const MatchGraphImage& a, const MatchGraphImage& b) {
              return a.image_id < b.image_id;
            });
  for (size_t i = 1; i < images.size(); ++i) {
    if (images[i].image_id == images[i - 1].image_id) {
      db.Fail("image_id " + std::to_string(images[i].image_id) +
              " appears twice");
    }
  }
  return images;
}

void ReadKeypointCounts(const SqliteDatabase& db, MatchGraph* graph) {
  SqliteStatement stmt(db, "SELECT image_id, rows FROM keypoints");
  while (stmt.Step()) {
    const int64_t id = stmt.Int(0);
    const int64_t rows = stmt.Int(1);
    if (rows < 0 || rows > std::numeric_limits<int32_t>::max()) {
      db.Fail("keypoints of image_id " + std::to_string(id) +
              " have an invalid row count " + std::to_string(rows));
    }
    const int index = (id >= 1 && id <= kMaxNumImages)
                          ? graph->FindImageIndex(static_cast<uint32_t>(id))
                          : -1;
    if (index >= 0) graph->images[index].num_keypoints = static_cast<int>(rows);
  }
}

std::string JoinConfigs(const std::vector<int>& configs) {
  std::ostringstream out;
  for (size_t i = 0; i < configs.size(); ++i) {
    out << (i ? "," : "") << configs[i];
  }
  return out.str();
}

// Streams the inlier blobs of the counted pairs once: fills graph->pairs and
// marks, per image, which keypoints take part in an inlier match.
void ReadVerifiedPairs(const SqliteDatabase& db,
                       const MatchGraphOptions& options, MatchGraph* graph) {
  std::vector<std::vector<uint8_t>> matched(graph->images.size());
  for (size_t i = 0; i < graph->images.size(); ++i) {
    matched[i].assign(graph->images[i].num_keypoints, 0);
  }
  SqliteStatement stmt(
      db,
      "SELECT pair_id, rows, cols, config, data "
      "FROM two_view_geometries WHERE rows >= ? AND config IN (" +
          JoinConfigs(options.verified_configs) + ")");
  stmt.BindInt(1, std::max(1, options.min_num_matches));
  while (stmt.Step()) {
    const int64_t pair_id = stmt.Int(0);
    const int64_t rows = stmt.Int(1);
    const int64_t cols = stmt.Int(2);
    auto where = [pair_id] {
      return "two_view_geometries pair_id " + std::to_string(pair_id);
    };
    if (pair_id < 0) db.Fail(where() + " is negative");
    const int64_t id2 = pair_id % kMaxNumImages;
    const int64_t id1 = (pair_id - id2) / kMaxNumImages;
    if (id1 > kMaxNumImages) db.Fail(where() + " is out of range");
    const int index1 = graph->FindImageIndex(static_cast<uint32_t>(id1));
    const int index2 = graph->FindImageIndex(static_cast<uint32_t>(id2));
    if (index1 < 0 || index2 < 0 || index1 == index2) {
      db.Fail(where() + " names image_id " + std::to_string(id1) + " and " +
              std::to_string(id2) + ", which are not two distinct images");
    }
    if (cols != 2 || rows > std::numeric_limits<int32_t>::max()) {
      db.Fail(where() + " has " + std::to_string(rows) + " x " +
              std::to_string(cols) + " inlier matches (expected N x 2)");
    }
    const int64_t expected_bytes = rows * cols * 4;
    if (stmt.IsNull(4) || stmt.BlobBytes(4) != expected_bytes) {
      db.Fail(where() + " has a data blob of " +
              std::to_string(stmt.IsNull(4) ? 0 : stmt.BlobBytes(4)) +
              " bytes, expected rows x cols x 4 = " +
              std::to_string(expected_bytes));
    }
    const auto* data = static_cast<const unsigned char*>(stmt.Blob(4));
    std::vector<uint8_t>& matched1 = matched[index1];
    std::vector<uint8_t>& matched2 = matched[index2];
    for (int64_t r = 0; r < rows; ++r) {
      uint32_t idx[2];
      std::memcpy(idx, data + r * 8, 8);
      if (idx[0] >= matched1.size() || idx[1] >= matched2.size()) {
        db.Fail(where() + " matches keypoint " + std::to_string(idx[0]) +
                " of image_id " + std::to_string(id1) + " (" +
                std::to_string(matched1.size()) + " keypoints) to keypoint " +
                std::to_string(idx[1]) + " of image_id " + std::to_string(id2) +
                " (" + std::to_string(matched2.size()) + " keypoints)");
      }
      matched1[idx[0]] = true;
      matched2[idx[1]] = true;
    }
    graph->pairs.push_back({index1, index2, static_cast<int>(rows),
                            static_cast<int>(stmt.Int(3))});
  }
  for (size_t i = 0; i < graph->images.size(); ++i) {
    graph->images[i].num_matched_keypoints =
        static_cast<int>(std::count(matched[i].begin(), matched[i].end(), 1));
  }
  std::sort(graph->pairs.begin(), graph->pairs.end(),
            [](const MatchGraphPair& a, const MatchGraphPair& b) {
              return std::tie(a.image1, a.image2) <
                     std::tie(b.image1, b.image2);
            });
}

}  // namespace

bool MatchGraphOptions::Check(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (min_num_matches < 1) return fail("min_num_matches must be >= 1");
  if (verified_configs.empty()) return fail("verified_configs is empty");
  for (const int config : verified_configs) {
    if (config < 0 || config > 9) {
      return fail("verified_configs holds " + std::to_string(config) +
                  ", not a COLMAP two-view configuration (0..9)");
    }
  }
  return true;
}

std::vector<MatchGraphImage> ReadDatabaseImages(
    const std::string& database_path) {
  SqliteDatabase db(database_path);
  RequireSchema(db);
  return ReadImages(db);
}

MatchGraph ReadMatchGraph(const std::string& database_path,
                          const MatchGraphOptions& options) {
  std::string error;
  if (!options.Check(&error)) {
    throw std::invalid_argument("MatchGraphOptions: " + error);
  }
  SqliteDatabase db(database_path);
  RequireSchema(db);
  MatchGraph graph;
  graph.images = ReadImages(db);
  ReadKeypointCounts(db, &graph);
  ReadVerifiedPairs(db, options, &graph);
  return graph;
}

}  // namespace tmr
