// BOP's pose results CSV: exact round trips (bytes and values), the header optional,
// and every malformed line an InputError naming the file and the line.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "host/dataset/bop_pose_results.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

constexpr const char* kHeader = "scene_id,im_id,obj_id,score,R,t,time\n";
// A 30 degree turn about z, printed with the digits a BOP file has.
constexpr const char* kGoodLine =
    "1,2,5,0.75,0.866025 -0.5 0 0.5 0.866025 0 0 0 1,10.5 -20 650,0.25\n";

// Records with awkward doubles: random rotations (no short decimal form), scores and
// times like 0.1 and 1/3, ids up to six digits, an unknown time (-1).
std::vector<PoseEstimateRecord> random_records(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<PoseEstimateRecord> records;
  for (int i = 0; i < count; ++i) {
    PoseEstimateRecord r;
    r.scene_id = i % 3;
    r.im_id = 100000 + i;
    r.obj_id = 1 + i % 30;
    r.score = i == 0 ? 0.1 : 1.0 / (i + 2);
    r.R = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized().toRotationMatrix();
    r.t = Eigen::Vector3d(unit(rng) * 100, unit(rng) * 100, 500 + unit(rng) * 300);
    r.time_s = i % 2 ? -1.0 : 0.01 * i;
    records.push_back(r);
  }
  return records;
}

void expect_same_records(const std::vector<PoseEstimateRecord>& a, const std::vector<PoseEstimateRecord>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].scene_id, b[i].scene_id) << i;
    EXPECT_EQ(a[i].im_id, b[i].im_id) << i;
    EXPECT_EQ(a[i].obj_id, b[i].obj_id) << i;
    EXPECT_EQ(a[i].score, b[i].score) << i;  // exact: shortest round-trip printing
    EXPECT_EQ(a[i].R, b[i].R) << i;
    EXPECT_EQ(a[i].t, b[i].t) << i;
    EXPECT_EQ(a[i].time_s, b[i].time_s) << i;
  }
}

}  // namespace

TEST(BopPoseResults, RoundTripGivesTheSameValuesAndBytes) {
  ScratchDir dir;
  const auto records = random_records(25, 7);
  write_bop_pose_results(dir / "a.csv", records);
  const std::string bytes = file_bytes(dir / "a.csv");
  EXPECT_EQ(bytes.rfind(kHeader, 0), 0u) << bytes.substr(0, 80);
  const auto back = read_bop_pose_results(dir / "a.csv");
  expect_same_records(records, back);
  write_bop_pose_results(dir / "b.csv", back);
  EXPECT_EQ(file_bytes(dir / "b.csv"), bytes);
}

TEST(BopPoseResults, WritesTheLinesBopWrites) {
  ScratchDir dir;
  PoseEstimateRecord r;
  r.scene_id = 1, r.im_id = 2, r.obj_id = 5, r.score = 0.5;
  r.t = Eigen::Vector3d(1.5, -2, 600);
  write_bop_pose_results(dir / "r.csv", {r});
  EXPECT_EQ(file_bytes(dir / "r.csv"), std::string(kHeader) + "1,2,5,0.5,1 0 0 0 1 0 0 0 1,1.5 -2 600,-1\n");
  write_bop_pose_results(dir / "empty.csv", {});
  EXPECT_EQ(file_bytes(dir / "empty.csv"), kHeader);
  EXPECT_TRUE(read_bop_pose_results(dir / "empty.csv").empty());
}

TEST(BopPoseResults, ReadsWithOrWithoutHeaderAndWithCrLf) {
  ScratchDir dir;
  write_file(dir / "with.csv", std::string(kHeader) + kGoodLine);
  write_file(dir / "without.csv", kGoodLine);
  std::string crlf = std::string(kHeader) + kGoodLine;
  crlf.insert(crlf.find('\n'), "\r");
  crlf.back() = '\r';
  crlf += "\n\n";  // and a blank last line
  write_file(dir / "crlf.csv", crlf);
  for (const char* name : {"with.csv", "without.csv", "crlf.csv"}) {
    const auto records = read_bop_pose_results(dir / name);
    ASSERT_EQ(records.size(), 1u) << name;
    const PoseEstimateRecord& r = records[0];
    EXPECT_EQ(r.scene_id, 1);
    EXPECT_EQ(r.im_id, 2);
    EXPECT_EQ(r.obj_id, 5);
    EXPECT_EQ(r.score, 0.75);
    EXPECT_EQ(r.R(0, 1), -0.5);
    EXPECT_EQ(r.R(1, 0), 0.5);
    EXPECT_EQ(r.t, Eigen::Vector3d(10.5, -20, 650));
    EXPECT_EQ(r.time_s, 0.25);
  }
}

// Each bad line, after a good one, names the file and line 3 and the problem.
TEST(BopPoseResults, BadLinesNameFileLineAndProblem) {
  ScratchDir dir;
  const struct {
    const char* line;
    const char* problem;
  } cases[] = {
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 600", "expected 7 comma-separated columns"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 600,-1,extra",
       "expected 7 comma-separated columns (scene_id,im_id,obj_id,score,R,t,time), found 8"},
      {"x,2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 600,-1", "scene_id: expected a whole number"},
      {"1,-2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 600,-1", "im_id: expected a whole number >= 0"},
      {"1,2,5.5,0.75,1 0 0 0 1 0 0 0 1,0 0 600,-1", "obj_id: expected a whole number"},
      {"1,2,5,high,1 0 0 0 1 0 0 0 1,0 0 600,-1", "score: expected a number, found 'high'"},
      {"1,2,5,nan,1 0 0 0 1 0 0 0 1,0 0 600,-1", "score: nan is not a finite number"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0,0 0 600,-1", "R: expected 9 space-separated numbers, found 8"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 600,-1", "t: expected 3 space-separated numbers, found 2"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 inf 600,-1", "t[1]: inf is not a finite number"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 600,soon", "time: expected a number"},
      {"1,2,5,0.75,2 0 0 0 1 0 0 0 1,0 0 600,-1", "R is not a rotation"},
      {"1,2,5,0.75,1 0 0 0 1.01 0 0 0 1,0 0 600,-1", "R is not a rotation"},
      {"1,2,5,0.75,-1 0 0 0 1 0 0 0 1,0 0 600,-1", "R is a reflection"},
      {"1,2,5,0.75,1.0004 0 0 0 1.0004 0 0 0 1.0004,0 0 600,-1",
       "R is not a rotation: det 1.0012"},
      {"1,2,5,0.75,1 0 0 0 1 0 0 0 1,0 0 1e300,-1",
       "t [0, 0, 1e+300] is farther than 100000 mm from the camera"},
  };
  for (const auto& c : cases) {
    write_file(dir / "bad.csv", std::string(kHeader) + kGoodLine + c.line + "\n");
    EXPECT_TRUE(throws_input_error([&] { read_bop_pose_results(dir / "bad.csv"); }, "bad.csv",
                                   std::string("line 3: ") + c.problem))
        << c.line;
  }
}

TEST(BopPoseResults, ToleratesRotationsPrintedWithFewDigits) {
  ScratchDir dir;
  // kGoodLine's R is off by 4e-7 from a rotation; 1e-4 off is still accepted.
  write_file(dir / "r.csv", "1,2,5,0.75,1.0001 0 0 0 1 0 0 0 1,0 0 600,-1\n");
  EXPECT_EQ(read_bop_pose_results(dir / "r.csv").size(), 1u);
}

TEST(BopPoseResults, MissingFileAndForeignHeaderAreNamed) {
  ScratchDir dir;
  EXPECT_TRUE(throws_input_error([&] { read_bop_pose_results(dir / "none.csv"); }, "none.csv",
                                 "does not exist"));
  write_file(dir / "h.csv", std::string("scene_id,image_id,obj_id,score,R,t,time\n") + kGoodLine);
  EXPECT_TRUE(throws_input_error([&] { read_bop_pose_results(dir / "h.csv"); }, "h.csv",
                                 "line 1: a header, but not BOP's"));
}

TEST(BopPoseResults, RefusesToWriteNumbersItCouldNotRead) {
  ScratchDir dir;
  PoseEstimateRecord r;
  r.t.z() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throws_input_error([&] { write_bop_pose_results(dir / "n.csv", {r}); }, "n.csv",
                                 "record 0 has a number that is not finite"));
  EXPECT_FALSE(fs::exists(dir / "n.csv"));
}

TEST(BopPoseResults, EmptyFileIsRefusedAndAFailedEstimateIsNot) {
  ScratchDir dir;
  write_file(dir / "empty.csv", "");
  EXPECT_TRUE(throws_input_error([&] { read_bop_pose_results(dir / "empty.csv"); }, "empty.csv",
                                 "is empty (expected BOP's header"));
  // A header alone: a run that found nothing.
  write_file(dir / "header.csv", kHeader);
  EXPECT_TRUE(read_bop_pose_results(dir / "header.csv").empty());
  // An estimate at the camera's centre is a wrong pose, scored as a miss, not a bad file.
  write_file(dir / "origin.csv", std::string(kHeader) + "1,2,5,0,1 0 0 0 1 0 0 0 1,0 0 0,-1\n");
  EXPECT_EQ(read_bop_pose_results(dir / "origin.csv").size(), 1u);
}
