// The RAII layer: device selection, error sentences, program cache and build log,
// buffers, argument and work-size checks.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/runtime/cl_device.h"
#include "host/runtime/shared_context.h"
#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

const KernelSource kBroken = {"broken.cl", 0x1234,
                              "__kernel void broken(__global float* out) { out[0] = undeclared; }"};
const KernelSource kTiny = {"tiny.cl", 0x5678,
                            "__kernel void tiny(__global float* out, int width, int height) {\n"
                            "  int x = get_global_id(0), y = get_global_id(1);\n"
                            "  if (x < width && y < height) out[y * width + x] = x + 100 * y;\n"
                            "}\n"};

// "#0 pthread-skylake-avx512-AMD EPYC (Portable Computing Language, CPU, OpenCL 3.0 ...)"
// for every device, in selector index order. Empty when there is no platform.
std::vector<std::string> list_opencl_devices() {
  std::vector<std::string> lines;
  for (const DeviceInfo& device : enumerate_devices()) lines.push_back(device.description());
  return lines;
}

TEST(OpenClRuntime, APlatformWithADeviceIsInstalled) {
  std::string why;
  ASSERT_TRUE(opencl_available(&why))
      << "no OpenCL device: " << why << " (install PoCL: apt-get install pocl-opencl-icd)";
  EXPECT_FALSE(list_opencl_devices().empty());
}

TEST(OpenClRuntime, TheTestDeviceRoundsDivisionAndSqrtCorrectly) {
  EXPECT_TRUE(context().device().correctly_rounded_divide_sqrt) << context().device().description();
}

TEST(OpenClRuntime, ErrorsReadAsSentencesNamingTheCall) {
  EXPECT_EQ(describe_failure("clBuildProgram", "pthread-cpu", CL_BUILD_PROGRAM_FAILURE),
            "clBuildProgram on 'pthread-cpu': CL_BUILD_PROGRAM_FAILURE: the kernel source does "
            "not compile for this device");
  EXPECT_EQ(status_name(-9999), "CL_ERROR_-9999");
}

TEST(OpenClRuntime, UnknownDeviceSelectorListsTheDevices) {
  try {
    select_device("no such device anywhere");
    FAIL() << "expected OpenClError";
  } catch (const OpenClError& error) {
    EXPECT_NE(std::string(error.what()).find(context().device().name), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(select_device("12345678901234567890"), OpenClError);
  EXPECT_EQ(select_device("0").index, 0);
}

TEST(OpenClRuntime, ABuildFailureThrowsWithTheBuildLog) {
  try {
    context().program(kBroken);
    FAIL() << "expected OpenClError";
  } catch (const OpenClError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.status(), CL_BUILD_PROGRAM_FAILURE);
    EXPECT_NE(message.find("clBuildProgram on '"), std::string::npos) << message;
    EXPECT_NE(message.find("broken.cl"), std::string::npos) << message;
    EXPECT_NE(message.find("undeclared"), std::string::npos) << message;
  }
}

TEST(OpenClRuntime, ProgramsAreCachedBySourceHashAndOptions) {
  cl_program first = context().program(kTiny);
  EXPECT_EQ(context().program(kTiny), first);
  EXPECT_NE(context().program(kTiny, "-DUNUSED=1"), first);
  EXPECT_EQ(context().program(kTiny, "-DUNUSED=1"), context().program(kTiny, "-DUNUSED=1"));
}

TEST(OpenClRuntime, BuffersRoundTripAndRefuseOutOfRangeTransfers) {
  Buffer<float> buffer(context(), std::vector<float>{1.5f, -2.0f, 3.25f}, "round trip");
  EXPECT_EQ(buffer.read(), (std::vector<float>{1.5f, -2.0f, 3.25f}));
  buffer.fill(7.0f);
  EXPECT_EQ(buffer.read(1, 2), (std::vector<float>{7.0f, 7.0f}));
  EXPECT_THROW(buffer.read(2, 2), std::out_of_range);
  EXPECT_THROW(buffer.write(std::vector<float>(4, 0.0f)), std::out_of_range);
  Buffer<std::uint8_t> empty(context(), 0, "empty");
  EXPECT_TRUE(empty.read().empty());
}

TEST(OpenClRuntime, TheContextCountsLiveBufferBytesAndTheirPeak) {
  Context& ctx = context();
  const size_t before = ctx.buffer_bytes();
  ctx.reset_peak();
  {
    Buffer<float> a(ctx, 1000, "a");
    Buffer<std::uint8_t> b(ctx, 24, "b");
    EXPECT_EQ(ctx.buffer_bytes(), before + 4024);
    Buffer<float> moved = std::move(a);  // a move carries the count, it does not double it
    EXPECT_EQ(ctx.buffer_bytes(), before + 4024);
  }
  EXPECT_EQ(ctx.buffer_bytes(), before);
  EXPECT_EQ(ctx.peak_buffer_bytes(), before + 4024);
}

// The message of the OpenClError that creating a buffer of `bytes` called `what` throws,
// after checking its status; empty (and a failure) when the buffer was created.
std::string buffer_refusal(Context& ctx, size_t bytes, const std::string& what,
                           cl_int expected_status) {
  try {
    Buffer<std::uint8_t> buffer(ctx, bytes, what);
  } catch (const OpenClError& error) {
    EXPECT_EQ(error.status(), expected_status);
    return error.what();
  }
  ADD_FAILURE() << "buffer '" << what << "' of " << bytes << " bytes was created";
  return {};
}

// The budget is checked before clCreateBuffer: a refused buffer is not created or
// counted, and one that fits exactly is accepted.
TEST(OpenClRuntime, BuffersBeyondTheMemoryBudgetAreRefusedNamingTheBuffer) {
  Context& ctx = context();
  struct RestoreBudget {
    ~RestoreBudget() { context().set_memory_budget(0); }
  } restore;
  const size_t before = ctx.buffer_bytes();
  ctx.set_memory_budget(before + 4096);
  Buffer<float> fits(ctx, 1024, "fits");
  const std::string message =
      buffer_refusal(ctx, sizeof(float), "one float too many", CL_MEM_OBJECT_ALLOCATION_FAILURE);
  EXPECT_NE(message.find("creating buffer 'one float too many': its "), std::string::npos)
      << message;
  EXPECT_NE(message.find("device memory budget"), std::string::npos) << message;
  EXPECT_EQ(ctx.buffer_bytes(), before + 4096);
}

// The device's own limit on one buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE), read from the
// driver: one byte more is refused with a sentence, not left to the driver.
TEST(OpenClRuntime, ABufferLargerThanTheDeviceAllowsIsRefusedNamingIt) {
  Context& ctx = context();
  ASSERT_GT(ctx.device().max_buffer_bytes, 0u);
  const size_t before = ctx.buffer_bytes();
  const std::string message =
      buffer_refusal(ctx, ctx.device().max_buffer_bytes + 1, "huge", CL_INVALID_BUFFER_SIZE);
  EXPECT_NE(message.find("creating buffer 'huge': it needs "), std::string::npos) << message;
  EXPECT_NE(message.find("more than the largest buffer the device allows"), std::string::npos)
      << message;
  EXPECT_EQ(ctx.buffer_bytes(), before);
}

TEST(OpenClRuntime, KernelsCheckArgumentsAndWorkSizes) {
  Kernel kernel(context(), context().program(kTiny), "tiny");
  Buffer<float> out = guarded_output<float>(7 * 5, "tiny out");
  EXPECT_THROW(kernel.set_args(out, 7), std::logic_error);
  kernel.set_args(out, 7, 5);
  EXPECT_THROW(kernel.launch(0, 5), std::invalid_argument);
  kernel.launch(7, 5);
  std::vector<float> values = read_checked(out, 7 * 5);
  ASSERT_EQ(values.size(), 35u);
  EXPECT_EQ(values[34], 6 + 100 * 4);
  EXPECT_THROW(Kernel(context(), context().program(kTiny), "missing"), OpenClError);
}

TEST(OpenClRuntime, StagesRefuseBuffersSmallerThanTheirPixels) {
  DeviceField coarse{4, 4, Buffer<float>(context(), 64, "coarse"), Buffer<float>()};
  DeviceField fine{8, 8, Buffer<float>(context(), 255, "fine"), Buffer<float>()};
  EXPECT_THROW(stages().carry_planes_to_finer(coarse, fine), std::invalid_argument);
}

}  // namespace
}  // namespace flexsight::opencl::test
