// Writing a dataset in the pairs_vts layout (eval/datasets/pairs_vts.h): what `symembed synth`
// and `symembed remesh` share.
#pragma once

#include <filesystem>
#include <string>

namespace symembed {

// Creates root/shapes and root/corres; throws IoError when they cannot be created.
void CreateDatasetFolders(const std::filesystem::path& root);

// Writes text to path; throws IoError naming it when it cannot be written.
void WriteDatasetFile(const std::filesystem::path& path, const std::string& text);

// Makes `out` ready for a dataset: absent or empty is fine; a non-empty directory is refused
// unless `force`, which removes the layout's entries (shapes/, corres/, test_pairs.txt,
// README.md) and leaves anything else. Throws IoError ("... use --force ..." when refused, or
// when out is a file).
void PrepareDatasetOutput(const std::filesystem::path& out, bool force);

}  // namespace symembed
