#include "host/runtime/cl_api.h"

namespace flexsight::opencl {
namespace {

// CL_PLATFORM_NOT_FOUND_KHR of cl_ext.h: what the ICD loader answers when no platform
// is installed, the most common failure on a machine without drivers.
constexpr cl_int kPlatformNotFoundKhr = -1001;

struct StatusText {
  cl_int status;
  const char* name;
  const char* meaning;
};

// The codes an OpenCL 1.2 host program can meet, with what they usually mean here.
constexpr StatusText kStatusTexts[] = {
    {CL_DEVICE_NOT_FOUND, "CL_DEVICE_NOT_FOUND", "no OpenCL device of the requested type"},
    {CL_DEVICE_NOT_AVAILABLE, "CL_DEVICE_NOT_AVAILABLE", "the device is busy or switched off"},
    {CL_COMPILER_NOT_AVAILABLE, "CL_COMPILER_NOT_AVAILABLE",
     "the driver has no OpenCL C compiler"},
    {CL_MEM_OBJECT_ALLOCATION_FAILURE, "CL_MEM_OBJECT_ALLOCATION_FAILURE",
     "the device could not allocate a buffer"},
    {CL_OUT_OF_RESOURCES, "CL_OUT_OF_RESOURCES",
     "the device ran out of resources (or a kernel accessed memory out of bounds)"},
    {CL_OUT_OF_HOST_MEMORY, "CL_OUT_OF_HOST_MEMORY", "the host ran out of memory"},
    {CL_PROFILING_INFO_NOT_AVAILABLE, "CL_PROFILING_INFO_NOT_AVAILABLE",
     "the event has no timing (queue without profiling, or command not finished)"},
    {CL_MEM_COPY_OVERLAP, "CL_MEM_COPY_OVERLAP", "source and destination overlap"},
    {CL_BUILD_PROGRAM_FAILURE, "CL_BUILD_PROGRAM_FAILURE",
     "the kernel source does not compile for this device"},
    {CL_MAP_FAILURE, "CL_MAP_FAILURE", "the buffer could not be mapped"},
    {CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST, "CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST",
     "a command this one waited for failed"},
    {CL_INVALID_VALUE, "CL_INVALID_VALUE", "an argument value is not allowed"},
    {CL_INVALID_DEVICE_TYPE, "CL_INVALID_DEVICE_TYPE", "the device type is not valid"},
    {CL_INVALID_PLATFORM, "CL_INVALID_PLATFORM", "the platform is not valid"},
    {CL_INVALID_DEVICE, "CL_INVALID_DEVICE", "the device is not valid"},
    {CL_INVALID_CONTEXT, "CL_INVALID_CONTEXT", "the context is not valid"},
    {CL_INVALID_QUEUE_PROPERTIES, "CL_INVALID_QUEUE_PROPERTIES",
     "the device does not support these queue properties"},
    {CL_INVALID_COMMAND_QUEUE, "CL_INVALID_COMMAND_QUEUE", "the command queue is not valid"},
    {CL_INVALID_MEM_OBJECT, "CL_INVALID_MEM_OBJECT", "a buffer argument is not valid"},
    {CL_INVALID_BINARY, "CL_INVALID_BINARY", "the program binary is not valid"},
    {CL_INVALID_BUILD_OPTIONS, "CL_INVALID_BUILD_OPTIONS",
     "the compiler rejected the build options"},
    {CL_INVALID_PROGRAM, "CL_INVALID_PROGRAM", "the program is not valid"},
    {CL_INVALID_PROGRAM_EXECUTABLE, "CL_INVALID_PROGRAM_EXECUTABLE",
     "the program was not built for this device"},
    {CL_INVALID_KERNEL_NAME, "CL_INVALID_KERNEL_NAME", "the program has no kernel of that name"},
    {CL_INVALID_KERNEL_DEFINITION, "CL_INVALID_KERNEL_DEFINITION",
     "the kernel differs between the devices of the program"},
    {CL_INVALID_KERNEL, "CL_INVALID_KERNEL", "the kernel is not valid"},
    {CL_INVALID_ARG_INDEX, "CL_INVALID_ARG_INDEX", "the kernel has fewer arguments"},
    {CL_INVALID_ARG_VALUE, "CL_INVALID_ARG_VALUE", "an argument value is not valid"},
    {CL_INVALID_ARG_SIZE, "CL_INVALID_ARG_SIZE",
     "an argument's size differs from the kernel's parameter"},
    {CL_INVALID_KERNEL_ARGS, "CL_INVALID_KERNEL_ARGS", "some kernel arguments were not set"},
    {CL_INVALID_WORK_DIMENSION, "CL_INVALID_WORK_DIMENSION", "the work dimension is not valid"},
    {CL_INVALID_WORK_GROUP_SIZE, "CL_INVALID_WORK_GROUP_SIZE",
     "the work-group size does not fit the kernel or the global size"},
    {CL_INVALID_WORK_ITEM_SIZE, "CL_INVALID_WORK_ITEM_SIZE",
     "a work-group dimension exceeds the device's limit"},
    {CL_INVALID_GLOBAL_OFFSET, "CL_INVALID_GLOBAL_OFFSET", "the global offset is not valid"},
    {CL_INVALID_EVENT_WAIT_LIST, "CL_INVALID_EVENT_WAIT_LIST", "the event wait list is not valid"},
    {CL_INVALID_EVENT, "CL_INVALID_EVENT", "the event is not valid"},
    {CL_INVALID_OPERATION, "CL_INVALID_OPERATION", "the operation is not allowed here"},
    {CL_INVALID_BUFFER_SIZE, "CL_INVALID_BUFFER_SIZE",
     "the buffer size is zero or above the device's limit"},
    {CL_INVALID_GLOBAL_WORK_SIZE, "CL_INVALID_GLOBAL_WORK_SIZE",
     "the global work size is zero or too large"},
    {CL_INVALID_PROPERTY, "CL_INVALID_PROPERTY", "a property is not valid"},
    {kPlatformNotFoundKhr, "CL_PLATFORM_NOT_FOUND_KHR",
     "no OpenCL platform is installed (no ICD found)"},
};

const StatusText* find_status(cl_int status) {
  for (const StatusText& text : kStatusTexts) {
    if (text.status == status) return &text;
  }
  return nullptr;
}

}  // namespace

std::string status_name(cl_int status) {
  const StatusText* text = find_status(status);
  return text ? text->name : "CL_ERROR_" + std::to_string(status);
}

std::string status_meaning(cl_int status) {
  const StatusText* text = find_status(status);
  return text ? text->meaning : "an error this program does not know";
}

std::string describe_failure(const char* call, const std::string& subject, cl_int status) {
  return std::string(call) + " on '" + subject + "': " + status_name(status) + ": " +
         status_meaning(status);
}

}  // namespace flexsight::opencl
