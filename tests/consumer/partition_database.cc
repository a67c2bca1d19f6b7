// Partitions a COLMAP database with libtmr via find_package(tmr): the
// verified match graph in, the TMR-tree out (kernels, their exemplars,
// image clusters and leaf clusters), printed and written as tree.json.
// Usage: partition_database DATABASE [TREE_JSON]
#include <tmr/io/database_reader.h>
#include <tmr/partition/tmr_tree.h>

#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: partition_database DATABASE [TREE_JSON]\n";
    return 2;
  }
  try {
    const tmr::MatchGraph graph = tmr::ReadMatchGraph(argv[1]);
    tmr::TmrTreeOptions options;
    options.seed = 7;  // same input and seed, same partition
    const tmr::TmrTree tree = tmr::BuildTmrTree(graph, options);
    std::cout << graph.NumImages() << " images, " << tree.kernels.size()
              << " kernels\n";
    for (const tmr::TmrKernelNode& kernel : tree.kernels) {
      std::cout << "kernel of " << kernel.kernel_images.size()
                << " images, exemplar " << tree.image_names[kernel.exemplar]
                << ", image cluster of " << kernel.cluster_images.size()
                << " in " << kernel.leaf_clusters.size() << " leaf clusters\n";
    }
    if (argc > 2) {
      std::ofstream out(argv[2]);
      tmr::WriteTmrTreeJson(tree, out);
    }
    return tree.kernels.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::cerr << "partition_database: error: " << e.what() << "\n";
    return 1;
  }
}
