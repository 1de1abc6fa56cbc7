#include "host/pose/template_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr char kMagic[8] = {'F', 'S', 'E', 'D', 'G', 'E', 'T', 'P'};
constexpr std::int32_t kVersion = 1;

class Writer {
 public:
  explicit Writer(std::ofstream& out) : out_(out) {}
  template <typename T>
  void put(T value) {
    out_.write(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put_vectors(const std::vector<Eigen::Vector3f>& vectors) {
    for (const auto& v : vectors) {
      put(v.x());
      put(v.y());
      put(v.z());
    }
  }

 private:
  std::ofstream& out_;
};

class Reader {
 public:
  Reader(std::ifstream& in, const std::string& path) : in_(in), path_(path) {}
  template <typename T>
  T get() {
    T value;
    in_.read(reinterpret_cast<char*>(&value), sizeof(T));
    if (!in_) throw InputError(path_, "truncated template file");
    return value;
  }
  float get_finite() {
    const float value = get<float>();
    if (!std::isfinite(value)) throw InputError(path_, "template file holds a value that is not finite");
    return value;
  }
  std::int32_t get_count(std::int32_t max, const char* what) {
    const auto value = get<std::int32_t>();
    if (value < 0 || value > max) {
      throw InputError(path_, std::string("template file: ") + what + " out of range (" +
                                  std::to_string(value) + ")");
    }
    return value;
  }
  std::vector<Eigen::Vector3f> get_vectors(int count) {
    std::vector<Eigen::Vector3f> vectors(count);
    for (auto& v : vectors) {
      const float x = get_finite(), y = get_finite(), z = get_finite();
      v = Eigen::Vector3f(x, y, z);
    }
    return vectors;
  }

 private:
  std::ifstream& in_;
  const std::string& path_;
};

}  // namespace

void write_template_set(const std::string& path, const TemplateSet& set) {
  write_atomically(path, [&](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary);
    if (!out) throw InputError(path, "cannot be written");
    Writer writer(out);
    out.write(kMagic, sizeof(kMagic));
    writer.put(kVersion);
    const TemplateParams& p = set.params;
    writer.put<std::int32_t>(p.views);
    writer.put<std::int32_t>(p.in_plane_steps);
    writer.put<std::int32_t>(p.points_per_view);
    writer.put<float>(p.crease_degrees);
    writer.put<std::int32_t>(p.render_size);
    writer.put<std::int32_t>(static_cast<std::int32_t>(set.parts.size()));
    for (const auto& part : set.parts) {
      writer.put<std::int32_t>(part.obj_id);
      writer.put<std::int32_t>(static_cast<std::int32_t>(part.name.size()));
      out.write(part.name.data(), static_cast<std::streamsize>(part.name.size()));
      writer.put<float>(part.diameter);
      writer.put<std::int32_t>(static_cast<std::int32_t>(part.views.size()));
      for (const auto& view : part.views) {
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) writer.put<double>(view.rotation(r, c));
        }
        writer.put<float>(view.surface_depth_offset);
        writer.put<std::int32_t>(static_cast<std::int32_t>(view.points.size()));
        writer.put_vectors(view.points);
        writer.put_vectors(view.tangents);
      }
    }
    out.flush();
    if (!out) throw InputError(path, "write failed");
  });
}

TemplateSet read_template_set(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be opened (make it with flexsight pose-templates)");
  char magic[sizeof(kMagic)] = {};
  in.read(magic, sizeof(magic));
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    throw InputError(path, "not a template file (flexsight pose-templates writes them)");
  }
  Reader reader(in, path);
  const auto version = reader.get<std::int32_t>();
  if (version != kVersion) {
    throw InputError(path, "template file format " + std::to_string(version) + ", this build reads " +
                               std::to_string(kVersion) + ": make the templates again");
  }
  TemplateSet set;
  TemplateParams& p = set.params;
  p.views = reader.get<std::int32_t>();
  p.in_plane_steps = reader.get<std::int32_t>();
  p.points_per_view = reader.get<std::int32_t>();
  p.crease_degrees = reader.get<float>();
  p.render_size = reader.get<std::int32_t>();
  try {
    p.check();
  } catch (const InputError& error) {
    throw InputError(path, std::string("template file: ") + error.what());
  }
  const int part_count = reader.get_count(100000, "part count");
  set.parts.resize(part_count);
  for (auto& part : set.parts) {
    part.obj_id = reader.get<std::int32_t>();
    const int name_length = reader.get_count(4096, "name length");
    part.name.resize(name_length);
    in.read(part.name.data(), name_length);
    part.diameter = reader.get_finite();
    if (!(part.diameter > 0.0f)) throw InputError(path, "template file: a part's diameter is not positive");
    const int view_count = reader.get_count(p.views, "view count");
    part.views.resize(view_count);
    for (auto& view : part.views) {
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) view.rotation(r, c) = reader.get<double>();
      }
      if (!view.rotation.allFinite() ||
          (view.rotation.transpose() * view.rotation - Eigen::Matrix3d::Identity()).norm() > 1e-6) {
        throw InputError(path, "template file: a view's rotation is not a rotation");
      }
      view.surface_depth_offset = reader.get_finite();
      const int point_count = reader.get_count(p.points_per_view, "point count");
      view.points = reader.get_vectors(point_count);
      view.tangents = reader.get_vectors(point_count);
    }
  }
  if (in.peek() != std::ifstream::traits_type::eof()) {
    throw InputError(path, "template file has bytes after its last part");
  }
  for (std::size_t i = 0; i < set.parts.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (set.parts[i].obj_id == set.parts[j].obj_id) {
        throw InputError(path, "template file holds object " + std::to_string(set.parts[i].obj_id) + " twice");
      }
    }
  }
  return set;
}

}  // namespace flexsight
