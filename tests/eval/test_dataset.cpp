// Benchmark folders, evaluation reports and the eval command, on small trees the tests
// write themselves. Discovery is also checked on the real benchmark copies, from the
// datasets folder of tests/common/real_datasets.h; a missing copy fails those tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/stereo/stereo_params.h"
#include "host/cli/commands.h"
#include "host/eval/dataset.h"
#include "host/eval/report.h"
#include "host/io/calibration.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "tests/common/mat_rows.h"
#include "tests/common/real_datasets.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---- fixtures on disk ------------------------------------------------------------

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    path_ = fs::temp_directory_path() /
            ("flexsight_" + std::string(info->name()) + "_" + std::to_string(random()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// Little-endian PFM written byte by byte here, so the fixtures do not depend on the
// writer under test elsewhere. Rows are stored bottom-up.
void write_pfm_by_hand(const fs::path& path, const cv::Mat& image) {
  ASSERT_EQ(image.type(), CV_32FC1);
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << image.cols << " " << image.rows << "\n-1\n";
  for (int y = image.rows - 1; y >= 0; --y) {
    for (int x = 0; x < image.cols; ++x) {
      std::uint32_t bits = 0;
      const float value = image.at<float>(y, x);
      std::memcpy(&bits, &value, sizeof bits);
      for (int byte = 0; byte < 4; ++byte) out.put(static_cast<char>((bits >> (8 * byte)) & 0xff));
    }
  }
}

void write_png(const fs::path& path, const cv::Mat& image) {
  fs::create_directories(path.parent_path());
  ASSERT_TRUE(cv::imwrite(path.string(), image)) << path;
}

cv::Mat random_rgb(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC3);
  cv::RNG(seed).fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

using testing_support::real_data_present;
using testing_support::real_datasets_dir;
using testing_support::rows_to_mask;
using testing_support::rows_to_mat;
using testing_support::rows_to_u16;

std::string middlebury_calib(int width, int height, int ndisp) {
  return "cam0=[100 0 " + std::to_string(width / 2) + "; 0 100 " + std::to_string(height / 2) +
         "; 0 0 1]\ncam1=[100 0 " + std::to_string(width / 2) + "; 0 100 " +
         std::to_string(height / 2) + "; 0 0 1]\ndoffs=0\nbaseline=100\nwidth=" +
         std::to_string(width) + "\nheight=" + std::to_string(height) + "\nndisp=" +
         std::to_string(ndisp) + "\nisint=0\nvmin=0\nvmax=" + std::to_string(ndisp - 1) + "\n";
}

// One MiddEval3 scene folder; images random, sizes taken from the ground truth.
void write_middeval3_scene(const fs::path& folder, const cv::Mat& gt, const cv::Mat& mask,
                           int ndisp) {
  write_png(folder / "im0.png", random_rgb(gt.cols, gt.rows, 1));
  write_png(folder / "im1.png", random_rgb(gt.cols, gt.rows, 2));
  write_text(folder / "calib.txt", middlebury_calib(gt.cols, gt.rows, ndisp));
  write_pfm_by_hand(folder / "disp0GT.pfm", gt);
  write_png(folder / "mask0nocc.png", mask);
}

void write_v2_scene(const fs::path& folder, const cv::Mat& gt8, const cv::Mat& nonocc) {
  write_png(folder / "imL.png", random_rgb(gt8.cols, gt8.rows, 3));
  write_png(folder / "imR.png", random_rgb(gt8.cols, gt8.rows, 4));
  write_png(folder / "groundtruth.png", gt8);
  write_png(folder / "nonocc.png", nonocc);
}

std::vector<std::string> names_of(const std::vector<Scene>& scenes) {
  std::vector<std::string> names;
  for (const Scene& scene : scenes) names.push_back(scene.name);
  return names;
}

// ---- discovery -------------------------------------------------------------------

void check_real_middeval3(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  const std::vector<std::string> expected = {
      "Adirondack", "ArtL",     "Jadeplant", "Motorcycle", "MotorcycleE",
      "Piano",      "PianoL",   "Pipes",     "Playroom",   "Playtable",
      "PlaytableP", "Recycle",  "Shelves",   "Teddy",      "Vintage"};
  ASSERT_EQ(names_of(scenes), expected);
  for (const Scene& scene : scenes) {
    EXPECT_EQ(scene.layout, DatasetLayout::MiddEval3);
    EXPECT_EQ(scene.ndisp, read_middlebury_calib(scene.calib_path).ndisp) << scene.name;
    EXPECT_FALSE(scene.gt_path.empty()) << scene.name;
    EXPECT_FALSE(scene.nonocc_path.empty()) << scene.name;
  }
  EXPECT_EQ(scenes[0].ndisp, 73);  // Adirondack's calib.txt
  const GroundTruth truth = load_ground_truth(scenes[0]);
  EXPECT_EQ(truth.disparity.size(), cv::Size(718, 496));
  EXPECT_EQ(truth.nonocc.size(), truth.disparity.size());
}

TEST(DiscoverScenes, MiddEval3Tree) {
  TempDir dir;
  const cv::Mat gt = rows_to_mat({{1, 2, 3}, {4, 5, kInf}});
  const cv::Mat mask = rows_to_mask({{255, 128, 255}, {255, 255, 0}});
  write_middeval3_scene(dir / "Beta", gt, mask, 40);
  write_middeval3_scene(dir / "Alpha", gt, mask, 24);
  write_text(dir / "notes" / "README.txt", "not a scene");  // ignored

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes), (std::vector<std::string>{"Alpha", "Beta"}));
  const Scene& alpha = scenes[0];
  EXPECT_EQ(alpha.layout, DatasetLayout::MiddEval3);
  EXPECT_EQ(alpha.ndisp, 24);
  EXPECT_EQ(scenes[1].ndisp, 40);
  EXPECT_EQ(fs::path(alpha.left_path), dir / "Alpha" / "im0.png");
  EXPECT_EQ(fs::path(alpha.right_path), dir / "Alpha" / "im1.png");
  EXPECT_EQ(fs::path(alpha.gt_path), dir / "Alpha" / "disp0GT.pfm");
  EXPECT_EQ(fs::path(alpha.nonocc_path), dir / "Alpha" / "mask0nocc.png");
  EXPECT_EQ(fs::path(alpha.calib_path), dir / "Alpha" / "calib.txt");
  EXPECT_STREQ(layout_name(alpha.layout), "MiddEval3");

  const GroundTruth truth = load_ground_truth(alpha);
  ASSERT_EQ(truth.disparity.type(), CV_32FC1);
  ASSERT_EQ(truth.disparity.size(), cv::Size(3, 2));
  EXPECT_EQ(truth.disparity.at<float>(1, 1), 5.0f);
  EXPECT_EQ(truth.disparity.at<float>(1, 2), kInf);
  ASSERT_EQ(truth.nonocc.type(), CV_8UC1);
  EXPECT_EQ(truth.nonocc.at<uchar>(0, 1), 128);

  const fs::path real = real_datasets_dir() / "MiddEval3-trainingQ";
  ASSERT_TRUE(real_data_present(real));
  check_real_middeval3(real);
}

TEST(DiscoverScenes, SingleSceneFolder) {
  TempDir dir;
  write_middeval3_scene(dir / "Alpha", rows_to_mat({{1, 2}}), rows_to_mask({{255, 255}}), 16);
  for (const std::string& root : {(dir / "Alpha").string(), (dir / "Alpha").string() + "/"}) {
    const std::vector<Scene> scenes = discover_scenes(root);
    ASSERT_EQ(scenes.size(), 1u) << root;
    EXPECT_EQ(scenes[0].name, "Alpha") << root;
    EXPECT_EQ(scenes[0].ndisp, 16);
  }
  write_v2_scene(dir / "venus", cv::Mat(2, 2, CV_8UC1, cv::Scalar(16)),
                 cv::Mat(2, 2, CV_8UC1, cv::Scalar(255)));
  const std::vector<Scene> v2 = discover_scenes((dir / "venus").string());
  ASSERT_EQ(v2.size(), 1u);
  EXPECT_EQ(v2[0].layout, DatasetLayout::MiddleburyV2);
  EXPECT_EQ(v2[0].ndisp, 32);
}

void check_real_v2(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  ASSERT_EQ(names_of(scenes), (std::vector<std::string>{"cones", "teddy", "tsukuba", "venus"}));
  const int ndisp[] = {64, 64, 16, 32};
  const double scale[] = {4, 4, 16, 8};
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    EXPECT_EQ(scenes[i].ndisp, ndisp[i]) << scenes[i].name;
    EXPECT_EQ(scenes[i].gt_scale, scale[i]) << scenes[i].name;
    const GroundTruth truth = load_ground_truth(scenes[i]);
    EXPECT_EQ(truth.nonocc.size(), truth.disparity.size()) << scenes[i].name;
    double max_disparity = 0;
    cv::minMaxLoc(truth.disparity, nullptr, &max_disparity, nullptr, nullptr,
                  truth.disparity < kInf);
    EXPECT_GT(max_disparity, ndisp[i] / 4) << scenes[i].name;
    EXPECT_LT(max_disparity, ndisp[i]) << scenes[i].name;
  }
  EXPECT_EQ(load_ground_truth(scenes[2]).disparity.size(), cv::Size(384, 288));  // tsukuba
}

TEST(DiscoverScenes, MiddleburyV2Tree) {
  TempDir dir;
  // tsukuba stores disparity * 16: 32 -> 2 px, 0 -> unknown.
  const cv::Mat gt8 = (cv::Mat_<uchar>(2, 3) << 32, 0, 48, 16, 16, 16);
  const cv::Mat nonocc = (cv::Mat_<uchar>(2, 3) << 255, 255, 0, 255, 255, 255);
  write_v2_scene(dir / "tsukuba", gt8, nonocc);
  write_v2_scene(dir / "venus", gt8, nonocc);
  write_v2_scene(dir / "cones", gt8, nonocc);
  write_v2_scene(dir / "mystery", gt8, nonocc);

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes),
            (std::vector<std::string>{"cones", "mystery", "tsukuba", "venus"}));
  for (const Scene& scene : scenes) EXPECT_EQ(scene.layout, DatasetLayout::MiddleburyV2);
  EXPECT_EQ(scenes[0].gt_scale, 4.0);
  EXPECT_EQ(scenes[0].ndisp, 64);
  EXPECT_EQ(scenes[1].gt_scale, 4.0);  // unknown scene: the common scale
  EXPECT_EQ(scenes[2].gt_scale, 16.0);
  EXPECT_EQ(scenes[2].ndisp, 16);
  EXPECT_EQ(scenes[3].gt_scale, 8.0);
  EXPECT_EQ(scenes[3].ndisp, 32);
  EXPECT_EQ(fs::path(scenes[2].left_path), dir / "tsukuba" / "imL.png");
  EXPECT_EQ(fs::path(scenes[2].right_path), dir / "tsukuba" / "imR.png");
  EXPECT_EQ(fs::path(scenes[2].gt_path), dir / "tsukuba" / "groundtruth.png");
  EXPECT_EQ(fs::path(scenes[2].nonocc_path), dir / "tsukuba" / "nonocc.png");

  const GroundTruth tsukuba = load_ground_truth(scenes[2]);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 0), 2.0f);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 1), kInf);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 2), 3.0f);
  EXPECT_EQ(tsukuba.nonocc.at<uchar>(0, 2), 0);
  EXPECT_EQ(load_ground_truth(scenes[3]).disparity.at<float>(0, 0), 4.0f);  // venus: 32 / 8

  const fs::path real = real_datasets_dir() / "middlebury-v2";
  ASSERT_TRUE(real_data_present(real));
  check_real_v2(real);
}

void check_real_kitti(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  ASSERT_EQ(names_of(scenes), std::vector<std::string>{"000070_10"});
  const Scene& scene = scenes[0];
  EXPECT_EQ(scene.layout, DatasetLayout::Kitti2012);
  EXPECT_EQ(fs::path(scene.left_path).parent_path().filename(), "colored_0");
  EXPECT_EQ(fs::path(scene.calib_path).filename(), "000070.txt");
  EXPECT_EQ(scene.ndisp, 256);
  const GroundTruth truth = load_ground_truth(scene);
  EXPECT_EQ(truth.disparity.size(), cv::Size(1241, 376));
  const int with_gt = cv::countNonZero(truth.disparity < kInf);
  const int nonocc = cv::countNonZero(truth.nonocc == 255);
  EXPECT_GT(nonocc, 0);
  EXPECT_LE(nonocc, with_gt);  // disp_noc is a subset of disp_occ
}

TEST(DiscoverScenes, Kitti2012Tree) {
  TempDir dir;
  const fs::path training = dir / "training";
  for (const char* folder : {"colored_0", "colored_1", "image_0", "image_1"}) {
    write_png(training / folder / "000001_10.png", random_rgb(3, 2, 5));
    write_png(training / folder / "000001_11.png", random_rgb(3, 2, 6));  // no GT frame
  }
  // disparity = value / 256, 0 = none; disp_noc has a subset of disp_occ.
  write_png(training / "disp_occ" / "000001_10.png", rows_to_u16({{256, 512, 0}, {384, 128, 64}}));
  write_png(training / "disp_noc" / "000001_10.png", rows_to_u16({{256, 0, 0}, {384, 128, 0}}));
  write_text(training / "calib" / "000001.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n");

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes), std::vector<std::string>{"000001_10"});
  const Scene& scene = scenes[0];
  EXPECT_EQ(scene.layout, DatasetLayout::Kitti2012);
  EXPECT_EQ(fs::path(scene.left_path), training / "colored_0" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.right_path), training / "colored_1" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.gt_path), training / "disp_occ" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.nonocc_path), training / "disp_noc" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.calib_path), training / "calib" / "000001.txt");
  EXPECT_EQ(scene.ndisp, 256);
  // training/ itself is accepted as the root too.
  EXPECT_EQ(names_of(discover_scenes(training.string())), names_of(scenes));

  const GroundTruth truth = load_ground_truth(scene);
  EXPECT_EQ(truth.disparity.at<float>(0, 1), 2.0f);
  EXPECT_EQ(truth.disparity.at<float>(1, 0), 1.5f);
  EXPECT_EQ(truth.disparity.at<float>(0, 2), kInf);
  const cv::Mat expected_nonocc = rows_to_mask({{255, 0, 0}, {255, 255, 0}});
  EXPECT_EQ(cv::countNonZero(truth.nonocc != expected_nonocc), 0);

  // Without colour images the gray ones are used.
  fs::remove_all(training / "colored_0");
  fs::remove_all(training / "colored_1");
  const std::vector<Scene> gray = discover_scenes(dir.path().string());
  ASSERT_EQ(gray.size(), 1u);
  EXPECT_EQ(fs::path(gray[0].left_path), training / "image_0" / "000001_10.png");

  const fs::path real = real_datasets_dir() / "KITTI2012";
  ASSERT_TRUE(real_data_present(real));
  check_real_kitti(real);
}

TEST(DiscoverScenes, Kitti2015Tree) {
  TempDir dir;
  const fs::path training = dir / "training";
  write_png(training / "image_2" / "000000_10.png", random_rgb(3, 2, 7));
  write_png(training / "image_3" / "000000_10.png", random_rgb(3, 2, 8));
  write_png(training / "disp_occ_0" / "000000_10.png", rows_to_u16({{256, 0, 0}, {0, 0, 0}}));
  write_png(training / "disp_noc_0" / "000000_10.png", rows_to_u16({{0, 0, 0}, {0, 0, 0}}));
  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_EQ(scenes[0].layout, DatasetLayout::Kitti2015);
  EXPECT_EQ(fs::path(scenes[0].gt_path), training / "disp_occ_0" / "000000_10.png");
  EXPECT_EQ(fs::path(scenes[0].nonocc_path), training / "disp_noc_0" / "000000_10.png");
  const GroundTruth truth = load_ground_truth(scenes[0]);
  EXPECT_EQ(truth.disparity.at<float>(0, 0), 1.0f);
  EXPECT_EQ(cv::countNonZero(truth.nonocc), 0);
}

TEST(DiscoverScenes, RejectsMissingRootAndUnknownLayout) {
  TempDir dir;
  const std::string missing = (dir / "no_such_folder").string();
  try {
    discover_scenes(missing);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(missing), std::string::npos) << error.what();
  }
  EXPECT_THROW(discover_scenes(dir.path().string()), InputError);  // empty folder
  write_text(dir / "something" / "file.txt", "x");
  EXPECT_THROW(discover_scenes(dir.path().string()), InputError);
  write_text(dir / "plain.txt", "x");
  EXPECT_THROW(discover_scenes((dir / "plain.txt").string()), InputError);  // not a folder
}

TEST(LoadGroundTruth, RejectsSceneWithoutGroundTruth) {
  TempDir dir;
  write_middeval3_scene(dir / "Alpha", rows_to_mat({{1, 2}}), rows_to_mask({{255, 255}}), 16);
  fs::remove(dir / "Alpha" / "disp0GT.pfm");
  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_TRUE(scenes[0].gt_path.empty());
  EXPECT_THROW(load_ground_truth(scenes[0]), InputError);
  // A mask of another size than the ground truth is a broken dataset.
  write_pfm_by_hand(dir / "Alpha" / "disp0GT.pfm", rows_to_mat({{1, 2, 3}}));
  EXPECT_THROW(load_ground_truth(discover_scenes(dir.path().string())[0]), InputError);
}

// ---- a small JSON reader, to check that the report is real JSON ------------------

struct Json {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  double number = 0;
  std::string text;
  std::vector<Json> items;           // array elements, or object values
  std::vector<std::string> keys;     // object keys, parallel to items

  const Json& operator[](const std::string& key) const {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == key) return items[i];
    }
    throw std::runtime_error("JSON object has no key " + key);
  }
  const Json& operator[](std::size_t index) const { return items.at(index); }
  double num() const {
    if (kind != Kind::Number) throw std::runtime_error("JSON value is not a number");
    return number;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : text_(text) {}

  Json document() {
    Json value = parse_value();
    skip_space();
    if (pos_ != text_.size()) fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(pos_));
  }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  char peek() {
    skip_space();
    if (pos_ >= text_.size()) fail("unexpected end");
    return text_[pos_];
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  bool consume(char c) {
    if (peek() != c) return false;
    ++pos_;
    return true;
  }
  bool literal(const std::string& word) {
    if (text_.compare(pos_, word.size(), word) != 0) return false;
    pos_ += word.size();
    return true;
  }

  Json parse_value() {
    const char c = peek();
    Json value;
    if (c == '{') return parse_object();
    if (c == '[') return parse_array();
    if (c == '"') {
      value.kind = Json::Kind::String;
      value.text = parse_string();
    } else if (literal("null")) {
      value.kind = Json::Kind::Null;
    } else if (literal("true") || literal("false")) {
      value.kind = Json::Kind::Bool;
    } else {
      value.kind = Json::Kind::Number;
      value.number = parse_number();
    }
    return value;
  }

  Json parse_object() {
    Json object;
    object.kind = Json::Kind::Object;
    expect('{');
    if (peek() != '}') {
      do {
        if (peek() != '"') fail("expected a key");
        object.keys.push_back(parse_string());
        expect(':');
        object.items.push_back(parse_value());
      } while (consume(','));
    }
    expect('}');
    return object;
  }

  Json parse_array() {
    Json array;
    array.kind = Json::Kind::Array;
    expect('[');
    if (peek() != ']') {
      do {
        array.items.push_back(parse_value());
      } while (consume(','));
    }
    expect(']');
    return array;
  }

  std::string parse_string() {
    expect('"');
    std::string out;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      const char c = text_[pos_++];
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= text_.size()) fail("unfinished escape");
      const char e = text_[pos_++];
      switch (e) {
        case '"': case '\\': case '/': out += e; break;
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'u': {
          if (pos_ + 4 > text_.size()) fail("short \\u escape");
          out += static_cast<char>(std::stoi(text_.substr(pos_, 4), nullptr, 16));  // ASCII only
          pos_ += 4;
          break;
        }
        default: fail("bad escape");
      }
    }
    expect('"');
    return out;
  }

  double parse_number() {
    const std::size_t start = pos_;
    if (pos_ < text_.size() && text_[pos_] == '-') ++pos_;
    while (pos_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[pos_])) ||
                                   text_[pos_] == '.' || text_[pos_] == 'e' ||
                                   text_[pos_] == 'E' || text_[pos_] == '+' || text_[pos_] == '-')) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a value");
    return std::stod(text_.substr(start, pos_ - start));
  }

  const std::string& text_;
  std::size_t pos_ = 0;
};

Json parse_json(const std::string& text) { return JsonReader(text).document(); }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// ---- reports ---------------------------------------------------------------------

EvalReport sample_report() {
  EvalReport report;
  report.dataset_root = "data/\"quoted\"\\path";
  report.method = "ppms";
  report.matcher = "reference path";
  report.parameters = {{"window", "35", true}, {"window-step", "3", false},
                       {"gamma-distance", "inf", false}};
  report.conventions = "test conventions";
  SceneReport a;
  a.name = "Adirondack";
  a.width = 718;
  a.height = 496;
  a.ndisp = 73;
  a.seconds = 12.5;
  a.scores.all.bad_percent = {40, 30, 20, 15, 10};
  a.scores.all.avg_error = 2.25;
  a.scores.all.density_percent = 100;
  a.scores.all.evaluated = 300000;
  a.scores.nonocc = a.scores.all;
  a.scores.nonocc.bad_percent[2] = 12.5;
  SceneReport b = a;
  b.name = "Motor\tcycle";
  b.seconds = 7.5;
  b.scores.all.bad_percent[2] = 10;
  b.scores.nonocc.bad_percent[2] = 7.5;
  report.scenes = {a, b};
  return report;
}

TEST(Report, AveragesAreUnweightedMeans) {
  const EvalReport report = sample_report();
  EXPECT_DOUBLE_EQ(report.average_all().bad_percent[2], 15.0);     // (20 + 10) / 2
  EXPECT_DOUBLE_EQ(report.average_nonocc().bad_percent[2], 10.0);  // (12.5 + 7.5) / 2
  EXPECT_DOUBLE_EQ(report.average_seconds(), 10.0);
}

TEST(Report, MarkdownHasScenesNumbersAndConventions) {
  const std::string markdown = to_markdown(sample_report());
  for (const char* text : {"Adirondack", "Motor", "average", "test conventions", "ppms",
                           "bad 0.5", "bad 2", "bad 4", "avg err", "density", "time",
                           "12.50", "20.00", "15.00", "10.00", "2.250", "718x496"}) {
    EXPECT_NE(markdown.find(text), std::string::npos) << text << "\n" << markdown;
  }
  // Where it ran, and the parameters that differ from the defaults, as options.
  EXPECT_NE(markdown.find("- Matcher: reference path"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("`--window-step 3 --gamma-distance inf`, the defaults otherwise"),
            std::string::npos)
      << markdown;
  EXPECT_EQ(markdown.find("--window 35"), std::string::npos) << markdown;
  // Both regions are tabulated.
  EXPECT_NE(markdown.find("## all"), std::string::npos);
  EXPECT_NE(markdown.find("## nonocc"), std::string::npos);
}

TEST(Report, JsonParsesAndHoldsTheNumbers) {
  const std::string text = to_json(sample_report());
  EXPECT_NE(text.find("\"bad_2\""), std::string::npos);
  const Json json = parse_json(text);
  EXPECT_EQ(json["dataset_root"].text, "data/\"quoted\"\\path");
  EXPECT_EQ(json["method"].text, "ppms");
  EXPECT_EQ(json["matcher"].text, "reference path");
  ASSERT_EQ(json["parameters"].keys.size(), 3u);  // every one, defaults included
  EXPECT_EQ(json["parameters"]["window"].text, "35");
  EXPECT_EQ(json["parameters"]["gamma-distance"].text, "inf");
  ASSERT_EQ(json["scenes"].items.size(), 2u);
  const Json& a = json["scenes"][0];
  EXPECT_EQ(a["name"].text, "Adirondack");
  EXPECT_EQ(a["width"].num(), 718);
  EXPECT_EQ(a["ndisp"].num(), 73);
  EXPECT_DOUBLE_EQ(a["seconds"].num(), 12.5);
  EXPECT_DOUBLE_EQ(a["all"]["bad_0.5"].num(), 40);
  EXPECT_DOUBLE_EQ(a["all"]["bad_2"].num(), 20);
  EXPECT_DOUBLE_EQ(a["nonocc"]["bad_2"].num(), 12.5);
  EXPECT_DOUBLE_EQ(a["all"]["avg_error"].num(), 2.25);
  EXPECT_DOUBLE_EQ(a["all"]["density"].num(), 100);
  EXPECT_EQ(a["all"]["evaluated"].num(), 300000);
  EXPECT_EQ(json["scenes"][1]["name"].text, "Motor\tcycle");  // escaped and restored
  EXPECT_DOUBLE_EQ(json["average"]["all"]["bad_2"].num(), 15);
  EXPECT_DOUBLE_EQ(json["average"]["nonocc"]["bad_2"].num(), 10);
  EXPECT_DOUBLE_EQ(json["average"]["seconds"].num(), 10);
}

TEST(Report, JsonOfEmptyReportParses) {
  EvalReport report;
  const Json json = parse_json(to_json(report));
  EXPECT_TRUE(json["scenes"].items.empty());
  EXPECT_EQ(json["average"]["all"]["evaluated"].num(), 0);
}

// ---- the eval command, end to end ------------------------------------------------

// Alpha (4x2), threshold results by hand. GT 8 everywhere except (3,1) unknown.
//   result row 0: 8 (err 0), 9 (1), 11 (3), NaN (none)
//   result row 1: 8.5 (0.5), 2 (6, occluded: mask 128), 8 (0), 8 (no GT)
// all:    7 evaluated, 6 with a result, errors 0 1 3 0.5 6 0 (sum 10.5)
//         bad>0.5: 1 3 6 + none = 4/7; >1: 3 6 + none = 3/7; >2: 3/7; >3: 6 + none = 2/7;
//         >4: 2/7; avg 10.5/6 = 1.75; density 6/7
// nonocc: 6 evaluated (without (1,1)), 5 with a result, errors 0 1 3 0.5 0 (sum 4.5)
//         bad>0.5: 1 3 + none = 3/6; >1: 3 + none = 2/6; >2: 2/6; >3: 1/6; >4: 1/6;
//         avg 4.5/5 = 0.9; density 5/6
// Beta (2x2): perfect result: 0% bad, avg 0, density 100.
struct EvalTree {
  TempDir dir;
  fs::path root = dir / "dataset";
  fs::path results = dir / "results";
  fs::path out = dir / "out";

  EvalTree() {
    write_middeval3_scene(root / "Alpha", rows_to_mat({{8, 8, 8, 8}, {8, 8, 8, kInf}}),
                          rows_to_mask({{255, 255, 255, 255}, {255, 128, 255, 0}}), 16);
    write_middeval3_scene(root / "Beta", rows_to_mat({{4, 4}, {4, 4}}),
                          rows_to_mask({{255, 255}, {255, 255}}), 16);
    // Both result layouts: <dir>/<scene>.pfm and a MiddEval3 submission folder.
    write_pfm_by_hand(results / "Alpha.pfm", rows_to_mat({{8, 9, 11, kNaN}, {8.5f, 2, 8, 8}}));
    write_pfm_by_hand(results / "Beta" / "disp0PPMS.pfm", rows_to_mat({{4, 4}, {4, 4}}));
  }

  std::vector<std::string> args(std::vector<std::string> extra = {}) const {
    std::vector<std::string> all = {root.string(), "--results", results.string(), "--out",
                                    out.string()};
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  }
};

void expect_stats(const Json& stats, const std::array<double, 5>& bad, double avg_error,
                  double density, long evaluated) {
  const char* keys[] = {"bad_0.5", "bad_1", "bad_2", "bad_3", "bad_4"};
  for (int t = 0; t < 5; ++t) EXPECT_NEAR(stats[keys[t]].num(), bad[t], 1e-6) << keys[t];
  EXPECT_NEAR(stats["avg_error"].num(), avg_error, 1e-6);
  EXPECT_NEAR(stats["density"].num(), density, 1e-6);
  EXPECT_EQ(stats["evaluated"].num(), evaluated);
}

TEST(EvalCommand, ScoresResultFilesEndToEnd) {
  const EvalTree tree;
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args()), 0);
  const std::string printed = testing::internal::GetCapturedStdout();

  const Json json = parse_json(read_file(tree.out / "report.json"));
  ASSERT_EQ(json["scenes"].items.size(), 2u);
  const Json& alpha = json["scenes"][0];
  EXPECT_EQ(alpha["name"].text, "Alpha");
  EXPECT_EQ(alpha["width"].num(), 4);
  EXPECT_EQ(alpha["height"].num(), 2);
  EXPECT_EQ(alpha["ndisp"].num(), 16);
  EXPECT_EQ(alpha["seconds"].num(), 0);
  expect_stats(alpha["all"], {400.0 / 7, 300.0 / 7, 300.0 / 7, 200.0 / 7, 200.0 / 7}, 1.75,
               600.0 / 7, 7);
  expect_stats(alpha["nonocc"], {50, 100.0 / 3, 100.0 / 3, 100.0 / 6, 100.0 / 6}, 0.9,
               500.0 / 6, 6);
  const Json& beta = json["scenes"][1];
  EXPECT_EQ(beta["name"].text, "Beta");
  expect_stats(beta["all"], {0, 0, 0, 0, 0}, 0, 100, 4);
  // Averages: plain means of Alpha and Beta.
  expect_stats(json["average"]["all"], {200.0 / 7, 150.0 / 7, 150.0 / 7, 100.0 / 7, 100.0 / 7},
               0.875, 50 + 300.0 / 7, 6);  // evaluated: (7 + 4) / 2 = 5.5, rounded to 6
  expect_stats(json["average"]["nonocc"], {25, 50.0 / 3, 50.0 / 3, 50.0 / 6, 50.0 / 6}, 0.45,
               50 + 250.0 / 6, 5);  // (6 + 4) / 2
  EXPECT_EQ(json["method"].text.rfind("files:", 0), 0u);

  // Pictures at the ground truth's size; no disparity written for read-in results.
  for (const char* file : {"Alpha_disp.png", "Alpha_error.png", "Beta_disp.png", "Beta_error.png"}) {
    const cv::Mat image = cv::imread((tree.out / file).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty()) << file;
    EXPECT_EQ(image.type(), CV_8UC3) << file;
  }
  EXPECT_EQ(cv::imread((tree.out / "Alpha_disp.png").string()).size(), cv::Size(4, 2));
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.pfm"));

  // The Markdown table is both printed and saved, with the conventions line.
  const std::string markdown = read_file(tree.out / "report.md");
  EXPECT_EQ(printed, markdown);
  for (const char* text : {"Alpha", "Beta", "57.14", "1.750", "85.71", "average",
                           "pixels without a result count as bad"}) {
    EXPECT_NE(markdown.find(text), std::string::npos) << text;
  }
}

TEST(EvalCommand, SceneSelectionAndMaxDispColor) {
  const EvalTree tree;
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args({"--scenes", "Beta", "--max-disp-color", "8"})), 0);
  testing::internal::GetCapturedStdout();
  const Json json = parse_json(read_file(tree.out / "report.json"));
  ASSERT_EQ(json["scenes"].items.size(), 1u);
  EXPECT_EQ(json["scenes"][0]["name"].text, "Beta");
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.png"));
  // Disparity 4 of a maximum of 8 is mid-scale: a different colour than 4 of 16.
  const cv::Mat half = cv::imread((tree.out / "Beta_disp.png").string());
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args({"--scenes", "Beta"})), 0);
  testing::internal::GetCapturedStdout();
  const cv::Mat quarter = cv::imread((tree.out / "Beta_disp.png").string());
  EXPECT_NE(half.at<cv::Vec3b>(0, 0), quarter.at<cv::Vec3b>(0, 0));
}

// Runs the command expecting an InputError whose message contains `needle`.
void expect_input_error(const std::vector<std::string>& args, const std::string& needle) {
  testing::internal::CaptureStdout();
  try {
    run_eval_command(args);
    testing::internal::GetCapturedStdout();
    ADD_FAILURE() << "expected InputError mentioning " << needle;
  } catch (const InputError& error) {
    testing::internal::GetCapturedStdout();
    EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
  }
}

TEST(EvalCommand, RejectsBadInput) {
  const EvalTree tree;
  expect_input_error(tree.args({"--scenes", "Alpha,Gamma"}), "Gamma");
  expect_input_error(tree.args({"--bogus"}), "--bogus");
  expect_input_error(tree.args({"--ndisp", "64"}), "--ndisp");
  expect_input_error(tree.args({"--max-disp-color", "-3"}), "--max-disp-color");
  expect_input_error({(tree.dir / "missing").string(), "--out", tree.out.string()}, "missing");
  expect_input_error({tree.results.string(), "--out", tree.out.string()}, tree.results.string());
  expect_input_error({"--out", tree.out.string()}, "DATASET_ROOT");

  // A missing result file is named in the message, and found before any scene is
  // scored (Beta comes after Alpha).
  fs::remove_all(tree.results / "Beta");
  expect_input_error(tree.args(), "Beta.pfm");
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.png"));
  // A result of another size than the ground truth.
  write_pfm_by_hand(tree.results / "Beta.pfm", rows_to_mat({{4, 4}, {4, 4}}));
  write_pfm_by_hand(tree.results / "Alpha.pfm", rows_to_mat({{1, 2}}));
  expect_input_error(tree.args(), "Alpha.pfm");
}

// What the confidence and depth columns of the report should hold for the Tiny scene of
// the test below, restated from their definitions (host/eval/confidence_depth_metrics.h)
// on the maps the command wrote. Every pixel of Tiny has ground truth (4 px). Its
// calib.txt (middlebury_calib) has f = 100 px, a baseline of 100 mm and doffs 0, so
// Z = 100 * 100 / d mm; a pixel without a result (not finite, or d <= 0: no depth) has
// an infinite depth error.
struct ExpectedConfidentDepth {
  double density_at_half = 0;  // percent of the pixels with ground truth with C >= 0.5
  double median_abs_mm_all = 0;
  double median_abs_mm_confident = 0;
};

double median_by_sorting(std::vector<double> values) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

ExpectedConfidentDepth confident_depth_by_hand(const cv::Mat& disparity, const cv::Mat& gt,
                                               const cv::Mat& confidence) {
  std::vector<double> all, confident;
  long known = 0, passed = 0;
  for (int y = 0; y < gt.rows; ++y) {
    for (int x = 0; x < gt.cols; ++x) {
      const double z_truth = 100.0 * 100.0 / gt.at<float>(y, x);
      const float d = disparity.at<float>(y, x);
      const double error = std::isfinite(d) && d > 0
                               ? std::abs(100.0 * 100.0 / d - z_truth)
                               : std::numeric_limits<double>::infinity();
      ++known;
      all.push_back(error);
      if (confidence.at<float>(y, x) >= 0.5f) {
        ++passed;
        confident.push_back(error);
      }
    }
  }
  return {100.0 * passed / known, median_by_sorting(all), median_by_sorting(confident)};
}

// The report writes a value that is not finite as null.
void expect_number_or_null(const Json& value, double expected) {
  if (std::isfinite(expected)) {
    // 6 decimals in the JSON; the depth through the calibration agrees to rounding.
    EXPECT_NEAR(value.num(), expected, 1e-5 + 1e-9 * std::abs(expected));
  } else {
    EXPECT_EQ(value.kind, Json::Kind::Null) << "expected null for " << expected;
  }
}

TEST(EvalCommand, RunsTheMatcherAndWritesItsDisparity) {
  TempDir dir;
  const fs::path root = dir / "dataset";
  const cv::Mat gt(48, 64, CV_32FC1, cv::Scalar(4));
  write_middeval3_scene(root / "Tiny", gt, cv::Mat(gt.size(), CV_8UC1, cv::Scalar(255)), 16);
  const fs::path out = dir / "out";

  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = run_eval_command(
      {root.string(), "--out", out.string(), "--threads", "1", "--preset", "fast", "--seed", "5"});
  const std::string progress = testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_NE(progress.find("[1/1] Tiny: "), std::string::npos) << progress;

  const cv::Mat disparity = read_pfm((out / "Tiny_disp.pfm").string());
  EXPECT_EQ(disparity.size(), gt.size());
  const Json json = parse_json(read_file(out / "report.json"));
  EXPECT_GT(json["scenes"][0]["seconds"].num(), 0);
  EXPECT_EQ(json["scenes"][0]["all"]["evaluated"].num(), 64 * 48);
  EXPECT_EQ(json["scenes"][0]["ndisp"].num(), 16);
  EXPECT_TRUE(fs::exists(out / "Tiny_error.png"));
  // The report records how it was made: every parameter (ndisp is the scene's), the
  // preset's among them, and the path that ran.
  StereoParams fast;
  apply_stereo_preset("fast", fast);
  const Json& parameters = json["parameters"];
  EXPECT_EQ(parameters["window-step-finest"].text, std::to_string(fast.window_step_finest));
  EXPECT_EQ(parameters["iterations-fine"].text, std::to_string(fast.iterations_fine));
  EXPECT_EQ(parameters["seed"].text, "5");
  EXPECT_EQ(parameters["threads"].text, "1");
  EXPECT_EQ(parameters["census-cap"].text, "10");
  EXPECT_THROW(parameters["ndisp"], std::runtime_error);
  EXPECT_FALSE(json["matcher"].text.empty());
  EXPECT_EQ(json["scenes"][0]["matcher"].text, json["matcher"].text);  // what ran there
  const std::string markdown = read_file(out / "report.md");
  EXPECT_NE(markdown.find("--seed 5"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("--window-step-finest " + std::to_string(fast.window_step_finest)),
            std::string::npos)
      << markdown;
  EXPECT_EQ(markdown.find("--census-cap"), std::string::npos) << markdown;  // a default

  // The output folder can be scored again as results: same numbers, no matcher time.
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int rescore = run_eval_command(
      {root.string(), "--results", out.string(), "--out", (dir / "out2").string()});
  testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  ASSERT_EQ(rescore, 0);
  const Json again = parse_json(read_file(dir / "out2" / "report.json"));
  EXPECT_EQ(again["scenes"][0]["seconds"].num(), 0);
  EXPECT_EQ(again["scenes"][0]["matcher"].text, "");  // read from files: no matcher
  EXPECT_EQ(again["matcher"].text, "");
  EXPECT_TRUE(again["parameters"].keys.empty());
  for (const char* region : {"all", "nonocc"}) {
    for (const char* key : {"bad_0.5", "bad_1", "bad_2", "avg_error", "density"}) {
      EXPECT_EQ(again["scenes"][0][region][key].num(), json["scenes"][0][region][key].num())
          << region << " " << key;
    }
  }
  // The confidence map written beside the disparity is read back with it, and the
  // scene's calib.txt gives the depth error: both reports hold the figures recomputed
  // here from the written maps, and so agree with each other.
  ASSERT_TRUE(fs::exists(out / "Tiny_conf.pfm"));
  const cv::Mat confidence = read_pfm((out / "Tiny_conf.pfm").string());
  ASSERT_EQ(confidence.size(), gt.size());
  const ExpectedConfidentDepth expected = confident_depth_by_hand(disparity, gt, confidence);
  for (const Json* report : {&json, &again}) {
    SCOPED_TRACE(report == &json ? "matcher run" : "read back from files");
    const Json& scene = (*report)["scenes"][0];
    EXPECT_NEAR(scene["confident"]["density"][1].num(), expected.density_at_half, 1e-5);
    expect_number_or_null(scene["depth_mm"]["median_abs_all"], expected.median_abs_mm_all);
    expect_number_or_null(scene["depth_mm"]["median_abs_confident"],
                          expected.median_abs_mm_confident);
  }
}

}  // namespace
}  // namespace flexsight
