// Tests of the projector's optional lines of calib.txt (host/io/calibration.h): they
// round-trip through projector_calib_text, are absent from older files, and a partial
// entry, a pattern that does not fit, or a missing or unreadable pattern file is an
// InputError naming the file and the key.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

namespace {

const char kPairCalib[] =
    "cam0=[400 0 150; 0 400 119.5; 0 0 1]\n"
    "cam1=[400 0 170; 0 400 119.5; 0 0 1]\n"
    "doffs=20\nbaseline=500.0\nwidth=320\nheight=240\nndisp=64\n";

flexsight::ProjectorCalib example_projector() {
  flexsight::ProjectorCalib p;
  p.K = {400, 0, 63.5, 0, 400, 47.5, 0, 0, 1};
  p.width = 128;
  p.height = 96;
  p.t = {-250, 0, 0};
  p.pattern = "pattern.png";
  return p;
}

void write_pattern(const std::string& path, int width, int height) {
  cv::Mat pattern(height, width, CV_8UC1, cv::Scalar(0));
  cv::randu(pattern, 0, 255);
  flexsight::write_image(path, pattern);
}

// The example's calib.txt with `key`'s line replaced by `line` ("" drops it).
std::string calib_with(const std::string& key, const std::string& line) {
  std::istringstream in(std::string(kPairCalib) + flexsight::projector_calib_text(example_projector()));
  std::string out;
  for (std::string current; std::getline(in, current);) {
    out += current.rfind(key + "=", 0) == 0 ? (line.empty() ? "" : line + "\n") : current + "\n";
  }
  return out;
}

}  // namespace

TEST(ProjectorCalibration, RoundTripsAndResolvesThePatternBesideTheFile) {
  ScratchDir dir;
  write_pattern(dir.file("pattern.png"), 128, 96);
  write_bytes(dir.file("calib.txt"), calib_with("none", ""));
  const flexsight::MiddleburyCalib calib = flexsight::read_middlebury_calib(dir.file("calib.txt"));
  ASSERT_TRUE(calib.projector.has_value());
  const flexsight::ProjectorCalib expected = example_projector();
  EXPECT_EQ(calib.projector->K, expected.K);
  EXPECT_EQ(calib.projector->R, expected.R);
  EXPECT_EQ(calib.projector->t, expected.t);
  EXPECT_EQ(calib.projector->width, 128);
  EXPECT_EQ(calib.projector->height, 96);
  EXPECT_EQ(calib.projector->pattern, "pattern.png");
  EXPECT_EQ(fs::path(calib.projector->pattern_path), fs::path(dir.file("pattern.png")));
  EXPECT_EQ(flexsight::projector_calib_text(*calib.projector), flexsight::projector_calib_text(expected));
}

TEST(ProjectorCalibration, OlderFilesHaveNoProjector) {
  ScratchDir dir;
  write_bytes(dir.file("calib.txt"), kPairCalib);
  EXPECT_FALSE(flexsight::read_middlebury_calib(dir.file("calib.txt")).projector.has_value());
}

TEST(ProjectorCalibration, BadEntriesNameTheFileAndTheProblem) {
  ScratchDir dir;
  write_pattern(dir.file("pattern.png"), 128, 96);
  write_pattern(dir.file("small.png"), 64, 96);
  write_bytes(dir.file("broken.png"), "not a png at all");
  const std::string calib = dir.file("calib.txt");
  const auto read = [&] { flexsight::read_middlebury_calib(calib); };
  const struct {
    std::string key, line, file, message;
  } cases[] = {
      {"projt", "", "calib.txt", "missing key 'projt'"},
      {"projpattern", "", "calib.txt", "missing key 'projpattern'"},
      {"projpattern", "projpattern=absent.png", "absent.png", ""},
      {"projpattern", "projpattern=broken.png", "broken.png", ""},
      {"projpattern", "projpattern=small.png", "small.png", "gives the projector 128x96"},
      {"proj", "proj=[400 0 300; 0 400 47.5; 0 0 1]", "calib.txt", "outside the 128x96 pattern"},
      {"proj", "proj=[0 0 63.5; 0 400 47.5; 0 0 1]", "calib.txt", "positive focal"},
      {"projR", "projR=[1 0 0; 0 2 0; 0 0 1]", "calib.txt", "not a rotation"},
      {"projt", "projt=[1 2]", "calib.txt", "is not a vector"},
      {"projwidth", "projwidth=-3", "calib.txt", "must be positive"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key + " -> " + c.line);
    write_bytes(calib, calib_with(c.key, c.line));
    EXPECT_TRUE(throws_input_error(read, c.file, c.message));
  }
}
