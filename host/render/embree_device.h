#pragma once
// The process's one Embree device (Embree's thread pool and memory), shared by every
// RenderScene, and the check that turns Embree's error codes into exceptions.
#include <embree3/rtcore.h>

namespace flexsight::render_detail {

// Created on first use; lives until the process ends.
RTCDevice embree_device();

// Throws std::runtime_error naming `step` and Embree's error when the device holds one.
void check_embree(const char* step);

}  // namespace flexsight::render_detail
