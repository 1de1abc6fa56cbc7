// The part and background libraries: which files they take, in which order, with which
// object ids, and the InputErrors for folders and files they cannot use.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "host/io/input_error.h"
#include "host/synth/background_library.h"
#include "host/synth/part_library.h"
#include "tests/synth/synth_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

// Runs `body`, expects an InputError whose message starts with `subject`.
template <class Body>
void expect_input_error(const std::string& subject, const Body& body) {
  try {
    body();
    ADD_FAILURE() << "no InputError for " << subject;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(subject + ": ", 0), 0u) << e.what();
  }
}

}  // namespace

TEST(SynthPartLibrary, ObjectIdIsTheLastNumberOfTheName) {
  EXPECT_EQ(object_id_from_name("obj_05"), 5);
  EXPECT_EQ(object_id_from_name("obj_000005"), 5);
  EXPECT_EQ(object_id_from_name("part12_v3"), 3);
  EXPECT_EQ(object_id_from_name("obj_000"), 0);
  EXPECT_EQ(object_id_from_name("bracket"), -1);
  EXPECT_EQ(object_id_from_name("obj_12345678901"), -1);
}

// The real folder: 23 STL files, ids from their names, sorted.
TEST(SynthPartLibrary, TlessFolderGivesTheTlessIds) {
  ASSERT_TRUE(folder_present(tless_cad_folder()));
  const PartLibrary& library = tless_parts();
  const std::vector<int> expected = {2,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13, 14,
                                     15, 16, 19, 20, 21, 22, 23, 24, 25, 26, 30};
  ASSERT_EQ(library.size(), int(expected.size()));
  for (int i = 0; i < library.size(); ++i) {
    EXPECT_EQ(library.part(i).obj_id, expected[i]);
    EXPECT_EQ(library.index_of(expected[i]), i);
    EXPECT_GT(library.part(i).mesh->triangles.size(), 1000u);
  }
  EXPECT_EQ(library.part(0).name, "obj_02.stl");
  EXPECT_EQ(library.index_of(1), -1);
}

TEST(SynthPartLibrary, EveryMeshFormatIsReadAndOtherFilesAreIgnored) {
  TempFolder folder;
  write_text(folder / "obj_000007.OBJ", tetrahedron_obj());
  write_text(folder / "obj_3.obj", tetrahedron_obj());
  write_text(folder / "readme.txt", "not a mesh");
  write_text(folder / "obj_4.png", "not a mesh either");
  const PartLibrary library = PartLibrary::load_folder(folder.str());
  ASSERT_EQ(library.size(), 2);
  // Sorted by name: "obj_000007.OBJ" < "obj_3.obj".
  EXPECT_EQ(library.part(0).obj_id, 7);
  EXPECT_EQ(library.part(1).obj_id, 3);
  EXPECT_EQ(library.part(1).mesh->triangles.size(), 4u);
}

TEST(SynthPartLibrary, NamesWithoutNumbersAreNumberedInOrder) {
  TempFolder folder;
  write_text(folder / "hinge.obj", tetrahedron_obj());
  write_text(folder / "bracket.obj", tetrahedron_obj());
  write_text(folder / "obj_9.obj", tetrahedron_obj());
  const PartLibrary library = PartLibrary::load_folder(folder.str());
  ASSERT_EQ(library.size(), 3);
  EXPECT_EQ(library.part(0).name, "bracket.obj");
  EXPECT_EQ(library.part(0).obj_id, 1);
  EXPECT_EQ(library.part(1).name, "hinge.obj");
  EXPECT_EQ(library.part(1).obj_id, 2);
  EXPECT_EQ(library.part(2).obj_id, 3);  // its 9 is ignored: not every name has a number
}

TEST(SynthPartLibrary, FoldersItCannotUseAreInputErrorsNamingThem) {
  TempFolder folder;
  expect_input_error(folder / "missing", [&] { PartLibrary::load_folder(folder / "missing"); });
  expect_input_error(folder.str(), [&] { PartLibrary::load_folder(folder.str()); });  // empty
  write_text(folder / "notes.txt", "no mesh here");
  expect_input_error(folder.str(), [&] { PartLibrary::load_folder(folder.str()); });
  expect_input_error(folder / "notes.txt",
                     [&] { PartLibrary::load_folder(folder / "notes.txt"); });  // a file
  write_text(folder / "obj_5.obj", tetrahedron_obj());
  write_text(folder / "obj_05.obj", tetrahedron_obj());
  expect_input_error(folder.str(), [&] { PartLibrary::load_folder(folder.str()); });
}

TEST(SynthPartLibrary, AMeshWithoutTrianglesIsAnInputErrorNamingTheFile) {
  TempFolder folder;
  write_text(folder / "obj_1.obj", tetrahedron_obj());
  // Two facets whose corners coincide: nothing is left to render.
  write_text(folder / "obj_2.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\nf 3 2 1\n");
  expect_input_error(folder / "obj_2.obj", [&] { PartLibrary::load_folder(folder.str()); });
}

TEST(SynthPartLibrary, InMemoryPartsNeedTrianglesAndDistinctIds) {
  const auto mesh = std::make_shared<const Mesh>(
      make_mesh("tetra", {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}},
                {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
  EXPECT_THROW(PartLibrary({}), std::invalid_argument);
  EXPECT_THROW(PartLibrary({{1, "a", mesh}, {1, "b", mesh}}), std::invalid_argument);
  EXPECT_THROW(PartLibrary({{1, "a", nullptr}}), std::invalid_argument);
  const PartLibrary library({{4, "a", mesh}, {2, "b", mesh}});
  EXPECT_EQ(library.index_of(2), 1);
}

TEST(SynthBackgroundLibrary, TakesJpgAndPngSortedAndDecodesToRgb) {
  TempFolder folder;
  // A pure blue picture (BGR on disk), a red one, and a file that is not an image.
  cv::imwrite(folder / "b.png", cv::Mat(4, 6, CV_8UC3, cv::Scalar(255, 0, 0)));
  cv::imwrite(folder / "a.JPG", cv::Mat(8, 8, CV_8UC3, cv::Scalar(0, 0, 255)));
  write_text(folder / "c.txt", "text");
  const BackgroundLibrary library(folder.str());
  ASSERT_EQ(library.size(), 2);
  EXPECT_EQ(library.path(0), folder / "a.JPG");
  const cv::Mat blue = library.load(1);
  ASSERT_EQ(blue.type(), CV_8UC3);
  EXPECT_EQ(blue.size(), cv::Size(6, 4));
  EXPECT_EQ(blue.at<cv::Vec3b>(2, 3), cv::Vec3b(0, 0, 255));  // RGB order
}

TEST(SynthBackgroundLibrary, RealFolderHasItsThreeHundredPhotographs) {
  ASSERT_TRUE(folder_present(backgrounds_folder()));
  const BackgroundLibrary& library = real_backgrounds();
  EXPECT_EQ(library.size(), 300);
  const cv::Mat first = library.load(0);
  EXPECT_EQ(first.type(), CV_8UC3);
  EXPECT_EQ(std::max(first.cols, first.rows), 481);
}

TEST(SynthBackgroundLibrary, FoldersAndFilesItCannotUseAreInputErrors) {
  TempFolder folder;
  expect_input_error(folder / "missing", [&] { BackgroundLibrary(folder / "missing"); });
  expect_input_error(folder.str(), [&] { BackgroundLibrary(folder.str()); });  // empty
  write_text(folder / "broken.jpg", "these bytes are no JPEG");
  const BackgroundLibrary library(folder.str());  // listing opens nothing
  expect_input_error(folder / "broken.jpg", [&] { library.load(0); });
}
