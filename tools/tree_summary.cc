// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tree_summary.h"

#include <algorithm>
#include <iomanip>
#include <string>
#include <vector>

namespace tmr {

void PrintTreeSummary(const TmrTree& tree, std::ostream& out) {
  out << "TMR-tree: " << tree.image_names.size()
      << " images, kernel size m = " << tree.kernel_size << ", "
      << tree.kernels.size() << " kernels, " << tree.unclustered.size()
      << " unclustered\n";
  out << "kernels by origin: " << DescribeKernels(tree);
  std::vector<size_t> leaf_sizes;
  for (const TmrKernelNode& node : tree.kernels) {
    for (const auto& leaf : node.leaf_clusters)
      leaf_sizes.push_back(leaf.size());
  }
  std::sort(leaf_sizes.begin(), leaf_sizes.end());
  out << "; " << leaf_sizes.size() << " leaf clusters";
  if (!leaf_sizes.empty()) {
    out << " of " << leaf_sizes.front() << "-" << leaf_sizes.back()
        << " images (median " << leaf_sizes[leaf_sizes.size() / 2] << ")";
  }
  size_t halo = 0;
  for (const TmrKernelNode& node : tree.kernels)
    for (const auto& images : node.leaf_halos) halo += images.size();
  out << "; halos of " << halo << " images from neighbouring clusters\n";
  out << std::setw(6) << "kernel" << std::setw(8) << "origin" << std::setw(8)
      << "kernel" << std::setw(9) << "cluster" << std::setw(7) << "leaves"
      << "  leaf cluster sizes"
      << "   exemplar\n";
  for (size_t k = 0; k < tree.kernels.size(); ++k) {
    const TmrKernelNode& node = tree.kernels[k];
    const char* origin = KernelOriginName(node.origin);
    std::string sizes;
    for (const auto& leaf : node.leaf_clusters) {
      sizes += (sizes.empty() ? "" : " ") + std::to_string(leaf.size());
    }
    if (sizes.size() > 30) sizes = sizes.substr(0, 27) + "...";
    out << std::setw(6) << k << std::setw(8) << origin << std::setw(8)
        << node.kernel_images.size() << std::setw(9)
        << node.cluster_images.size() << std::setw(7)
        << node.leaf_clusters.size() << "  " << std::left << std::setw(30)
        << sizes << std::right << " " << tree.image_names.at(node.exemplar)
        << "\n";
  }
  const auto& t = tree.timing;
  out << std::fixed << std::setprecision(3) << "time: graphs " << t.graphs_s
      << " s, kernels " << t.kernels_s << " s, exemplars " << t.exemplars_s
      << " s, image clusters " << t.image_clusters_s << " s, leaf clusters "
      << t.leaf_clusters_s << " s, halos " << t.halos_s << " s\n"
      << std::defaultfloat;
}

}  // namespace tmr
