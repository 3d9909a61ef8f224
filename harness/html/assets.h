// The files of the HTML report's page (harness/html/assets/: index.html, report.css and the
// scripts), compiled into the binary by CMake (cmake/embed_assets.cmake) so that `symembed
// report` needs nothing beside it.
#pragma once

#include <string>
#include <vector>

namespace symembed {

struct ReportAsset {
  std::string name;   // file name inside the report folder
  std::string bytes;  // its contents
};

// Every asset, sorted by name.
const std::vector<ReportAsset>& ReportAssets();

}  // namespace symembed
