#pragma once
// The tiny SSD fixture (tests/data/detect/tiny_ssd/, made by
// scripts/detect/make_fixture_model.py; its README says what it holds) as the detector
// tests and the detect command's tests use it: its paths, the picture's geometry, and a
// writable copy of the model folder to break one file of.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace flexsight::testing_support {

inline std::string tiny_ssd_dir() {
  return std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tiny_ssd";
}
inline std::string tiny_ssd_model() { return tiny_ssd_dir() + "/model.onnx"; }
inline std::string tiny_ssd_image() { return tiny_ssd_dir() + "/image.png"; }

// The picture's boxes (make_fixture_model.py RED_BOX, BLUE_BOX): x0, y0, x1, y1
// (exclusive) in pixels of the 317x241 image, and the category ids of labels.txt.
constexpr int kTinyRedBox[4] = {40, 60, 140, 150};
constexpr int kTinyBlueBox[4] = {200, 30, 290, 100};
constexpr int kTinyRedCategory = 5;
constexpr int kTinyGreenCategory = 7;
constexpr int kTinyBlueCategory = 9;
constexpr int kTinyClasses = 3;

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A copy of the model folder (model.onnx, anchors.csv, labels.txt, model.json) in
// `folder`; returns the copy's model.onnx.
inline std::string copy_tiny_ssd(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  for (const char* name : {"model.onnx", "anchors.csv", "labels.txt", "model.json"}) {
    fs::copy_file(fs::path(tiny_ssd_dir()) / name, folder / name,
                  fs::copy_options::overwrite_existing);
  }
  return (folder / "model.onnx").string();
}

// `text` without its last non-empty line (an anchors file one anchor short, ...).
inline std::string without_last_line(const std::string& text) {
  std::string cut = text;
  while (!cut.empty() && cut.back() == '\n') cut.pop_back();
  return cut.substr(0, cut.rfind('\n') + 1);
}

// A raw little-endian float32 file (expected_*.f32).
inline std::vector<float> read_floats(const std::string& path) {
  const std::string bytes = read_text(path);
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
  return values;
}

}  // namespace flexsight::testing_support
