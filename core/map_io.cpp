#include "core/map_io.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace symembed {

namespace {

std::string Trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

std::vector<int> ParseMap(const std::string& text, int base, int expected_length,
                          int num_target_vertices, const std::string& where) {
  if (base != 0 && base != 1) {
    throw InvalidInputError(where + ": map base must be 0 or 1, got " + std::to_string(base));
  }
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) lines.push_back(Trim(line));
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  if (lines.empty()) throw InvalidInputError(where + ": empty map");
  if (expected_length >= 0 && static_cast<int>(lines.size()) != expected_length) {
    throw InvalidInputError(where + ": " + std::to_string(lines.size()) + " entries, expected " +
                            std::to_string(expected_length) + " (one per source vertex)");
  }
  // With base 0, an id equal to #V in a file without a 0 is a 1-based file given the wrong
  // base (checked only on that error path).
  auto looks_one_based = [&](int id) {
    if (base != 0 || id != num_target_vertices) return false;
    for (const std::string& token : lines) {
      if (!token.empty() && std::strtod(token.c_str(), nullptr) == 0.0) return false;
    }
    return true;
  };
  std::vector<int> map(lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string at = where + ":" + std::to_string(i + 1) + ": ";
    const std::string& token = lines[i];
    if (token.empty()) throw InvalidInputError(at + "missing entry (blank line)");
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') {
      throw InvalidInputError(at + "not a number: '" + token + "'");
    }
    if (std::isnan(value)) throw InvalidInputError(at + "NaN entry");
    if (!std::isfinite(value) || value != std::floor(value) || std::abs(value) > 2e9) {
      throw InvalidInputError(at + "not an integral vertex id: '" + token + "'");
    }
    const int id = static_cast<int>(value) - base;
    if (id < 0 || (num_target_vertices >= 0 && id >= num_target_vertices)) {
      throw InvalidInputError(at + "vertex id " + token + " out of range [" +
                              std::to_string(base) + ", " +
                              (num_target_vertices >= 0
                                   ? std::to_string(num_target_vertices - 1 + base)
                                   : std::string("inf")) +
                              "] (" + std::to_string(base) + "-based)" +
                              (looks_one_based(id)
                                   ? "; no id is 0 and this one is the vertex count: the file "
                                     "looks 1-based (--base 1)"
                                   : ""));
    }
    map[i] = id;
  }
  return map;
}

std::vector<int> ReadMapFile(const std::string& path, int base, int expected_length,
                             int num_target_vertices) {
  if (std::filesystem::is_directory(path)) throw IoError(path + ": is a folder, not a map file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot read map file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseMap(text.str(), base, expected_length, num_target_vertices, path);
}

std::string FormatMap(const std::vector<int>& map_zero_based) {
  std::string out;
  out.reserve(map_zero_based.size() * 6);
  for (int id : map_zero_based) {
    out += std::to_string(id + 1);
    out += '\n';
  }
  return out;
}

void WriteMapFile(const std::string& path, const std::vector<int>& map_zero_based) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::ofstream out(path, std::ios::binary);
  out << FormatMap(map_zero_based);
  if (!out) throw IoError(path + ": cannot write map file");
}

}  // namespace symembed
