// Merging shards (host/dataset/dataset_merge.h): two shards that split the images (and
// scene 0) between them merge into the very bytes a single writer gives, in either
// order; overlapping, unfinished, incomplete or differently set-up shards are refused.
#include <gtest/gtest.h>

#include <thread>

#include "host/dataset/dataset_merge.h"
#include "host/dataset/dataset_writer.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

DatasetWriterOptions options() {
  DatasetWriterOptions options;
  options.settings = {{"seed", 42}, {"parts", {"obj_01", "obj_02"}}, {"exposure", 0.7}};
  return options;
}

// Writes the images whose index passes `take` as a finished dataset, from two threads
// and in reverse order, to show that neither matters.
void write_dataset(const std::string& root, const DatasetWriterOptions& options,
                   const std::function<bool(int)>& take) {
  const std::vector<AnnotatedImage> images = sample_images();
  DatasetWriter writer(root, options);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      for (int i = static_cast<int>(images.size()) - 1 - t; i >= 0; i -= 2) {
        if (take(i)) writer.add(images[i], 100 + i);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  writer.finish();
}

bool even(int i) { return i % 2 == 0; }
bool odd(int i) { return i % 2 == 1; }
bool all(int) { return true; }

}  // namespace

TEST(DatasetMerge, TwoShardsGiveTheBytesOfOneWriter) {
  ScratchDir dir;
  write_dataset(dir / "single", options(), all);
  write_dataset(dir / "a", options(), even);
  write_dataset(dir / "b", options(), odd);
  EXPECT_EQ(merge_datasets({dir / "a", dir / "b"}, dir / "merged"), 6);
  EXPECT_EQ(merge_datasets({dir / "b", dir / "a"}, dir / "merged_ba"), 6);

  const auto single = tree_bytes(dir / "single");
  // 2 scenes x (folder, 4 subfolders, 3 JSON files), 6 x (rgb, depth), 9 parts x 2 masks,
  // COCO, dataset_info.
  EXPECT_EQ(single.size(), 2u * 8u + 12u + 18u + 2u);
  for (const char* merged : {"merged", "merged_ba"}) {
    SCOPED_TRACE(merged);
    const auto files = tree_bytes(dir / merged);
    EXPECT_EQ(files.size(), single.size());
    for (const auto& [name, bytes] : single) {
      const auto found = files.find(name);
      ASSERT_NE(found, files.end()) << name;
      EXPECT_TRUE(found->second == bytes) << name << " differs";
    }
  }
  EXPECT_NE(single.at("dataset_info.json").find("\"image_count\": 6"), std::string::npos);
}

TEST(DatasetMerge, FixedCategoriesMergeToo) {
  ScratchDir dir;
  DatasetWriterOptions fixed = options();
  fixed.categories = {
      {1, "bracket", "part"}, {2, "cover", "part"}, {3, "hub", "part"}, {4, "unused", "part"}};
  write_dataset(dir / "single", fixed, all);
  write_dataset(dir / "a", fixed, even);
  write_dataset(dir / "b", fixed, odd);
  merge_datasets({dir / "a", dir / "b"}, dir / "merged");
  EXPECT_TRUE(tree_bytes(dir / "single") == tree_bytes(dir / "merged"));
}

TEST(DatasetMerge, OverlappingImagesAreRefusedNamingTheShard) {
  ScratchDir dir;
  write_dataset(dir / "a", options(), even);
  write_dataset(dir / "c", options(), [](int i) { return i == 2 || i == 3; });
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "a", dir / "c"}, dir / "out");
      },
      "c/000000/scene_gt.json", "image 2 of scene 0 is also in the shard"));
  EXPECT_FALSE(fs::exists(dir / "out"));  // refused before anything was written
}

TEST(DatasetMerge, OverlappingImageIdsAreRefused) {
  ScratchDir dir;
  const std::vector<AnnotatedImage> images = sample_images();
  for (int shard : {0, 1}) {
    DatasetWriter writer(dir / ("s" + std::to_string(shard)), options());
    writer.add(images[shard], 7);  // different images, the same global index
    writer.finish();
  }
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "s0", dir / "s1"}, dir / "out");
      },
      "s1/coco_instances.json", "image id 7 is also in the shard"));
}

TEST(DatasetMerge, DifferentSettingsOrRgbFormatAreRefused) {
  ScratchDir dir;
  write_dataset(dir / "a", options(), even);
  DatasetWriterOptions other = options();
  other.settings["seed"] = 43;
  write_dataset(dir / "b", other, odd);
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "a", dir / "b"}, dir / "out");
      },
      "b/dataset_info.json", "differs in \"settings\""));
  DatasetWriterOptions png = options();
  png.bop.rgb_format = BopWriterOptions::RgbFormat::png;
  write_dataset(dir / "p", png, odd);
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "a", dir / "p"}, dir / "out");
      },
      "p/dataset_info.json", "differs in \"bop\""));
}

TEST(DatasetMerge, MissingFilesAndUnfinishedShardsAreRefused) {
  ScratchDir dir;
  write_dataset(dir / "a", options(), even);
  write_dataset(dir / "b", options(), odd);
  fs::remove(dir / "b/000001/mask/000007_000001.png");
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "a", dir / "b"}, dir / "out");
      },
      "b/000001/mask/000007_000001.png", "does not exist"));
  fs::remove(dir / "a/dataset_info.json");
  EXPECT_TRUE(throws_input_error(
      [&] {
        merge_datasets({dir / "a", dir / "b"}, dir / "out");
      },
      "a/dataset_info.json", "did not finish"));
}

TEST(DatasetMerge, OutputFolderMustBeEmpty) {
  ScratchDir dir;
  write_dataset(dir / "a", options(), even);
  EXPECT_TRUE(
      throws_input_error([&] { merge_datasets({dir / "a"}, dir / "a"); }, "a", "is not empty"));
}
