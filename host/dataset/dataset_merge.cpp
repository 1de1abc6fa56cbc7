#include "host/dataset/dataset_merge.h"

#include <filesystem>
#include <map>
#include <set>

#include "host/dataset/bop_json.h"
#include "host/dataset/bop_layout.h"
#include "host/dataset/coco_reader.h"
#include "host/dataset/coco_writer.h"
#include "host/dataset/dataset_files.h"
#include "host/dataset/dataset_info.h"
#include "host/io/atomic_file.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

struct Shard {
  std::string root;
  DatasetInfo info;
  std::map<int, BopSceneRecords> scenes;
  CocoDataset coco;
};

// The scene folders of a writer's output: six-digit names holding scene_camera.json.
std::map<int, BopSceneRecords> read_scenes(const std::string& root) {
  std::map<int, BopSceneRecords> scenes;
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    const std::string dir = entry.path().string();
    if (!entry.is_directory() || name.empty() || name.size() > 9 ||
        name.find_first_not_of("0123456789") != std::string::npos ||
        !dataset_files::is_file(dir + "/" + bop_layout::kSceneCamera)) {
      continue;
    }
    scenes[std::stoi(name)] = read_bop_scene_json(dir, true).images;
  }
  return scenes;
}

// The files of one image, relative to the root, as the writer with `options` wrote them.
std::vector<std::string> image_files(int scene_id, int im_id, const BopImageRecord& record,
                                     const BopWriterOptions& options) {
  std::vector<std::string> files{bop_layout::rgb_file(scene_id, im_id, options.rgb_extension())};
  if (options.write_depth) files.push_back(bop_layout::depth_file(scene_id, im_id));
  if (options.write_masks) {
    for (std::size_t gt_id = 0; gt_id < record.parts.size(); ++gt_id) {
      for (bool visible : {false, true}) {
        files.push_back(bop_layout::mask_file(scene_id, im_id, static_cast<int>(gt_id), visible));
      }
    }
  }
  return files;
}

Shard read_shard(const std::string& root) {
  Shard shard;
  shard.root = root;
  const std::string info_path = root + "/" + bop_layout::kDatasetInfo;
  if (!dataset_files::is_file(info_path)) {
    throw InputError(info_path, "does not exist (not a dataset, or its writer did not finish)");
  }
  shard.info = read_dataset_info(info_path);
  shard.scenes = read_scenes(root);
  const std::string coco_path = root + "/" + bop_layout::kCocoFile;
  shard.coco = read_coco(coco_path);

  // The COCO file and the BOP files describe the same images.
  std::set<std::string> bop_files;
  for (const auto& [scene_id, records] : shard.scenes) {
    for (const auto& [im_id, record] : records) {
      for (const std::string& file : image_files(scene_id, im_id, record, shard.info.options.bop)) {
        if (!dataset_files::is_file(root + "/" + file)) {
          throw InputError(root + "/" + file, "does not exist, but " + root + "/" +
                                                  bop_layout::scene_dir(scene_id) + "/" +
                                                  bop_layout::kSceneGt + " lists its image");
        }
      }
      bop_files.insert(
          bop_layout::rgb_file(scene_id, im_id, shard.info.options.bop.rgb_extension()));
    }
  }
  for (const CocoImage& image : shard.coco.images) {
    if (bop_files.count(image.file_name) == 0) {
      throw InputError(coco_path,
                       "lists image " + image.file_name + ", which the shard's scene files do not");
    }
  }
  if (shard.coco.images.size() != bop_files.size() ||
      shard.info.image_count != static_cast<std::int64_t>(bop_files.size())) {
    throw InputError(info_path, "says " + std::to_string(shard.info.image_count) +
                                    " images, the COCO file lists " +
                                    std::to_string(shard.coco.images.size()) +
                                    " and the scene files " + std::to_string(bop_files.size()));
  }
  return shard;
}

void make_folder(const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec) throw InputError(path, "cannot be created (" + ec.message() + ")");
}

void copy_file(const std::string& from, const std::string& to) {
  write_atomically(to, [&](const std::string& tmp_path) {
    std::error_code ec;
    fs::copy_file(from, tmp_path, fs::copy_options::overwrite_existing, ec);
    if (ec) throw InputError(to, "cannot be copied from " + from + " (" + ec.message() + ")");
  });
}

}  // namespace

std::int64_t merge_datasets(const std::vector<std::string>& shard_roots, const std::string& out) {
  if (shard_roots.empty()) throw InputError(out, "merge of no shards");
  std::vector<Shard> shards;
  for (const std::string& root : shard_roots) shards.push_back(read_shard(root));

  // Everything is checked before anything is written.
  const DatasetWriterOptions& options = shards.front().info.options;
  CocoWriter coco(out + "/" + bop_layout::kCocoFile, options.categories);
  std::map<std::pair<int, int>, std::string> owner;  // (scene_id, im_id) -> shard root
  std::map<std::int64_t, std::string> image_owner;   // COCO image id -> shard root
  for (const Shard& shard : shards) {
    const std::string info_path = shard.root + "/" + bop_layout::kDatasetInfo;
    const std::string difference = dataset_info_difference(shards.front().info, shard.info);
    if (!difference.empty()) {
      throw InputError(info_path, "differs in \"" + difference + "\" from " + shards.front().root +
                                      "/" + bop_layout::kDatasetInfo +
                                      " (shards of one data set share their options)");
    }
    for (const auto& [scene_id, records] : shard.scenes) {
      for (const auto& [im_id, record] : records) {
        const auto [found, added] = owner.emplace(std::make_pair(scene_id, im_id), shard.root);
        if (!added) {
          throw InputError(
              shard.root + "/" + bop_layout::scene_dir(scene_id) + "/" + bop_layout::kSceneGt,
              "image " + std::to_string(im_id) + " of scene " + std::to_string(scene_id) +
                  " is also in the shard " + found->second + " (shards must hold disjoint images)");
        }
      }
    }
    for (const CocoImage& image : shard.coco.images) {
      const auto [found, added] = image_owner.emplace(image.id, shard.root);
      if (!added) {
        throw InputError(
            shard.root + "/" + bop_layout::kCocoFile,
            "image id " + std::to_string(image.id) + " is also in the shard " + found->second);
      }
    }
    // A list derived from the annotations is the union of the shards' lists.
    if (options.categories.empty()) {
      for (const CocoCategory& category : shard.coco.categories) coco.add_category(category);
    }
  }

  dataset_files::create_empty_directory(out);
  std::map<int, BopSceneRecords> scenes;
  for (const Shard& shard : shards) {
    for (const auto& [scene_id, records] : shard.scenes) {
      if (scenes.count(scene_id) == 0) {
        for (const std::string& folder : options.bop.scene_folders()) {
          make_folder(out + "/" + bop_layout::scene_dir(scene_id) + "/" + folder);
        }
      }
      for (const auto& [im_id, record] : records) {
        for (const std::string& file : image_files(scene_id, im_id, record, options.bop)) {
          copy_file(shard.root + "/" + file, out + "/" + file);
        }
        scenes[scene_id][im_id] = record;
      }
    }
    // Annotations keep their order within an image: the writer's gt_id order.
    std::map<std::int64_t, std::vector<CocoAnnotation>> annotations;
    for (const CocoAnnotation& annotation : shard.coco.annotations) {
      annotations[annotation.image_id].push_back(annotation);
    }
    for (const CocoImage& image : shard.coco.images) coco.add(image, annotations[image.id]);
  }
  for (const auto& [scene_id, records] : scenes) {
    write_bop_scene_json(out + "/" + bop_layout::scene_dir(scene_id), records);
  }
  coco.finish();
  DatasetInfo info{options, static_cast<std::int64_t>(owner.size())};
  dataset_files::write_text(out + "/" + bop_layout::kDatasetInfo, dataset_info_text(info));
  return info.image_count;
}

}  // namespace flexsight
