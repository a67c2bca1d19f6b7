// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#include "controllers/memory_budget.h"

#include <algorithm>
#include <cstdio>

#include "tmr/util/process.h"

namespace tmr {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

// Measured rates (docs/mapper.md, "Memory"), in bytes unless named MiB.
// A process with COLMAP loaded, before any data.
constexpr double kProcessMiB = 130.0;
// A kernel or leaf task: per keypoint stored and per matched keypoint of
// its images.
constexpr double kTaskPerKeypoint = 60.0;
constexpr double kTaskPerMatchedKeypoint = 900.0;
// COLMAP's correspondence cache of all images.
constexpr double kCachePerKeypoint = 40.0;
constexpr double kCachePerMatchedKeypoint = 200.0;
// The cluster models and the scene beside the cache, per matched keypoint.
constexpr double kModelsPerMatchedKeypoint = 150.0;
// The adjustment on the longest tracks: per image and track.
constexpr double kLongestTracksPerImageTrack = 1360.0;
// The join's adjustment on its groups' longest tracks: per image and track
// of the scene, beside what one group's models left in the process, per
// photo of the largest group (city10, 14 groups of up to 1,021 photos: peak
// 3,319 MiB at 170 tracks per image, 4,120 MiB at 232).
constexpr double kJoinAdjustmentPerImageTrack = 1560.0;
constexpr double kJoinGroupMiBPerImage = 0.75;
// Fewer tracks per image than this fix little of the large-scale shape
// (city10: 149 gave 0.046 deg against 0.048 without; the 192-photo test
// scene: 100 gave 0.084 against 0.075), so the join then does not adjust.
constexpr int kMinJoinTracksPerImage = 150;
// A block adjustment with all points: per matched keypoint of the block.
constexpr double kBlockPerMatchedKeypoint = 790.0;

}  // namespace

MemoryLoad LoadOfImages(const MatchGraph& graph,
                        const std::vector<int>& images) {
  MemoryLoad load;
  for (const int i : images) {
    ++load.images;
    load.keypoints += graph.images.at(i).num_keypoints;
    load.matched_keypoints += graph.images.at(i).num_matched_keypoints;
  }
  return load;
}

double TaskPeakMiB(const MemoryLoad& task) {
  return kProcessMiB + (kTaskPerKeypoint * task.keypoints +
                        kTaskPerMatchedKeypoint * task.matched_keypoints) /
                           kMiB;
}

double CorrespondencesMiB(const MemoryLoad& scene) {
  return (kCachePerKeypoint * scene.keypoints +
          kCachePerMatchedKeypoint * scene.matched_keypoints) /
         kMiB;
}

double MergePeakMiB(const MemoryLoad& scene, int longest_tracks_per_image,
                    int max_block_images) {
  const double held =
      kProcessMiB + CorrespondencesMiB(scene) +
      kModelsPerMatchedKeypoint * scene.matched_keypoints / kMiB;
  const double longest =
      LongestTracksMiB(scene.images, longest_tracks_per_image);
  const double block_share =
      max_block_images > 0 && scene.images > max_block_images
          ? static_cast<double>(max_block_images) / scene.images
          : 1.0;
  const double block =
      kBlockPerMatchedKeypoint * block_share * scene.matched_keypoints / kMiB;
  return held + std::max(longest, block);
}

double LongestTracksMiB(int64_t images, int tracks_per_image) {
  return kLongestTracksPerImageTrack * images * tracks_per_image / kMiB;
}

double JoinAdjustmentMiB(int64_t images, int tracks_per_image,
                         int64_t largest_group_images) {
  if (tracks_per_image <= 0) return 0.0;
  return kJoinAdjustmentPerImageTrack * images * tracks_per_image / kMiB +
         kJoinGroupMiBPerImage * largest_group_images;
}

int JoinTracksThatFit(int wanted, double budget_mib, int64_t images,
                      int64_t largest_group_images) {
  if (images <= 0) return wanted;
  const double fit = (budget_mib - kProcessMiB -
                      kJoinGroupMiBPerImage * largest_group_images) *
                     kMiB / (kJoinAdjustmentPerImageTrack * images);
  if (fit < std::min(wanted, kMinJoinTracksPerImage)) return 0;
  return std::max(0, std::min(wanted, static_cast<int>(fit)));
}

double JoinPeakMiB(const MemoryLoad& largest_group, const MemoryLoad& job_seams,
                   double adjustment_mib) {
  const double group =
      kModelsPerMatchedKeypoint * largest_group.matched_keypoints / kMiB;
  const double job =
      kModelsPerMatchedKeypoint * job_seams.matched_keypoints / kMiB +
      CorrespondencesMiB(job_seams);
  return kProcessMiB + std::max({job, group, adjustment_mib});
}

double JoinJobMiB(double join_mib) {
  return std::max(1.0, join_mib - kProcessMiB);
}

double ProcessMiB() { return kProcessMiB; }

MemoryBudget ResolveMemoryBudget(double budget_gib) {
  if (budget_gib > 0) return {budget_gib * 1024.0, "--Tmr.memory_budget"};
  const double available = AvailableMemoryMiB();
  if (available <= 0)
    return {8 * 1024.0, "8 GiB: this system does not say its memory"};
  return {available / 2,
          "half of the " + GiBText(available) + " this process may use"};
}

std::string MergeOverBudgetWarning(double merge_mib,
                                   const MemoryBudget& budget) {
  if (merge_mib <= budget.mib) return "";
  return "warning: the merge stage is expected to need " + GiBText(merge_mib) +
         ", above the memory budget of " + GiBText(budget.mib) +
         "; give a budget it fits in, or run it where it fits";
}

std::string GiBText(double mib) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f GiB", mib / 1024.0);
  return text;
}

}  // namespace tmr
