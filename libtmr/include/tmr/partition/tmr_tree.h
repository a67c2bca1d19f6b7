// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "tmr/io/database_reader.h"
#include "tmr/partition/cluster_halo.h"
#include "tmr/partition/exemplar.h"
#include "tmr/partition/image_clustering.h"
#include "tmr/partition/kernels.h"
#include "tmr/partition/leaf_clustering.h"
#include "tmr/scene/match_graph.h"
#include "tmr/util/option_table.h"

namespace tmr {

struct TmrTreeOptions {
  KernelOptions kernels;
  ExemplarOptions exemplar;
  MultiLayerShortestPathOptions image_clustering;
  RadialAgglomerateOptions leaf_clustering;
  ClusterHaloOptions halo;
  // Seed of every random choice (copied into exemplar.ap.seed).
  uint64_t seed = 0;

  // Lists every option of the tree as a --Tmr.* row
  // (tmr/util/option_table.h): the command line and tree.json read them.
  void AddTo(OptionTable* table);
  bool Check(std::string* error = nullptr) const;
};

// A middle node of the tree: a kernel, its seed images and its image
// cluster split into leaf clusters. Images are vertex indices of the match
// graph (TmrTree::image_names gives their names).
struct TmrKernelNode {
  std::vector<int> kernel_images;
  int exemplar = -1;
  std::vector<int> second_images;  // best first
  std::vector<int> ap_centres;
  double exemplar_score = 0.0;
  KernelOrigin origin = KernelOrigin::kLayer;
  int layer = 0;
  std::vector<int> cluster_images;  // kernel and leaves, sorted
  std::vector<std::vector<int>> leaf_clusters;
  // Per leaf cluster, the images of other clusters its task also registers
  // (the cluster's halo, FindClusterHalos); empty lists without a halo.
  std::vector<std::vector<int>> leaf_halos;
};

struct TmrTreeTiming {
  double graphs_s = 0.0, kernels_s = 0.0, exemplars_s = 0.0,
         image_clusters_s = 0.0, leaf_clusters_s = 0.0, halos_s = 0.0;
};

// The Trilaminar Multiway Reconstruction tree (paper Sec. 4): the root is
// the image set, the middle layer the kernels with their image clusters, the
// bottom layer the leaf clusters.
struct TmrTree {
  std::vector<std::string> image_names;  // by vertex index
  std::vector<uint32_t> image_ids;       // database ids, by vertex index
  int kernel_size = 0;                   // m
  std::vector<TmrKernelNode> kernels;
  std::vector<int> unclustered;  // images that reach no kernel
  TmrTreeOptions options;
  TmrTreeTiming timing;
};

// The database ids of the images at `vertices` of the tree.
std::vector<uint32_t> ImageIdsOf(const TmrTree& tree,
                                 const std::vector<int>& vertices);

// Builds S and D (Eq. 1-2) from the match graph, then kernels (Sec. 4.1),
// exemplars, image clusters by Multi-layer Shortest Path (Sec. 4.2) and leaf
// clusters by Radial Agglomerate Clustering (Sec. 4.3), and the halo of
// every image cluster split among its leaves (FindClusterHalos,
// AssignHaloToLeaves; not in the paper). Deterministic for a
// given match graph and options.seed. Throws std::invalid_argument when
// options.Check() fails.
TmrTree BuildTmrTree(const MatchGraph& match_graph,
                     const TmrTreeOptions& options);

// The kernels by origin and their size range, for summaries:
// "8 place, 13 rescue; 3-64 images" ("" without kernels).
std::string DescribeKernels(const TmrTree& tree);

// tree.json: per kernel "exemplar", "second_image", "second_images",
// "kernel_images", "leaf_clusters", "leaf_halos" (lists of names); top level
// "unclustered", "kernel_size", "parameters" (every row of
// TmrTreeOptions::AddTo by name, e.g. "Tmr.alpha": 1.5), "timing_s". Images
// by name.
void WriteTmrTreeJson(const TmrTree& tree, std::ostream& out);

// The tree.json of an output folder: the one path rule for every tool.
std::string TmrTreeJsonPath(const std::string& folder);

// Writes WriteTmrTreeJson's text to TmrTreeJsonPath(folder), atomically
// (the folder must exist); false when it cannot.
bool WriteTmrTreeJsonFile(const TmrTree& tree, const std::string& folder);

// The first step of tmr_partition and tmr_mapper: the verified match graph
// of a COLMAP database (ReadMatchGraph, read-only) and its TMR-tree. Throws
// DatabaseError for the database, std::runtime_error for a database without
// images, std::invalid_argument for options that fail their Check().
struct DatabasePartition {
  MatchGraph graph;
  TmrTree tree;
  double read_seconds = 0.0;  // reading the match graph
  double seconds = 0.0;       // reading and partitioning
};
DatabasePartition PartitionDatabase(const std::string& database_path,
                                    const MatchGraphOptions& graph_options,
                                    const TmrTreeOptions& tree_options);

// Reads tree.json. Images get vertex indices in the order of first
// appearance in `image_names` if given (the match graph's names), else in
// order of first appearance in the file. Throws std::runtime_error with the
// problem for malformed input.
TmrTree ReadTmrTreeJson(std::istream& in,
                        const std::vector<std::string>& image_names = {});

}  // namespace tmr
