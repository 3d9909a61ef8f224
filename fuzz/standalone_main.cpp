// A driver for the fuzz targets in builds without libFuzzer, with libFuzzer's command line for
// what the smoke tests use: TARGET [-max_total_time=SECONDS] [-seed=N] DIR_OR_FILE...
// Runs every input file once, then, until the time is up, inputs made from them by random
// byte edits (flip, insert, delete, duplicate a range, splice tokens parsers treat specially).
// It is no coverage-guided fuzzer (scripts/fuzz runs libFuzzer); it keeps every target built
// and exercised on inputs near the seeds. Prints the number of executions; on a crash, writes
// the input to <artifact_prefix>crash-input.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/fuzz_target.h"

namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The input being run and where a crash writes it (libFuzzer's -artifact_prefix).
const std::string* current = nullptr;
std::string artifact_prefix = "./";

extern "C" void WriteCrashInput(int signal) {
  if (current) {
    const std::string path = artifact_prefix + "crash-input";
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
      std::fwrite(current->data(), 1, current->size(), f);
      std::fclose(f);
      std::fprintf(stderr, "standalone fuzz driver: signal %d; input written to %s\n", signal,
                   path.c_str());
    }
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void Run(const std::string& input) {
  current = &input;
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
  current = nullptr;
}

// Tokens that sit on the parsers' edge cases: signs, huge and special numbers, line ends,
// header words of the mesh formats, YAML structure.
const std::vector<std::string>& Tokens() {
  static const std::vector<std::string> tokens = {
      "-1", "0", "1", "4294967296", "99999999999999999999", "nan", "inf", "-inf", "1e308",
      "1e-320", "0x10", " ", "\t", "\n", "\r\n", "#", "OFF", "COFF", "ply", "format",
      "binary_little_endian", "binary_big_endian", "ascii", "element vertex", "property",
      "end_header", "solid", "facet normal", "vertex", "endloop", "v ", "f ", "//", "/",
      "{", "}", "[", "]", ":", "- ", "${", "${X:-", "&a", "*a", "!!", "'", "\"", "type:",
      "variants:", "set:", "name:"};
  return tokens;
}

std::string Mutate(std::string s, std::mt19937_64& rng) {
  auto pick = [&](size_t n) { return n == 0 ? 0 : static_cast<size_t>(rng() % n); };
  const int edits = 1 + static_cast<int>(rng() % 8);
  for (int e = 0; e < edits; ++e) {
    const size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!s.empty()) s[pick(s.size())] ^= static_cast<char>(1 << (rng() % 8));
        break;
      case 1:
        s.insert(at, 1, static_cast<char>(rng() % 256));
        break;
      case 2:
        s.erase(at, std::min(s.size() - std::min(at, s.size()), pick(64) + 1));
        break;
      case 3: {
        const size_t from = pick(s.size() + 1);
        s.insert(at, s.substr(from, pick(256) + 1));
        break;
      }
      case 4:
        s.insert(at, Tokens()[pick(Tokens().size())]);
        break;
      default:
        s.resize(pick(s.size() + 1));
        break;
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 1.0;
  uint64_t seed = 1;
  std::vector<std::string> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("-max_total_time=", 0) == 0) {
      seconds = std::atof(arg.c_str() + 16);
    } else if (arg.rfind("-artifact_prefix=", 0) == 0) {
      artifact_prefix = arg.substr(17);
    } else if (arg.rfind("-seed=", 0) == 0) {
      seed = std::strtoull(arg.c_str() + 6, nullptr, 10);
    } else if (arg.rfind("-", 0) == 0) {
      continue;  // other libFuzzer flags
    } else if (fs::is_directory(arg)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::recursive_directory_iterator(arg)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& f : files) inputs.push_back(ReadAll(f));
    } else if (fs::is_regular_file(arg)) {
      inputs.push_back(ReadAll(arg));
    } else {
      std::fprintf(stderr, "%s: no such file or folder\n", arg.c_str());
      return 2;
    }
  }
  for (int signal : {SIGABRT, SIGSEGV, SIGFPE, SIGBUS, SIGILL}) std::signal(signal, WriteCrashInput);
  long long executions = 0;
  for (const std::string& input : inputs) {
    Run(input);
    ++executions;
  }
  if (inputs.empty()) inputs.push_back("");
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    for (int k = 0; k < 64; ++k, ++executions) {
      Run(Mutate(inputs[rng() % inputs.size()], rng));
    }
  }
  std::printf("standalone fuzz driver: %lld executions, no crash\n", executions);
  return 0;
}
