// Uses tmr::colmap_plugin (and through it COLMAP) via find_package(tmr).
#include <tmr/colmap/synthetic_scene.h>
#include <tmr/io/database_reader.h>

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "consumer.db";
  std::filesystem::remove(path);
  tmr::SyntheticSceneOptions options;
  options.cameras_per_place = 20;
  options.num_unlinked_places = 0;
  options.link_spacing = 0;
  options.num_places = 1;
  std::string error;
  if (!tmr::WriteSyntheticScene(options, path, "", nullptr, &error)) {
    std::cerr << error << "\n";
    return 1;
  }
  const tmr::MatchGraph graph = tmr::ReadMatchGraph(path);
  std::cout << graph.NumImages() << " images, " << graph.NumPairs()
            << " pairs\n";
  return graph.NumImages() == 20 && graph.NumPairs() > 0 ? 0 : 1;
}
