// File reading shared by the dataset loaders. Every error names the file and, where there is
// one, the 1-based line: InvalidInputError("path:line: what"); IoError when a file cannot be
// opened.
#pragma once

#include <string>
#include <vector>

#include "registry/dataset.h"
#include "registry/options.h"

namespace symembed {

// Throws InvalidInputError "path:line: what".
[[noreturn]] void ThrowAtLine(const std::string& path, int line, const std::string& what);

// The lines of a text file, without their line ends; IoError when it cannot be opened.
std::vector<std::string> ReadTextLines(const std::string& path);

// The restrictions every loader accepts in the config.
struct DatasetRestrictions {
  std::vector<std::string> classes;  // empty: all classes
  int max_pairs = 0;                 // > 0: keep the first max_pairs pairs (file order)
  std::string pairs_file;            // replaces the layout's pairs list; relative to the root
};

// Reads `classes`, `max_pairs` and `pairs_file` (strict, through the reader).
DatasetRestrictions ReadRestrictions(OptionReader& options);

// The class of a shape name: the name without its trailing digits ("cat10" -> "cat").
std::string ClassOfName(const std::string& name);

// A path relative to root (unchanged when absolute).
std::string ResolvePath(const std::string& root, const std::string& path);

// Mesh files (.off, .obj, .ply) directly in dir: stem -> path, sorted by stem; a mesh name that
// does not resolve to a file (a symbolic link in a loop or to nothing) is listed too, so that its
// shape fails alone when read. Throws InvalidInputError when two files share a stem, IoError when
// dir is not a directory.
std::vector<std::pair<std::string, std::string>> ListMeshes(const std::string& dir);

// Vertex count from a mesh file's header (OFF, PLY) or its `v` lines (OBJ).
int CountMeshVertices(const std::string& path);

// The vertex count shared by the meshes of a class whose vertex ids are common (the class's
// template): the count most of the meshes have; on a tie, the count of the earliest mesh in
// `mesh_paths` among the tied counts. `meshes` of the `total` meshes have it, `example` is the
// first of them. Reads only the files' headers (CountMeshVertices).
struct ClassTemplate {
  int vertices = 0;
  int meshes = 0;
  int total = 0;
  std::string example;
};
ClassTemplate FindClassTemplate(const std::vector<std::string>& mesh_paths);

// Throws InvalidInputError "MESH: N vertices, but the template of CLASS has M (...)" when a
// mesh's vertex count differs from its class's template: the class's vertex ids do not apply to
// it, so it has no ground truth.
void CheckClassTemplate(const std::string& mesh_path, int num_vertices,
                        const ClassTemplate& class_template, const std::string& class_name);

// One integer per line; trailing blank lines are allowed, other blank lines are not.
// Returns the values in line order (value k is on line k + 1).
std::vector<long long> ReadIntegerLines(const std::string& path);
// The same for text already read; `path` names it in messages.
std::vector<long long> ParseIntegerLines(const std::string& text, const std::string& path);

// 1-based vertex ids (line k + 1 of path) to 0-based ids; with allow_zero, 0 means "missing"
// and becomes -1. Throws "path:line: vertex id V out of range [1, num_vertices]".
std::vector<int> OneBasedIds(const std::vector<long long>& values, const std::string& path,
                             int num_vertices, bool allow_zero);

struct PairLine {
  std::string source, target;
  int line = 0;  // 1-based line in the pairs file
};

// Two whitespace-separated shape names per line (TOSCA uses a tab); blank lines and lines
// starting with '#' are skipped.
std::vector<PairLine> ReadPairsFile(const std::string& path);
// The same for text already read; `path` names it in messages.
std::vector<PairLine> ParsePairsText(const std::string& text, const std::string& path);

// All unordered pairs (i < j) of shapes within each class, in index order.
std::vector<DatasetPair> AllPairsWithinClasses(const std::vector<DatasetShape>& shapes);

// Keeps the pairs whose two shapes are in `classes` (all when empty), then the first
// max_pairs (all when 0), and the shapes they name (sorted by name). Throws InvalidInputError
// when a requested class has no shape.
DatasetIndex Restrict(const std::vector<DatasetShape>& shapes, const std::vector<DatasetPair>& pairs,
                      const DatasetRestrictions& restrictions, const std::string& where);

}  // namespace symembed
