// Whole-file reads and atomic writes, for everything the harness writes: the per-shape cache,
// the run folders (maps, records, summaries) and the baselines.
#pragma once

#include <optional>
#include <string>

namespace symembed {

// Writes bytes to path through a temporary file in the same folder (unique per process and
// call, so concurrent writers never share one) and a rename, so that a reader sees the old
// file or the new one, never a part; creates the parent folders. Throws IoError naming path.
void WriteFileAtomically(const std::string& path, const std::string& bytes);

// The bytes of a file, or std::nullopt when it cannot be opened or read.
std::optional<std::string> ReadFileBytes(const std::string& path);

// The bytes of a file. Throws IoError "<path>: cannot read" when it cannot be opened or read.
std::string ReadFileOrThrow(const std::string& path);

}  // namespace symembed
