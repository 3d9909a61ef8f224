// The files of the correspondence benchmark of [Kim, Lipman & Funkhouser 2011] "Blended
// intrinsic maps" (read by the `kim2011` loader, eval/datasets/kim2011.h): landmark files,
// mirror files and query files. Every error is InvalidInputError "path:line: what" (IoError when
// a file cannot be opened); lines are 1-based in messages, landmark lines 0-based in the data.
#pragma once

#include <string>
#include <vector>

namespace symembed {

// A landmark file (Corrs/CLASS.pid, Corrs/N.vts): one landmark per line, the line starting with
// its 0-based vertex id; the rest of the line (the point's coordinates) is ignored. Returns the
// ids in line order (landmark line k is file line k + 1). Trailing blank lines are allowed; a
// blank line before the last landmark, a first token that is not an integer, a negative id and
// a file without landmarks are errors. Ids are checked against a mesh by the caller.
std::vector<long long> ReadLandmarkIds(const std::string& path);

// A mirror file (Corrs/CLASS.sym.info, Corrs/N.sym.info) for a landmark file of num_landmarks
// lines: each line lists two landmark lines (0-based) that are each other's left-right mirror,
// or one that lies on the symmetry plane (its own mirror). Returns mirror[k] for every landmark
// line k: its partner, itself, or -1 when the file does not list it. Errors: a line of zero or
// more than two numbers, a number that is not a landmark line of the file named by
// landmark_path, a landmark listed twice. Blank lines are skipped.
std::vector<int> ReadMirrorLines(const std::string& path, int num_landmarks,
                                 const std::string& landmark_path);

// One group of a query file (Results/Corr_<Set>.query): a mesh of a set to evaluate.
struct KimQuery {
  std::string set;   // as written in the file
  int index = 0;     // the mesh index, 0-based (see kim2011.h for what it indexes)
  int set_line = 0;  // the file lines of the set name and of the index
  int line = 0;
};

// A query file: groups of three lines -- set name, `1` (the group names one mesh), mesh index
// (a non-negative integer). Blank lines are skipped; lines are trimmed. Errors: a second line
// other than `1`, an index that is not a non-negative integer, a file that ends inside a group.
std::vector<KimQuery> ReadQueryFile(const std::string& path);

}  // namespace symembed
