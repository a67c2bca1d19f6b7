// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "tmr/partition/dense_places.h"

#include <gtest/gtest.h>

#include "partition/test_graphs.h"

namespace tmr {
namespace {

ImageGraph Similarity(int num_images, const std::vector<WeightedEdge>& edges) {
  return BuildSimilarityGraph(
      test::MatchGraphWithSimilarities(num_images, edges));
}

// Places of 35 to 200 images chained by streets whose photos see only their
// neighbours: each place is found whole, and no street photo is in one.
TEST(FindDensePlaces, EveryPlaceWholeWhateverItsSize) {
  const test::PlacesAndStreets scene({35, 90, 200, 60}, 15);
  const std::vector<DensePlace> places = FindDensePlaces(
      Similarity(scene.num_images, scene.edges), DensePlaceOptions());
  ASSERT_EQ(places.size(), scene.places.size());
  for (size_t p = 0; p < places.size(); ++p) {
    EXPECT_EQ(places[p].images, scene.places[p]) << "place " << p;
    EXPECT_EQ(places[p].birth, 0.0);
    EXPECT_GT(places[p].stability, 0.0);
  }
}

// A connected part that is one dense place is that place (HDBSCAN's single
// cluster); a part below min_place_size and a sparse chain are none.
TEST(FindDensePlaces, WholePartSmallPartAndChain) {
  test::PlacesAndStreets scene({50, 20}, 0);  // two unlinked places
  for (int v = 0; v < 40; ++v) {              // and a chain of 41 photos
    scene.edges.push_back(
        {scene.num_images + v, scene.num_images + v + 1, 0.2});
  }
  scene.num_images += 41;
  const std::vector<DensePlace> places = FindDensePlaces(
      Similarity(scene.num_images, scene.edges), DensePlaceOptions());
  ASSERT_EQ(places.size(), 1u);
  EXPECT_EQ(places[0].images, scene.places[0]);

  DensePlaceOptions small;
  small.min_place_size = 20;
  EXPECT_EQ(
      FindDensePlaces(Similarity(scene.num_images, scene.edges), small).size(),
      2u);
}

// Two places that overlap (every photo of one sees two of the other, at a
// lower similarity than inside either) are two places, not one.
TEST(FindDensePlaces, OverlappingPlacesStayApart) {
  test::PlacesAndStreets scene({40, 40}, 0);
  for (int i = 0; i < 40; ++i) {
    scene.edges.push_back({scene.places[0][i], scene.places[1][i], 0.1});
    scene.edges.push_back(
        {scene.places[0][i], scene.places[1][(i + 1) % 40], 0.1});
  }
  const std::vector<DensePlace> places = FindDensePlaces(
      Similarity(scene.num_images, scene.edges), DensePlaceOptions());
  ASSERT_EQ(places.size(), 2u);
  EXPECT_EQ(places[0].images, scene.places[0]);
  EXPECT_EQ(places[1].images, scene.places[1]);
  EXPECT_GT(places[0].birth, 0.0);
}

TEST(FindDensePlaces, EmptyGraphAndBadOptions) {
  EXPECT_TRUE(FindDensePlaces(ImageGraph(0, {}), DensePlaceOptions()).empty());
  EXPECT_TRUE(FindDensePlaces(ImageGraph(4, {}), DensePlaceOptions()).empty());
  DensePlaceOptions bad;
  bad.core_neighbors = 0;
  EXPECT_FALSE(bad.Check());
  EXPECT_THROW(FindDensePlaces(ImageGraph(0, {}), bad), std::invalid_argument);
}

}  // namespace
}  // namespace tmr
