// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
#pragma once

#include <colmap/scene/database_cache.h>
#include <colmap/scene/reconstruction.h>

#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "controllers/memory_budget.h"
#include "controllers/task_graph.h"
#include "controllers/task_workspace.h"
#include "tmr/colmap/tmr_mapper.h"

namespace tmr {

class SceneAssembler;
struct ModelPairAlignment;

// The steps of tmr_mapper (paper Sec. 5) on its work folder
// (output_path/.tmr_work), each with its inputs and outputs on disk: the
// partition, one kernel or leaf task, a kernel's cluster merge, the scene
// assembly. RunTmrMapper runs them in one process on its task graph; the
// staged entry points (PlanTmrMapper, RunTmrMapperTask, MergeTmrMapper) run
// them in separate processes, possibly on other machines sharing
// output_path (the expected memory of each step is in
// tmr_mapper_memory.cc). What one task needs of another (a leaf task of its
// kernel's result) it reads from disk in both cases, so both give the same
// models.
class TmrMapperStages {
 public:
  using Progress = std::function<void(const std::string&)>;
  using Record = std::function<void(const TmrTaskReport&)>;

  // A group of image clusters that a merge stage by parts merges on its
  // own (docs/distributed.md): its kernels' clusters with their halos, and
  // the unclustered images with the most verified matches into them.
  struct ClusterGroup {
    std::vector<int> kernels;
    std::vector<int> extra_images;  // tree indices
    int num_images = 0;             // all of its images
    double memory_mib = 0.0;        // its merge's expected peak
    // The later groups that images both hold or verified pairs link it to
    // (the pairs of groups that the join aligns).
    std::vector<int> links;
    // Each link's seam (tree indices, sorted): the images both hold, and
    // those of verified pairs across the two groups. Empty lists in a plan
    // written before them.
    std::vector<std::vector<int>> link_seams;
  };

  explicit TmrMapperStages(const TmrMapperOptions& options);

  // Builds the TMR-tree, checks its tasks against the memory budget
  // (CheckMemory; `one_process`: the run that follows holds the
  // correspondences beside them), writes tree.json and plan.txt (one line
  // per task: id, images, base images, expected MiB; then the merge's) and
  // opens the work folder, resuming an earlier run's tasks when the
  // database, partition and task options are the same (options.resume).
  // Fills report->num_images and partition_seconds.
  bool Plan(TmrMapperReport* report, bool one_process, const Progress& progress,
            std::string* error);
  // The tree and work folder of an earlier Plan with the same options.
  bool Load(std::string* error);

  const TmrTree& tree() const { return tree_; }
  bool resuming() const { return work_.resuming(); }
  const TaskWorkspace& work() const { return work_; }

  // Every kernel task, then every leaf task, with its state on disk and its
  // expected memory.
  std::vector<TmrMapperTask> Tasks() const;
  // The merge stage's expected peak memory (MiB); by parts, the join's.
  double MergeMemoryMiB() const;
  // The groups of a merge stage by parts (GroupClusters), made when the
  // whole merge stage is expected to need more than the budget; empty
  // when it fits.
  const std::vector<ClusterGroup>& cluster_groups() const { return groups_; }
  // The largest group's expected peak, and its photos (0 without groups).
  double LargestGroupMiB() const;
  int LargestGroupImages() const;
  // The first of `tasks` (Tasks()) that group g merges and that has not
  // finished; "" when the group is ready.
  std::string UnfinishedTaskOfGroup(
      int g, const std::vector<TmrMapperTask>& tasks) const;
  // Whether group g's models are in the work folder.
  bool GroupMerged(int g) const;

  // The memory budget (options.memory_budget, resolved once).
  const MemoryBudget& budget() const { return budget_; }
  // Expected memory (MiB) of the correspondences of all images and of
  // kernel k's cluster merge; known after Plan only.
  double CorrespondencesMemoryMiB() const { return correspondences_mib_; }
  double ClusterMergeMemoryMiB(int k) const {
    return k < static_cast<int>(cluster_mib_.size()) ? cluster_mib_[k] : 0.0;
  }

  // Runs a kernel or leaf task, or reuses its finished result
  // (row.reused). A leaf task whose kernel task failed records a failed
  // result at once. False with `error` when the task cannot run: its task
  // database cannot be written, or its kernel task has not finished.
  bool RunTask(const TmrMapperTask& task, int num_threads, TmrTaskReport* row,
               std::string* error) const;
  // The report row of a finished task; nothing when it has not finished.
  std::optional<TmrTaskReport> FinishedTaskRow(const TmrMapperTask& task) const;

  // COLMAP's correspondences of all images, from a task database of all
  // images in the work folder.
  std::shared_ptr<const colmap::DatabaseCache> LoadCache(
      std::string* error) const;

  // The image-cluster model of kernel k from its finished kernel and leaf
  // tasks (MergeLeafModels); null when the kernel task failed. `row`
  // describes the merge, `notes` the leaf models left out.
  std::shared_ptr<colmap::Reconstruction> MergeCluster(
      int k, std::shared_ptr<const colmap::DatabaseCache> cache,
      int num_threads, TmrTaskReport* row,
      std::vector<std::string>* notes) const;

  // Kernel k's cluster merge (MergeCluster) as a task of a TaskGraph: it
  // runs once `depends` have finished, if *cache then holds the
  // correspondences; its notes go to `progress`, its row to `record` (when
  // it gave a model), its model to *cluster. The callbacks are called from
  // worker threads.
  TaskGraph::Task ClusterMergeTask(
      int k, std::vector<int> depends,
      const std::shared_ptr<const colmap::DatabaseCache>* cache,
      const Progress& progress, const Record& record,
      std::shared_ptr<colmap::Reconstruction>* cluster) const;
  // The cluster models of `kernels` (their ClusterMergeTask side by side
  // on num_threads workers).
  std::vector<std::shared_ptr<colmap::Reconstruction>> MergeClusters(
      const std::vector<int>& kernels,
      std::shared_ptr<const colmap::DatabaseCache> cache, int num_threads,
      const Record& record, const Progress& progress) const;

  // The models the finished tasks made of the images their main model
  // left (of the tasks of `kernels` only, when given).
  std::vector<std::shared_ptr<colmap::Reconstruction>> PartModels(
      const std::vector<int>* kernels = nullptr) const;

  // The last stage: scene models from the cluster and part models
  // (SceneAssembler), written to output_path/0, 1, ..., largest first.
  bool AssembleAndWrite(
      std::vector<std::shared_ptr<colmap::Reconstruction>> models,
      std::shared_ptr<const colmap::DatabaseCache> cache, int num_threads,
      const Record& record, const Progress& progress, TmrMapperReport* report,
      std::string* error) const;

  // The merge stage by parts. Group g's merge: the correspondences of its
  // images only, its cluster merges, SceneAssembler on them (no model
  // dropped: a small one may join another group's), its models written to
  // the work folder; reused when they are there already.
  bool MergeGroup(int g, int num_threads, const Record& record,
                  const Progress& progress, std::string* error) const;
  // Then the join (tmr_mapper_join.cc): light copies of the groups' models
  // (MakeSeamModel, one group's models in memory at a time), each linked
  // pair of groups aligned on the correspondences of its link's seam, and
  // each group's own models when its merge left several
  // (SceneAssembler::AlignModelPairs, side by side within the budget),
  // the models placed by one similarity averaging (PlaceJoin), each scene
  // written to output_path piece by piece (ModelWriter), one group's model
  // in memory at a time. Every group must have been merged.
  bool JoinGroups(int num_threads, const Record& record,
                  const Progress& progress, TmrMapperReport* report,
                  std::string* error) const;

 private:
  // Sets *error to `message`; returns false.
  static bool Fail(const std::string& message, std::string* error) {
    *error = message;
    return false;
  }

  struct KernelState {
    bool finished = false;
    bool success = false;
    int num_registered = 0;
    std::vector<uint32_t> part_images;  // in the kernel's part models
  };
  KernelState ReadKernelState(int k) const;
  // Tasks() without their state on disk (finished is false).
  std::vector<TmrMapperTask> PlannedTasks() const;
  // A task's images (tree indices): a kernel task its kernel's; a leaf
  // task its kernel's, then its leaf cluster's and its halo.
  std::vector<int> TaskImages(const TmrMapperTask& task) const;
  // Fills the expected memory of every step (controllers/memory_budget.h),
  // and the cluster groups (PlanGroups; for memory in a staged plan only
  // with options.memory_budget given).
  void EstimateMemory(const MatchGraph& graph, bool one_process);
  // The cluster groups (GroupClusters) and their memory, and the join's:
  // when the scene has more photos than merge.max_group_images, or when
  // `for_memory` and its merge is expected to need more than the budget.
  void PlanGroups(const MatchGraph& graph, bool for_memory);
  // A group's images (tree indices, sorted).
  std::vector<int> GroupImages(const ClusterGroup& group) const;
  // Per image (tree index), the groups that hold it.
  std::vector<std::vector<int>> GroupsOfImages(int num_images) const;
  // The images of the seams between groups, whose correspondences the join
  // loads: those several groups hold, and those of verified pairs across
  // groups.
  std::vector<int> SeamImages(const MatchGraph& graph) const;
  // Each group's links and their seams (ClusterGroup::links,
  // link_seams): images both hold, or verified pairs between their images.
  void LinkGroups(const MatchGraph& graph);
  // The seam images (tree indices, sorted) that the join loads to align
  // group g's own models: all of g's seams.
  std::vector<int> GroupSeamImages(int g) const;
  // Those it loads to align the models of linked groups g and h: their
  // link's seam; all the seams of both for a plan without link seams.
  std::vector<int> LinkSeamImages(int g, int h) const;
  // The plan.txt lines of the merge stage by parts, which ReadPlanMemory
  // reads back: one per group ("merge.G IMAGES 0 MIB kernels=K,...
  // extra=I,... links=G,...", extra and links maybe empty), then
  // "seams N 0 0 I,...", then one per link ("seam.G.H N 0 0 I,...").
  std::string GroupPlanLines() const;
  // Whether the groups read from a plan name kernels and images of the
  // tree, each kernel in one group.
  bool GroupsFitTheTree() const;
  // What group g's merge depends on, recorded with its models: its
  // clusters and extra images, its tasks' results and the options that
  // change results (not Mapper.num_threads nor the budget, which a join
  // job on Slurm sets otherwise).
  std::string GroupRecord(int g) const;
  // Reads such a line back (the fields after the first four in `rest`);
  // false for a line of another kind.
  bool ReadGroupPlanLine(const std::string& id, int images, double mib,
                         std::istringstream* rest);
  // Writes scenes (largest first) to output_path/0, 1, ..., then
  // FinishScenes.
  bool WriteScenes(
      const std::vector<std::shared_ptr<colmap::Reconstruction>>& scenes,
      const SceneAssembler& assembler, const Progress& progress,
      TmrMapperReport* report, std::string* error) const;
  // After output_path/0 .. num_scenes - 1 are written: removes the models
  // of an earlier run beyond them, reports the weak links.
  void FinishScenes(size_t num_scenes, std::vector<TmrWeakLink> weak_links,
                    const Progress& progress, TmrMapperReport* report) const;
  // The join's steps (tmr_mapper_join.cc): the pairs of groups it aligns
  // (ClusterGroup::links; every pair for a plan written without them);
  // its alignment jobs run side by side while their expected memory
  // (JoinJobMiB) fits the budget, their alignments appended to *aligned in
  // job order; one job (number `number`, which names its task database):
  // the pairs of models it links on its seam's correspondences, in the
  // join's numbering of `entries`.
  struct JoinEntry;
  struct JoinJob;
  // The longest tracks per image of the join's adjustment
  // (refinement.points_per_image, fewer where the budget needs; 0 without
  // merge.adjust_join).
  int JoinPointsPerImage() const;
  std::vector<std::pair<int, int>> LinkedGroupPairs() const;
  bool RunJoinJobs(const std::vector<JoinJob>& jobs,
                   const std::vector<JoinEntry>& entries, int num_threads,
                   const Record& record, const Progress& progress,
                   std::vector<ModelPairAlignment>* aligned,
                   std::string* error) const;
  bool AlignJoinJob(const JoinJob& job, int number,
                    const std::vector<JoinEntry>& entries, int num_threads,
                    const Record& record,
                    std::vector<ModelPairAlignment>* aligned,
                    std::string* error) const;
  // Reads the expected memory of every step from plan.txt (0 where an
  // older plan has none).
  bool ReadPlanMemory(std::string* error);
  // Says what the run expects to need against the budget; false with
  // `error` when a task would not fit (`one_process`: beside the
  // correspondences of all images, which the one-process run holds from
  // its start). A staged plan made with the default budget only warns (it
  // may be made on a smaller machine than the tasks run on), and so does
  // the merge stage above the budget.
  bool CheckMemory(bool one_process, const Progress& progress,
                   std::string* error) const;
  std::string Model(const TmrMapperTask& task) const;
  // A task's report row; a leaf's counts are relative to `kernel`, its
  // kernel's state (unused for a kernel task).
  TmrTaskReport Row(const TmrMapperTask& task,
                    const ReconstructionTaskResult& result, bool reused,
                    const KernelState& kernel) const;

  const TmrMapperOptions& o_;
  MemoryBudget budget_;
  TaskWorkspace work_;
  TmrTree tree_;
  // Expected peak memory (MiB) by task id, and of the "merge" stage.
  std::unordered_map<std::string, double> memory_mib_;
  double correspondences_mib_ = 0.0;
  std::vector<double> cluster_mib_;
  std::vector<ClusterGroup> groups_;
  std::vector<int> seam_images_;  // SeamImages, written with the plan
};

}  // namespace tmr
