#include "host/runtime/cl_buffer.h"

namespace flexsight::opencl {

MemHandle create_buffer(Context& context, size_t bytes, const std::string& what) {
  context.check_allocation(bytes, what);
  cl_int status = CL_SUCCESS;
  // OpenCL refuses empty buffers; one byte keeps a 0-element Buffer valid as an argument.
  MemHandle mem(clCreateBuffer(context.context(), CL_MEM_READ_WRITE, bytes > 0 ? bytes : 1,
                               nullptr, &status));
  check(status, "clCreateBuffer", what + " (" + std::to_string(bytes) + " bytes)");
  return mem;
}

void write_bytes(Context& context, cl_mem buffer, size_t offset, size_t bytes, const void* data,
                 const std::string& what) {
  if (bytes == 0) return;
  check(clEnqueueWriteBuffer(context.queue(), buffer, CL_TRUE, offset, bytes, data, 0, nullptr,
                             nullptr),
        "clEnqueueWriteBuffer", what);
}

void read_bytes(Context& context, cl_mem buffer, size_t offset, size_t bytes, void* data,
                const std::string& what) {
  if (bytes == 0) return;
  check(clEnqueueReadBuffer(context.queue(), buffer, CL_TRUE, offset, bytes, data, 0, nullptr,
                            nullptr),
        "clEnqueueReadBuffer", what);
}

void fill_bytes(Context& context, cl_mem buffer, const void* pattern, size_t pattern_bytes,
                size_t bytes, const std::string& what) {
  if (bytes == 0) return;
  check(clEnqueueFillBuffer(context.queue(), buffer, pattern, pattern_bytes, 0, bytes, 0, nullptr,
                            nullptr),
        "clEnqueueFillBuffer", what);
}

}  // namespace flexsight::opencl
