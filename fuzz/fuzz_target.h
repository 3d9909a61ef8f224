// The entry point every fuzz target defines, as libFuzzer calls it: one input, any bytes. A
// target feeds the bytes to one parser of user files and returns 0. The parser's documented
// errors (symembed::Error: InvalidInputError, ConfigError, IoError) are expected and caught;
// anything else (another exception, a crash, a sanitizer report, a hang) is a finding.
//
// Built with clang and SYMEMBED_FUZZ=ON the targets link libFuzzer (with ASan and UBSan);
// otherwise they link standalone_main.cpp, which replays the seed inputs and mutations of them,
// so that every build can smoke-test them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace symembed::fuzz {

inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace symembed::fuzz
