// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// Partition benchmark: generated match graphs of N images (random positions
// in a plane, each image paired with its ~30 nearest neighbours, inlier
// counts falling with distance) written through COLMAP's Database class;
// then, per database, the time of a raw scan of two_view_geometries (every
// blob read) beside the time and peak memory of each partition stage.
//
// Usage: bench_partition [--sizes 1000,5000,20000,100000] [--nearest 27]
//                        [--dir out/bench_partition] [--paper 0|1]
// --paper 1: the paper's kernel search on the whole graph and its image
// clustering across single-pair links (per_place 0, min_bridge_side 0).
#include <colmap/estimators/two_view_geometry.h>
#include <colmap/scene/database.h>
#include <sqlite3.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "tmr/io/database_reader.h"
#include "tmr/partition/tmr_tree.h"

namespace fs = std::filesystem;

namespace {

constexpr int kKeypoints = 200;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

double PeakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

void WriteGraphDatabase(const std::string& path, int n, int nearest) {
  std::mt19937_64 rng(n);
  const double side = std::sqrt(static_cast<double>(n));
  std::uniform_real_distribution<double> coordinate(0.0, side);
  std::vector<std::pair<double, double>> xy(n);
  for (auto& p : xy) p = {coordinate(rng), coordinate(rng)};
  // Grid buckets of unit cells for the neighbour search.
  const int cells = static_cast<int>(std::ceil(side));
  std::vector<std::vector<int>> bucket(cells * cells);
  auto cell = [&](double v) {
    return std::min(cells - 1, static_cast<int>(v));
  };
  for (int i = 0; i < n; ++i)
    bucket[cell(xy[i].first) * cells + cell(xy[i].second)].push_back(i);

  const std::shared_ptr<colmap::Database> database =
      colmap::Database::Open(path);
  colmap::DatabaseTransaction transaction(database.get());
  for (int i = 0; i < n; ++i) {
    const auto camera_id =
        database->WriteCamera(colmap::Camera::CreateFromModelName(
            colmap::kInvalidCameraId, "SIMPLE_RADIAL", 1000, 1024, 768));
    colmap::Image image;
    image.SetName("img" + std::to_string(i) + ".jpg");
    image.SetCameraId(camera_id);
    database->WriteKeypoints(database->WriteImage(image),
                             colmap::FeatureKeypoints(kKeypoints));
  }
  std::uniform_int_distribution<int> keypoint(0, kKeypoints - 1);
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> near;
    const int cx = cell(xy[i].first), cy = cell(xy[i].second);
    for (int dx = -4; dx <= 4; ++dx) {
      for (int dy = -4; dy <= 4; ++dy) {
        const int x = cx + dx, y = cy + dy;
        if (x < 0 || y < 0 || x >= cells || y >= cells) continue;
        for (const int j : bucket[x * cells + y]) {
          if (j == i) continue;
          const double ddx = xy[i].first - xy[j].first,
                       ddy = xy[i].second - xy[j].second;
          near.emplace_back(ddx * ddx + ddy * ddy, j);
        }
      }
    }
    std::sort(near.begin(), near.end());
    near.resize(std::min<size_t>(near.size(), nearest));
    for (const auto& [dist2, j] : near) {
      // Each pair is written once (nearest-neighbour lists overlap).
      colmap::TwoViewGeometry geometry;
      geometry.config = colmap::TwoViewGeometry::CALIBRATED;
      const int count = std::max(15, static_cast<int>(150 * std::exp(-dist2)));
      for (int k = 0; k < count; ++k)
        geometry.inlier_matches.emplace_back(keypoint(rng), keypoint(rng));
      if (i < j) {
        database->WriteTwoViewGeometry(i + 1, j + 1, geometry);
      } else if (!database->ExistsTwoViewGeometry(j + 1, i + 1)) {
        database->WriteTwoViewGeometry(i + 1, j + 1, geometry);
      }
    }
  }
}

// Reads every row and blob of two_view_geometries: the floor for any reader.
double RawScanSeconds(const std::string& path, size_t* num_rows) {
  const auto start = std::chrono::steady_clock::now();
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* stmt = nullptr;
  sqlite3_prepare_v2(db, "SELECT pair_id, rows, data FROM two_view_geometries",
                     -1, &stmt, nullptr);
  size_t checksum = 0;
  *num_rows = 0;
  while (sqlite3_step(stmt) == SQLITE_ROW) {
    const auto* data =
        static_cast<const unsigned char*>(sqlite3_column_blob(stmt, 2));
    const int bytes = sqlite3_column_bytes(stmt, 2);
    if (data && bytes > 0) checksum += data[bytes - 1];
    ++*num_rows;
  }
  if (checksum == 1) std::cerr << "";  // keep the reads
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return Seconds(start);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {1000, 5000, 20000, 100000};
  std::string dir = "out/bench_partition";
  int nearest = 27;  // gives about 30 neighbours per image
  tmr::TmrTreeOptions options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--sizes") {
      sizes.clear();
      std::stringstream list(argv[i + 1]);
      for (std::string item; std::getline(list, item, ',');)
        sizes.push_back(std::stoi(item));
    } else if (flag == "--nearest") {
      nearest = std::stoi(argv[i + 1]);
    } else if (flag == "--dir") {
      dir = argv[i + 1];
    } else if (flag == "--paper") {  // the paper's kernels and clusters
      if (std::stoi(argv[i + 1]) != 0) {
        options.kernels.per_place = false;
        options.image_clustering.min_bridge_side = 0;
      }
    } else {
      std::cerr << "bench_partition: error: unknown option " << flag << "\n";
      return 2;
    }
  }
  fs::create_directories(dir);
  std::cout << std::fixed << std::setprecision(3)
            << "images    pairs   raw scan  read+n_i  S,D      kernels  "
               "exemplar  MSP      RAC      "
               "partition  x raw  kernels  peak MiB\n";
  for (const int n : sizes) {
    const std::string path = dir + "/graph_" + std::to_string(n) + "_" +
                             std::to_string(nearest) + ".db";
    if (!fs::exists(path)) {
      const auto start = std::chrono::steady_clock::now();
      WriteGraphDatabase(path, n, nearest);
      std::cerr << "wrote " << path << " in " << Seconds(start) << " s\n";
    }
    size_t rows = 0;
    RawScanSeconds(path, &rows);  // warm the page cache
    const double raw = RawScanSeconds(path, &rows);
    auto start = std::chrono::steady_clock::now();
    const tmr::MatchGraph graph = tmr::ReadMatchGraph(path);
    const double read = Seconds(start);
    const tmr::TmrTree tree = tmr::BuildTmrTree(graph, options);
    const auto& t = tree.timing;
    const double partition = t.graphs_s + t.kernels_s + t.exemplars_s +
                             t.image_clusters_s + t.leaf_clusters_s;
    std::cout << std::setw(7) << n << std::setw(9) << graph.NumPairs()
              << std::setw(10) << raw << std::setw(10) << read << std::setw(9)
              << t.graphs_s << std::setw(9) << t.kernels_s << std::setw(10)
              << t.exemplars_s << std::setw(9) << t.image_clusters_s
              << std::setw(9) << t.leaf_clusters_s << std::setw(11)
              << read + partition << std::setw(7) << std::setprecision(2)
              << (read + partition) / raw << std::setprecision(3)
              << std::setw(9) << tree.kernels.size() << std::setw(10)
              << std::setprecision(0) << PeakRssMiB() << std::setprecision(3)
              << "\n";
  }
  return 0;
}
