// Map files (`A_B.map`, named as eval/pair_names.h says): one target vertex id per source
// vertex, one per line, in the vertex ids of the input meshes. symembed writes 1-based ids (the
// format peers publish); other methods' maps may be 0- or 1-based, integers or integral floats
// ("123", "1.23e+02").
#pragma once

#include <string>
#include <vector>

namespace symembed {

// Parses map text. base: 0 or 1, the id of the first target vertex in the file.
// expected_length: number of source vertices (-1: any); num_target_vertices: number of target
// vertices (-1: unchecked). Returns 0-based target ids. Blank lines at the end are ignored.
// Throws InvalidInputError naming `where`:line for an empty, missing (blank) or non-numeric
// entry, NaN, a non-integral value, an id out of range, or the wrong number of lines.
std::vector<int> ParseMap(const std::string& text, int base, int expected_length,
                          int num_target_vertices, const std::string& where);

// Reads a map file (ParseMap); throws IoError when it cannot be read.
std::vector<int> ReadMapFile(const std::string& path, int base, int expected_length,
                             int num_target_vertices);

// The text of a map written 1-based, one id per line ("\n"-terminated).
std::string FormatMap(const std::vector<int>& map_zero_based);

// Writes FormatMap(map) to path, creating its folder (not atomically; the caller renames when
// it needs that).
// Throws IoError.
void WriteMapFile(const std::string& path, const std::vector<int>& map_zero_based);

}  // namespace symembed
