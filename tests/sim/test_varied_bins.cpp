// Dense piles (`--pile dense`) and per-bin randomisation (`--vary`): a dense pile stacks
// parts in several layers, all at rest inside the bin and none inside another; a varied
// bin records what it drew, its two views differ in brightness as the recorded exposure
// and gain say, and the same seed gives the same bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "host/io/physical_checks.h"
#include "host/sim/bin_scene.h"
#include "tests/sim/pile_checks.h"

using namespace flexsight;

namespace {

std::vector<std::shared_ptr<const Mesh>> some_tless_parts() {
  std::vector<std::shared_ptr<const Mesh>> meshes;
  for (const char* name : {"obj_02.stl", "obj_05.stl", "obj_11.stl", "obj_19.stl", "obj_26.stl"}) {
    meshes.push_back(std::make_shared<const Mesh>(load_mesh(std::string(FLEXSIGHT_TLESS_CAD_DIR) + "/" + name)));
  }
  return meshes;
}

// Parts whose centre lies over another part (inside the xy box of its vertices) and
// 10 mm or more above that part's centre: parts lying on others (the middle of its box).
int parts_on_others(const std::vector<std::shared_ptr<const Mesh>>& meshes, const std::vector<RestingPart>& parts) {
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<Eigen::Vector3d> centres;
  for (const RestingPart& part : parts) {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3f& p : meshes[part.part]->positions) box.extend(part.world.R * p.cast<double>() + part.world.t);
    boxes.push_back(box);
    centres.push_back(box.center());
  }
  int stacked = 0;
  for (std::size_t a = 0; a < parts.size(); ++a) {
    for (std::size_t b = 0; b < parts.size(); ++b) {
      const Eigen::Vector3d& c = centres[a];
      if (a != b && c.x() > boxes[b].min().x() && c.x() < boxes[b].max().x() && c.y() > boxes[b].min().y() &&
          c.y() < boxes[b].max().y() && c.z() > centres[b].z() + 10.0) {
        ++stacked;
        break;
      }
    }
  }
  return stacked;
}

BinSimSettings small_settings() {
  BinSimSettings settings;
  settings.rig.width = 320;
  settings.rig.height = 240;
  settings.min_parts = settings.max_parts = 6;
  settings.threads = 2;
  return settings;
}

const PartLibrary& tless() {
  static const PartLibrary parts = PartLibrary::load_folder(FLEXSIGHT_TLESS_CAD_DIR);
  return parts;
}

// sRGB byte -> linear value.
double linear(int v) {
  const double s = v / 255.0;
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

}  // namespace

TEST(DensePile, StacksPartsInLayersAllAtRestInsideTheBin) {
  const auto meshes = some_tless_parts();
  std::vector<PartHull> hulls;
  for (const auto& mesh : meshes) hulls.push_back(make_part_hull(*mesh));
  BinSimSettings dense;
  use_dense_pile(dense);
  // Half the default bin's floor (500 x 340 mm): the 30 parts of the smallest dense pile
  // cover it about once side by side, as 60 cover the default bin (kept small for time).
  BinGeometry bin;
  bin.length_mm = 340.0;
  bin.width_mm = 250.0;
  std::vector<int> order;
  for (int i = 0; i < dense.min_parts; ++i) order.push_back(i % int(hulls.size()));
  const PhysicsResult pile = drop_parts(hulls, order, bin, dense.physics, synth_detail::SynthRandom(5, 0, 1));
  EXPECT_TRUE(pile.at_rest) << pile.steps << " steps";
  ASSERT_GE(pile.parts.size(), order.size() - 2) << pile.removed << " removed";

  // A sparse pile's 12 parts for comparison: one layer with few parts on others.
  const PhysicsResult layer = drop_parts(hulls, std::vector<int>(order.begin(), order.begin() + 12), bin,
                                         BinSimSettings{}.physics, synth_detail::SynthRandom(5, 0, 1));
  const int stacked = parts_on_others(meshes, pile.parts);
  EXPECT_GE(stacked, int(pile.parts.size()) / 8) << stacked << " of " << pile.parts.size();
  EXPECT_GT(stacked, parts_on_others(meshes, layer.parts)) << stacked;

  double highest = 0.0;
  for (const RestingPart& part : pile.parts) {
    EXPECT_EQ(physical_checks::rotation_problem(part.world.R), "");
    for (const Eigen::Vector3f& p : meshes[part.part]->positions) {
      const Eigen::Vector3d w = part.world.R * p.cast<double>() + part.world.t;
      ASSERT_GE(w.z(), -1.5);
      ASSERT_LE(std::abs(w.x()), 0.5 * bin.length_mm + 1.5);
      ASSERT_LE(std::abs(w.y()), 0.5 * bin.width_mm + 1.5);
      highest = std::max(highest, w.z());
    }
  }
  EXPECT_GT(highest, 60.0);  // several layers of 20 to 40 mm parts
  int tested = 0;
  const int inside_count = pile_checks::vertices_inside_other_parts(meshes, pile.parts, tested);
  EXPECT_LT(inside_count, std::max(3, tested / 500)) << inside_count << " of " << tested;
}

TEST(VariedBin, RecordsItsDrawsAndTheViewsDifferInGainAsRecorded) {
  BinSimSettings settings = small_settings();
  settings.vary = kVaryCamera;
  settings.noise_level_min = settings.noise_level_max = 0.0;  // the least noise
  // A bin whose two cameras differ by at least 15 % in exposure x gain.
  std::int64_t index = 0;
  auto ratio_of = [](const BinVariation& v) {
    return v.cameras[0].exposure * v.cameras[0].gain / (v.cameras[1].exposure * v.cameras[1].gain);
  };
  while (std::abs(ratio_of(draw_bin_variation(settings, 2000.0, 3, index, 0)) - 1.0) < 0.15) ++index;
  const BinSimulator simulator(settings, tless());
  const BinViews views = simulator.simulate(3, index);
  const double recorded = ratio_of(views.variation);

  // Left passive pixels against the right ones their disparity points at, linear.
  double left_sum = 0.0, right_sum = 0.0;
  int count = 0;
  for (int y = 0; y < views.im0.rows; ++y) {
    for (int x = 0; x < views.im0.cols; ++x) {
      if (views.nocc0.at<std::uint8_t>(y, x) == 0) continue;
      const int u = int(std::lround(x - views.disp0.at<float>(y, x)));
      if (u < 0 || u >= views.im1.cols) continue;
      const cv::Vec3b a = views.im0_passive.at<cv::Vec3b>(y, x), b = views.im1_passive.at<cv::Vec3b>(y, u);
      if (std::max(a[1], b[1]) >= 250 || std::min(a[1], b[1]) <= 5) continue;  // clipped
      left_sum += linear(a[1]);
      right_sum += linear(b[1]);
      ++count;
    }
  }
  ASSERT_GT(count, 10000);
  EXPECT_NEAR(left_sum / right_sum, recorded, 0.03 * recorded) << "recorded " << recorded;

  const nlohmann::json info = variation_json(views.variation);
  EXPECT_EQ(info.at("aspects"), "camera");
  ASSERT_EQ(info.at("cameras").size(), 2u);
  EXPECT_DOUBLE_EQ(info["cameras"][0]["gain"].get<double>(), views.variation.cameras[0].gain);
  EXPECT_FALSE(info.contains("material"));
}

TEST(VariedBin, EveryAspectDrawnInItsRangeAndTheSameSeedGivesTheSameBytes) {
  BinSimSettings settings = small_settings();
  settings.vary = kVaryAll;
  const BinSimulator simulator(settings, tless());
  const BinViews a = simulator.simulate(8, 1), b = simulator.simulate(8, 1);
  for (const cv::Mat* image : {&a.im0, &a.im1, &a.im0_passive, &a.im1_passive}) {
    const cv::Mat& other = image == &a.im0 ? b.im0 : image == &a.im1 ? b.im1 : image == &a.im0_passive ? b.im0_passive : b.im1_passive;
    EXPECT_EQ(cv::norm(*image, other, cv::NORM_INF), 0.0);
  }
  const nlohmann::json info = variation_json(a.variation);
  EXPECT_EQ(info.dump(), variation_json(b.variation).dump());
  EXPECT_NE(info.dump(), variation_json(simulator.simulate(8, 2).variation).dump());
  for (const char* key : {"material", "lights", "projector", "cameras", "noise_level"}) EXPECT_TRUE(info.contains(key)) << key;
  EXPECT_EQ(info["material"]["parts"].size(), a.parts.size());
  const auto& lamps = info["lights"]["lamps"];
  EXPECT_GE(lamps.size(), 1u);
  EXPECT_LE(lamps.size(), 3u);
  for (const auto& camera : info["cameras"]) {
    EXPECT_GE(camera["vignetting"].get<double>(), 0.0);
    EXPECT_LT(camera["vignetting"].get<double>(), 0.35);
    EXPECT_LT(camera["defocus_px"].get<double>(), 0.8);
    EXPECT_GE(camera["full_well_e"].get<double>(), 1500.0);
  }
  // A metal part is darker than the darkest plastic and has a stronger, narrower highlight.
  for (std::size_t i = 0; i < a.variation.part_materials.size(); ++i) {
    const Material& m = a.variation.part_materials[i];
    EXPECT_EQ(a.parts[i].albedo, m.albedo);
    if (a.variation.part_is_metal[i]) {
      EXPECT_LT(m.albedo.maxCoeff(), 0.16f);
      EXPECT_GE(m.specular, 1.0f);
    } else {
      EXPECT_LE(m.specular, 0.4f);
    }
  }
  // Without --vary nothing is drawn, and the same bin looks different.
  BinSimSettings plain = small_settings();
  const BinViews fixed = BinSimulator(plain, tless()).simulate(8, 1);
  EXPECT_EQ(fixed.variation.aspects, 0u);
  EXPECT_GT(cv::norm(fixed.im0, a.im0, cv::NORM_L1), 0.0);
}

TEST(VariedBin, MetalHighlightsDifferBetweenTheTwoViews) {
  BinSimSettings settings = small_settings();
  settings.vary = kVaryMaterial;
  settings.noise_sigma = 0.0;
  settings.min_parts = settings.max_parts = 10;
  const BinSimulator simulator(settings, tless());
  // A bin with metal and plastic parts.
  std::int64_t index = 0;
  BinViews views = simulator.simulate(21, index);
  auto mixed = [](const BinViews& v) {
    const auto& metal = v.variation.part_is_metal;
    return std::count(metal.begin(), metal.end(), true) >= 2 && std::count(metal.begin(), metal.end(), false) >= 2;
  };
  while (!mixed(views) && index < 20) views = simulator.simulate(21, ++index);
  ASSERT_TRUE(mixed(views));

  // Left against right at the ground truth's pixel, per material, inside the parts' faces
  // (away from depth edges, where interpolation differs): the 99th percentile of the grey
  // difference (highlights are small; the rest of a part matches).
  const auto smooth = [](const cv::Mat& disparity, int x, int y) {
    if (x < 1 || y < 1 || x + 1 >= disparity.cols || y + 1 >= disparity.rows) return false;
    const float d = disparity.at<float>(y, x);
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      if (!(std::abs(disparity.at<float>(y + dy, x + dx) - d) < 0.3f)) return false;
    }
    return true;
  };
  std::vector<int> metal_differences, plastic_differences;
  for (std::size_t i = 0; i < views.parts.size(); ++i) {
    const cv::Mat& mask = views.left.parts[i].mask_visib;
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        if (mask.at<std::uint8_t>(y, x) == 0 || views.nocc0.at<std::uint8_t>(y, x) == 0) continue;
        if (!smooth(views.disp0, x, y)) continue;
        const int u = int(std::lround(x - views.disp0.at<float>(y, x)));
        if (u < 0 || u >= views.im1.cols) continue;
        const int a = views.im0_passive.at<cv::Vec3b>(y, x)[1], b = views.im1_passive.at<cv::Vec3b>(y, u)[1];
        (views.variation.part_is_metal[i] ? metal_differences : plastic_differences).push_back(std::abs(a - b));
      }
    }
  }
  auto percentile_99 = [](std::vector<int> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() * 99 / 100];
  };
  ASSERT_GT(metal_differences.size(), 100u);
  ASSERT_GT(plastic_differences.size(), 100u);
  EXPECT_GT(percentile_99(metal_differences), 2 * percentile_99(plastic_differences))
      << percentile_99(metal_differences) << " vs " << percentile_99(plastic_differences);
}
