#include "host/stereo/opencl_stage_set.h"

#include "fallback/stereo/image_pyramid.h"

namespace flexsight::opencl {
namespace {

const char* const kViewNames[2] = {"left", "right"};

DeviceView make_view(Context& context, int width, int height, const char* name) {
  const size_t pixels = static_cast<size_t>(width) * height;
  return {width, height, Buffer<float>(context, 4 * pixels, std::string(name) + " colour"),
          Buffer<float>(context, 2 * pixels, std::string(name) + " gradient")};
}

}  // namespace

std::vector<DeviceView> OpenClStageSet::build_pyramid(const cv::Mat& rgb8, int levels,
                                                      int view, PmsCensusShape census) {
  const char* name = kViewNames[view];
  std::vector<DeviceView> pyramid;
  pyramid.reserve(levels);
  pyramid.push_back(make_view(context(), rgb8.cols, rgb8.rows, name));
  pyramid.back().color.write(view_color(rgb8));
  compute_gradient(pyramid.back(), census);
  for (int level = 1; level < levels; ++level) {
    const DeviceView& fine = pyramid.back();
    DeviceView coarse =
        make_view(context(), (fine.width + 1) / 2, (fine.height + 1) / 2, name);
    downsample_color(fine, coarse);
    compute_gradient(coarse, census);
    pyramid.push_back(std::move(coarse));
  }
  return pyramid;
}

DeviceField OpenClStageSet::field(int width, int height, int view) {
  const size_t pixels = static_cast<size_t>(width) * height;
  const std::string name = kViewNames[view];
  return {width, height, Buffer<float>(context(), 4 * pixels, name + " planes"),
          Buffer<float>(context(), pixels, name + " cost")};
}

void OpenClStageSet::prepare_level(Level& in, const View& left, const View& right,
                                   const Array<float>& weights, const PmsCostParams& cost,
                                   int ndisp, std::uint32_t seed) {
  in.views[PMS_VIEW_LEFT] = &left;
  in.views[PMS_VIEW_RIGHT] = &right;
  in.weights = &weights;
  in.cost = cost;
  in.ndisp = ndisp;
  in.seed = seed;
  const size_t pixels = static_cast<size_t>(left.width) * left.height;
  for (int view = 0; view < 2; ++view) {
    in.match_records[view] = Buffer<float>(context(), match_record_floats(pixels),
                                           "match records");
    pack_match_samples(*in.views[view], in.match_records[view]);
    in.match[view] = &in.match_records[view];
  }
}

}  // namespace flexsight::opencl
