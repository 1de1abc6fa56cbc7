// PLY output: exact byte layout of the binary format, round trip of the ASCII one, and
// atomic writing. (An independent reader checks real clouds: tests/ply_meshio_check.py.)
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "host/io/input_error.h"
#include "host/geometry/ply.h"
#include "tests/common/test_support.h"

using namespace flexsight;
namespace fs = std::filesystem;

namespace {

PointCloud three_points(bool with_confidence) {
  PointCloud cloud;
  cloud.unit = "mm";
  cloud.points = {{1.5f, -2.25f, 1000.0f}, {0, 0, 1}, {-3e-7f, 12345.678f, 0.5f}};
  cloud.normals = {{0, 0, -1}, {0.6f, 0, -0.8f}, {0, -1, 0}};
  cloud.colors = {{255, 0, 7}, {1, 2, 3}, {128, 64, 32}};
  if (with_confidence) cloud.confidence = {1.0f, 0.25f, 0.0f};
  cloud.pixel = {0, 1, 2};
  return cloud;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

float float_le(const std::string& bytes, size_t offset) {
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= std::uint32_t(std::uint8_t(bytes[offset + i])) << (8 * i);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

class Ply : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override {
    dir_ = testing_support::fresh_temp_dir(
        std::string("ply_") + (GetParam() ? "conf" : "noconf"));
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

}  // namespace

TEST_P(Ply, BinaryLayoutIsHeaderThenPackedLittleEndianVertices) {
  const bool with_confidence = GetParam();
  const PointCloud cloud = three_points(with_confidence);
  const std::string path = (dir_ / "cloud.ply").string();
  write_ply(path, cloud);
  const std::string bytes = slurp(path);
  const std::string header =
      std::string("ply\nformat binary_little_endian 1.0\n") +
      "comment FlexSight point cloud, unit mm, left camera frame (x right, y down, z forward)\n"
      "element vertex 3\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n" +
      (with_confidence ? "property float confidence\n" : "") + "end_header\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  const size_t stride = ply_vertex_bytes(with_confidence);
  EXPECT_EQ(stride, with_confidence ? 31u : 27u);
  ASSERT_EQ(bytes.size(), header.size() + 3 * stride);
  for (size_t i = 0; i < 3; ++i) {
    const size_t v = header.size() + i * stride;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(float_le(bytes, v + 4 * k), cloud.points[i][k]);
      EXPECT_EQ(float_le(bytes, v + 12 + 4 * k), cloud.normals[i][k]);
      EXPECT_EQ(std::uint8_t(bytes[v + 24 + k]), cloud.colors[i][k]);
    }
    if (with_confidence) {
      EXPECT_EQ(float_le(bytes, v + 27), cloud.confidence[i]);
    }
  }
}

TEST_P(Ply, AsciiRoundTripsEveryFloatExactly) {
  const bool with_confidence = GetParam();
  const PointCloud cloud = three_points(with_confidence);
  const std::string path = (dir_ / "cloud.ply").string();
  write_ply(path, cloud, PlyFormat::ascii);
  std::istringstream in(slurp(path));
  std::string line;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("format", 0) == 0) {
      EXPECT_EQ(line, "format ascii 1.0");
    }
  }
  for (size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream values(line);
    float p[3], n[3], conf;
    int c[3];
    values >> p[0] >> p[1] >> p[2] >> n[0] >> n[1] >> n[2] >> c[0] >> c[1] >> c[2];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(p[k], cloud.points[i][k]);
      EXPECT_EQ(n[k], cloud.normals[i][k]);
      EXPECT_EQ(c[k], cloud.colors[i][k]);
    }
    if (with_confidence) {
      values >> conf;
      EXPECT_EQ(conf, cloud.confidence[i]);
    }
    EXPECT_FALSE(values.fail());
    std::string rest;
    EXPECT_FALSE(values >> rest) << "extra value " << rest;
  }
  EXPECT_FALSE(std::getline(in, line)) << "extra line " << line;
}

INSTANTIATE_TEST_SUITE_P(WithAndWithoutConfidence, Ply, ::testing::Bool());

TEST(PlyWriting, AFailedWriteLeavesNoFile) {
  const fs::path dir = testing_support::fresh_temp_dir("ply_failed_write");
  const std::string path = (dir / "missing_folder" / "cloud.ply").string();
  EXPECT_THROW(write_ply(path, three_points(true)), InputError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(PlyWriting, RejectsInconsistentAttributes) {
  PointCloud cloud = three_points(true);
  cloud.normals.pop_back();
  const fs::path dir = testing_support::fresh_temp_dir("ply_inconsistent");
  EXPECT_THROW(write_ply((dir / "c.ply").string(), cloud), InputError);
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}
