#include "host/runtime/cl_api.h"

namespace flexsight::opencl {
namespace {

// CL_PLATFORM_NOT_FOUND_KHR of cl_ext.h: what the ICD loader answers when no platform
// is installed, the most common failure on a machine without drivers.
#ifndef CL_PLATFORM_NOT_FOUND_KHR
#define CL_PLATFORM_NOT_FOUND_KHR -1001
#endif

struct StatusText {
  cl_int status;
  const char* name;
  const char* meaning;
};

// A code with its name, spelt as the headers spell the code, and its meaning.
#define FLEXSIGHT_STATUS(code, meaning) StatusText{code, #code, meaning}

// The codes an OpenCL 1.2 host program can meet, with what they usually mean here.
constexpr StatusText kStatusTexts[] = {
    FLEXSIGHT_STATUS(CL_DEVICE_NOT_FOUND, "no OpenCL device of the requested type"),
    FLEXSIGHT_STATUS(CL_DEVICE_NOT_AVAILABLE, "the device is busy or switched off"),
    FLEXSIGHT_STATUS(CL_COMPILER_NOT_AVAILABLE, "the driver has no OpenCL C compiler"),
    FLEXSIGHT_STATUS(CL_MEM_OBJECT_ALLOCATION_FAILURE, "the device could not allocate a buffer"),
    FLEXSIGHT_STATUS(CL_OUT_OF_RESOURCES,
                     "the device ran out of resources (or a kernel accessed memory out of bounds)"),
    FLEXSIGHT_STATUS(CL_OUT_OF_HOST_MEMORY, "the host ran out of memory"),
    FLEXSIGHT_STATUS(CL_PROFILING_INFO_NOT_AVAILABLE,
                     "the event has no timing (queue without profiling, or command not finished)"),
    FLEXSIGHT_STATUS(CL_MEM_COPY_OVERLAP, "source and destination overlap"),
    FLEXSIGHT_STATUS(CL_BUILD_PROGRAM_FAILURE,
                     "the kernel source does not compile for this device"),
    FLEXSIGHT_STATUS(CL_MAP_FAILURE, "the buffer could not be mapped"),
    FLEXSIGHT_STATUS(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST,
                     "a command this one waited for failed"),
    FLEXSIGHT_STATUS(CL_INVALID_VALUE, "an argument value is not allowed"),
    FLEXSIGHT_STATUS(CL_INVALID_DEVICE_TYPE, "the device type is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_PLATFORM, "the platform is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_DEVICE, "the device is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_CONTEXT, "the context is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_QUEUE_PROPERTIES,
                     "the device does not support these queue properties"),
    FLEXSIGHT_STATUS(CL_INVALID_COMMAND_QUEUE, "the command queue is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_MEM_OBJECT, "a buffer argument is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_BINARY, "the program binary is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_BUILD_OPTIONS, "the compiler rejected the build options"),
    FLEXSIGHT_STATUS(CL_INVALID_PROGRAM, "the program is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_PROGRAM_EXECUTABLE, "the program was not built for this device"),
    FLEXSIGHT_STATUS(CL_INVALID_KERNEL_NAME, "the program has no kernel of that name"),
    FLEXSIGHT_STATUS(CL_INVALID_KERNEL_DEFINITION,
                     "the kernel differs between the devices of the program"),
    FLEXSIGHT_STATUS(CL_INVALID_KERNEL, "the kernel is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_ARG_INDEX, "the kernel has fewer arguments"),
    FLEXSIGHT_STATUS(CL_INVALID_ARG_VALUE, "an argument value is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_ARG_SIZE, "an argument's size differs from the kernel's parameter"),
    FLEXSIGHT_STATUS(CL_INVALID_KERNEL_ARGS, "some kernel arguments were not set"),
    FLEXSIGHT_STATUS(CL_INVALID_WORK_DIMENSION, "the work dimension is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_WORK_GROUP_SIZE,
                     "the work-group size does not fit the kernel or the global size"),
    FLEXSIGHT_STATUS(CL_INVALID_WORK_ITEM_SIZE,
                     "a work-group dimension exceeds the device's limit"),
    FLEXSIGHT_STATUS(CL_INVALID_GLOBAL_OFFSET, "the global offset is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_EVENT_WAIT_LIST, "the event wait list is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_EVENT, "the event is not valid"),
    FLEXSIGHT_STATUS(CL_INVALID_OPERATION, "the operation is not allowed here"),
    FLEXSIGHT_STATUS(CL_INVALID_BUFFER_SIZE, "the buffer size is zero or above the device's limit"),
    FLEXSIGHT_STATUS(CL_INVALID_GLOBAL_WORK_SIZE, "the global work size is zero or too large"),
    FLEXSIGHT_STATUS(CL_INVALID_PROPERTY, "a property is not valid"),
    FLEXSIGHT_STATUS(CL_PLATFORM_NOT_FOUND_KHR, "no OpenCL platform is installed (no ICD found)"),
};

#undef FLEXSIGHT_STATUS

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
