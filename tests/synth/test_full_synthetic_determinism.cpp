// An image is a function of (settings, libraries, seed, index): the same bytes twice,
// from any thread in any order; other indices and seeds give other images; the options
// that skip masks or depth change nothing else; bad inputs are InputErrors naming the
// option or file.
#include <gtest/gtest.h>

#include <thread>

#include "host/io/input_error.h"
#include "host/synth/full_synthetic.h"
#include "tests/render/render_test_support.h"
#include "tests/synth/synth_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

// Pixels, depth, masks and every number of two images are the same.
::testing::AssertionResult same_image(const AnnotatedImage& a, const AnnotatedImage& b) {
  if (!same_mat_bytes(a.rgb, b.rgb)) return ::testing::AssertionFailure() << "rgb differs";
  if (!same_mat_bytes(a.depth, b.depth)) return ::testing::AssertionFailure() << "depth differs";
  if (a.camera.K != b.camera.K || a.flipped_horizontally != b.flipped_horizontally ||
      a.flipped_vertically != b.flipped_vertically || a.parts.size() != b.parts.size()) {
    return ::testing::AssertionFailure() << "camera, flips or part count differ";
  }
  for (size_t i = 0; i < a.parts.size(); ++i) {
    const PartAnnotation& p = a.parts[i];
    const PartAnnotation& q = b.parts[i];
    if (p.obj_id != q.obj_id || p.cam_R_m2c != q.cam_R_m2c || p.cam_t_m2c != q.cam_t_m2c ||
        !(p.bbox_obj == q.bbox_obj) || !(p.bbox_visib == q.bbox_visib) ||
        p.px_count_all != q.px_count_all || p.px_count_valid != q.px_count_valid ||
        p.px_count_visib != q.px_count_visib || p.visib_fract != q.visib_fract) {
      return ::testing::AssertionFailure() << "part " << i << "'s annotation differs";
    }
    if (!same_mat_bytes(p.mask, q.mask) || !same_mat_bytes(p.mask_visib, q.mask_visib)) {
      return ::testing::AssertionFailure() << "part " << i << "'s masks differ";
    }
  }
  return ::testing::AssertionSuccess();
}

AnnotatedImage render(const FullSyntheticSettings& settings, std::uint32_t seed,
                      std::int64_t index) {
  return render_full_synthetic(settings, tless_parts(), real_backgrounds(), seed, index);
}

}  // namespace

TEST(SynthFullSyntheticDeterminism, SameKeySameBytesOtherKeysOtherImages) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  const FullSyntheticSettings settings;
  const AnnotatedImage first = render(settings, 7, 4);
  EXPECT_TRUE(same_image(first, render(settings, 7, 4)));
  EXPECT_FALSE(same_mat_bytes(first.rgb, render(settings, 7, 5).rgb));
  EXPECT_FALSE(same_mat_bytes(first.rgb, render(settings, 8, 4).rgb));
  // Indices beyond 32 bits are keys of their own.
  EXPECT_FALSE(same_mat_bytes(render(settings, 7, 4 + (std::int64_t(1) << 32)).rgb, first.rgb));
}

// Eight images in order on this thread, then on two threads in other orders (each
// thread's pooled scene has another history): the same bytes.
TEST(SynthFullSyntheticDeterminism, ThreadsAndOrderDoNotMatter) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  settings.width = 160;
  settings.height = 120;
  constexpr int kImages = 8;
  std::vector<AnnotatedImage> in_order;
  for (int i = 0; i < kImages; ++i) in_order.push_back(render(settings, 99, i));
  std::vector<AnnotatedImage> threaded(kImages);
  std::thread down([&] {
    for (int i = kImages - 1; i >= 0; i -= 2) threaded[i] = render(settings, 99, i);
  });
  std::thread up([&] {
    for (int i = 0; i < kImages; i += 2) threaded[i] = render(settings, 99, i);
  });
  down.join();
  up.join();
  for (int i = 0; i < kImages; ++i) EXPECT_TRUE(same_image(in_order[i], threaded[i])) << i;
}

TEST(SynthFullSyntheticDeterminism, SkippingMasksOrDepthChangesNothingElse) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  const AnnotatedImage full = render(settings, 5, 1);
  settings.store_masks = false;
  settings.store_depth = false;
  const AnnotatedImage lean = render(settings, 5, 1);
  EXPECT_TRUE(lean.depth.empty());
  EXPECT_TRUE(same_mat_bytes(lean.rgb, full.rgb));
  ASSERT_EQ(lean.parts.size(), full.parts.size());
  for (size_t i = 0; i < full.parts.size(); ++i) {
    EXPECT_TRUE(lean.parts[i].mask.empty());
    EXPECT_TRUE(lean.parts[i].mask_visib.empty());
    EXPECT_EQ(lean.parts[i].bbox_obj, full.parts[i].bbox_obj);
    EXPECT_EQ(lean.parts[i].px_count_valid, full.parts[i].px_count_valid);
    EXPECT_EQ(lean.parts[i].visib_fract, full.parts[i].visib_fract);
  }
}

TEST(SynthFullSyntheticDeterminism, TimingsAreReported) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticStats stats;
  const AnnotatedImage image =
      render_full_synthetic({}, tless_parts(), real_backgrounds(), 1, 0, &stats);
  EXPECT_GT(stats.raycast_ms, 0.0);
  EXPECT_GT(stats.shading_ms, 0.0);
  EXPECT_GT(stats.compositing_ms, 0.0);
  EXPECT_GE(stats.pose_attempts, int(image.parts.size()));
}

TEST(SynthFullSyntheticDeterminism, BadSettingsAndUndecodableBackgroundsAreInputErrors) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  FullSyntheticSettings settings;
  settings.min_parts = settings.max_parts = 0;
  try {
    render(settings, 1, 0);
    ADD_FAILURE() << "no error for 0 parts";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("option --min-parts: ", 0), 0u) << e.what();
  }
  TempFolder folder;
  write_text(folder / "broken.png", "not a PNG at all");
  const BackgroundLibrary broken(folder.str());
  try {
    render_full_synthetic({}, tless_parts(), broken, 1, 0);
    ADD_FAILURE() << "no error for an undecodable background";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(folder / "broken.png" + ": ", 0), 0u) << e.what();
  }
}
