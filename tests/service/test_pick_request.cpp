// A POST /pick body read into its files and pick's option tokens (host/service/
// pick_request.h): keys become pick's option names, values their tokens, and every bad
// body a 400 whose message names the key; a request's options replace the same options
// the service was started with.
#include "host/service/pick_request.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace flexsight {
namespace {

using Tokens = std::vector<std::string>;

// The status and message of the RequestError `body` raises (0 and "" when it raises none).
std::pair<int, std::string> refusal(const std::string& body) {
  try {
    parse_pick_request(body);
  } catch (const RequestError& e) {
    return {e.status(), e.what()};
  }
  return {0, ""};
}

const std::string kPair = R"("left": "a/im0.png", "right": "a/im1.png", "calib": "a/calib.txt")";

TEST(PickRequest, FilesAndOptionsAreRead) {
  const PickRequest r = parse_pick_request("{" + kPair + R"(, "passive_left": "a/p.png", "score": 0.1,
      "classes_per_box": 3, "tile": "auto", "quiet": true, "depth_proposals": "on", "half_turns": false,
      "stereo_downscale": 2.0, "parts": [5, 12]})");
  EXPECT_EQ(r.files.left, "a/im0.png");
  EXPECT_EQ(r.files.right, "a/im1.png");
  EXPECT_EQ(r.files.calib, "a/calib.txt");
  EXPECT_EQ(r.files.passive_left, "a/p.png");
  EXPECT_TRUE(r.left_bytes.empty());
  // nlohmann's objects iterate in key order.
  EXPECT_EQ(r.option_tokens, (Tokens{"--classes-per-box", "3", "--depth-proposals", "on", "--parts", "5,12", "--quiet",
                                     "--score", "0.1", "--stereo-downscale", "2", "--tile", "auto"}));
}

TEST(PickRequest, EveryBadBodyIsA400NamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"not json", "body: not JSON"},
      {"[1, 2]", "body: expected a JSON object, got array"},
      {R"({"right": "b", "calib": "c"})", "key left: missing"},
      {R"({"left": "a", "calib": "c"})", "key right: missing"},
      {R"({"left": "a", "right": "b"})", "key calib: missing"},
      {R"({"left": 3, "right": "b", "calib": "c"})", "key left: expected a non-empty string"},
      {R"({"left": "", "right": "b", "calib": "c"})", "key left: expected a non-empty string"},
      {R"({"left": "a", "left_png": "AAAA", "right": "b", "calib": "c"})", "key left: give the path or left_png, not both"},
      {R"({"left_png": "not base64!", "right": "b", "calib": "c"})", "key left_png: not base64"},
      {"{" + kPair + R"(, "templates": "t.tpl"})", "key templates: loaded once when flexsight serve starts"},
      {"{" + kPair + R"(, "cad": "cad"})", "key cad: loaded once"},
      {"{" + kPair + R"(, "model": "m.onnx"})", "key model: loaded once"},
      {"{" + kPair + R"(, "namer": "n.onnx"})", "key namer: loaded once"},
      {"{" + kPair + R"(, "o": "x.json"})", "key o: the service answers the PICKS.json"},
      {"{" + kPair + R"(, "Score": 1})", "key Score: not an option of flexsight pick"},
      {"{" + kPair + R"(, "--score": 1})", "key --score: not an option"},
      {"{" + kPair + R"(, "score": null})", "key score: expected a string, a number, true/false or a list, got null"},
      {"{" + kPair + R"(, "score": {"a": 1}})", "key score: expected"},
  };
  for (const auto& [body, message] : cases) {
    SCOPED_TRACE(body);
    const auto [status, text] = refusal(body);
    EXPECT_EQ(status, 400);
    EXPECT_EQ(text.rfind(message, 0), 0u) << text;
    EXPECT_EQ(text.find('\n'), std::string::npos) << "one line";
  }
}

TEST(PickRequest, ImageBytesAreDecodedFromBase64) {
  // "PNG\x89" and a byte of padding's worth: RFC 4648's alphabet, padding and line breaks.
  const PickRequest r = parse_pick_request(R"({"left_png": "UE5H\niQ==", "right_png": "/+8=", "calib": "c"})");
  EXPECT_EQ(r.left_bytes, std::string("PNG\x89"));
  EXPECT_EQ(r.right_bytes, std::string("\xff\xef"));
  EXPECT_TRUE(r.files.left.empty());
  EXPECT_EQ(decode_base64("aGVsbG8=", "f"), "hello");
  EXPECT_EQ(decode_base64("aGVsbG8h", "f"), "hello!");
  EXPECT_THROW(decode_base64("aGVs=bG8", "f"), RequestError) << "data after the padding";
  EXPECT_THROW(decode_base64("", "f"), RequestError) << "no bytes";
}

TEST(PickRequest, TheRequestsOptionsReplaceTheStartOnes) {
  const Tokens base = {"--templates", "t.tpl", "--score", "0.2", "--quiet", "--tile", "off", "--threads", "2"};
  EXPECT_EQ(merge_pick_arguments(base, {"--tile", "auto", "--classes-per-box", "1"}),
            (Tokens{"--templates", "t.tpl", "--score", "0.2", "--quiet", "--threads", "2", "--tile", "auto",
                    "--classes-per-box", "1"}));
  EXPECT_EQ(merge_pick_arguments(base, {}), base);
  EXPECT_EQ(merge_pick_arguments(base, {"--quiet"}),
            (Tokens{"--templates", "t.tpl", "--score", "0.2", "--tile", "off", "--threads", "2", "--quiet"}));
}

}  // namespace
}  // namespace flexsight
