// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The seams between the groups of a merge stage by parts
// (docs/distributed.md): the images the join loads, the groups' links and
// each link's seam, and what the join loads to align one pair of groups.
#include <algorithm>
#include <iterator>
#include <map>
#include <set>

#include "controllers/tmr_mapper_stages.h"

namespace tmr {

std::vector<std::vector<int>> TmrMapperStages::GroupsOfImages(
    int num_images) const {
  std::vector<std::vector<int>> groups_of(num_images);
  for (int g = 0; g < static_cast<int>(groups_.size()); ++g)
    for (const int i : GroupImages(groups_[g])) groups_of.at(i).push_back(g);
  return groups_of;
}

std::vector<int> TmrMapperStages::SeamImages(const MatchGraph& graph) const {
  const std::vector<std::vector<int>> groups_of =
      GroupsOfImages(graph.NumImages());
  std::vector<bool> seam(graph.NumImages(), false);
  for (int i = 0; i < graph.NumImages(); ++i) seam[i] = groups_of[i].size() > 1;
  for (const MatchGraphPair& pair : graph.pairs) {
    const std::vector<int>& a = groups_of[pair.image1];
    const std::vector<int>& b = groups_of[pair.image2];
    if (std::find_first_of(a.begin(), a.end(), b.begin(), b.end()) == a.end())
      seam[pair.image1] = seam[pair.image2] = true;
  }
  std::vector<int> seams;
  for (int i = 0; i < graph.NumImages(); ++i)
    if (seam[i]) seams.push_back(i);
  return seams;
}

void TmrMapperStages::LinkGroups(const MatchGraph& graph) {
  const std::vector<std::vector<int>> groups_of =
      GroupsOfImages(graph.NumImages());
  // Each link's seam images, by the link's first group.
  std::vector<std::map<int, std::set<int>>> links(groups_.size());
  const auto link = [&](int g, int h, int i, int j) {
    if (g == h) return;
    std::set<int>& seam = links[std::min(g, h)][std::max(g, h)];
    seam.insert(i);
    seam.insert(j);
  };
  for (int i = 0; i < graph.NumImages(); ++i)
    for (const int g : groups_of[i])
      for (const int h : groups_of[i]) link(g, h, i, i);
  for (const MatchGraphPair& pair : graph.pairs)
    for (const int g : groups_of[pair.image1])
      for (const int h : groups_of[pair.image2])
        link(g, h, pair.image1, pair.image2);
  for (size_t g = 0; g < groups_.size(); ++g) {
    groups_[g].links.clear();
    groups_[g].link_seams.clear();
    for (const auto& [h, seam] : links[g]) {
      groups_[g].links.push_back(h);
      groups_[g].link_seams.emplace_back(seam.begin(), seam.end());
    }
  }
}

std::vector<int> TmrMapperStages::GroupSeamImages(int g) const {
  const std::vector<int> held = GroupImages(groups_.at(g));
  std::vector<int> seams;
  std::set_intersection(held.begin(), held.end(), seam_images_.begin(),
                        seam_images_.end(), std::back_inserter(seams));
  return seams;
}

std::vector<int> TmrMapperStages::LinkSeamImages(int g, int h) const {
  const ClusterGroup& first = groups_.at(std::min(g, h));
  const auto l =
      std::find(first.links.begin(), first.links.end(), std::max(g, h));
  if (l != first.links.end() && first.link_seams.size() == first.links.size()) {
    const std::vector<int>& link = first.link_seams[l - first.links.begin()];
    std::vector<int> seams;  // as the light copies have them
    std::set_intersection(link.begin(), link.end(), seam_images_.begin(),
                          seam_images_.end(), std::back_inserter(seams));
    return seams;
  }
  std::vector<int> images = GroupSeamImages(g), other = GroupSeamImages(h);
  images.insert(images.end(), other.begin(), other.end());
  std::sort(images.begin(), images.end());
  images.erase(std::unique(images.begin(), images.end()), images.end());
  return images;
}

}  // namespace tmr
