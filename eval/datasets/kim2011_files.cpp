#include "eval/datasets/kim2011_files.h"

#include <optional>
#include <sstream>

#include "core/errors.h"
#include "eval/datasets/dataset_files.h"

namespace symembed {

namespace {

// The whole token as an integer, or nothing (trailing characters, overflow).
std::optional<long long> ParseInteger(const std::string& token) {
  try {
    size_t used = 0;
    const long long value = std::stoll(token, &used);
    if (used == token.size()) return value;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

struct WordLine {
  int line = 0;  // 1-based
  std::vector<std::string> words;
  std::string Text() const {
    std::string text;
    for (const auto& w : words) text += (text.empty() ? "" : " ") + w;
    return text;
  }
};

// The non-blank lines of a file, split at whitespace.
std::vector<WordLine> WordLines(const std::string& path) {
  std::vector<WordLine> out;
  const std::vector<std::string> lines = ReadTextLines(path);
  for (size_t i = 0; i < lines.size(); ++i) {
    std::istringstream in(lines[i]);
    WordLine line{static_cast<int>(i) + 1, {}};
    std::string w;
    while (in >> w) line.words.push_back(w);
    if (!line.words.empty()) out.push_back(line);
  }
  return out;
}

}  // namespace

std::vector<long long> ReadLandmarkIds(const std::string& path) {
  const std::vector<WordLine> lines = WordLines(path);
  if (lines.empty()) ThrowAtLine(path, 1, "no landmark lines");
  std::vector<long long> ids;
  for (const WordLine& line : lines) {
    // A blank line before a landmark would shift it and every later one by one line.
    const int expected = static_cast<int>(ids.size()) + 1;
    if (line.line != expected) ThrowAtLine(path, expected, "blank line before the last landmark");
    const std::string& token = line.words[0];
    const std::optional<long long> id = ParseInteger(token);
    if (!id) {
      ThrowAtLine(path, line.line,
                  "expected a line starting with a vertex id, got '" + token + "'");
    }
    if (*id < 0) {
      ThrowAtLine(path, line.line, "vertex id " + token + " is negative (ids are 0-based)");
    }
    ids.push_back(*id);
  }
  return ids;
}

std::vector<int> ReadMirrorLines(const std::string& path, int num_landmarks,
                                 const std::string& landmark_path) {
  std::vector<int> mirror(num_landmarks, -1);
  std::vector<int> listed_on(num_landmarks, 0);
  for (const WordLine& line : WordLines(path)) {
    if (line.words.size() > 2) {
      const std::string expected =
          "expected one or two landmark lines (a mirror pair, or a landmark on the symmetry "
          "plane)";
      ThrowAtLine(path, line.line, expected + ", got '" + line.Text() + "'");
    }
    int k[2];
    for (size_t w = 0; w < line.words.size(); ++w) {
      const std::string& token = line.words[w];
      const std::optional<long long> value = ParseInteger(token);
      if (!value || *value < 0 || *value >= num_landmarks) {
        ThrowAtLine(path, line.line,
                    "'" + token + "' is not a landmark line of " + landmark_path + " (0 to " +
                        std::to_string(num_landmarks - 1) + ")");
      }
      k[w] = static_cast<int>(*value);
      if (listed_on[k[w]]) {
        ThrowAtLine(path, line.line,
                    "landmark line " + token + " already listed on line " +
                        std::to_string(listed_on[k[w]]));
      }
      listed_on[k[w]] = line.line;
    }
    const int a = k[0], b = line.words.size() == 2 ? k[1] : k[0];
    mirror[a] = b;
    mirror[b] = a;
  }
  return mirror;
}

std::vector<KimQuery> ReadQueryFile(const std::string& path) {
  const std::vector<WordLine> lines = WordLines(path);
  std::vector<KimQuery> queries;
  for (size_t i = 0; i < lines.size(); i += 3) {
    KimQuery q{lines[i].Text(), 0, lines[i].line, 0};
    if (i + 2 >= lines.size()) {
      ThrowAtLine(path, q.set_line,
                  "the file ends inside this group (a group is three lines: set name, 1, mesh "
                  "index)");
    }
    const WordLine& count = lines[i + 1];
    if (count.Text() != "1") {
      ThrowAtLine(path, count.line,
                  "expected 1 (a group is three lines: set name, 1, mesh index), got '" +
                      count.Text() + "'");
    }
    const WordLine& index = lines[i + 2];
    const std::optional<long long> value = ParseInteger(index.Text());
    if (!value || *value < 0 || *value > 1000000000) {
      ThrowAtLine(path, index.line,
                  "expected a mesh index (a non-negative integer), got '" + index.Text() + "'");
    }
    q.index = static_cast<int>(*value);
    q.line = index.line;
    queries.push_back(q);
  }
  return queries;
}

}  // namespace symembed
