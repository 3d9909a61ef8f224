// Writing a dataset in the pairs_vts layout (eval/datasets/pairs_vts.h): what `symembed synth`
// and `symembed remesh` share.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace symembed {

// Creates root/shapes and root/corres; throws IoError when they cannot be created.
void CreateDatasetFolders(const std::filesystem::path& root);

// Writes text to path; throws IoError naming it when it cannot be written.
void WriteDatasetFile(const std::filesystem::path& path, const std::string& text);

// The text of a .vts file of a shape whose vertex v is vertex kept[v] of a source mesh with
// num_source vertices (the synthetic rest shape, a remeshed input), or no source vertex when
// kept[v] < 0 (a vertex a subdivision added): line i is the 1-based id of
// the shape's vertex that is source vertex lines[i], or 0 when lines[i] < 0 or the shape did not
// keep that vertex.
std::string VtsText(const std::vector<int>& kept, const std::vector<int>& lines, int num_source);

// Makes `out` ready for a dataset: absent or empty is fine; a non-empty directory is refused
// unless `force`, which removes the layout's entries (shapes/, corres/, test_pairs.txt,
// README.md) and leaves anything else. Throws IoError ("... use --force ..." when refused, or
// when out is a file).
void PrepareDatasetOutput(const std::filesystem::path& out, bool force);

// 16 hex digits of the 64-bit FNV-1a hash of text: the name of a generated dataset's cache
// folder.
std::string HashHex(const std::string& text);

// Makes `folder` hold what write(dir) writes into an empty dir, unless folder/README.md exists:
// written to a temporary sibling and renamed into place, so that concurrent users see it
// complete or not at all. Throws IoError when it cannot be moved there.
void GenerateOnce(const std::string& folder, const std::function<void(const std::string&)>& write);

}  // namespace symembed
