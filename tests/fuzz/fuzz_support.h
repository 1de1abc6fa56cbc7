#pragma once
// What the libFuzzer harnesses share (docs/reliability.md). Most readers take a path,
// so a harness writes its input to a file in a scratch folder of its own (in /dev/shm
// where there is one: no disk traffic at a few thousand inputs a second) and reads it
// back. The contract being checked: a reader either returns or throws InputError; any
// other exception escapes LLVMFuzzerTestOneInput, ends in std::terminate and is
// reported as a crash, like a sanitizer report, a leak or a time-out.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "host/io/input_error.h"

namespace fuzz {

// The process's scratch folder, made on first use and removed at exit.
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    const char* base = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
    std::string pattern = std::string(base) + "/flexsight_fuzz_XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("mkdtemp");
      std::abort();
    }
    static const std::string made = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(made, ignored);
    });
    return pattern;
  }();
  return dir;
}

// Writes bytes to scratch_dir()/name (truncating it) and returns the path.
inline std::string write_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    std::perror(path.c_str());
    std::abort();
  }
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  return path;
}

inline std::string write_file(const std::string& name, std::string_view text) {
  return write_file(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// The input cut at each `separator` byte: several files (a BOP scene's three JSON
// files) or tokens (a command line) from one input.
inline std::vector<std::string> split(const std::uint8_t* data, std::size_t size, char separator) {
  std::vector<std::string> parts(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (static_cast<char>(data[i]) == separator) {
      parts.emplace_back();
    } else {
      parts.back().push_back(static_cast<char>(data[i]));
    }
  }
  return parts;
}

// Runs `read`; InputError is the documented answer to a bad input, so it is swallowed.
template <typename Read>
void expect_input_error_only(Read&& read) {
  try {
    read();
  } catch (const flexsight::InputError&) {
  }
}

}  // namespace fuzz
