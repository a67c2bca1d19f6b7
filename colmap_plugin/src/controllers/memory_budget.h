// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmr/scene/match_graph.h"

namespace tmr {

// What a step of tmr_mapper loads, which its memory grows with.
struct MemoryLoad {
  int64_t images = 0;
  int64_t keypoints = 0;          // stored for those images
  int64_t matched_keypoints = 0;  // in a verified match (n_i of Eq. 1)
};

// The load of `images` (indices into graph.images).
MemoryLoad LoadOfImages(const MatchGraph& graph,
                        const std::vector<int>& images);

// A model of the peak resident memory of tmr_mapper's steps, in MiB, from
// their loads; rates measured on tmr_synth cities with COLMAP 4.1
// (docs/mapper.md, "Memory"). A task's figure includes the process it runs
// in; a step inside a larger process adds the rest to that process's.
//
// One kernel or leaf task: COLMAP's correspondences of its images, its
// model and the global adjustments of the incremental mapper.
double TaskPeakMiB(const MemoryLoad& task);
// The correspondences of all images (COLMAP's DatabaseCache of the merge
// database), held from the first cluster merge to the end of the run.
double CorrespondencesMiB(const MemoryLoad& scene);
// The merge stage at its peak: the correspondences, the cluster models and
// the scene, and the larger of the two adjustments of the whole scene:
// every pose on `longest_tracks_per_image` tracks, then blocks of up to
// `max_block_images` images (0: the whole scene) with all their points.
double MergePeakMiB(const MemoryLoad& scene, int longest_tracks_per_image,
                    int max_block_images);
// The adjustment of every pose of `images` images on `tracks_per_image`
// longest tracks each (AdjustOnLongestTracks).
double LongestTracksMiB(int64_t images, int tracks_per_image);
// The same by the join of a merge by parts (JoinAdjustment), which builds
// its scene from the groups' compact models after holding the largest
// group's models (0 without tracks).
double JoinAdjustmentMiB(int64_t images, int tracks_per_image,
                         int64_t largest_group_images);
// `wanted` tracks per image, or fewer so that the join's adjustment of
// `images` images fits `budget_mib`; 0 (no adjustment) when fewer than 150
// fit, too few to help.
int JoinTracksThatFit(int wanted, double budget_mib, int64_t images,
                      int64_t largest_group_images);
// The join of a merge stage by parts (docs/distributed.md), one step at a
// time: one group's models (`largest_group`'s load), read to make their
// light copies or to write the scenes; one alignment job, the light
// copies of a group's or two linked groups' models beside the
// correspondences of their seam (`job_seams`, the largest job's load); or
// the adjustment of the joined scene (`adjustment_mib`).
double JoinPeakMiB(const MemoryLoad& largest_group, const MemoryLoad& job_seams,
                   double adjustment_mib);
// What each of the join's alignment jobs may hold beside the others, from
// the join's expected peak (JoinPeakMiB): the jobs run side by side while
// their sum fits the budget less ProcessMiB().
double JoinJobMiB(double join_mib);
// A process with COLMAP loaded, before any data.
double ProcessMiB();

// The memory every step must fit (--Tmr.memory_budget).
struct MemoryBudget {
  double mib = 0.0;
  // Where it comes from, for the start line: "--Tmr.memory_budget" or
  // "half of the 23.4 GiB this process may use".
  std::string source;
};
// `budget_gib` > 0, or half of AvailableMemoryMiB() (tmr/util/process.h);
// 8 GiB where that is unknown.
MemoryBudget ResolveMemoryBudget(double budget_gib);

// The warning when the merge stage is expected to need more than the
// budget; "" when it fits.
std::string MergeOverBudgetWarning(double merge_mib,
                                   const MemoryBudget& budget);

// "1.25 GiB".
std::string GiBText(double mib);

}  // namespace tmr
