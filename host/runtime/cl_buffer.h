#pragma once
// A device buffer of `size()` elements of T, with blocking transfers on the context's
// queue (the pipeline only transfers at its start and end, so blocking costs nothing
// and keeps the host data's lifetime obvious). The Context must outlive the buffer.
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "host/runtime/cl_context.h"

namespace flexsight::opencl {

// Byte-level operations behind Buffer<T>; `what` names the buffer in error messages.
MemHandle create_buffer(Context& context, size_t bytes, const std::string& what);
void write_bytes(Context& context, cl_mem buffer, size_t offset, size_t bytes, const void* data,
                 const std::string& what);
void read_bytes(Context& context, cl_mem buffer, size_t offset, size_t bytes, void* data,
                const std::string& what);
void fill_bytes(Context& context, cl_mem buffer, const void* pattern, size_t pattern_bytes,
                size_t bytes, const std::string& what);

// Counts a buffer's bytes on its context while it lives (moves carry the count along).
class BufferBytes {
 public:
  BufferBytes() = default;
  BufferBytes(Context& context, size_t bytes) : context_(&context), bytes_(bytes) {
    context.note_allocated(bytes);
  }
  BufferBytes(BufferBytes&& other) noexcept
      : context_(std::exchange(other.context_, nullptr)), bytes_(other.bytes_) {}
  BufferBytes& operator=(BufferBytes&& other) noexcept {
    if (this != &other) {
      release();
      context_ = std::exchange(other.context_, nullptr);
      bytes_ = other.bytes_;
    }
    return *this;
  }
  ~BufferBytes() { release(); }

 private:
  void release() {
    if (context_) context_->note_released(bytes_);
    context_ = nullptr;
  }
  Context* context_ = nullptr;
  size_t bytes_ = 0;
};

template <typename T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>, "device buffers hold plain values");

 public:
  Buffer() = default;
  // Uninitialised; `what` names it in error messages ("planes (left)").
  Buffer(Context& context, size_t size, std::string what = "buffer")
      : context_(&context), size_(size), what_(std::move(what)),
        mem_(create_buffer(context, bytes(), what_)), counted_(context, bytes()) {}
  Buffer(Context& context, const std::vector<T>& values, std::string what = "buffer")
      : Buffer(context, values.size(), std::move(what)) {
    write(values);
  }

  size_t size() const { return size_; }
  size_t bytes() const { return size_ * sizeof(T); }
  cl_mem get() const { return mem_.get(); }
  const std::string& what() const { return what_; }

  // The first values.size() elements (at most size()).
  void write(const std::vector<T>& values) { write(values.data(), values.size()); }
  void write(const T* values, size_t count, size_t first = 0) {
    require(first + count <= size_, "write past the end");
    write_bytes(*context_, get(), first * sizeof(T), count * sizeof(T), values, what_);
  }
  std::vector<T> read() const { return read(0, size_); }
  std::vector<T> read(size_t first, size_t count) const {
    require(first + count <= size_, "read past the end");
    std::vector<T> values(count);
    read_bytes(*context_, get(), first * sizeof(T), count * sizeof(T), values.data(), what_);
    return values;
  }
  void fill(const T& value) { fill_bytes(*context_, get(), &value, sizeof(T), bytes(), what_); }

 private:
  void require(bool ok, const char* problem) const {
    if (!ok) throw std::out_of_range("buffer '" + what_ + "': " + problem);
  }

  Context* context_ = nullptr;
  size_t size_ = 0;
  std::string what_;
  MemHandle mem_;
  BufferBytes counted_;
};

// A stage's buffer must hold its elements: kernels trust the sizes they are given, so the
// host stages check them before every launch.
template <typename T>
void require_size(const Buffer<T>& buffer, long long elements, const char* stage) {
  if (elements < 0 || buffer.size() < static_cast<size_t>(elements)) {
    throw std::invalid_argument(std::string(stage) + ": buffer '" + buffer.what() + "' holds " +
                                std::to_string(buffer.size()) + " elements, the stage needs " +
                                std::to_string(elements));
  }
}

}  // namespace flexsight::opencl
