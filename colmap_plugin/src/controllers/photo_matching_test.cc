// Copyright (c) 2026, the tmr authors. BSD-3-Clause.
// The matching stage of tmr_reconstruct: numbered sequences told from
// unordered names, the matcher "auto" picks, and a vocabulary tree built
// with COLMAP's VisualIndex from the SIFT descriptors of a database written
// by COLMAP's Database class (the same seed gives the same retrieval).
#include "controllers/photo_matching.h"

#include <colmap/retrieval/visual_index.h>
#include <colmap/scene/database.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>

#include "tmr/io/atomic_file.h"

namespace tmr {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> Names(const std::string& pattern, int first, int count,
                               int step) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) {
    char name[256];
    std::snprintf(name, sizeof(name), pattern.c_str(), first + i * step);
    names.push_back(name);
  }
  return names;
}

TEST(IsNumberedSequence, FramesAndCameraNumbersAre) {
  EXPECT_TRUE(IsNumberedSequence(Names("video/frame_%06d.jpg", 1, 500, 1)));
  EXPECT_TRUE(IsNumberedSequence(Names("IMG_%04d.JPG", 4711, 300, 3)));
  EXPECT_TRUE(IsNumberedSequence(Names("templeR%04d.png", 1, 47, 1)));
  // A few photos of another name do not break a sequence.
  std::vector<std::string> names = Names("DSC%05d.jpg", 100, 95, 1);
  for (const char* other : {"a.jpg", "b.jpg", "c.jpg", "d.jpg", "e.jpg"})
    names.push_back(other);
  EXPECT_TRUE(IsNumberedSequence(names));
}

TEST(IsNumberedSequence, UnorderedNamesAreNot) {
  // Photo-sharing ids: numbers far apart.
  EXPECT_FALSE(IsNumberedSequence(Names("%d_photo.jpg", 10000, 200, 7919)));
  // Hashes, and two cameras' numbers in two folders.
  EXPECT_FALSE(IsNumberedSequence(
      {"3f2a.jpg", "b7c1.jpg", "09de.jpg", "e4f0.jpg", "aa12.jpg"}));
  std::vector<std::string> names = Names("left/%04d.png", 1, 50, 1);
  for (const std::string& name : Names("right/%04d.png", 1, 50, 1))
    names.push_back(name);
  EXPECT_FALSE(IsNumberedSequence(names));
  // The same number twice is not one sequence.
  EXPECT_FALSE(IsNumberedSequence({"a01.jpg", "a1.jpg", "a2.jpg", "a3.jpg"}));
  EXPECT_FALSE(IsNumberedSequence({"1.jpg", "2.jpg"}));
}

TEST(ChooseMatcher, AutoByCountAndNames) {
  ReconstructImagesOptions options;
  options.max_exhaustive_images = 100;
  std::string reason;
  EXPECT_EQ(ChooseMatcher(options, Names("f%04d.jpg", 1, 100, 1), &reason),
            "exhaustive");
  EXPECT_EQ(reason, "100 images, at most 100");
  EXPECT_EQ(ChooseMatcher(options, Names("f%04d.jpg", 1, 101, 1), &reason),
            "sequential");
  EXPECT_EQ(ChooseMatcher(options, Names("%d.jpg", 1, 101, 977), &reason),
            "retrieval");
  EXPECT_EQ(reason, "101 images, more than 100, not a numbered sequence");
  options.matcher = "spatial";
  EXPECT_EQ(ChooseMatcher(options, Names("%d.jpg", 1, 101, 977), &reason),
            "spatial");
}

class VocabularyTreeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("photo_matching_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    database_path_ = (dir_ / "database.db").string();
    auto database = colmap::Database::Open(database_path_);
    const colmap::camera_t camera_id =
        database->WriteCamera(colmap::Camera::CreateFromModelName(
            colmap::kInvalidCameraId, "SIMPLE_RADIAL", 500, 640, 480));
    // SIFT-like descriptors around 100 centres.
    std::mt19937 random(7);
    std::uniform_int_distribution<int> centre(0, 99), value(0, 255),
        noise(-6, 6);
    colmap::FeatureDescriptorsData centres(100, 128);
    for (int c = 0; c < centres.rows(); ++c)
      for (int k = 0; k < 128; ++k) centres(c, k) = value(random);
    for (int i = 0; i < 8; ++i) {
      colmap::Image image;
      image.SetName("image" + std::to_string(i) + ".jpg");
      image.SetCameraId(camera_id);
      const colmap::image_t id = database->WriteImage(image);
      colmap::FeatureDescriptorsData data(1000, 128);
      for (int r = 0; r < data.rows(); ++r) {
        const int c = centre(random);
        for (int k = 0; k < 128; ++k)
          data(r, k) = static_cast<uint8_t>(
              std::clamp(centres(c, k) + noise(random), 0, 255));
      }
      database->WriteKeypoints(id, colmap::FeatureKeypoints(data.rows()));
      database->WriteDescriptors(
          id, colmap::FeatureDescriptors(colmap::FeatureExtractorType::SIFT,
                                         std::move(data)));
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The database's images ranked by similarity to its first image, with
  // the vocabulary at `path`.
  std::vector<std::pair<int, float>> Ranking(const std::string& path) {
    auto index = colmap::retrieval::VisualIndex::Read(path);
    auto database = colmap::Database::Open(database_path_);
    colmap::retrieval::VisualIndex::IndexOptions indexing;
    indexing.num_threads = 1;
    const std::vector<colmap::Image> images = database->ReadAllImages();
    for (const colmap::Image& image : images) {
      index->Add(indexing, image.ImageId(),
                 database->ReadKeypoints(image.ImageId()),
                 database->ReadDescriptors(image.ImageId()).ToFloat());
    }
    index->Prepare();
    colmap::retrieval::VisualIndex::QueryOptions query;
    query.num_threads = 1;
    std::vector<colmap::retrieval::ImageScore> scores;
    index->Query(query,
                 database->ReadDescriptors(images.front().ImageId()).ToFloat(),
                 &scores);
    std::vector<std::pair<int, float>> ranking;
    for (const auto& score : scores)
      ranking.emplace_back(score.image_id, score.score);
    return ranking;
  }

  fs::path dir_;
  std::string database_path_;
};

TEST(VocabularyWordsTest, TwoPerPhotoBetween1024AndTheLimit) {
  EXPECT_EQ(VocabularyWords(200, 4096), 1024);
  EXPECT_EQ(VocabularyWords(1000, 4096), 2000);
  EXPECT_EQ(VocabularyWords(2000, 4096), 4000);
  EXPECT_EQ(VocabularyWords(100000, 4096), 4096);
  EXPECT_EQ(VocabularyWords(200, 500), 500);  // the user's limit first
}

TEST_F(VocabularyTreeTest, BuildsAReadableTreeRepeatably) {
  VocabularyOptions options;
  options.num_visual_words = 125;  // the fewest words of 64 descriptors each
  options.num_iterations = 5;
  options.seed = 3;
  const std::string first = (dir_ / "first.bin").string();
  const std::string second = (dir_ / "second.bin").string();
  std::string error;
  ASSERT_TRUE(BuildVocabularyTree(database_path_, first, options, &error))
      << error;
  ASSERT_TRUE(BuildVocabularyTree(database_path_, second, options, &error))
      << error;
  EXPECT_FALSE(fs::exists(first + ".partial"));
  const auto index = colmap::retrieval::VisualIndex::Read(first);
  EXPECT_EQ(index->NumVisualWords(), 125u);
  EXPECT_EQ(index->FeatureType(), colmap::FeatureExtractorType::SIFT);
  // The same words: the same ranking with the same scores. (The files
  // themselves may differ in bytes faiss leaves unset.)
  const auto ranking = Ranking(first);
  ASSERT_EQ(ranking.size(), 8u);
  EXPECT_EQ(ranking.front().first, 1);  // the query image itself first
  EXPECT_EQ(ranking, Ranking(second));
}

TEST_F(VocabularyTreeTest, FewFeaturesGiveFewerWordsOrAReason) {
  VocabularyOptions options;
  options.num_visual_words = 4096;  // 8,000 descriptors: 125 words
  options.num_iterations = 2;
  const std::string path = (dir_ / "tree.bin").string();
  std::string error;
  ASSERT_TRUE(BuildVocabularyTree(database_path_, path, options, &error))
      << error;
  EXPECT_EQ(colmap::retrieval::VisualIndex::Read(path)->NumVisualWords(), 125u);
  options.descriptors_per_word = 100;  // 80 words: too few
  EXPECT_FALSE(BuildVocabularyTree(database_path_, path, options, &error));
  EXPECT_EQ(error, "too few features (8000) for a vocabulary tree");
}

TEST_F(VocabularyTreeTest, AFileThatIsNoTreeIsRefusedBeforeMatching) {
  ReconstructImagesOptions options;
  options.image_path = dir_.string();
  options.workspace_path = dir_.string();
  options.vocab_tree_path = (dir_ / "not_a_tree.bin").string();
  ASSERT_TRUE(WriteFileAtomically(options.vocab_tree_path, "no tree"));
  PhotoMatcher matcher;
  std::string error;
  EXPECT_FALSE(
      CreatePhotoMatcher(options, "retrieval", 8, &matcher, &error, nullptr));
  EXPECT_EQ(error.rfind("'" + options.vocab_tree_path +
                            "' is not a COLMAP vocabulary tree: ",
                        0),
            0u)
      << error;
  EXPECT_EQ(matcher.thread, nullptr);
}

}  // namespace
}  // namespace tmr
