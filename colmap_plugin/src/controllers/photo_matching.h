// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The matching stage of tmr_reconstruct (RunReconstructImages): which of
// COLMAP's pairings the photos get, and the vocabulary tree that retrieval
// and loop detection need, built from the set's own features.
#pragma once

#include <colmap/util/threading.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tmr/colmap/reconstruct_images.h"

namespace tmr {

// Whether image names (with their folders) are a numbered sequence, as the
// frames of a video or photos taken one after the other: at least 90% of
// them share a folder and the text around their last run of digits, and
// those numbers, sorted, are on average at most 10 apart.
bool IsNumberedSequence(const std::vector<std::string>& names);

// The pairing of options.matcher, with "auto" resolved for these image
// names: exhaustive up to options.max_exhaustive_images images; above,
// sequential (with loop detection) for a numbered sequence and retrieval
// otherwise. `reason` says why, for the summary.
std::string ChooseMatcher(const ReconstructImagesOptions& options,
                          const std::vector<std::string>& names,
                          std::string* reason);

// COLMAP's vocabulary tree (retrieval::VisualIndex: visual words by k-means
// with a Hamming embedding, Schönberger et al., ACCV 2016) built from a
// random sample of the database's descriptors, at most
// descriptors_per_word per word.
struct VocabularyOptions {
  int num_visual_words = 4096;    // fewer when the database has few features
  int descriptors_per_word = 64;  // faiss warns below 39
  int num_iterations = 20;        // k-means iterations
  uint64_t seed = 0;              // sampling and Hamming projection
};

// Words of the vocabulary built for `num_images` photos: 2 per photo, at
// least 1,024 and at most `max_words`. The k-means time grows with the
// square of the words (64 descriptors each) and not with the photos: at
// 200 views (docs/benchmarks.md) 1,024 words took 11 s and 4,096 words
// 166 s, and retrieval found 89% against 94% of the pairs exhaustive
// matching verified, with as many photos registered.
int VocabularyWords(int num_images, int max_words);

// Builds the vocabulary from the database at `database_path` and writes it
// to `path` through a temporary file; the same database and seed give the
// same words and retrieval. False with one reason in `error`.
bool BuildVocabularyTree(const std::string& database_path,
                         const std::string& path,
                         const VocabularyOptions& options, std::string* error);

// A COLMAP matcher thread over the workspace database and the number of
// pairs it will match at most (for the progress line): exact for
// exhaustive matching, an upper bound for the others (a pair found from
// both of its photos is matched once).
struct PhotoMatcher {
  std::unique_ptr<colmap::Thread> thread;
  int64_t max_pairs = 0;
  bool max_pairs_exact = false;
};

// Creates COLMAP's matcher for the pairing `name` (ChooseMatcher) over
// `num_images` images. Retrieval and sequential loop detection read
// options.vocab_tree_path, or a vocabulary built from the workspace's
// features (workspace_path/vocab_tree.bin, reused by a rerun). False with
// one reason in `error`.
bool CreatePhotoMatcher(
    const ReconstructImagesOptions& options, const std::string& name,
    int64_t num_images, PhotoMatcher* matcher, std::string* error,
    const std::function<void(const std::string&)>& progress);

}  // namespace tmr
