// Uses libtmr through find_package(tmr): plain ids and counts in, S out.
#include <tmr/scene/graph_summary.h>
#include <tmr/scene/image_graph.h>

#include <iostream>

int main() {
  tmr::MatchGraph graph;
  graph.images = {{1, "a.jpg", 1, 100, 40}, {2, "b.jpg", 1, 100, 50}};
  graph.pairs = {{0, 1, 30, 2}};
  const tmr::ImageGraph s = tmr::BuildSimilarityGraph(graph);
  tmr::PrintGraphSummary(tmr::SummarizeGraph(graph, s), std::cout);
  return s.Weight(0, 1) == 30.0 / 60.0 ? 0 : 1;
}
